//! Vehicle state: identity, drawn parameters, kinematics, driving mode and statistics.

use crate::rng::Stream;
use platoonsim_model::cav::{CavMode, Family};
use platoonsim_model::human::HumanParams;
use platoonsim_model::lanechange::{LaneChangeParams, Side};

/// Vehicle type (`as usize`: human 0, CAV 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Human = 0,
    Cav = 1,
}

impl Kind {
    /// `human` or `cav`, as in the trip, trajectory and collision records.
    pub fn as_str(self) -> &'static str {
        match self {
            Kind::Human => "human",
            Kind::Cav => "cav",
        }
    }
}

/// Driving mode of the lane-change state machine (spec 4.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// Normal car following.
    Cf,
    /// Before lane change toward `side`; `mandatory` if the desire is mandatory; `auto` if a
    /// CAV's automation stays engaged while its driver waits for a gap toward the PD lane
    /// (`cav.organize_while_automated`) or asks for a cooperative change (spec 9.2); `ask`
    /// counts the steps of the cooperative request cycle (0: none; live while
    /// `platoonsim_model::cooperative::asking`).
    Blc {
        side: Side,
        mandatory: bool,
        auto: bool,
        ask: u16,
    },
    /// Yielding to the vehicle with id `to` (a neighbour in BLC toward this lane); `auto` if
    /// an automated CAV yields through its automation (spec 6.5 flag); `coop` if it opens a
    /// gap for a cooperative change (spec 9.2).
    Ycf { to: u64, auto: bool, coop: bool },
}

/// Which relaxation is running (spec 4.6): none, or one that started at a step, after one's
/// own change (ALC) or after being cut in (RCF). Eight bytes (the step, `NEVER` for none), so
/// that the lane-change state fits the vehicle's second cache line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Relaxation(u64);

impl Relaxation {
    /// No relaxation running.
    pub const NONE: Relaxation = Relaxation(NEVER);

    /// A relaxation that starts at `step`.
    pub fn since(step: u64) -> Relaxation {
        debug_assert!(step != NEVER);
        Relaxation(step)
    }

    /// The step it started at, if one is running.
    pub fn started(self) -> Option<u64> {
        (self.0 != NEVER).then_some(self.0)
    }
}

/// Step index meaning "never".
pub const NEVER: u64 = u64::MAX;

/// `Vehicle::exit` of a vehicle that leaves at the mainline end.
pub const NO_EXIT: u32 = u32::MAX;

/// One vehicle: its kinematic state, identity and driving mode first, then its state by
/// concern.
///
/// Laid out by hand (`repr(C)`, cache-line aligned) for the step's sweeps over the lanes: the
/// first cache line holds what every phase reads (position, speed, acceleration, id, lane,
/// type, mode), the second the CAV controller's and the lane-change state, then the route
/// (its exit is read every step) and the driver's drawn parameters (body length first:
/// `rear()`), then the bookkeeping, cold, in the padding of the last line.
#[derive(Clone, Debug)]
#[repr(C, align(64))]
pub(crate) struct Vehicle {
    /// Front bumper position (m, engine coordinate).
    pub x: f64,
    /// Speed (m/s).
    pub v: f64,
    /// Acceleration applied in the last step (m/s²).
    pub a: f64,
    /// Position before the last step (m): detectors count crossings with it.
    pub x_prev: f64,
    /// Unique, increasing in creation order.
    pub id: u64,
    /// Lane (0 = rightmost).
    pub lane: u32,
    pub kind: Kind,
    pub mode: Mode,
    /// The CAV controller's state (zero for a human driver).
    pub cacc: CaccState,
    /// Lane-change history: relaxation, the last change, the count.
    pub lcs: LaneChangeState,
    /// Where it came from and where it leaves.
    pub route: Route,
    /// Steps an automated CAV has waited below the creep speed for a gap toward its organized
    /// lane, in the current wait (0 outside one; `cav.organize_hold`, 6.20). In the padding
    /// between the route and the driver.
    pub hold_wait: u32,
    /// The driver's drawn parameters and random stream.
    pub driver: Driver,
    /// Bookkeeping for the statistics, the safety measures and the observers; the driving
    /// model never reads it.
    pub stats: Stats,
}

