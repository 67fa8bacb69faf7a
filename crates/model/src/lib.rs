//! # platoonsim-model: the driving laws, as pure functions
//!
//! Every function here is a pure function of small `Copy` inputs (speeds, gaps,
//! parameters); nothing reads the world. The engine (`platoonsim-sim`) assembles
//! the inputs. Section numbers ("spec 2.3") refer to the project's model reference,
//! `docs/model-reference.md`: "spec 2.3" is its section 2.3.
//!
//! | module | what | spec |
//! |---|---|---|
//! | [`dist`] | truncated-normal per-driver parameter distributions | 1, 2.6 |
//! | [`human`] | human car following: min(Newell, IDM free term, Gipps), smoothing | 2 |
//! | [`cav`] | CAV control: speed regulation, ACC, CACC, safety override, limits | 3 |
//! | [`lanechange`] | lane-change desire, anticipated-minimum-gap acceptance, relaxation | 4 |
//! | [`safegap`] | the safe-deceleration constraint on lag and lead gaps (an extension) | 9.1 |
//! | [`cooperative`] | cooperative lane changes of automated CAVs (request, gap opening, safe join) | 9.2 |
//! | [`driver`] | the lane-change decision procedure, rule by rule | 4.2, 4.3, 4.7 |
//! | [`safety`] | emergency braking limit, time to collision, TET/TIT exposure | docs/safety.md |
//! | [`commanded`] | an outside controller's acceleration within the limits and the safe speed | 2.3, 3.4 |
//! | [`energy`] | fuel (VT-CPFM-1), battery-electric energy, platoon drag reduction | docs/energy.md |
//! | [`meter`] | ramp metering: one car per green, ALINEA, queue override | docs/network-scenarios.md |
//!
//! Conventions: SI units inside (m, s, m/s, m/s²); decelerations are negative
//! numbers (`max_decel = -4.0`); gaps are *net* gaps (leader's rear bumper to the
//! subject's front bumper), i.e. spec's `s - L`.

pub mod cav;
pub mod commanded;
pub mod cooperative;
pub mod dist;
pub mod driver;
pub mod energy;
pub mod human;
pub mod lanechange;
pub mod meter;
pub mod safegap;
pub mod safety;

/// What a follower knows about its leader: the net gap and the leader's speed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Leader {
    /// Net gap, leader's rear bumper to the subject's front bumper (m). May be negative only
    /// after a collision, which the engine counts and reports.
    pub gap_m: f64,
    /// Leader speed (m/s).
    pub v_mps: f64,
}

/// Multiplicative relaxation of the human car-following parameters (spec 2.5, 4.6).
/// `Relax::NONE` (all 1.0) is normal car following.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Relax {
    /// Factor on the Newell headway τ (φ_h while fully relaxed).
    pub headway: f64,
    /// Factor on the jam gap d_jam (φ_j).
    pub jam: f64,
    /// Factor on the reaction time τ_r (φ_r).
    pub reaction: f64,
}

impl Relax {
    /// No relaxation.
    pub const NONE: Relax = Relax {
        headway: 1.0,
        jam: 1.0,
        reaction: 1.0,
    };
}

/// `f64::min`/`f64::max` against a bound that is never NaN, as one `minsd`/`maxsd`.
///
/// `f64::min(x, b)` must return the other operand when either one is NaN; with two operands
/// that may both be NaN the compiler emits a comparison, a NaN test and a blend (four to five
/// instructions with a dependency chain) instead of the one instruction of a plain comparison.
/// These helpers give the same result as `x.min(b)` / `x.max(b)` for every `x`, NaN included
/// (a NaN `x` gives `b`), provided `b` is not NaN: a driver parameter (validated finite), or a
/// value that is itself such a bound. The only other difference is the sign of a zero result
/// when `x` and `b` are zeros of opposite sign (`f64::min` leaves that unspecified).
pub mod bounded {
    /// `x.min(b)` for a `b` that is never NaN (see the module).
    #[inline(always)]
    pub fn min(x: f64, b: f64) -> f64 {
        if x < b {
            x
        } else {
            b
        }
    }

    /// `x.max(b)` for a `b` that is never NaN (see the module).
    #[inline(always)]
    pub fn max(x: f64, b: f64) -> f64 {
        if x > b {
            x
        } else {
            b
        }
    }
}

/// Unit conversion helpers.
pub mod units {
    /// km/h to m/s.
    pub fn kmh_to_mps(kmh: f64) -> f64 {
        kmh / 3.6
    }
    /// m/s to km/h.
    pub fn mps_to_kmh(mps: f64) -> f64 {
        mps * 3.6
    }
}
