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
//!                v_G = max(0, A + sqrt(A² − C))  (0 if A² − C < 0),  a_G = min(a_M, (v_G − v)/τ_r)
//! target (2.4):  a* = min(a_F, a_N, a_G)  (a_F alone without a leader)
//! smoothing:     a(t) = a(t−Δt) + (a* − a(t−Δt)) / ω
//! friction (2.7, optional): v_F' = v_adj + c_fr (v_F − v_adj)  if v_adj < v_F, else v_F
//! ```
//!
//! Cross-lane friction [P15-code] (spec 2.7) is an optional refinement: v_adj is the slower of
//! the average speeds ahead in the adjacent lanes, c_fr ∈ (0, 1] (`network.cross_lane_friction`;
//! value not published, 1 = off, the default).
//!
//! Relaxation (spec 2.5/4.6) multiplies τ, d_jam, τ_r by the factors of a [`Relax`].
//!
//! | symbol | field | default | distribution (spec 2.6) | unit |
//! |---|---|---|---|---|
//! | L | `length_m` | 4.0 | fixed | m |
//! | d_jam | `jam_gap_m` | 1.5 | N(1.5, 0.5) in [1.0, 2.0] | m |
//! | τ | `headway_s` | 1.25 | N(1.25, 0.3) in [1.05, 1.45] | s |
//! | τ_r | `reaction_s` | 1.2 | N(1.2, 0.2) in [1.0, 1.4] | s |
//! | θ | `buffer_s` | 0.10 | fixed; calibrated: steady-state capacity 2,000 veh/h/lane with d_jam in the Gipps term (spec 2.3, 2.8, 6.1; docs/calibration.md) | s |
//! | c_b | `leader_brake_factor` | 1.1 | fixed | – |
//! | a_M | `max_accel` | 1.5 | N(1.5, 0.5) in [1, 2] | m/s² |
//! | b_f | `max_decel` | −4.0 | fixed | m/s² |
//! | v_F | `desired_speed` | 110 km/h | N(110, 10) in [100, 120] km/h | m/s inside |
//! | δ | `free_exponent` | 4 | fixed | – |
//! | ω | `smoothing` | 2 | fixed | – |
//! | b_c | `comfort_decel` | −2.0 (= 0.5 b_f) | fixed | m/s² |
//! | b_e | `emergency_decel_mps2` (scenario only) | 9.0 | fixed, positive | m/s² |
//!
//! b_e bounds every acceleration the engine applies to the vehicle, whatever produced it
//! (`safety::braking_limited`); braking harder than 4 m/s² is a hard-braking episode
//! (docs/safety.md, spec 9.4).

use crate::bounded;
use crate::dist::Dist;
use crate::{Leader, Relax};
use serde::{Deserialize, Serialize};

/// One driver's human car-following parameters (already drawn). SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)] // `length_m` first: the simulator reads it with the position (vehicle.rs)
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
    /// b_e (m/s², positive): the hardest braking the vehicle can apply (docs/safety.md).
    pub emergency_decel_mps2: f64,
    /// The powertrain of human-driven vehicles (`combustion` or `electric`; energy.rs). Not
    /// written when it is the default, so that older configurations keep their identity.
    #[serde(skip_serializing_if = "crate::energy::Powertrain::is_default")]
    pub powertrain: crate::energy::Powertrain,
}

