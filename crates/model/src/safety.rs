//! Braking limits and surrogate safety measures (issue 18): the emergency braking limit that
//! bounds every applied acceleration, and time to collision (TTC) with the exposure measures
//! built on it.
//!
//! Papers: Minderhoud & Bovy (2001), "Extended time-to-collision measures for road traffic
//! safety assessment", Accident Analysis & Prevention 33 (TET, TIT); Eclipse SUMO's SSM device
//! (TTC threshold 3.0 s) and vehicle type attributes `decel` / `emergencyDecel` (passenger car
//! 9.0 m/s²). The project's definitions and choices are in docs/safety.md.
//!
//! ```text
//! braking limit:  a_applied = max(a, −b_e)           b_e > 0, the emergency deceleration
//! emergency:      a_applied < b                      b < 0, the vehicle's normal limit (max_decel)
//! TTC:            TTC = g / (v_f − v_l)  if v_f > v_l, else none (not closing)
//!                 g = net gap (leader's rear bumper to the follower's front bumper)
//! TET:            Σ Δt over follower-steps with TTC < TTC*
//! TIT:            Σ (TTC* − TTC) Δt over the same follower-steps
//! conflict:       one episode of a (follower, leader) pair with TTC < TTC* in consecutive steps
//! ```
//!
//! | symbol | field | default | unit | source |
//! |---|---|---|---|---|
//! | b_e | `human.emergency_decel_mps2`, `cav.emergency_decel_mps2` | 9.0 | m/s² (positive) | SUMO `emergencyDecel`, passenger car |
//! | b | `human.max_decel`, `cav.max_decel` | −4.0 | m/s² (negative) | seed paper |
//! | TTC* | `safety.ttc_threshold_s` | 3.0 | s | SUMO SSM device default |

use serde::{Deserialize, Serialize};

/// Default emergency deceleration b_e (m/s², positive): SUMO's passenger-car `emergencyDecel`.
pub const DEFAULT_EMERGENCY_DECEL_MPS2: f64 = 9.0;

/// Scenario section `[safety]`: the surrogate safety measures' settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SafetyParams {
    /// TTC* (s): a follower with a time to collision below it is in a conflict.
    pub ttc_threshold_s: f64,
}

impl Default for SafetyParams {
    fn default() -> Self {
        SafetyParams {
            ttc_threshold_s: 3.0,
        }
    }
}

/// The acceleration a vehicle can apply: `a` bounded below by the emergency deceleration
/// `emergency_decel` (positive, m/s²). A NaN command gives −`emergency_decel` (the engine then
/// reports the non-finite state it came from elsewhere; braking is the safe reading).
#[inline]
pub fn braking_limited(a: f64, emergency_decel: f64) -> f64 {
    if a >= -emergency_decel {
        a
    } else {
        -emergency_decel
    }
}

/// Is an applied acceleration an emergency braking: harder than the normal limit `max_decel`
/// (negative, m/s²)?
#[inline]
pub fn is_emergency(a: f64, max_decel: f64) -> bool {
    a < max_decel
}

/// Time to collision (s) of a follower at speed `v_f` behind a leader at `v_l` with net gap
/// `gap` (m): g / (v_f − v_l) while the follower closes in, `None` otherwise. A gap at or below
/// zero while closing gives `Some(0.0)` (the vehicles touch).
#[inline]
pub fn ttc(gap: f64, v_f: f64, v_l: f64) -> Option<f64> {
    let closing = v_f - v_l;
    (closing > 0.0).then(|| gap.max(0.0) / closing)
}

/// The TET and TIT increments of one follower-step of length `dt` (s) at time to collision
/// `ttc` (s) against the threshold `threshold` (s): (Δt, (TTC* − TTC) Δt) below it, zeros
/// otherwise.
#[inline]
pub fn exposure(ttc: f64, threshold: f64, dt: f64) -> (f64, f64) {
    if ttc < threshold {
        (dt, (threshold - ttc) * dt)
    } else {
        (0.0, 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn braking_is_bounded_by_the_emergency_limit() {
        assert_eq!(braking_limited(-16.8, 9.0), -9.0);
        assert_eq!(braking_limited(-9.0, 9.0), -9.0);
        assert_eq!(braking_limited(-3.0, 9.0), -3.0);
        assert_eq!(braking_limited(1.5, 9.0), 1.5);
        assert_eq!(braking_limited(f64::NAN, 9.0), -9.0);
        assert_eq!(braking_limited(f64::NEG_INFINITY, 6.0), -6.0);
    }

    #[test]
    fn emergency_is_harder_than_the_normal_limit() {
        assert!(!is_emergency(-4.0, -4.0));
        assert!(is_emergency(-4.01, -4.0));
        assert!(!is_emergency(-2.0, -4.0));
    }

    #[test]
    fn ttc_only_while_closing() {
        assert_eq!(ttc(20.0, 30.0, 20.0), Some(2.0));
        assert_eq!(ttc(20.0, 20.0, 20.0), None);
        assert_eq!(ttc(20.0, 10.0, 20.0), None);
        assert_eq!(ttc(-1.0, 12.0, 10.0), Some(0.0));
    }

    #[test]
    fn exposure_below_the_threshold() {
        assert_eq!(exposure(1.0, 3.0, 0.1), (0.1, 0.2));
        assert_eq!(exposure(3.0, 3.0, 0.1), (0.0, 0.0));
        assert_eq!(exposure(5.0, 3.0, 0.1), (0.0, 0.0));
        let (tet, tit) = exposure(0.0, 3.0, 0.5);
        assert_eq!((tet, tit), (0.5, 1.5));
    }
}
