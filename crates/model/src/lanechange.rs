//! Lane changing (spec 4): desire (mandatory, discretionary), anticipated-minimum-gap
//! acceptance, relaxation. The state machine (BLC, yielding, execution) lives in the engine;
//! this module holds the pure decision formulas.
//!
//! Model: PATH / Yeo et al. (2008) lane-change model as documented in [P15-doc]/[P15-code],
//! used by Liu et al. (2018) and the seed paper (calibrated in Kan et al. 2019).
//!
//! ```text
//! mandatory (4.2): γ_m = 0 if d_e ≥ N E and t_e ≥ N T;  1 if d_e ≤ E_min or t_e ≤ T_min;
//!                  else clamp(max(1 − (d_e − E_min)/(N(E − E_min)), 1 − (t_e − T_min)/(N(T − T_min))), 0, 1)
//! discretionary:   v_ref = max(v̄_0, 2.3 m/s);  γ_d = min(1, max(0, (v_ant − v_ref)/v_ref)) · η_dir
//!                  η_dir = 1 (left), η_r = 0.7 (right)
//! combination:     mandatory side: γ = γ_m + κ γ_d (same side), κ = 0.8; otherwise max over sides
//! gap test (4.3):  t* = max(0, −Δv/Δa); g_min = g0 + Δv t* + ½ Δa t*² if Δa > 0 and
//!                  (b_ℓ* ≥ 0 or −v_ℓ/b_ℓ* > t*); else t_f = −v_f/b_f, g_min = g0 + min(0, Δv t_f + ½ Δa t_f²)
//!                  accept iff g0 > d_jam' and g_min − v_f (τ_r' + θ) − d_jam' > 0
//!                  lead gap: b_ℓ* = σ_f c_b b;  lag gap: b_ℓ* = max(a_ant, σ_b c_b b)
//! relaxation (4.6): φ_x(t) = φ_x + (1 − φ_x) · t / t_s  for 0 ≤ t ≤ t_s, then 1
//! ```
//!
//! | symbol | field | default | distribution | unit |
//! |---|---|---|---|---|
//! | E | `mandatory_distance_m` | 300 | N(300, 50) in [250, 400] | m |
//! | T | `mandatory_time_s` | 30 | N(30, 20) in [20, 60] | s |
//! | E_min, T_min | `mandatory_min_distance_m`, `mandatory_min_time_s` | 50, 3 | fixed | m, s |
//! | η_r | `right_discount` | 0.7 | fixed | – |
//! | κ | `mandatory_weight` | 0.8 | fixed | – |
//! | ε | `threshold` | 0.25 | N(0.25, 0.2) in [0.1, 0.5] (floor lowered from 0.2: docs/calibration.md) | – |
//! | σ_f, σ_b | `sigma_forward`, `sigma_backward` | 0.6, 0.75 | fixed | – |
//! | φ_h, φ_j, φ_r | `relax_headway`, `relax_jam`, `relax_reaction` | 0.4, 0.6, 0.5 | fixed; φ_r calibrated between [P15-doc] 0.2 and [P15-code] 1.0 (spec 6.19, docs/calibration.md) | – |
//! | t_s | `relax_time_s` | 8 | fixed | s |
//! | ζ | `cooperativeness` | 0.8 | N(0.8, 0.2) in [0.5, 0.9] | – |
//! | – | `discretionary_coop_factor` | 0.5 | fixed | – |
//! | d_scan, n_scan | `scan_distance_m`, `scan_vehicles` | 50, 5 | fixed | m, veh |
//! | t_min,LC | `min_interval_s` | 5 | fixed (×`return_factor` = 3 back) | s |
//! | – | `slow_down_desire` | 0.5 | fixed | – |
//! | w_CAV | `cav_weight_leader`, `cav_weight_follower` | 0.5, 0 | fixed | – |
//! | – | `follower_anticipates` | true | a platoon follower upstream of a busy on-ramp uses `cav_weight_leader` \[D\] | – |
//! | – | `yield_range_m` | 100 | fixed; farthest yield requester (rear ahead of the driver's front) \[D\] | m |
//! | v_ref floor | `min_reference_speed_mps` | 2.3 | fixed | m/s |
//! | – | `min_speed_gain_mps` | 2.34 (5 mph) | fixed; γ_d = 0 below this gain ([P15-doc] gate) | m/s |
//! | – | `gap_rule` | safe | `safe` (spec 9.1) or `published` (spec 4.3 alone) | – |
//! | b_safe | `safe_follower_decel_mps2` | 3.0 | fixed; MOBIL b_safe (spec 9.1) | m/s² (positive) |
//! | b_safe,m | `mandatory_safe_decel_mps2` | 4.0 | fixed; mandatory change with γ ≥ 1 (spec 9.1) | m/s² (positive) |

