//! CAV control (spec 3): speed regulation, ACC behind a non-CAV, CACC behind a CAV, the
//! safety override and the vehicle limits.
//!
//! Papers: Milanés & Shladover (2014) ACC/CACC laws; operating modes and gains of Xiao,
//! Wang & van Arem (2017) as implemented in Eclipse SUMO's ACC/CACC models; PATH/Liu et al.
//! (2018) as used by the seed paper. Equations (g = net gap, Δv = v_l − v):
//!
//! ```text
//! speed regulation (3.2): a = k0 (v_F − v)
//! ACC (3.3):  e = g − t_A v − d0,  d0 = max(s_min, min(75/v − 5, 2))
//!             spacing > 120 m → speed regulation; < 100 m → gap family; between: previous family
//!             regulation  |e| < 0.2 and |Δv| < 0.1 : a = k1 e + k2 Δv    (0.23, 0.07)
//!             avoidance   e < 0                    : a = k1c e + k2c Δv  (0.8, 0.23)
//!             closing     otherwise                : a = k1g e + k2g Δv  (0.04, 0.8)
//! CACC (3.4): e = g − t_C v − s_min,  ė = Δv − t_C a,  v(k+1) = v(k) + kp e + kd ė  (per 0.1 s)
//!             tg = g/v > 2 s and e > 1.66 m → speed regulation; tg < 1.5 s → CACC family;
//!             between: previous family
//!             regulation  0 < e < 0.2 and |Δv| < 0.1 : (0.45, 0.0125)
//!             avoidance   e < 0                      : (0.45, 0.05)
//!             closing     otherwise                  : (0.005, 0.05)
//!             a = (v(k+1) − v(k)) / 0.1 applied over Δt
//! safety (3.4, 3.8): v_safe = Gipps speed with τ_r = 0.4 s, θ = 0, b̂ = b;
//!             if v_new > v_safe + min(2, g): v_new = max(0, v_safe + min(2, g))
//! limits:     (v_new − v)/Δt ∈ [b, a_M], 0 ≤ v_new ≤ v_F
//! ```
//!
//! | symbol | field | default | unit | source |
//! |---|---|---|---|---|
//! | k0 | `speed_gain` | 0.4 | 1/s | SUMO, [P15-code] |
//! | t_A | `acc_time_gap_s` | 1.1 | s | spec 3.3 [D] |
//! | k1, k2 | `acc_reg_gains` | 0.23, 0.07 | 1/s², 1/s | Milanés & Shladover 2014 |
//! | k1g, k2g | `acc_closing_gains` | 0.04, 0.8 | | Xiao 2017 |
//! | k1c, k2c | `acc_avoid_gains` | 0.8, 0.23 | | SUMO |
//! | – | `acc_range_m` | 100, 120 | m | hysteresis band |
//! | kp, kd | `cacc_reg_gains` | 0.45, 0.0125 | per 0.1 s | Xiao 2017 |
//! | kp, kd | `cacc_closing_gains` | 0.005, 0.05 | per 0.1 s | Xiao 2017 |
//! | kp, kd | `cacc_avoid_gains` | 0.45, 0.05 | per 0.1 s | SUMO |
//! | – | `cacc_tg_band_s` | 1.5, 2.0 | s | hysteresis band |
//! | – | `speed_control_min_gap_m` | 1.66 | m | SUMO |
//! | – | `reg_gap_band_m`, `reg_speed_band_mps` | 0.2, 0.1 | m, m/s | Xiao 2017 |
//! | s_min | `standstill_gap_m` | 1.5 | m | seed "minimum space gap" |
//! | τ_r | `reaction_s` | 0.4 | s | seed, spec 3.8 |
//! | a_M | `max_accel` | 1.5 | m/s² | seed (swapped row) |
//! | b | `max_decel` | −4.0 | m/s² | seed (swapped row) |
//! | – | `inter_platoon_gap_s` | 1.5 | s | seed |
//! | – | `max_platoon` | 10 | veh | seed |
//! | – | `sensor_range_m` | 250 | m | spec 3.9 |
//! | – | `time_gap_shares` | 0.6:0.57, 0.7:0.24, 0.9:0.07, 1.1:0.12 | s : share | Nowakowski, spec 3.5 |

use crate::Leader;
use serde::{Deserialize, Serialize};

/// CAV controller parameters (shared by all CAVs; the CACC time gap is per vehicle).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CavParams {
    pub speed_gain: f64,
    pub acc_time_gap_s: f64,
    pub acc_reg_gains: [f64; 2],
    pub acc_closing_gains: [f64; 2],
    pub acc_avoid_gains: [f64; 2],
    pub acc_range_m: [f64; 2],
    pub cacc_reg_gains: [f64; 2],
    pub cacc_closing_gains: [f64; 2],
    pub cacc_avoid_gains: [f64; 2],
    pub cacc_tg_band_s: [f64; 2],
    pub speed_control_min_gap_m: f64,
    pub reg_gap_band_m: f64,
    pub reg_speed_band_mps: f64,
    pub standstill_gap_m: f64,
    pub reaction_s: f64,
    pub max_accel: f64,
    pub max_decel: f64,
    pub inter_platoon_gap_s: f64,
    pub max_platoon: u32,
    pub sensor_range_m: f64,
    /// (CACC time gap in s, share) pairs; shares sum to 1.
    pub time_gap_shares: Vec<(f64, f64)>,
}

