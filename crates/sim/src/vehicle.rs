//! Vehicle state: identity, drawn parameters, kinematics, driving mode and statistics.

use crate::rng::Stream;
use platoonsim_model::cav::Family;
use platoonsim_model::human::HumanParams;
use platoonsim_model::lanechange::{LaneChangeParams, Side};

/// Vehicle type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Human,
    Cav,
}

/// Driving mode of the lane-change state machine (spec 4.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Normal car following.
    Cf,
    /// Before lane change toward `side`; `mandatory` if the desire is mandatory.
    Blc { side: Side, mandatory: bool },
    /// Yielding to the vehicle with id `to` (a neighbour in BLC toward this lane).
    Ycf { to: u64 },
}

/// Which relaxation is running (spec 4.6), and since which step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Relaxation {
    None,
    /// After one's own change (ALC) or after being cut in (RCF), started at `since` (step).
    Since(u64),
}

/// Step index meaning "never".
pub const NEVER: u64 = u64::MAX;

/// `Vehicle::exit` of a vehicle that leaves at the mainline end.
pub const NO_EXIT: u32 = u32::MAX;

/// One vehicle.
#[derive(Clone, Debug)]
pub struct Vehicle {
    /// Unique, increasing in creation order.
    pub id: u64,
    pub kind: Kind,
    /// Step at which it entered the road.
    pub entered_step: u64,
    /// Entered during the measurement window: counts in the statistics.
    pub measured: bool,
    pub human: HumanParams,
    pub lc: LaneChangeParams,
    /// CACC time gap t_C (s); CAVs only (0 for humans).
    pub cacc_gap_s: f64,
    /// Id of the predecessor whose CACC string this CAV has joined (`NEVER`: it leads its own
    /// string). Membership is sticky: see `sense.rs`.
    pub string_pred: u64,
    /// Effective target time gap of the CAV controller, ramping toward the current setting
    /// (spec 3.5 transitions); 0 before the first setting.
    pub time_gap_s: f64,
    /// Own random stream (lane choice, yielding draws).
    pub rng: Stream,

    pub x: f64,
    pub x_prev: f64,
    pub v: f64,
    pub a: f64,
    pub lane: u32,

    pub mode: Mode,
    pub relax: Relaxation,
    /// CAV controller family (hysteresis state, spec 3.3/3.4).
    pub family: Family,
    /// Step and side of the last lane change.
    pub last_lc_step: u64,
    pub last_lc_side: Option<Side>,
    /// Lane changes made.
    pub lane_changes: u32,
    /// Largest platoon this CAV has been in (1 = never), paper definition: a chain of CAVs each
    /// directly following the previous one under CACC within sensor range (`sense.rs`).
    pub max_platoon: u32,
    /// The same with the spec 6.15 link criterion (follower not in speed regulation, tg ≤ 2 s).
    pub max_platoon_tg2: u32,
    /// Index of the off-ramp it leaves by (`NO_EXIT`: the mainline end).
    pub exit: u32,
}

impl Vehicle {
    /// A CAV that is not driving manually (spec 3.1): plain car following, no relaxation.
    pub fn automated(&self) -> bool {
        self.kind == Kind::Cav && self.mode == Mode::Cf && self.relax == Relaxation::None
    }

    pub fn is_cav(&self) -> bool {
        self.kind == Kind::Cav
    }

    /// Rear bumper position.
    pub fn rear(&self) -> f64 {
        self.x - self.human.length_m
    }
}