use crate::dist::Dist;
use crate::human::HumanParams;
use crate::Relax;
use serde::{Deserialize, Serialize};

/// Which side a lane change goes to. Lanes are numbered from the right (0 = rightmost), so
/// `Left` is lane + 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Side {
    Left,
    Right,
}

/// One driver's lane-change parameters (already drawn).
///
/// In C order, those read in most steps first (the simulator keeps them in the cache lines it
/// reads anyway: the engine's `Vehicle` layout), those of lane changes and mandatory desires
/// after them.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct LaneChangeParams {
    pub min_speed_gain_mps: f64,
    pub min_reference_speed_mps: f64,
    pub right_discount: f64,
    pub threshold: f64,
    pub min_interval_s: f64,
    pub return_factor: f64,
    pub relax_time_s: f64,
    pub relax_jam: f64,
    pub mandatory_weight: f64,
    pub cooperativeness: f64,
    pub relax_headway: f64,
    pub relax_reaction: f64,
    pub mandatory_distance_m: f64,
    pub mandatory_time_s: f64,
    pub mandatory_min_distance_m: f64,
    pub mandatory_min_time_s: f64,
    pub discretionary_coop_factor: f64,
    pub sigma_forward: f64,
    pub sigma_backward: f64,
    pub slow_down_desire: f64,
}

/// Scenario-level lane-change parameters with per-driver distributions (spec 4.9).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LaneChangeDists {
    pub mandatory_distance_m: Dist,
    pub mandatory_time_s: Dist,
    pub mandatory_min_distance_m: f64,
    pub mandatory_min_time_s: f64,
    pub right_discount: f64,
    pub mandatory_weight: f64,
    pub threshold: Dist,
    pub sigma_forward: f64,
    pub sigma_backward: f64,
    pub relax_headway: f64,
    pub relax_jam: f64,
    pub relax_reaction: f64,
    pub relax_time_s: f64,
    pub cooperativeness: Dist,
    pub discretionary_coop_factor: f64,
    pub scan_distance_m: f64,
    pub scan_vehicles: u32,
    pub min_interval_s: f64,
    pub return_factor: f64,
    pub slow_down_desire: f64,
    pub min_reference_speed_mps: f64,
    /// Smallest absolute speed gain v_ant − v̄_0 that creates a discretionary desire (m/s).
    pub min_speed_gain_mps: f64,
    pub cav_weight_leader: f64,
    pub cav_weight_follower: f64,
    /// A platoon follower in the anticipation range of a busy on-ramp (spec 4.2
    /// "Anticipatory") weighs its discretionary desire with `cav_weight_leader` instead of
    /// `cav_weight_follower` \[D\]. No effect on a road without on-ramps.
    pub follower_anticipates: bool,
    /// No lane changes within this distance of an entrance ("forbid zone", spec 4.1) (m).
    pub forbid_zone_m: f64,
    /// Anticipation of on-ramps (spec 4.2 "Anticipatory"): range upstream of a ramp's merge
    /// point within which drivers in the two rightmost lanes react to it (m).
    pub anticipation_distance_m: f64,
    /// c_inc, strength of the on-ramp anticipation (spec 4.2, 4.9) (-).
    pub anticipation_strength: f64,
    /// E_exit: no discretionary change within this distance of the driver's exit (m).
    pub exit_no_change_m: f64,
    /// η_e penalty on a discretionary change away from the exit lane (-), applied within
    /// `anticipation_distance_m` of the exit.
    pub exit_lane_penalty: f64,
    /// A driver answers a yield request only from a requester whose rear is at most this far
    /// ahead of its front (spec 4.5 "immediate leaders in the adjacent lanes"; \[D\]) (m).
    pub yield_range_m: f64,
    /// The gap-acceptance rule: `safe` (spec 4.3 and the safe decelerations of spec 9.1, the
    /// default) or `published` (spec 4.3 alone).
    pub gap_rule: crate::safegap::GapRule,
    /// b_safe (m/s², positive): under the safe rule no change may make the new follower, or
    /// the changer behind its new leader, brake harder than this by its own law (spec 9.1).
    pub safe_follower_decel_mps2: f64,
    /// b_safe,m (m/s², positive): the bound for a mandatory change whose desire has reached 1
    /// (spec 9.1).
    pub mandatory_safe_decel_mps2: f64,
}