impl Default for CavParams {
    fn default() -> Self {
        CavParams {
            speed_gain: 0.4,
            acc_time_gap_s: 1.1,
            acc_reg_gains: [0.23, 0.07],
            acc_closing_gains: [0.04, 0.8],
            acc_avoid_gains: [0.8, 0.23],
            acc_range_m: [100.0, 120.0],
            cacc_reg_gains: [0.45, 0.0125],
            cacc_closing_gains: [0.005, 0.05],
            cacc_avoid_gains: [0.45, 0.05],
            cacc_tg_band_s: [1.5, 2.0],
            speed_control_min_gap_m: 1.66,
            reg_gap_band_m: 0.2,
            reg_speed_band_mps: 0.1,
            standstill_gap_m: 1.5,
            reaction_s: 0.4,
            max_accel: 1.5,
            max_decel: -4.0,
            inter_platoon_gap_s: 1.5,
            max_platoon: 10,
            sensor_range_m: 250.0,
            time_gap_shares: vec![(0.6, 0.57), (0.7, 0.24), (0.9, 0.07), (1.1, 0.12)],
        }
    }
}

/// Controller family kept between steps for the hysteresis of spec 3.3/3.4.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Family {
    /// Speed regulation (cruise).
    #[default]
    Speed,
    /// Gap control (regulation / closing / avoidance).
    Gap,
}

/// The sub-mode a controller used this step (for statistics and debugging).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CavMode {
    SpeedRegulation,
    GapRegulation,
    GapClosing,
    CollisionAvoidance,
}

/// A controller's output: the commanded acceleration (before the safety override and limits),
/// the sub-mode used, and the family to remember for the next step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Command {
    pub accel: f64,
    pub mode: CavMode,
    pub family: Family,
}

/// Speed regulation (spec 3.2): k0 (v_des − v).
pub fn speed_regulation(p: &CavParams, v: f64, v_des: f64) -> f64 {
    let _ = (p, v, v_des);
    todo!("spec 3.2")
}

/// ACC (spec 3.3) with time gap `time_gap_s` (normally `p.acc_time_gap_s`), hysteresis on the
/// spacing; `leader = None` (or beyond the sensor) means speed regulation. `leader_length_m` is
/// needed because the 100/120 m hysteresis is on spacing (front to front).
pub fn acc(p: &CavParams, v: f64, v_des: f64, leader: Option<Leader>, time_gap_s: f64, prev: Family) -> Command {
    let _ = (p, v, v_des, leader, time_gap_s, prev);
    todo!("spec 3.3")
}

/// CACC (spec 3.4) with time gap `time_gap_s` (the vehicle's t_C, or the inter-platoon gap for
/// a new string leader behind a full platoon). `a_own` is the vehicle's current acceleration
/// (for ė = Δv − t_C a). Returns the acceleration equivalent of the speed update, per spec
/// (computed for the 0.1 s control interval; independent of the simulation step).
pub fn cacc(p: &CavParams, v: f64, a_own: f64, v_des: f64, leader: Leader, time_gap_s: f64, prev: Family) -> Command {
    let _ = (p, v, a_own, v_des, leader, time_gap_s, prev);
    todo!("spec 3.4")
}

/// Gipps-type safe speed for the CAV safety override (spec 3.4, 3.8): τ_r = `p.reaction_s`,
/// θ = 0, b̂ = b = `p.max_decel`, jam gap `p.standstill_gap_m`.
pub fn safe_speed(p: &CavParams, gap_m: f64, v_leader: f64) -> f64 {
    let _ = (p, gap_m, v_leader);
    todo!("spec 3.4/3.8")
}

/// Apply the safety override (if there is a leader) and the vehicle limits to a commanded
/// acceleration: returns the acceleration to integrate over `dt`, such that
/// (v_new − v)/dt ∈ [max_decel, max_accel] except where the safety override requires harder
/// braking (never below what reaches v = 0 in this step), 0 ≤ v_new ≤ v_des.
pub fn finalize(p: &CavParams, v: f64, a_cmd: f64, v_des: f64, leader: Option<Leader>, dt: f64) -> f64 {
    let _ = (p, v, a_cmd, v_des, leader, dt);
    todo!("spec 3.4 'After the law'")
}

/// Steady-state net gap of a CAV following at time gap t at speed v under CACC (t v + s_min),
/// but never below the safety-override gap (spec 3.8). Used for insertion.
pub fn cacc_equilibrium_gap(p: &CavParams, time_gap_s: f64, v: f64) -> f64 {
    let _ = (p, time_gap_s, v);
    todo!()
}

/// Steady-state net gap of a CAV under ACC at speed v: t_A v + d0(v), not below the safety gap.
pub fn acc_equilibrium_gap(p: &CavParams, time_gap_s: f64, v: f64) -> f64 {
    let _ = (p, time_gap_s, v);
    todo!()
}

/// The CACC time gap for a uniform deviate `u` in [0, 1) from `p.time_gap_shares` (spec 3.5).
pub fn draw_time_gap(p: &CavParams, u: f64) -> f64 {
    let _ = (p, u);
    todo!("spec 3.5")
}
