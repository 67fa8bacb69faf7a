//! Ramp metering (issue 45 item 3): a signal at an on-ramp that lets one vehicle go per green,
//! at a fixed rate or at the rate of the ALINEA feedback law, with a queue override.
//!
//! ```text
//! one car per green:  c = 3600 / r                    cycle c (s) of a meter at rate r (veh/h)
//! green:              t ≥ g + c                       g = when the last green started
//! green start:        g' = g + c   if the release is on the first step at or after g + c
//!                     g' = t       otherwise (the ramp was empty, or the head waited for a gap)
//! ALINEA:             r(k) = r(k−1) + K_R (o* − o_out(k−1)),  clamped to [r_min, r_max]
//!                     o_out(k−1): occupancy (%) of the through lanes at the detector downstream
//!                     of the merge over control period k−1 (length T); r(0) = r_max
//! queue override:     n > n_max  →  the meter releases at r_max (ALINEA) or is off (fixed)
//!                     n: vehicles waiting on the ramp, until n ≤ n_max again
//! ```
//!
//! Sources. One vehicle per green is the usual US practice for a single-lane meter (Caltrans
//! Ramp Meter Design Manual, 2000; FHWA Ramp Management and Control Handbook, FHWA-HOP-05-072,
//! 2006, chapter 5). ALINEA: Papageorgiou, Hadj-Salem & Blosseville (1991), "ALINEA: a local
//! feedback control law for on-ramp metering", Transportation Research Record (volume 1320
//! \[R\]); an integral regulator of the downstream occupancy, whose clamping to
//! [r_min, r_max] each period keeps it from winding up. The queue override is the field
//! practice of a queue detector near the ramp's entry that raises the rate when the queue
//! reaches it (Caltrans Ramp Meter Design Manual; FHWA Handbook chapter 5); Smaragdis &
//! Papageorgiou (2003, Transportation Research Record \[R\]) combine it with ALINEA. The
//! green-start rule is this project's discretization of a continuous meter to the step: on a
//! saturated ramp the greens keep their phase, so the mean rate is r exactly and each headway
//! is c within one step \[D\].
//!
//! | symbol | field | default | unit | source |
//! |---|---|---|---|---|
//! | r | `rate_vph` (fixed) | required | veh/h | the meter's plan |
//! | o* | `occupancy_target_pct` | required | % (0-100) | the critical occupancy of the downstream detector, site-specific (Papageorgiou et al. 1991) |
//! | K_R | `gain_vph` | 70 | veh/h per % occupancy | Papageorgiou et al. (1991) \[R\] |
//! | T | `period_s` | 60 | s | \[D\]; ALINEA's field tests ran periods of tens of seconds to a few minutes \[R\] |
//! | r_min, r_max | `min_rate_vph`, `max_rate_vph` | required | veh/h | the meter's plan (e.g. 240-900 veh/h for one lane, one car per green \[R\]) |
//! | n_max | `queue_max_veh` | none (no override) | veh | the ramp's storage up to its queue detector |

use serde::Serialize;

/// Default ALINEA gain K_R (veh/h per % occupancy): the value of Papageorgiou et al. (1991)
/// and of most ALINEA deployments since \[R\].
pub const DEFAULT_GAIN_VPH: f64 = 70.0;

/// Default ALINEA control period T (s) \[D\].
pub const DEFAULT_PERIOD_S: f64 = 60.0;

/// Tolerance of the time comparisons (s): step times are sums of a floating Δt, and a green
/// due at 12 s must open at the step that ends at 12 s, not one step later.
pub const TIME_EPS_S: f64 = 1e-9;

/// The ALINEA law's parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Alinea {
    /// o*: the target (critical) occupancy of the downstream detector (%).
    pub occupancy_target_pct: f64,
    /// K_R: the regulator's gain (veh/h per % occupancy).
    pub gain_vph: f64,
    /// r_min, r_max: the range of the rate (veh/h).
    pub min_rate_vph: f64,
    pub max_rate_vph: f64,
    /// T: the control period (s).
    pub period_s: f64,
}

/// The cycle c (s) of a one-car-per-green meter at `rate_vph` (veh/h): 3600 / r.
#[inline]
pub fn cycle_s(rate_vph: f64) -> f64 {
    3600.0 / rate_vph
}

/// Whether the meter shows green at `now_s`: a whole cycle `cycle_s` has passed since the last
/// green started at `last_green_s` (−∞ before the first).
#[inline]
pub fn green(now_s: f64, last_green_s: f64, cycle_s: f64) -> bool {
    now_s >= last_green_s + cycle_s - TIME_EPS_S
}

/// When the green of a release at `now_s` (the end of a step of `dt_s`) started: on schedule,
/// g + c, if the release came on the first step at or after the green was due, so that a
/// saturated meter keeps its phase and does not drift by the step's rounding; otherwise `now_s`
/// (the vehicle came to an empty ramp, or waited at the green for a gap).
#[inline]
pub fn green_start(now_s: f64, last_green_s: f64, cycle_s: f64, dt_s: f64) -> f64 {
    let due = last_green_s + cycle_s;
    if now_s - due < dt_s - TIME_EPS_S {
        due
    } else {
        now_s
    }
}

