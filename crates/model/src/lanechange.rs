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
//! | ε | `threshold` | 0.25 | N(0.25, 0.2) in [0.2, 0.5] | – |
//! | σ_f, σ_b | `sigma_forward`, `sigma_backward` | 0.6, 0.75 | fixed | – |
//! | φ_h, φ_j, φ_r | `relax_headway`, `relax_jam`, `relax_reaction` | 0.4, 0.6, 0.2 | fixed | – |
//! | t_s | `relax_time_s` | 8 | fixed | s |
//! | ζ | `cooperativeness` | 0.8 | N(0.8, 0.2) in [0.5, 0.9] | – |
//! | – | `discretionary_coop_factor` | 0.5 | fixed | – |
//! | d_scan, n_scan | `scan_distance_m`, `scan_vehicles` | 50, 5 | fixed | m, veh |
//! | t_min,LC | `min_interval_s` | 5 | fixed (×`return_factor` = 3 back) | s |
//! | – | `slow_down_desire` | 0.5 | fixed | – |
//! | w_CAV | `cav_weight_leader`, `cav_weight_follower` | 0.5, 0 | fixed | – |
//! | v_ref floor | `min_reference_speed_mps` | 2.3 | fixed | m/s |

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
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaneChangeParams {
    pub mandatory_distance_m: f64,
    pub mandatory_time_s: f64,
    pub mandatory_min_distance_m: f64,
    pub mandatory_min_time_s: f64,
    pub right_discount: f64,
    pub mandatory_weight: f64,
    pub threshold: f64,
    pub sigma_forward: f64,
    pub sigma_backward: f64,
    pub relax_headway: f64,
    pub relax_jam: f64,
    pub relax_reaction: f64,
    pub relax_time_s: f64,
    pub cooperativeness: f64,
    pub discretionary_coop_factor: f64,
    pub min_interval_s: f64,
    pub return_factor: f64,
    pub slow_down_desire: f64,
    pub min_reference_speed_mps: f64,
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
    pub cav_weight_leader: f64,
    pub cav_weight_follower: f64,
    /// No lane changes within this distance of an entrance ("forbid zone", spec 4.1) (m).
    pub forbid_zone_m: f64,
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
            threshold: Dist::clamped(0.25, 0.2, 0.2, 0.5),
            sigma_forward: 0.6,
            sigma_backward: 0.75,
            relax_headway: 0.4,
            relax_jam: 0.6,
            relax_reaction: 0.2,
            relax_time_s: 8.0,
            cooperativeness: Dist::clamped(0.8, 0.2, 0.5, 0.9),
            discretionary_coop_factor: 0.5,
            scan_distance_m: 50.0,
            scan_vehicles: 5,
            min_interval_s: 5.0,
            return_factor: 3.0,
            slow_down_desire: 0.5,
            min_reference_speed_mps: 2.3,
            cav_weight_leader: 0.5,
            cav_weight_follower: 0.0,
            forbid_zone_m: 100.0,
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
pub fn mandatory_desire(p: &LaneChangeParams, d_e_m: f64, v: f64, n: u32) -> f64 {
    let _ = (p, d_e_m, v, n);
    todo!("spec 4.2 mandatory")
}

/// Discretionary desire γ_d toward `side` (spec 4.2, [P15-code] Oct 2015 form): `v_ant` the
/// anticipated speed in the target lane, `v_cur` the average speed ahead in the current lane.
/// Includes η_dir (1 left, `right_discount` right). In [0, 1].
pub fn discretionary_desire(p: &LaneChangeParams, v_ant: f64, v_cur: f64, side: Side) -> f64 {
    let _ = (p, v_ant, v_cur, side);
    todo!("spec 4.2 discretionary")
}

/// Closest approach g_min of a leader/follower pair while both brake (spec 4.3): initial net
/// gap `g0`, leader speed `v_l` braking at `b_l` (assumed rate, ≤ 0 or ≥ 0), follower speed
/// `v_f` braking at `b_f` < 0.
pub fn min_gap_while_braking(g0: f64, v_l: f64, b_l: f64, v_f: f64, b_f: f64) -> f64 {
    let _ = (g0, v_l, b_l, v_f, b_f);
    todo!("spec 4.3")
}

/// The relaxed parameter factors used in gap acceptance (fully relaxed: φ_h, φ_j, φ_r).
pub fn gap_relax(p: &LaneChangeParams) -> Relax {
    Relax {
        headway: p.relax_headway,
        jam: p.relax_jam,
        reaction: p.relax_reaction,
    }
}

/// Lead (forward) gap acceptance (spec 4.3): may the subject (params `h`, `lc`, speed `v`) move
/// in behind a target-lane leader at net gap `g0` driving at `v_leader`?
pub fn accept_lead_gap(h: &HumanParams, lc: &LaneChangeParams, g0: f64, v: f64, v_leader: f64) -> bool {
    let _ = (h, lc, g0, v, v_leader);
    todo!("spec 4.3 forward")
}

/// Lag (backward) gap acceptance (spec 4.3): may the subject cut in ahead of a target-lane
/// follower at net gap `g0` (subject's rear to follower's front) driving at `v_follower`?
/// `a_ant` is the subject's anticipated acceleration behind its new leader. The follower is
/// assumed to have the subject's parameters.
pub fn accept_lag_gap(h: &HumanParams, lc: &LaneChangeParams, g0: f64, v: f64, v_follower: f64, a_ant: f64) -> bool {
    let _ = (h, lc, g0, v, v_follower, a_ant);
    todo!("spec 4.3 backward")
}

/// Relaxation factors `elapsed_s` after the event (spec 4.6): linear from φ to 1 over t_s.
pub fn relax_at(p: &LaneChangeParams, elapsed_s: f64) -> Relax {
    let _ = (p, elapsed_s);
    todo!("spec 4.6")
}