/// The CAV controller's state, and the largest platoon the CAV has been in (updated by the
/// sense phase every step, so kept in this hot line rather than with the bookkeeping).
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct CaccState {
    /// Id of the predecessor whose CACC string this CAV has joined (`NEVER`: it leads its own
    /// string). Membership is sticky: see `sense.rs`.
    pub pred: u64,
    /// Effective target time gap of the CAV controller, ramping toward the current setting
    /// (spec 3.5 transitions); 0 before the first setting.
    pub time_gap_s: f64,
    /// CACC time gap t_C (s) drawn for this CAV (0 for humans).
    pub gap_s: f64,
    /// CAV controller family (hysteresis state, spec 3.3/3.4).
    pub family: Family,
    /// The CAV controller's regime in the last step while automated (spec 3.9); `None` for a
    /// human driver or a CAV driven manually.
    pub regime: Option<CavMode>,
    /// What the automation's realism did in the last step (spec 9.3): AEB braked this CAV,
    /// its CACC fell back to ACC.
    pub auto: AutoFlags,
    /// Largest platoon this CAV has been in (1 = never), paper definition: a chain of CAVs each
    /// directly following the previous one under CACC within sensor range (`sense.rs`).
    pub max_platoon: u32,
    /// The same with the spec 6.15 link criterion (follower not in speed regulation, tg ≤ 2 s).
    pub max_platoon_tg2: u32,
    /// Steps since the CAV last received a V2V beacon (spec 9.3; 0 without packet loss).
    pub beacon_age: u32,
}

/// What the automation did to a CAV in a step that the counts or the next step need (spec
/// 9.3's AEB and CACC fallback, the field law's take-over request, 6.20's organizing wait), as
/// bit flags in one byte
/// (the decision and the vehicle carry it; one test per vehicle and step).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AutoFlags(u8);

impl AutoFlags {
    pub const NONE: AutoFlags = AutoFlags(0);
    const AEB: u8 = 1;
    const FALLBACK: u8 = 2;
    const TOR: u8 = 4;
    /// The driver waits for a gap toward its organized lane under automation (6.20).
    const WAIT: u8 = 8;
    /// … below the creep speed: the step counts toward `cav.organize_hold_timeout_s`.
    const WAIT_SLOW: u8 = 16;

    /// `aeb`: the automation's demand exceeded `cav.max_automated_decel_mps2` and AEB applied
    /// it; `fallback`: no V2V beacon from the CAV leader within `cav.beacon_timeout_s`, ACC.
    #[inline]
    pub fn new(aeb: bool, fallback: bool) -> AutoFlags {
        AutoFlags((u8::from(aeb) * Self::AEB) | (u8::from(fallback) * Self::FALLBACK))
    }

    /// AEB braked the CAV.
    #[inline]
    pub fn aeb(self) -> bool {
        self.0 & Self::AEB != 0
    }

    /// The CAV's CACC fell back to ACC for want of beacons.
    #[inline]
    pub fn degraded(self) -> bool {
        self.0 & Self::FALLBACK != 0
    }

    /// The organizing wait of 6.20, and whether the CAV is below the creep speed in it.
    #[inline]
    pub(crate) fn waiting(slow: bool) -> AutoFlags {
        AutoFlags(Self::WAIT | (u8::from(slow) * Self::WAIT_SLOW))
    }

    /// In the organizing wait of 6.20.
    #[inline]
    pub(crate) fn in_wait(self) -> bool {
        self.0 & Self::WAIT != 0
    }

    /// In it below the creep speed.
    #[inline]
    pub(crate) fn wait_slow(self) -> bool {
        self.0 & Self::WAIT_SLOW != 0
    }

    /// A take-over request (field law): the demand exceeded the ISO 15622 envelope.
    pub const TAKEOVER: AutoFlags = AutoFlags(Self::TOR);

    /// The automation asked its driver to take over (field law).
    #[inline]
    pub fn takeover(self) -> bool {
        self.0 & Self::TOR != 0
    }

    /// None of the flags.
    #[inline]
    pub fn is_none(self) -> bool {
        self.0 == 0
    }

    /// Either flag in `self` or `other`.
    #[inline]
    pub fn union(self, other: AutoFlags) -> AutoFlags {
        AutoFlags(self.0 | other.0)
    }
}

/// Lane-change history.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct LaneChangeState {
    /// Which relaxation is running (spec 4.6).
    pub relax: Relaxation,
    /// Step of the last lane change (`NEVER`: none yet).
    pub last_step: u64,
    /// Lane changes made.
    pub count: u32,
    /// Side of the last lane change.
    pub last_side: Option<Side>,
    /// Cooperative lane changes made (spec 9.2; in the padding after `last_side`).
    pub coop_count: u16,
}

/// A driver's drawn parameters (spec 2, 4) and own random stream.
#[derive(Clone, Debug)]
#[repr(C)]
pub(crate) struct Driver {
    pub human: HumanParams,
    pub lc: LaneChangeParams,
    /// Own random stream (lane choice, yielding draws).
    pub rng: Stream,
}

