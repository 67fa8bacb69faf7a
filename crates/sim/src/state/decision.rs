//! The decide phase's result for each vehicle (phase 2), carried out by integrate and the
//! lane changes: step state, so it lives with the state.

use crate::events::LaneChangeReason;
use crate::vehicle::{AutoFlags, Mode};
use platoonsim_model::cav::{CavMode, Family};
use platoonsim_model::lanechange::Side;

/// Per-vehicle result of the decide phase (indexed by slot).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Decision {
    pub accel: f64,
    pub mode: Mode,
    pub family: Family,
    /// The control regime of an automated CAV's controller in this step (`None`: manual).
    pub regime: Option<CavMode>,
    /// Effective CAV time gap after this step (spec 3.5 transitions).
    pub time_gap: f64,
    /// Lane change to execute after integration, and why.
    pub change: Option<Side>,
    pub why: LaneChangeReason,
    /// An automated CAV hands over to its driver in this step: relaxation starts (spec 4.6).
    pub takeover: bool,
    /// The change is a cooperative one, made under automation (spec 9.2).
    pub coop: bool,
    /// Spec 9.3: AEB intervenes (the automation's demand exceeds its braking bound); an
    /// automated CAV behind a CAV runs ACC for want of V2V beacons.
    pub auto: AutoFlags,
    /// The change is mandatory with γ ≥ 1: the safe rule's harder bound (spec 9.1).
    pub urgent: bool,
}
