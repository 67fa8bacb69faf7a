//! Phase 2, last: the commands in force (`command.rs`) override their vehicles' decisions.

use super::View;
use crate::command::{Active, Command};
use crate::events::LaneChangeReason;
use crate::state::Decision;
use crate::vehicle::{AutoFlags, Vehicle};
use platoonsim_model::commanded::{self, Limits};
use platoonsim_model::lanechange::Side;
use platoonsim_model::{cav, human, Leader};

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
            Command::AccelerateSafe { accel_mps2, .. } => {
                // This acceleration within the vehicle's limits and below its collision-free
                // speed; the model's lane change and automation state stand.
                let d = &mut decisions[s as usize];
                d.accel = view.safe_accel(s, accel_mps2, d.change);
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

impl View<'_> {
    /// The acceleration of an `AccelerateSafe` command (`platoonsim_model::commanded`): `a`
    /// within the limits of vehicle `s`, its desired speed, and its model's collision-free
    /// speed behind its leader or its lane's end and, if it changes lanes in this step
    /// (`change`), behind the target lane's leader too.
    fn safe_accel(&self, s: u32, a: f64, change: Option<Side>) -> f64 {
        let me = self.me(s);
        let v = me.v;
        let cav = v.is_cav();
        let safe = |l: Leader| {
            if cav {
                cav::safe_speed(&self.cfg.cav, l.gap_m, l.v_mps)
            } else {
                human::gipps_safe_speed(&v.driver.human, v.v, l, self.relax_now(v))
            }
        };
        let mut v_safe = me.leader.map_or(f64::INFINITY, safe);
        if let Some(side) = change {
            let nb = me.nb();
            let ld = match side {
                Side::Left => nb.left_leader,
                Side::Right => nb.right_leader,
            };
            if let Some(l) = self.view(v, ld) {
                v_safe = v_safe.min(safe(l));
            }
        }
        let (max_decel, max_accel) = if cav {
            (self.cfg.cav.max_decel, self.cfg.cav.max_accel)
        } else {
            (v.driver.human.max_decel, v.driver.human.max_accel)
        };
        let lim = Limits {
            v: v.v,
            v_max: self.own_v_des(&me),
            max_decel,
            max_accel,
            v_safe,
        };
        commanded::bounded_accel(a, &lim, self.clock.dt)
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