impl Default for LaneChangeDists {
    fn default() -> Self {
        LaneChangeDists {
            mandatory_distance_m: Dist::clamped(300.0, 50.0, 250.0, 400.0),
            mandatory_time_s: Dist::clamped(30.0, 20.0, 20.0, 60.0),
            mandatory_min_distance_m: 50.0,
            mandatory_min_time_s: 3.0,
            right_discount: 0.7,
            mandatory_weight: 0.8,
            // [P15-doc] mean and sd; floor 0.1 instead of 0.2 (calibration, spec 6.19; docs/calibration.md).
            threshold: Dist::clamped(0.25, 0.2, 0.1, 0.5),
            sigma_forward: 0.6,
            sigma_backward: 0.75,
            relax_headway: 0.4,
            relax_jam: 0.6,
            // spec 6.19: between [P15-doc] (0.2) and [P15-code] (1.0); calibrated on the seed's
            // Table 3 lane-change rates (docs/calibration.md).
            relax_reaction: 0.5,
            relax_time_s: 8.0,
            cooperativeness: Dist::clamped(0.8, 0.2, 0.5, 0.9),
            discretionary_coop_factor: 0.5,
            scan_distance_m: 50.0,
            scan_vehicles: 5,
            min_interval_s: 5.0,
            return_factor: 3.0,
            slow_down_desire: 0.5,
            min_reference_speed_mps: 2.3,
            min_speed_gain_mps: 2.34,
            cav_weight_leader: 0.5,
            cav_weight_follower: 0.0,
            follower_anticipates: true,
            forbid_zone_m: 100.0,
            anticipation_distance_m: 2000.0,
            anticipation_strength: 1.0,
            exit_no_change_m: 300.0,
            exit_lane_penalty: 0.5,
            yield_range_m: 100.0,
            gap_rule: crate::safegap::GapRule::Safe,
            // spec 9.1: MOBIL's b_safe (Kesting et al. 2007) kept below b_f = 4 m/s².
            safe_follower_decel_mps2: 3.0,
            mandatory_safe_decel_mps2: 4.0,
        }
    }
}

/// Number of standard-normal deviates [`LaneChangeDists::sample`] consumes.
pub const LC_DRAWS: usize = 4;

impl LaneChangeDists {
    /// Draw one driver: z = [E, T, threshold, cooperativeness].
    pub fn sample(&self, z: &[f64; LC_DRAWS]) -> LaneChangeParams {
        LaneChangeParams {
            mandatory_distance_m: self.mandatory_distance_m.sample(z[0]),
            mandatory_time_s: self.mandatory_time_s.sample(z[1]),
            mandatory_min_distance_m: self.mandatory_min_distance_m,
            mandatory_min_time_s: self.mandatory_min_time_s,
            right_discount: self.right_discount,
            mandatory_weight: self.mandatory_weight,
            threshold: self.threshold.sample(z[2]),
            sigma_forward: self.sigma_forward,
            sigma_backward: self.sigma_backward,
            relax_headway: self.relax_headway,
            relax_jam: self.relax_jam,
            relax_reaction: self.relax_reaction,
            relax_time_s: self.relax_time_s,
            cooperativeness: self.cooperativeness.sample(z[3]),
            discretionary_coop_factor: self.discretionary_coop_factor,
            min_interval_s: self.min_interval_s,
            return_factor: self.return_factor,
            slow_down_desire: self.slow_down_desire,
            min_reference_speed_mps: self.min_reference_speed_mps,
            min_speed_gain_mps: self.min_speed_gain_mps,
        }
    }

