//! Braking limits and surrogate safety measures (issues 18, 29): the emergency braking limit
//! that bounds every applied acceleration, the classes of hard-braking episodes, and time to
//! collision (TTC) with the exposure measures built on it (spec 9.4).
//!
//! Papers and standards: Minderhoud & Bovy (2001), "Extended time-to-collision measures for
//! road traffic safety assessment", Accident Analysis & Prevention 33 (TET, TIT); Gettman &
//! Head (2003), "Surrogate safety measures from traffic simulation models", TRR 1840, and the
//! FHWA Surrogate Safety Assessment Model (SSAM, FHWA-HRT-08-051, 2008), whose conflict
//! threshold is TTC ≤ 1.5 s; Dingus et al. (2006), "The 100-Car Naturalistic Driving Study,
//! Phase II", DOT HS 810 593 (VTTI), whose kinematic trigger for near-crash candidates is a
//! longitudinal deceleration of about 0.6 g; Eclipse SUMO's vehicle type attributes `decel` /
//! `emergencyDecel` (passenger car 9.0 m/s²). The project's definitions and choices are in
//! docs/safety.md.
//!
//! ```text
//! braking limit:  a_applied = max(a, −b_e)           b_e > 0, the emergency deceleration
//! episode:        consecutive steps of one vehicle with −a_applied > d_hard
//! peak:           d_peak = the episode's largest −a_applied
//! classes:        hard      d_peak > d_hard         (every episode)
//!                 severe    d_peak ≥ d_severe
//!                 at limit  d_peak ≥ b_e            (the vehicle's own emergency limit)
//! rate:           count / vehicle-km × 100           (per 100 veh-km, measurement window)
//! TTC:            TTC = g / (v_f − v_l)  if v_f > v_l, else none (not closing)
//!                 g = net gap (leader's rear bumper to the follower's front bumper)
//! TET:            Σ Δt over follower-steps with TTC < TTC*
//! TIT:            Σ (TTC* − TTC) Δt over the same follower-steps
//! conflict:       one episode of a (follower, leader) pair with TTC < TTC* in consecutive
//!                 steps: lane-change if the pair was formed by a lane change in the step it
//!                 starts, rear-end otherwise
//! ```
//!
//! | symbol | field | default | unit | source |
//! |---|---|---|---|---|
//! | b_e | `human.emergency_decel_mps2`, `cav.emergency_decel_mps2` | 9.0 | m/s² (positive) | SUMO `emergencyDecel`, passenger car |
//! | b | `human.max_decel`, `cav.max_decel` | −4.0 | m/s² (negative) | seed paper |
//! | TTC* | `safety.ttc_threshold_s` | 1.5 | s | FHWA SSAM (Gettman & Head 2003) |
//! | d_hard | `HARD_BRAKING_MPS2` (constant) | 4.0 | m/s² (positive) | the seed paper's normal limit b |
//! | d_severe | `SEVERE_BRAKING_MPS2` (constant) | 6.0 | m/s² (positive) | 100-Car study near-crash trigger, ~0.6 g \[R\] |

use serde::{Deserialize, Serialize};

/// Default emergency deceleration b_e (m/s², positive): SUMO's passenger-car `emergencyDecel`.
pub const DEFAULT_EMERGENCY_DECEL_MPS2: f64 = 9.0;

/// Default TTC* (s): the FHWA SSAM conflict threshold (Gettman & Head 2003).
pub const DEFAULT_TTC_THRESHOLD_S: f64 = 1.5;

/// d_hard (m/s², positive): a step braking harder than this is part of a hard-braking
/// episode. The seed paper's normal braking limit b = −4 m/s² (the laws are designed not to
/// need more); about 0.4 g.
pub const HARD_BRAKING_MPS2: f64 = 4.0;

/// d_severe (m/s², positive): an episode peaking at or above it is severe. About 0.6 g, the
/// longitudinal-deceleration trigger of near-crash candidates in the 100-Car naturalistic
/// driving study (Dingus et al. 2006, VTTI).
pub const SEVERE_BRAKING_MPS2: f64 = 6.0;

/// Lower edges of the episode-peak histogram's bins (m/s²): [4, 5), [5, 6), …, [8, 9) and
/// the open bin [9, ∞) (a peak exactly at 4 is not an episode; SUMO's default b_e = 9 falls
/// in the last bin).
pub const PEAK_BIN_EDGES_MPS2: [f64; 6] = [4.0, 5.0, 6.0, 7.0, 8.0, 9.0];

