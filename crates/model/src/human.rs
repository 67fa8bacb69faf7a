//! Human-driven car following (spec 2): the minimum of the Newell, IDM free-road and
//! Gipps terms, with first-order acceleration smoothing.
//!
//! Paper: Woo & Skabardonis (seed) Table "Microscopic Driving Parameters"; model of
//! Liu et al. (2018) as documented by the PATH 2015 Aimsun plug-in ([P15-doc]/[P15-code]).
//! Equations (spec 2.1-2.4), g = net gap, v own speed, v_l leader speed:
//!
//! ```text
//! Newell (2.1):  a_N = ((g − d_jam)/τ − v) / (τ/2),           clamped to [b_f, a_M]
//! IDM free (2.2): a_F = a_M [1 − (v/v_F)^δ],                   bounded below by b_c when v > v_F
//! Gipps (2.3):   A = b_f (τ_r/2 + θ),  b̂ = c_b b_f,
//!                C = b_f [2(g − d_jam) − v τ_r − v_l²/b̂],
//!                v_G = A + sqrt(A² − C)  (0 if A² − C < 0),  a_G = min(a_M, (v_G − v)/τ_r)
//! target (2.4):  a* = min(a_F, a_N, a_G)  (a_F alone without a leader)
//! smoothing:     a(t) = a(t−Δt) + (a* − a(t−Δt)) / ω
//! ```
//!
//! Relaxation (spec 2.5/4.6) multiplies τ, d_jam, τ_r by the factors of a [`Relax`].
//!
//! | symbol | field | default | distribution (spec 2.6) | unit |
//! |---|---|---|---|---|
//! | L | `length_m` | 4.0 | fixed | m |
//! | d_jam | `jam_gap_m` | 1.5 | N(1.5, 0.5) in [1.0, 2.0] | m |
//! | τ | `headway_s` | 1.25 | N(1.25, 0.3) in [1.05, 1.45] | s |
//! | τ_r | `reaction_s` | 1.2 | N(1.2, 0.2) in [1.0, 1.4] | s |
//! | θ | `buffer_s` | 0.15 | fixed (calibration knob, spec 2.8) | s |
//! | c_b | `leader_brake_factor` | 1.1 | fixed | – |
//! | a_M | `max_accel` | 1.5 | N(1.5, 0.5) in [1, 2] | m/s² |
//! | b_f | `max_decel` | −4.0 | fixed | m/s² |
//! | v_F | `desired_speed` | 110 km/h | N(110, 10) in [100, 120] km/h | m/s inside |
//! | δ | `free_exponent` | 4 | fixed | – |
//! | ω | `smoothing` | 2 | fixed | – |
//! | b_c | `comfort_decel` | −2.0 (= 0.5 b_f) | fixed | m/s² |

use crate::dist::Dist;
use crate::{Leader, Relax};
use serde::{Deserialize, Serialize};

/// One driver's human car-following parameters (already drawn). SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HumanParams {
    /// Own vehicle length L (m).
    pub length_m: f64,
    /// Jam gap d_jam (m).
    pub jam_gap_m: f64,
    /// Newell headway τ (s).
    pub headway_s: f64,
    /// Reaction time τ_r of the Gipps term (s).
    pub reaction_s: f64,
    /// Gipps safety buffer θ (s).
    pub buffer_s: f64,
    /// c_b: the follower assumes the leader may brake at c_b·b_f.
    pub leader_brake_factor: f64,
    /// a_M > 0 (m/s²).
    pub max_accel: f64,
    /// b_f < 0 (m/s²).
    pub max_decel: f64,
    /// v_F, maximum desired speed (m/s).
    pub desired_speed: f64,
    /// δ, IDM free-road exponent.
    pub free_exponent: f64,
    /// ω ≥ 1, acceleration smoothing factor.
    pub smoothing: f64,
    /// b_c < 0, comfortable deceleration (m/s²).
    pub comfort_decel: f64,
}

impl Default for HumanParams {
    /// The spec 2.6 means (desired speed 110 km/h).
    fn default() -> Self {
        HumanDists::default().mean()
    }
}

/// Scenario-level distributions of the human parameters (spec 2.6). Desired speed in km/h
/// (the field's convention); everything else SI.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct HumanDists {
    pub length_m: Dist,
    pub jam_gap_m: Dist,
    pub headway_s: Dist,
    pub reaction_s: Dist,
    pub buffer_s: f64,
    pub leader_brake_factor: f64,
    pub max_accel: Dist,
    pub max_decel: Dist,
    pub desired_speed_kmh: Dist,
    pub free_exponent: f64,
    pub smoothing: f64,
    /// b_c as a fraction of b_f (b̂_c, spec 4.9): b_c = comfort_factor · b_f.
    pub comfort_factor: f64,
}