    /// Parameters at every distribution's mean.
    pub fn mean(&self) -> LaneChangeParams {
        self.sample(&[0.0; LC_DRAWS])
    }
}

impl Default for LaneChangeParams {
    fn default() -> Self {
        LaneChangeDists::default().mean()
    }
}

/// Mandatory desire γ_m (spec 4.2) at distance `d_e_m` to the last point for the change, own
/// speed `v` (t_e = d_e / v; v = 0 gives t_e = ∞), `n` changes still needed (n = 0 → 0).
///
/// Uses the [P15-code] form that falls with distance (spec 4.2 notes that the middle case
/// printed in [P15-doc] rises with distance). The cases are tested in the spec's order: first
/// "far away in both distance and time" → 0, then "within E_min or T_min" → 1, otherwise the
/// larger of the distance and time terms, clamped to [0, 1]. A negative `d_e_m` (the point
/// has been passed) gives 1.
#[inline]
pub fn mandatory_desire(p: &LaneChangeParams, d_e_m: f64, v: f64, n: u32) -> f64 {
    if n == 0 {
        return 0.0;
    }
    let n = f64::from(n);
    // spec 4.2: t_e = d_e / v; a standing vehicle has all the time in the world.
    let t_e = if v > 0.0 { d_e_m / v } else { f64::INFINITY };
    let (e, t) = (p.mandatory_distance_m, p.mandatory_time_s);
    let (e_min, t_min) = (p.mandatory_min_distance_m, p.mandatory_min_time_s);
    if d_e_m >= n * e && t_e >= n * t {
        return 0.0;
    }
    if d_e_m <= e_min || t_e <= t_min {
        return 1.0;
    }
    // Here d_e > E_min and t_e > T_min, so both numerators are > 0: a zero denominator
    // (E = E_min or T = T_min) gives −∞ for that term, never NaN; t_e = ∞ likewise.
    let by_distance = 1.0 - (d_e_m - e_min) / (n * (e - e_min));
    let by_time = 1.0 - (t_e - t_min) / (n * (t - t_min));
    by_distance.max(by_time).clamp(0.0, 1.0)
}

/// Discretionary desire γ_d toward `side` (spec 4.2, [P15-code] Oct 2015 form): `v_ant` the
/// anticipated speed in the target lane, `v_cur` the average speed ahead in the current lane.
/// Includes η_dir (1 left, `right_discount` right). In [0, 1].
///
/// v_ref = max(v_cur, `min_reference_speed_mps`); γ_d = min(1, max(0, (v_ant − v_ref)/v_ref))·η.
/// The floor on v_ref keeps the relative gain finite in a jam; if the floor is configured
/// to 0 and v_cur ≤ 0, any positive v_ant counts as the full gain 1.
#[inline]
pub fn discretionary_desire(p: &LaneChangeParams, v_ant: f64, v_cur: f64, side: Side) -> f64 {
    let eta = match side {
        Side::Left => 1.0,
        Side::Right => p.right_discount,
    };
    // [P15-doc]: no discretionary desire below an absolute speed gain (the code's commented
    // 2.34 m/s = 5 mph); keeps drivers in slow queues from chasing small lane-speed noise.
    if v_ant - v_cur < p.min_speed_gain_mps {
        return 0.0;
    }
    let v_ref = v_cur.max(p.min_reference_speed_mps);
    let gain = if v_ref > 0.0 {
        ((v_ant - v_ref) / v_ref).clamp(0.0, 1.0)
    } else if v_ant > v_ref {
        1.0
    } else {
        0.0
    };
    gain * eta
}

