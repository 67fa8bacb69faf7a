//! Phase 2, last: the commands in force (`command.rs`) override their vehicles' decisions.

use super::View;
use crate::command::{Active, Command};
use crate::events::LaneChangeReason;
use crate::state::Decision;
use crate::vehicle::{AutoFlags, Vehicle};
use platoonsim_model::lanechange::Side;

/// Phase 2, after the models: the commands in force override the decisions of their
/// vehicles. Commands of vehicles that left the road end; finished ones are removed.
#[cold]
#[inline(never)]
pub(crate) fn apply_commands(
    view: &View<'_>,
    commands: &mut Vec<Active>,
    decisions: &mut [Decision],
) {
    let mut k = 0;
    while k < commands.len() {
        let a = commands[k].clone();
        let Some(s) = view.traffic.slot_of(a.id) else {
            commands.remove(k);
            continue;
        };
        let v = &view.traffic.vehicles[s as usize];
        let done = match a.command {
            Command::Accelerate { accel_mps2, .. } => {
                // Under external control: the commanded acceleration, and no lane change.
                decisions[s as usize].accel = accel_mps2;
                let d = &mut decisions[s as usize];
                d.auto = AutoFlags::new(false, d.auto.degraded());
                decisions[s as usize].change = None;
                commands[k].left -= 1;
                commands[k].left == 0
            }
            Command::AccelerateCapped { accel_mps2, .. } => {
                // A controller on top of the model: at most the model's acceleration; the
                // model's lane change and automation state stand (a ramp vehicle still
                // merges, a CAV's automation stays engaged).
                let d = &mut decisions[s as usize];
                d.accel = accel_mps2.min(d.accel);
                commands[k].left -= 1;
                commands[k].left == 0
            }
            Command::DesiredSpeed { .. } => false,
            Command::ChangeLane { side } => {
                if u64::from(v.lane) == a.left {
                    true
                } else if toward(v, side, a.left) {
                    // A mandatory desire of 1, with the gap acceptance and before-lane-change
                    // behaviour of the driver model.
                    let mut d = view.forced_change(s, side);
                    d.why = LaneChangeReason::Commanded;
                    decisions[s as usize] = d;
                    false
                } else {
                    true // it moved elsewhere meanwhile (another change): the command lapses
                }
            }
            Command::Release => true,
        };
        if done {
            commands.remove(k);
        } else {
            k += 1;
        }
    }
}

/// Is `target` the lane next to the vehicle on `side`?
fn toward(v: &Vehicle, side: Side, target: u64) -> bool {
    match side {
        Side::Left => u64::from(v.lane) + 1 == target,
        Side::Right => u64::from(v.lane) == target + 1,
    }
}

#[cfg(test)]
mod tests {
    use super::toward;
    use crate::insert::place_for_test;
    use crate::vehicle::Kind;
    use crate::{Config, Simulation};
    use platoonsim_model::lanechange::Side;

    #[test]
    fn a_commanded_change_is_toward_its_target_lane_only_from_the_lane_beside_it() {
        let mut cfg = Config::homogeneous(0.0, 0.0, 60.0, 0.0, 1);
        cfg.road.lanes = 4;
        let mut sim = Simulation::new(cfg).unwrap();
        let id = place_for_test(&mut sim, Kind::Human, 1, 1000.0, 25.0);
        let v = &sim.traffic.vehicles[sim.traffic.slot_of(id).unwrap() as usize];
        assert!(toward(v, Side::Left, 2));
        assert!(toward(v, Side::Right, 0));
        assert!(!toward(v, Side::Left, 3), "two lanes away");
        assert!(!toward(v, Side::Right, 2), "the wrong side");
        assert!(!toward(v, Side::Left, 1), "its own lane");
    }
}