impl Default for HumanDists {
    fn default() -> Self {
        HumanDists {
            length_m: Dist::fixed(4.0),
            jam_gap_m: Dist::clamped(1.5, 0.5, 1.0, 2.0),
            headway_s: Dist::clamped(1.25, 0.3, 1.05, 1.45),
            reaction_s: Dist::clamped(1.2, 0.2, 1.0, 1.4),
            buffer_s: 0.15,
            leader_brake_factor: 1.1,
            max_accel: Dist::clamped(1.5, 0.5, 1.0, 2.0),
            max_decel: Dist::fixed(-4.0),
            desired_speed_kmh: Dist::clamped(110.0, 10.0, 100.0, 120.0),
            free_exponent: 4.0,
            smoothing: 2.0,
            comfort_factor: 0.5,
        }
    }
}

/// Number of standard-normal deviates [`HumanDists::sample`] consumes.
pub const HUMAN_DRAWS: usize = 6;

impl HumanDists {
    /// Draw one driver. `z` holds standard-normal deviates in this fixed order:
    /// length, jam gap, headway, reaction, max accel, max decel… see [`HUMAN_DRAWS`]; the
    /// desired speed is drawn separately by the caller through [`HumanDists::desired_speed_mps`]
    /// so that a scenario can override it per lane or road.
    pub fn sample(&self, z: &[f64; HUMAN_DRAWS], desired_speed_mps: f64) -> HumanParams {
        let max_decel = self.max_decel.sample(z[5]);
        HumanParams {
            length_m: self.length_m.sample(z[0]),
            jam_gap_m: self.jam_gap_m.sample(z[1]),
            headway_s: self.headway_s.sample(z[2]),
            reaction_s: self.reaction_s.sample(z[3]),
            buffer_s: self.buffer_s,
            leader_brake_factor: self.leader_brake_factor,
            max_accel: self.max_accel.sample(z[4]),
            max_decel,
            desired_speed: desired_speed_mps,
            free_exponent: self.free_exponent,
            smoothing: self.smoothing,
            comfort_decel: self.comfort_factor * max_decel,
        }
    }

    /// Desired speed (m/s) for a standard-normal deviate.
    pub fn desired_speed_mps(&self, z: f64) -> f64 {
        self.desired_speed_kmh.sample(z) / 3.6
    }

    /// The parameters at every distribution's mean.
    pub fn mean(&self) -> HumanParams {
        let max_decel = self.max_decel.mean;
        HumanParams {
            length_m: self.length_m.mean,
            jam_gap_m: self.jam_gap_m.mean,
            headway_s: self.headway_s.mean,
            reaction_s: self.reaction_s.mean,
            buffer_s: self.buffer_s,
            leader_brake_factor: self.leader_brake_factor,
            max_accel: self.max_accel.mean,
            max_decel,
            desired_speed: self.desired_speed_kmh.mean / 3.6,
            free_exponent: self.free_exponent,
            smoothing: self.smoothing,
            comfort_decel: self.comfort_factor * max_decel,
        }
    }
}

/// Newell term a_N (spec 2.1), with relaxed τ and d_jam, clamped to [b_f, a_M].
pub fn newell_accel(p: &HumanParams, v: f64, gap_m: f64, r: Relax) -> f64 {
    let _ = (p, v, gap_m, r);
    todo!("spec 2.1")
}

/// IDM free-road term a_F (spec 2.2) toward desired speed `v_des` (m/s); when v > v_des the
/// result is bounded below by b_c (shed excess speed gently). `v_des` may differ from
/// `p.desired_speed` (lane caps, spec 2.7).
pub fn free_accel(p: &HumanParams, v: f64, v_des: f64) -> f64 {
    let _ = (p, v, v_des);
    todo!("spec 2.2")
}

/// Gipps safe-distance term a_G (spec 2.3), Ciuffo form, relaxed τ_r and d_jam; capped above
/// by a_M, not clamped below (emergency braking may exceed b_f).
pub fn gipps_accel(p: &HumanParams, v: f64, leader: Leader, r: Relax) -> f64 {
    let _ = (p, v, leader, r);
    todo!("spec 2.3")
}

/// Target acceleration a* = min(a_F, a_N, a_G) (spec 2.4); a_F alone without a leader.
pub fn target_accel(p: &HumanParams, v: f64, v_des: f64, leader: Option<Leader>, r: Relax) -> f64 {
    let _ = (p, v, v_des, leader, r);
    todo!("spec 2.4")
}

/// Acceleration smoothing (spec 2.4): a_prev + (a_target − a_prev)/ω.
pub fn smooth_accel(a_prev: f64, a_target: f64, smoothing: f64) -> f64 {
    let _ = (a_prev, a_target, smoothing);
    todo!("spec 2.4")
}

/// Steady-state (equilibrium) net gap at speed v (leader at the same speed): the smallest gap g
/// for which both the Newell and the Gipps terms allow holding speed v, i.e.
/// max(d_jam' + τ' v, g_Gipps(v)) with the relaxed parameters. Used for insertion and the
/// capacity checks of spec 2.8.
pub fn equilibrium_gap(p: &HumanParams, v: f64, r: Relax) -> f64 {
    let _ = (p, v, r);
    todo!("spec 2.8")
}
