//! Control from outside: commands to single vehicles, applied at one phase of the step.
//!
//! A command given between two steps ([`crate::Simulation::command`]) takes effect in the next
//! step's decide phase (phase 2), after the driver models have decided, in the order the
//! commands were given; it lasts until it ends by itself or is released. Nothing else changes:
//! the commanded acceleration is bounded by the vehicle's braking limit in integrate like any
//! other, a commanded lane change is checked against the gaps in the lane-change phase like
//! any other, and a command that drives a vehicle into another is a collision.
//!
//! | command | effect | ends |
//! |---|---|---|
//! | `Accelerate { accel_mps2, steps }` | this acceleration (m/s²) instead of the model's, and no lane change | after `steps` steps |
//! | `AccelerateCapped { accel_mps2, steps }` | this acceleration, but never above the model's own of the step: the driver model's car following (for a CAV its ACC/CACC law with collision avoidance) is a ceiling, so a controller can brake and hold back but not drive into the vehicle ahead; the model's lane changes and automation state stand | after `steps` steps |
//! | `DesiredSpeed { speed_mps }` | the model drives with this desired speed (CAV: set speed) | on `Release` |
//! | `ChangeLane { side }` | a mandatory lane-change desire toward `side` (gap acceptance of spec 4.3 and 9.1, before-lane-change behaviour of spec 4.3 without braking for the change: `driver::commanded_target`) | once in the target lane |
//! | `Release` | every command of the vehicle ends; the model drives | at once |

use crate::decide::View;
use crate::error::SimError;
use crate::events::LaneChangeReason;
use crate::sim::{Decision, Simulation};
use crate::state::Traffic;
use crate::vehicle::Vehicle;
use platoonsim_model::lanechange::Side;

/// A command to one vehicle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Command {
    /// Apply `accel_mps2` for the next `steps` steps.
    Accelerate { accel_mps2: f64, steps: u64 },
    /// Apply `accel_mps2`, or the model's acceleration if lower, for the next `steps` steps.
    AccelerateCapped { accel_mps2: f64, steps: u64 },
    /// Drive with this desired speed (m/s) until released.
    DesiredSpeed { speed_mps: f64 },
    /// Change one lane toward `side` as soon as the gaps allow.
    ChangeLane { side: Side },
    /// Hand the vehicle back to its model.
    Release,
}

/// A command in force.
#[derive(Clone, Debug)]
pub(crate) struct Active {
    pub id: u64,
    pub command: Command,
    /// `Accelerate`: steps left; `ChangeLane`: the target lane; `DesiredSpeed`: unused.
    pub left: u64,
    /// `DesiredSpeed`: the driver's own desired speed, restored on release.
    pub own_speed: f64,
}

/// The largest |acceleration| a command may ask for (m/s²); the vehicle's braking limit
/// bounds it further.
pub const MAX_COMMAND_ACCEL_MPS2: f64 = 20.0;

impl Simulation {
    /// Command vehicle `id` (on the road now) from the next step on (module `command`).
    pub fn command(&mut self, id: u64, command: Command) -> Result<(), SimError> {
        let Some(s) = self.slot_of(id) else {
            return Err(SimError::Command(format!(
                "vehicle {id} is not on the road"
            )));
        };
        let v = &self.traffic.vehicles[s as usize];
        let mut active = Active {
            id,
            command,
            left: 0,
            own_speed: v.driver.human.desired_speed,
        };
        match command {
            Command::Accelerate { accel_mps2, steps }
            | Command::AccelerateCapped { accel_mps2, steps } => {
                if !(accel_mps2.is_finite() && accel_mps2.abs() <= MAX_COMMAND_ACCEL_MPS2) {
                    return Err(SimError::Command(format!(
                        "Accelerate.accel_mps2 = {accel_mps2}: must be finite, within \
                         ±{MAX_COMMAND_ACCEL_MPS2} m/s²"
                    )));
                }
                if steps == 0 {
                    return Err(SimError::Command(
                        "Accelerate.steps = 0: must be at least 1".into(),
                    ));
                }
                active.left = steps;
            }
            Command::DesiredSpeed { speed_mps } => {
                if !(speed_mps.is_finite() && (0.0..=100.0).contains(&speed_mps)) {
                    return Err(SimError::Command(format!(
                        "DesiredSpeed.speed_mps = {speed_mps}: must be in [0, 100] m/s"
                    )));
                }
                // A second DesiredSpeed keeps the driver's own speed of the first.
                if let Some(a) = self
                    .control
                    .commands
                    .iter()
                    .find(|a| a.id == id && matches!(a.command, Command::DesiredSpeed { .. }))
                {
                    active.own_speed = a.own_speed;
                }
                self.release_kind(id, |c| matches!(c, Command::DesiredSpeed { .. }));
                self.traffic.vehicles[s as usize].driver.human.desired_speed = speed_mps;
            }
            Command::ChangeLane { side } => {
                let to = match side {
                    Side::Left => v.lane + 1,
                    Side::Right => v.lane.wrapping_sub(1),
                };
                if !self.road.geom.can_enter(to, v.x) {
                    return Err(SimError::Command(format!(
                        "vehicle {id} cannot change {side:?} at x = {:.1} m: no lane it may \
                         enter there",
                        v.x + self.cfg.road.network.as_ref().map_or(0.0, |n| n.origin_m)
                    )));
                }
                active.left = u64::from(to);
            }
            Command::Release => {
                self.release_kind(id, |_| true);
                return Ok(());
            }
        }
        self.control.commands.push(active);
        Ok(())
    }

    /// The vehicles under command now (ids, in the order the commands were given).
    pub fn commanded(&self) -> impl Iterator<Item = u64> + '_ {
        self.control.commands.iter().map(|a| a.id)
    }

    /// End the commands of `id` that `which` selects (restoring a desired speed).
    fn release_kind(&mut self, id: u64, which: impl Fn(&Command) -> bool) {
        let slot = self.slot_of(id);
        let mut k = 0;
        while k < self.control.commands.len() {
            let a = &self.control.commands[k];
            if a.id == id && which(&a.command) {
                if let (Command::DesiredSpeed { .. }, Some(s)) = (a.command, slot) {
                    self.traffic.vehicles[s as usize].driver.human.desired_speed = a.own_speed;
                }
                self.control.commands.remove(k);
            } else {
                k += 1;
            }
        }
    }

    /// Slot of the vehicle with this id, if it is on the road.
    pub(crate) fn slot_of(&self, id: u64) -> Option<u32> {
        slot_of(&self.traffic, id)
    }
}

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
        let Some(s) = slot_of(view.traffic, a.id) else {
            commands.remove(k);
            continue;
        };
        let v = &view.traffic.vehicles[s as usize];
        let done = match a.command {
            Command::Accelerate { accel_mps2, .. } => {
                // Under external control: the commanded acceleration, and no lane change.
                decisions[s as usize].accel = accel_mps2;
                let d = &mut decisions[s as usize];
                d.auto = crate::vehicle::AutoFlags::new(false, d.auto.degraded());
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
                    let mut d = view.forced_change(s, v, side);
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

/// Slot of the vehicle with this id, if it is on the road.
fn slot_of(traffic: &Traffic, id: u64) -> Option<u32> {
    traffic
        .lanes
        .iter()
        .flatten()
        .copied()
        .find(|&s| traffic.vehicles[s as usize].id == id)
}

/// Is `target` the lane next to the vehicle on `side`?
fn toward(v: &Vehicle, side: Side, target: u64) -> bool {
    match side {
        Side::Left => u64::from(v.lane) + 1 == target,
        Side::Right => u64::from(v.lane) == target + 1,
    }
}
