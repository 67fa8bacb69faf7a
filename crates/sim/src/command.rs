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
//! | `AccelerateSafe { accel_mps2, steps }` | this acceleration, bounded by the vehicle's limits (`cav.max_decel`/`max_accel` for a CAV, its driver's for a human), its desired speed, and its model's collision-free speed behind the vehicle ahead or its lane's end (a CAV's safety-override speed, spec 3.4/3.8; a human's Gipps speed, spec 2.3; `platoonsim_model::commanded`): it can accelerate above the model, never into the vehicle ahead (SUMO's speed mode that regards the safe speed); only the safe speed may brake harder than the limit, down to the emergency limit; the model's lane changes stand, and while one is decided the target lane's leader bounds it too | after `steps` steps |
//! | `DesiredSpeed { speed_mps }` | the model drives with this desired speed (CAV: set speed) | on `Release` |
//! | `ChangeLane { side }` | a mandatory lane-change desire toward `side` (gap acceptance of spec 4.3 and 9.1, before-lane-change behaviour of spec 4.3 without braking for the change: `driver::commanded_target`) | once in the target lane |
//! | `Release` | every command of the vehicle ends; the model drives | at once |

//!
//! This module holds what a command is; `decide/commands.rs` applies the commands in force
//! (phase 2) and `steer.rs` the library's methods that give them ([`crate::Simulation::command`]).

use platoonsim_model::lanechange::Side;

/// A command to one vehicle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Command {
    /// Apply `accel_mps2` for the next `steps` steps.
    Accelerate { accel_mps2: f64, steps: u64 },
    /// Apply `accel_mps2`, or the model's acceleration if lower, for the next `steps` steps.
    AccelerateCapped { accel_mps2: f64, steps: u64 },
    /// Apply `accel_mps2` within the vehicle's limits and below its collision-free speed
    /// (`platoonsim_model::commanded`) for the next `steps` steps.
    AccelerateSafe { accel_mps2: f64, steps: u64 },
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