impl Default for HumanDists {
    fn default() -> Self {
        HumanDists {
            length_m: Dist::fixed(4.0),
            jam_gap_m: Dist::clamped(1.5, 0.5, 1.0, 2.0),
            headway_s: Dist::clamped(1.25, 0.3, 1.05, 1.45),
            reaction_s: Dist::clamped(1.2, 0.2, 1.0, 1.4),
            // Calibrated (spec 6.1): 3600/(τ_r + θ + 0.5) = 2,000 veh/h/lane; docs/calibration.md.
            buffer_s: 0.10,
            leader_brake_factor: 1.1,
            max_accel: Dist::clamped(1.5, 0.5, 1.0, 2.0),
            max_decel: Dist::fixed(-4.0),
            desired_speed_kmh: Dist::clamped(110.0, 10.0, 100.0, 120.0),
            free_exponent: 4.0,
            smoothing: 2.0,
            comfort_factor: 0.5,
            emergency_decel_mps2: crate::safety::DEFAULT_EMERGENCY_DECEL_MPS2,
            powertrain: crate::energy::Powertrain::Combustion,
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

/// Smallest time constant (s) used in any division (guards degenerate τ, τ_r, relax factors).
const MIN_TIME_S: f64 = 1e-3;
/// Weakest braking magnitude (m/s²) accepted for b_f and b̂ (guards b_f ≥ 0).
const MIN_BRAKE_MPS2: f64 = 1e-3;

/// The relaxed Newell parameters (τ', d_jam'), spec 2.5: τ' = φ_h τ, d_jam' = φ_j d_jam.
fn newell_params(p: &HumanParams, r: Relax) -> (f64, f64) {
    let tau = (r.headway * p.headway_s).max(MIN_TIME_S);
    let jam = r.jam * p.jam_gap_m;
    (tau, jam)
}

/// The relaxed Gipps parameters (τ_r', d_jam', θ, b_f, b̂), spec 2.3/2.5, with guards so that
/// τ_r' > 0 and b_f, b̂ < 0 even for degenerate inputs.
struct GippsParams {
    reaction: f64,
    jam: f64,
    buffer: f64,
    b_f: f64,
    b_hat: f64,
}

fn gipps_params(p: &HumanParams, r: Relax) -> GippsParams {
    let b_f = p.max_decel.min(-MIN_BRAKE_MPS2);
    GippsParams {
        reaction: (r.reaction * p.reaction_s).max(MIN_TIME_S),
        jam: r.jam * p.jam_gap_m,
        buffer: p.buffer_s.max(0.0),
        b_f,
        b_hat: (p.leader_brake_factor * b_f).min(-MIN_BRAKE_MPS2),
    }
}

/// `x` clamped to [lo, hi] without panicking when lo > hi (then `lo` wins); a NaN `x` gives
/// `hi` (then `lo` if larger). `lo` and `hi` are driver parameters, never NaN ([`bounded`]).
#[inline]
fn bound(x: f64, lo: f64, hi: f64) -> f64 {
    bounded::max(bounded::min(x, hi), lo)
}

/// Newell term a_N (spec 2.1), with relaxed τ and d_jam, clamped to [b_f, a_M].
#[inline]
pub fn newell_accel(p: &HumanParams, v: f64, gap_m: f64, r: Relax) -> f64 {
    let (tau, jam) = newell_params(p, r);
    // spec 2.1: v_N = (s − L − d_jam)/τ with s − L = g (net gap); a_N = (v_N − v)/(τ/2).
    let v_newell = (gap_m - jam) / tau;
    let a = (v_newell - v) / (0.5 * tau);
    bound(a, p.max_decel, p.max_accel)
}

/// IDM free-road term a_F (spec 2.2) toward desired speed `v_des` (m/s); when v > v_des the
/// result is bounded below by b_c (shed excess speed gently). `v_des` may differ from
/// `p.desired_speed` (lane caps, spec 2.7).
#[inline]
pub fn free_accel(p: &HumanParams, v: f64, v_des: f64) -> f64 {
    let v = v.max(0.0);
    if v_des <= 0.0 {
        // Degenerate desired speed: hold a standstill, shed any speed at b_c (spec 2.2).
        return if v > 0.0 {
            p.comfort_decel.min(0.0)
        } else {
            0.0
        };
    }
    // spec 2.2: a_F = a_M [1 − (v/v_F)^δ].
    let a = p.max_accel * (1.0 - pow_exponent(v / v_des, p.free_exponent));
    if v > v_des {
        // [P15-code]: excess speed is shed no harder than the comfortable deceleration b_c.
        bounded::max(a, p.comfort_decel)
    } else {
        a
    }
}

/// Gipps speed v_G (spec 2.3, Ciuffo form) for net gap `gap_m`, own speed `v`, leader speed
/// `v_l`. Negative radicand → 0 ("the follower must stop", [P15-code]); the result is also
/// floored at 0 because the literal formula gives v_G = A < 0 just above the radicand's root
/// and would then jump back to 0 below it (a_G would brake *less* at a smaller gap).
fn gipps_speed(g: &GippsParams, v: f64, gap_m: f64, v_l: f64) -> f64 {
    let a = g.b_f * (0.5 * g.reaction + g.buffer);
    let c = g.b_f * (2.0 * (gap_m - g.jam) - v * g.reaction - v_l * v_l / g.b_hat);
    let radicand = a * a - c;
    if radicand < 0.0 {
        0.0
    } else {
        (a + radicand.sqrt()).max(0.0)
    }
}

/// x^δ, exact and fast for the usual whole exponents (δ = 4 by default): powi instead of powf.
#[inline]
fn pow_exponent(x: f64, delta: f64) -> f64 {
    if delta == 4.0 {
        let x2 = x * x;
        x2 * x2
    } else if delta.fract() == 0.0 && delta.abs() <= 16.0 {
        x.powi(delta as i32)
    } else {
        x.powf(delta)
    }
}

/// Gipps safe-distance term a_G (spec 2.3), Ciuffo form, relaxed τ_r and d_jam; capped above
/// by a_M, not clamped below (emergency braking may exceed b_f).
#[inline]
pub fn gipps_accel(p: &HumanParams, v: f64, leader: Leader, r: Relax) -> f64 {
    let g = gipps_params(p, r);
    let v_g = gipps_speed(&g, v, leader.gap_m, leader.v_mps.max(0.0));
    // spec 2.3: a_G = (v_G − v)/τ_r, capped above by a_M only.
    bounded::min((v_g - v) / g.reaction, p.max_accel)
}

/// The Gipps speed v_G (spec 2.3) behind `leader` as a collision-free speed: the largest speed
/// from which, after τ_r + θ, braking at b_f stops the driver behind a leader braking at b̂
/// (Gipps 1981). The bound of a commanded acceleration (`commanded`) for a human driver.
#[inline]
pub fn gipps_safe_speed(p: &HumanParams, v: f64, leader: Leader, r: Relax) -> f64 {
    let g = gipps_params(p, r);
    gipps_speed(&g, v, leader.gap_m, leader.v_mps.max(0.0))
}

/// Target acceleration a* = min(a_F, a_N, a_G) (spec 2.4); a_F alone without a leader.
#[inline]
pub fn target_accel(p: &HumanParams, v: f64, v_des: f64, leader: Option<Leader>, r: Relax) -> f64 {
    let a_free = free_accel(p, v, v_des);
    match leader {
        None => a_free,
        // Both terms are bounded by parameters, so never NaN ([`bounded`]).
        Some(l) => bounded::min(
            bounded::min(a_free, newell_accel(p, v, l.gap_m, r)),
            gipps_accel(p, v, l, r),
        ),
    }
}

/// Acceleration smoothing (spec 2.4): a_prev + (a_target − a_prev)/ω.
#[inline]
pub fn smooth_accel(a_prev: f64, a_target: f64, smoothing: f64) -> f64 {
    // ω ≥ 1 (spec 2.4); anything smaller (or NaN) is treated as ω = 1 (no smoothing).
    let omega = smoothing.max(1.0);
    let d = a_target - a_prev;
    // ω = 2 (the default): halving is exact, so d · 0.5 is bit for bit d / 2, without the
    // division's latency.
    a_prev + if omega == 2.0 { d * 0.5 } else { d / omega }
}

/// Cross-lane friction (spec 2.7, [P15-code]): the desired speed of a driver whose slower
/// adjacent lane runs at `v_adj` (the average speed ahead there) below its own desired speed
/// `v_f`: v_adj + c_fr (v_f − v_adj). At or above v_f, or with c_fr = 1, it is v_f itself.
/// The result lies in [v_adj, v_f] for c_fr ∈ [0, 1].
#[inline]
pub fn friction_desired_speed(v_f: f64, v_adj: f64, c_fr: f64) -> f64 {
    if v_adj < v_f {
        v_adj + c_fr * (v_f - v_adj)
    } else {
        v_f
    }
}

/// Steady-state (equilibrium) net gap at speed v (leader at the same speed): the smallest gap g
/// for which both the Newell and the Gipps terms allow holding speed v, i.e.
/// max(d_jam' + τ' v, g_Gipps(v)) with the relaxed parameters. Used for insertion and the
/// capacity checks of spec 2.8.
///
/// Gipps closed form (spec 2.3 with v_l = v): v_G ≥ v ⇔ A² − C ≥ (v − A)² (v − A > 0 since
/// A < 0) ⇔ g ≥ g_Gipps(v) = d_jam' + (τ_r' + θ) v + ½ v² (1/b̂ − 1/b_f).
///
/// Note: the capacity table of spec 2.8 (2,027 veh/h at θ = 0.15 s) is reproduced only if
/// d_jam is left out of g_Gipps; with d_jam inside C as spec 2.3 writes it, the maximum
/// steady-state flow of the mean driver is about 1,946 veh/h (tests document both).
pub fn equilibrium_gap(p: &HumanParams, v: f64, r: Relax) -> f64 {
    let v = v.max(0.0);
    let (tau, jam_n) = newell_params(p, r);
    let g = gipps_params(p, r);
    let newell = jam_n + tau * v;
    let gipps = g.jam + (g.reaction + g.buffer) * v + 0.5 * v * v * (1.0 / g.b_hat - 1.0 / g.b_f);
    newell.max(gipps)
}
