//! The CACC realism of spec 9.3, shared by both laws (docs/model-reference.md 9.3):
//!
//! ```text
//! lag:        a_real(k+1) = a_cmd + (a_real(k) − a_cmd) e^{−Δt/τ_a}
//! bound:      a_cmd = max(a_req, −D_auto); a_req < −D_auto: AEB applies a_req (counted)
//! beacons:    age a = steps since the last reception; the law reads the broadcast of step
//!             k − a − d (d = the delay in steps); a Δt > T_b → ACC until beacons return
//! ```
//!
//! Parameters: the `actuator_lag_s`, `comm_delay_s`, `packet_loss`, `beacon_timeout_s` and
//! `max_automated_decel_mps2` rows of the table in `cav.rs`.

use super::MIN_DT_S;

/// Default beacon timeout T_b (s, spec 9.3) \[D\]: five missed beacons at the 10 Hz rate of
/// CACC field tests; longer is the "persistent packet loss" after which Ploeg et al. (2015)
/// degrade CACC to ACC.
pub const DEFAULT_BEACON_TIMEOUT_S: f64 = 0.5;

/// Default bound D_auto (m/s², positive) on the automation's braking (spec 9.3): the largest
/// automatic deceleration ISO 15622 allows an ACC (at low speed; 3.5 m/s² above 20 m/s) \[R\].
pub const DEFAULT_MAX_AUTOMATED_DECEL_MPS2: f64 = 5.0;

/// Whole steps in `seconds` at step `dt` (spec 9.3: delays and timeouts are rounded to
/// steps); 0 for a non-positive or non-finite duration.
#[inline]
pub fn whole_steps(seconds: f64, dt: f64) -> u64 {
    let n = (seconds / dt.max(MIN_DT_S)).round();
    if n.is_finite() && n > 0.0 {
        n as u64
    } else {
        0
    }
}

/// The share of the gap to the command that a first-order lag with time constant `tau` (s)
/// closes in one step of `dt` (s): 1 − e^{−Δt/τ} (spec 9.3), the exact solution for a command
/// held over the step (Plexe's `FirstOrderLagModel` uses the backward-Euler Δt/(τ + Δt),
/// which agrees to first order in Δt/τ). 1 for τ ≤ 0 (no lag).
#[inline]
pub fn lag_gain(dt: f64, tau: f64) -> f64 {
    if tau > 0.0 {
        1.0 - (-dt.max(MIN_DT_S) / tau).exp()
    } else {
        1.0
    }
}

/// What the automation applies this step (spec 9.3), and whether AEB intervenes: `a_req` is
/// the automation's demand (the control law after the safety override, the limits, yielding),
/// `a_real` the acceleration realized in the last step, `gain` from [`lag_gain`] (1 = no lag),
/// `bound` = D_auto (positive). The command is bounded, a_cmd = max(a_req, −D_auto), and lags:
/// a_real + (a_cmd − a_real)·gain. A demand beyond the bound is an AEB intervention, which
/// applies a_req itself (within the step; the engine bounds it by b_e). Without lag and
/// within the bound the result is `a_req`, bit for bit.
#[inline]
pub fn actuate(a_real: f64, a_req: f64, gain: f64, bound: f64) -> (f64, bool) {
    if a_req < -bound {
        return (a_req, true);
    }
    if gain >= 1.0 {
        return (a_req, false);
    }
    (a_real + (a_req - a_real) * gain, false)
}

/// Age (steps) of the freshest beacon a CAV holds after this step's reception (spec 9.3): 0 if
/// a beacon arrived (`lost` false), else one step older than before (saturating).
#[inline]
pub fn next_beacon_age(age: u32, lost: bool) -> u32 {
    if lost {
        age.saturating_add(1)
    } else {
        0
    }
}

/// Whether a beacon `age` steps old is still held (spec 9.3): age ≤ the timeout in steps.
/// Past it the follower falls back to ACC.
#[inline]
pub fn beacon_held(age: u32, timeout_steps: u64) -> bool {
    u64::from(age) <= timeout_steps
}

/// The step whose broadcast the follower uses at `step` with a beacon `age` steps old and a
/// delay of `delay_steps` (spec 9.3): step − age − delay, not before step 0.
#[inline]
pub fn broadcast_step(step: u64, age: u32, delay_steps: u64) -> u64 {
    step.saturating_sub(u64::from(age) + delay_steps)
}