/// Where a vehicle came from and where it leaves.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct Route {
    /// Index of the off-ramp it leaves by (`NO_EXIT`: the mainline end).
    pub exit: u32,
    /// Entrance it came in by: 0 the mainline, i + 1 on-ramp i.
    pub origin: u32,
    /// The off-ramp it chose on entry (`NO_EXIT`: the mainline end). Unlike `exit`, kept when it
    /// misses that off-ramp.
    pub planned_exit: u32,
}

/// What the run keeps about a vehicle for its outputs; the driving model never reads it.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct Stats {
    /// Step at which it entered the road.
    pub entered_step: u64,
    /// The last step in which it was in a conflict (TTC below the threshold, `safety.rs`), and
    /// with which leader: a conflict continues while both stay the same from step to step.
    pub conflict_step: u64,
    pub conflict_leader: u64,
    /// Entered during the measurement window: counts in the statistics (read when it leaves).
    pub measured: bool,
    /// The driving mode and regime last reported to observers (`events.rs`).
    pub(crate) reported: (ModeLabel, Option<CavMode>),
}

impl Vehicle {
    /// A CAV that is not driving manually (spec 3.1): plain car following, no relaxation.
    pub fn automated(&self) -> bool {
        self.kind == Kind::Cav
            && matches!(
                self.mode,
                Mode::Cf | Mode::Ycf { auto: true, .. } | Mode::Blc { auto: true, .. }
            )
            && self.lcs.relax == Relaxation::NONE
    }

    pub fn is_cav(&self) -> bool {
        self.kind == Kind::Cav
    }

    /// Rear bumper position.
    pub fn rear(&self) -> f64 {
        self.x - self.driver.human.length_m
    }

    /// The driving mode for the records ([`ModeLabel`]).
    pub fn mode_label(&self) -> ModeLabel {
        let auto = self.automated();
        match (self.mode, auto) {
            (Mode::Cf, false) => ModeLabel::Cf,
            (Mode::Cf, true) => ModeLabel::CfAuto,
            (Mode::Blc { .. }, false) => ModeLabel::Blc,
            (Mode::Blc { .. }, true) => ModeLabel::BlcAuto,
            (Mode::Ycf { .. }, false) => ModeLabel::Ycf,
            (Mode::Ycf { .. }, true) => ModeLabel::YcfAuto,
        }
    }
}

/// The driving mode as the trajectory records give it: the [`Mode`] variant, and whether a
/// CAV's automation is engaged ([`crate::VehicleView::automated`]; never for a human driver).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModeLabel {
    Cf,
    CfAuto,
    Blc,
    BlcAuto,
    Ycf,
    YcfAuto,
}

impl ModeLabel {
    /// `cf`, `blc` or `ycf`, with `-auto` appended while automated.
    pub fn as_str(self) -> &'static str {
        match self {
            ModeLabel::Cf => "cf",
            ModeLabel::CfAuto => "cf-auto",
            ModeLabel::Blc => "blc",
            ModeLabel::BlcAuto => "blc-auto",
            ModeLabel::Ycf => "ycf",
            ModeLabel::YcfAuto => "ycf-auto",
        }
    }

    pub fn automated(self) -> bool {
        matches!(
            self,
            ModeLabel::CfAuto | ModeLabel::BlcAuto | ModeLabel::YcfAuto
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::mem::{align_of, offset_of, size_of};

    #[test]
    fn layout_keeps_the_hot_state_together() {
        assert_eq!(align_of::<Vehicle>(), 64);
        // Line 0: what every phase reads.
        assert_eq!(offset_of!(Vehicle, x), 0);
        assert_eq!(offset_of!(Vehicle, mode) + size_of::<Mode>(), 64);
        // Line 1: the controller and the lane-change state.
        assert_eq!(offset_of!(Vehicle, cacc), 64);
        assert_eq!(offset_of!(Vehicle, lcs) + size_of::<LaneChangeState>(), 128);
        // Then the route and the driver, body length first.
        assert_eq!(offset_of!(Vehicle, route), 128);
        assert_eq!(offset_of!(Vehicle, hold_wait), 140);
        assert_eq!(offset_of!(Vehicle, driver.human.length_m), 144);
        assert_eq!(offset_of!(HumanParams, length_m), 0);
        // The bookkeeping is cold: last, after the random stream, in the padding of the last
        // line (seven lines in all, as before the fields were grouped).
        assert!(
            offset_of!(Vehicle, stats) >= offset_of!(Vehicle, driver.rng) + size_of::<Stream>()
        );
        assert_eq!(size_of::<Vehicle>(), 448);
    }
}