/// Closest approach g_min of a leader/follower pair while both brake (spec 4.3): initial net
/// gap `g0`, leader speed `v_l` braking at `b_l` (assumed rate, ≤ 0 or ≥ 0), follower speed
/// `v_f` braking at `b_f` < 0.
///
/// With Δv = v_l − v_f, Δa = b_l − b_f and t* = max(0, −Δv/Δa):
/// * if Δa > 0 and the leader is still moving at t* (b_l ≥ 0, or −v_l/b_l > t*), the gap is
///   smallest when the relative speed vanishes: g_min = g0 + Δv t* + ½Δa t*²
///   (= g0 − Δv²/(2Δa) when Δv < 0, g0 otherwise);
/// * otherwise the gap is evaluated when the follower stops, t_f = −v_f/b_f:
///   g_min = g0 + min(0, Δv t_f + ½Δa t_f²). As in spec 4.3 the leader's motion is
///   extrapolated with the constant rate b_l also after it would have stopped, which can only
///   make g_min smaller (conservative).
///
/// Outside the model's precondition b_f < 0 (a follower that does not brake) the result is
/// still defined and never NaN: g0 if the follower can never close in (it stands still, or
/// both keep a constant relative speed Δv ≥ 0), −∞ if it never stops and the extrapolated
/// gap is unbounded below.
pub fn min_gap_while_braking(g0: f64, v_l: f64, b_l: f64, v_f: f64, b_f: f64) -> f64 {
    let dv = v_l - v_f;
    let da = b_l - b_f;
    if da > 0.0 {
        // Closest approach of the two constant-deceleration parabolas (spec 4.3, first case).
        let t_star = if dv < 0.0 { -dv / da } else { 0.0 };
        let leader_moving_at_t_star = b_l >= 0.0 || -v_l / b_l > t_star;
        if leader_moving_at_t_star {
            // Closed form of g0 + Δv t* + ½Δa t*²; avoids ∞ − ∞ when Δa is tiny.
            return if dv < 0.0 {
                g0 - dv * dv / (2.0 * da)
            } else {
                g0
            };
        }
    }
    // Second case of spec 4.3: evaluate at the follower's stopping time.
    if v_f <= 0.0 && b_f <= 0.0 {
        // t_f = 0: a standing follower (that does not accelerate) cannot close in.
        return g0;
    }
    let t_f = if b_f < 0.0 { -v_f / b_f } else { f64::INFINITY };
    if !t_f.is_finite() {
        // The follower never stops (b_f ≥ 0, outside the model): the gap stays bounded only
        // if the relative speed stays constant and non-negative.
        return if da == 0.0 && dv >= 0.0 {
            g0
        } else {
            f64::NEG_INFINITY
        };
    }
    // Δv t_f + ½Δa t_f², factored so that a huge t_f with Δa = 0 cannot produce ∞ · 0.
    let change = t_f * (dv + 0.5 * da * t_f);
    g0 + change.min(0.0)
}

/// The relaxed parameter factors used in gap acceptance (fully relaxed: φ_h, φ_j, φ_r).
pub fn gap_relax(p: &LaneChangeParams) -> Relax {
    Relax {
        headway: p.relax_headway,
        jam: p.relax_jam,
        reaction: p.relax_reaction,
    }
}

/// The acceptance criterion of spec 4.3 shared by the lead and lag tests: g0 > d_jam' and
/// g_min − v_f (τ_r' + θ) − d_jam' > 0, with the subject's fully relaxed τ_r' = φ_r τ_r and
/// d_jam' = φ_j d_jam ("the changer assumes the others are like itself") and θ = `buffer_s`.
fn gap_criterion(h: &HumanParams, lc: &LaneChangeParams, g0: f64, g_min: f64, v_f: f64) -> bool {
    let relax = gap_relax(lc);
    let reaction = relax.reaction * h.reaction_s;
    let jam = relax.jam * h.jam_gap_m;
    g0 > jam && g_min - v_f * (reaction + h.buffer_s) - jam > 0.0
}

