//! # platoonsim-model: the driving laws, as pure functions
//!
//! Every function here is a pure function of small `Copy` inputs (speeds, gaps,
//! parameters); nothing reads the world. The engine (`platoonsim-sim`) assembles
//! the inputs. Section numbers ("spec 2.3") refer to `shared/docs/model-spec.md`.
//!
//! | module | what | spec |
//! |---|---|---|
//! | [`dist`] | truncated-normal per-driver parameter distributions | 1, 2.6 |
//! | [`human`] | human car following: min(Newell, IDM free term, Gipps), smoothing | 2 |
//! | [`cav`] | CAV control: speed regulation, ACC, CACC, safety override, limits | 3 |
//! | [`lanechange`] | lane-change desire, anticipated-minimum-gap acceptance, relaxation | 4 |
//!
//! Conventions: SI units inside (m, s, m/s, m/s²); decelerations are negative
//! numbers (`max_decel = -4.0`); gaps are *net* gaps (leader's rear bumper to the
//! subject's front bumper), i.e. spec's `s - L`.

pub mod cav;
pub mod dist;
pub mod human;
pub mod lanechange;

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