/// Largest emergency deceleration b_e a scenario may set (m/s², about 1.2 g: above the
/// tyre-road friction of any road car on dry asphalt, about 0.8-1.0 g).
pub const MAX_EMERGENCY_DECEL_MPS2: f64 = 12.0;

/// Largest TTC* a scenario may set (s): the literature uses 1-4 s (SSAM 1.5 s, SUMO's SSM
/// device 3 s); beyond 10 s every follower closing in at a few m/s is "in conflict".
pub const MAX_TTC_THRESHOLD_S: f64 = 10.0;

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
            ttc_threshold_s: DEFAULT_TTC_THRESHOLD_S,
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

/// Is an applied acceleration (m/s²) a hard-braking step: a deceleration above d_hard?
#[inline]
pub fn is_hard(a: f64) -> bool {
    a < -HARD_BRAKING_MPS2
}

/// The classes of a hard-braking episode, decided by its peak deceleration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BrakingClass {
    /// d_peak > d_hard: every episode.
    pub hard: bool,
    /// d_peak ≥ d_severe.
    pub severe: bool,
    /// d_peak ≥ b_e: the vehicle reached its emergency limit.
    pub at_limit: bool,
}

/// The classes of an episode peaking at `peak` (m/s², positive) for a vehicle whose emergency
/// limit is `emergency_decel` (b_e, positive). The integrate phase applies exactly −b_e when
/// it limits a command, so reaching the limit is an exact comparison.
#[inline]
pub fn classify(peak: f64, emergency_decel: f64) -> BrakingClass {
    BrakingClass {
        hard: peak > HARD_BRAKING_MPS2,
        severe: peak >= SEVERE_BRAKING_MPS2,
        at_limit: peak >= emergency_decel,
    }
}

/// The histogram bin of an episode peak (m/s², positive): the last edge of
/// [`PEAK_BIN_EDGES_MPS2`] at or below it (bin 0 for a peak below the first edge).
#[inline]
pub fn peak_bin(peak: f64) -> usize {
    PEAK_BIN_EDGES_MPS2
        .iter()
        .rposition(|&e| peak >= e)
        .unwrap_or(0)
}

/// A count per 100 vehicle-km: `None` when no distance was driven (the rate does not apply).
#[inline]
pub fn per_100_vkm(count: u64, vehicle_km: f64) -> Option<f64> {
    (vehicle_km > 0.0).then(|| count as f64 * 100.0 / vehicle_km)
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
    fn a_hard_step_brakes_beyond_four() {
        assert!(!is_hard(-4.0));
        assert!(is_hard(-4.01));
        assert!(!is_hard(-2.0));
        assert!(!is_hard(1.0));
    }

    #[test]
    fn an_episode_is_classed_by_its_peak() {
        let hard = BrakingClass {
            hard: true,
            ..BrakingClass::default()
        };
        assert_eq!(classify(5.0, 9.0), hard);
        assert_eq!(classify(4.0, 9.0), BrakingClass::default());
        assert_eq!(
            classify(6.5, 9.0),
            BrakingClass {
                severe: true,
                ..hard
            }
        );
        assert!(classify(6.0, 9.0).severe);
        assert!(!classify(5.99, 9.0).severe);
        let all = BrakingClass {
            hard: true,
            severe: true,
            at_limit: true,
        };
        assert_eq!(classify(9.0, 9.0), all);
        assert!(!classify(8.99, 9.0).at_limit);
        // A vehicle with a weaker emergency limit reaches it sooner.
        assert_eq!(
            classify(5.5, 5.5),
            BrakingClass {
                at_limit: true,
                ..hard
            }
        );
    }

    #[test]
    fn peaks_fall_in_unit_bins_from_four_to_nine() {
        assert_eq!(peak_bin(4.01), 0);
        assert_eq!(peak_bin(4.99), 0);
        assert_eq!(peak_bin(5.0), 1);
        assert_eq!(peak_bin(6.5), 2);
        assert_eq!(peak_bin(8.99), 4);
        assert_eq!(peak_bin(9.0), 5);
        assert_eq!(peak_bin(12.0), 5);
    }

    #[test]
    fn rates_per_hundred_vehicle_km() {
        assert_eq!(per_100_vkm(3, 200.0), Some(1.5));
        assert_eq!(per_100_vkm(0, 50.0), Some(0.0));
        assert_eq!(per_100_vkm(2, 0.0), None);
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