/// ALINEA's next rate (veh/h): r(k) = r(k−1) + K_R (o* − o_out), clamped to [r_min, r_max];
/// `occupancy_pct` is o_out over the last control period (%). A non-finite measurement keeps
/// the rate.
#[inline]
pub fn alinea_rate(p: &Alinea, previous_vph: f64, occupancy_pct: f64) -> f64 {
    if !occupancy_pct.is_finite() {
        return previous_vph;
    }
    let r = previous_vph + p.gain_vph * (p.occupancy_target_pct - occupancy_pct);
    r.clamp(p.min_rate_vph, p.max_rate_vph)
}

/// Whether the queue override is on: more than `queue_max_veh` vehicles wait on the ramp.
#[inline]
pub fn queue_override(waiting: usize, queue_max_veh: u32) -> bool {
    waiting > queue_max_veh as usize
}

#[cfg(test)]
mod tests {
    use super::*;

    fn alinea() -> Alinea {
        Alinea {
            occupancy_target_pct: 10.0,
            gain_vph: DEFAULT_GAIN_VPH,
            min_rate_vph: 240.0,
            max_rate_vph: 900.0,
            period_s: DEFAULT_PERIOD_S,
        }
    }

    #[test]
    fn one_car_per_green_at_600_vph_is_a_six_second_cycle() {
        assert_eq!(cycle_s(600.0), 6.0);
        assert_eq!(cycle_s(900.0), 4.0);
        assert_eq!(cycle_s(240.0), 15.0);
    }

    /// A saturated meter stepped at Δt = 0.1 s releases on the step the green is due and keeps
    /// its phase: 700 veh/h (c = 5.142857 s) gives 700 releases in an hour, each headway
    /// within one step of c.
    #[test]
    fn a_saturated_meter_keeps_its_rate_at_any_cycle() {
        for rate in [600.0, 700.0, 900.0, 1000.0, 257.0] {
            let (c, dt) = (cycle_s(rate), 0.1);
            let mut last = f64::NEG_INFINITY;
            let mut releases = Vec::new();
            for step in 1..=36_000u64 {
                let now = step as f64 * dt;
                if green(now, last, c) {
                    last = green_start(now, last, c, dt);
                    releases.push(now);
                }
            }
            // The first green opens at once; after it one per cycle.
            let expected = (3600.0 - 0.1) / c + 1.0;
            assert!(
                (releases.len() as f64 - expected).abs() <= 1.0,
                "{rate}: {} releases",
                releases.len()
            );
            for w in releases.windows(2) {
                let h = w[1] - w[0];
                assert!(
                    h > c - dt - 1e-9 && h < c + dt + 1e-9,
                    "{rate}: headway {h}"
                );
            }
        }
    }

    #[test]
    fn a_late_release_restarts_the_cycle() {
        // Due at 6 s, released at 9 s (the ramp was empty): the next green is at 15 s.
        assert_eq!(green_start(9.0, 0.0, 6.0, 0.1), 9.0);
        assert!(!green(14.9, 9.0, 6.0));
        assert!(green(15.0, 9.0, 6.0));
        // On time (the first step at or after the due green): the phase is kept.
        assert_eq!(green_start(6.05, 0.0, 6.0, 0.1), 6.0);
        // The first green opens at once.
        assert!(green(0.1, f64::NEG_INFINITY, 6.0));
        assert_eq!(green_start(0.1, f64::NEG_INFINITY, 6.0, 0.1), 0.1);
    }

    #[test]
    fn alinea_lowers_the_rate_above_the_target_and_raises_it_below() {
        let p = alinea();
        // o = 15 % > o* = 10 %: 600 − 70 × 5 = 250 veh/h.
        assert_eq!(alinea_rate(&p, 600.0, 15.0), 250.0);
        // o = 8 %: 600 + 70 × 2 = 740 veh/h.
        assert_eq!(alinea_rate(&p, 600.0, 8.0), 740.0);
        // At the target the rate holds.
        assert_eq!(alinea_rate(&p, 600.0, 10.0), 600.0);
    }

    #[test]
    fn alinea_is_clamped_to_its_range_and_ignores_a_missing_measurement() {
        let p = alinea();
        assert_eq!(alinea_rate(&p, 300.0, 40.0), 240.0);
        assert_eq!(alinea_rate(&p, 880.0, 0.0), 900.0);
        assert_eq!(alinea_rate(&p, 500.0, f64::NAN), 500.0);
        // No wind-up: after a long congested spell one free period lifts the rate at once.
        let mut r = 900.0;
        for _ in 0..100 {
            r = alinea_rate(&p, r, 50.0);
        }
        assert_eq!(r, 240.0);
        assert_eq!(alinea_rate(&p, r, 5.0), 240.0 + 350.0);
    }

    #[test]
    fn the_override_is_on_only_above_the_maximum_queue() {
        assert!(!queue_override(20, 20));
        assert!(queue_override(21, 20));
        assert!(!queue_override(0, 0));
        assert!(queue_override(1, 0));
    }
}