/// Lead (forward) gap acceptance (spec 4.3): may the subject (params `h`, `lc`, speed `v`) move
/// in behind a target-lane leader at net gap `g0` driving at `v_leader`?
///
/// Leader = target-lane leader braking at b_ℓ* = σ_f c_b b; follower = the subject braking at
/// its b = `h.max_decel`; the criterion uses the subject's speed as v_f.
pub fn accept_lead_gap(
    h: &HumanParams,
    lc: &LaneChangeParams,
    g0: f64,
    v: f64,
    v_leader: f64,
) -> bool {
    let b_leader = lc.sigma_forward * h.leader_brake_factor * h.max_decel;
    let g_min = min_gap_while_braking(g0, v_leader, b_leader, v, h.max_decel);
    gap_criterion(h, lc, g0, g_min, v)
}

/// Lag (backward) gap acceptance (spec 4.3): may the subject cut in ahead of a target-lane
/// follower at net gap `g0` (subject's rear to follower's front) driving at `v_follower`?
/// `a_ant` is the subject's anticipated acceleration behind its new leader. The follower is
/// assumed to have the subject's parameters.
///
/// Leader = the subject braking at b_ℓ* = max(a_ant, σ_b c_b b) (it will not brake harder than
/// it has to); follower = the target-lane follower braking at b = `h.max_decel`; the criterion
/// uses the follower's speed as v_f.
pub fn accept_lag_gap(
    h: &HumanParams,
    lc: &LaneChangeParams,
    g0: f64,
    v: f64,
    v_follower: f64,
    a_ant: f64,
) -> bool {
    let b_leader = a_ant.max(lc.sigma_backward * h.leader_brake_factor * h.max_decel);
    let g_min = min_gap_while_braking(g0, v, b_leader, v_follower, h.max_decel);
    gap_criterion(h, lc, g0, g_min, v_follower)
}

/// Relaxation factors `elapsed_s` after the event (spec 4.6): linear from φ to 1 over t_s.
///
/// φ_x(t) = φ_x + (1 − φ_x) t / t_s for 0 ≤ t < t_s, exactly 1 (`Relax::NONE`) from t_s on.
/// A negative (or NaN) `elapsed_s` counts as 0; t_s ≤ 0 means no relaxation at all.
#[inline]
pub fn relax_at(p: &LaneChangeParams, elapsed_s: f64) -> Relax {
    let t = elapsed_s.max(0.0);
    if t >= p.relax_time_s || p.relax_time_s.is_nan() {
        return Relax::NONE;
    }
    let frac = t / p.relax_time_s;
    let recover = |phi: f64| phi + (1.0 - phi) * frac;
    Relax {
        headway: recover(p.relax_headway),
        jam: recover(p.relax_jam),
        reaction: recover(p.relax_reaction),
    }
}

/// Does a driver with cooperativeness ζ agree to yield (spec 4.5)? `u` is the driver's uniform
/// draw for this request; a discretionary request is granted with probability
/// ζ · `discretionary_coop_factor`, a mandatory one with probability ζ.
#[inline]
pub fn agrees_to_yield(p: &LaneChangeParams, mandatory: bool, u: f64) -> bool {
    let zeta = if mandatory {
        p.cooperativeness
    } else {
        p.cooperativeness * p.discretionary_coop_factor
    };
    u < zeta
}

/// Yielding car following (YCF, spec 4.5): follow both the real leader (normal target
/// acceleration `a_cf`) and the requester as a virtual leader with the relaxed parameters, take
/// the more restrictive, but never brake harder than b_c for the sake of the yield.
pub fn yield_accel(
    h: &HumanParams,
    p: &LaneChangeParams,
    v: f64,
    v_des: f64,
    a_cf: f64,
    requester: crate::Leader,
) -> f64 {
    let a_virtual = crate::human::target_accel(h, v, v_des, Some(requester), gap_relax(p));
    a_cf.min(a_virtual.max(h.comfort_decel))
}
