//! Safe lag and lead gaps (spec 9.1): a documented extension of the published gap rule of
//! spec 4.3, after the safety criterion of MOBIL (Kesting, Treiber & Helbing 2007) and the
//! secure-gap check of SUMO's LC2013 lane-change model (Erdmann 2014).
//!
//! The published rule (spec 4.3) tests both gaps with the *changer's* relaxed parameters and
//! lets the new follower brake at its whole normal deceleration b_f. The safe rule keeps that
//! test and adds one constraint: after the change, no one has to brake harder than a safe
//! deceleration b_safe, each by its *own* car-following law.
//!
//! ```text
//! lag gap:  a_f  = the new follower's law with the changer as its leader (net gap g_lag, speed v):
//!                  human driver (or a CAV driven by hand): human::target_accel (spec 2.4, before
//!                  smoothing) with its own parameters, relaxed by its own φ as after being cut in
//!                  (RCF, spec 4.6: the factors at t = 0);
//!                  automated CAV: its ACC or CACC law, time-gap transition and limits (spec 3.9),
//!                  not relaxed (spec 4.6); under the field law the law's demand before the
//!                  deceleration limit (what it needs, not what it may apply)
//! lead gap: a_ant = the changer's law behind its new leader (relaxed, spec 4.3, 4.6)
//! accept  ⇔ published test (spec 4.3)  ∧  a_f ≥ −b_safe  ∧  a_ant ≥ −b_safe
//! b_safe  = safe_follower_decel_mps2, or mandatory_safe_decel_mps2 for a mandatory change
//!           whose desire has reached 1 (the lane end, exit or drop is close, spec 4.2)
//! ```
//!
//! "Need to brake" is the law's target acceleration, not the smoothed one (spec 2.4): the
//! smoothing only delays the braking the law asks for. The Newell term is clamped at b_f
//! (spec 2.1), the Gipps term is not (spec 2.3), so a_f below −b_f can only come from the
//! Gipps term; b_safe < |b_f| is what leaves the follower a reserve for the changer's own
//! braking after the change.
//!
//! | symbol | field | default | unit | source |
//! |---|---|---|---|---|
//! | – | `gap_rule` | safe | – | `safe` (this file) or `published` (spec 4.3 alone) \[D\] |
//! | b_safe | `safe_follower_decel_mps2` | 3.0 | m/s² (positive) | MOBIL b_safe (Kesting et al. 2007: 4 m/s², twice the IDM comfortable deceleration), below b_f = 4 (spec 9.1) |
//! | b_safe,m | `mandatory_safe_decel_mps2` | 4.0 | m/s² (positive) | mandatory change with γ ≥ 1: MOBIL's 4 m/s² = b_f, below SUMO's passenger decel 4.5 and far below b_e = 9 |

use crate::cav::{self, CavParams, Family};
use crate::human::{self, HumanParams};
use crate::lanechange::{self as lcm, LaneChangeParams};
use crate::{bounded, Leader};
use serde::{Deserialize, Serialize};

/// Which gap-acceptance rule the lane changes use (`lane_change.gap_rule`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum GapRule {
    /// The published rule (spec 4.3) and the safe-deceleration constraint of spec 9.1.
    #[default]
    Safe,
    /// The published rule of spec 4.3 alone (the seed paper's model).
    Published,
}

impl GapRule {
    /// `safe` or `published`, as in scenario files.
    pub fn as_str(self) -> &'static str {
        match self {
            GapRule::Safe => "safe",
            GapRule::Published => "published",
        }
    }
}

/// The safe decelerations of spec 9.1 (positive m/s²).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SafeDecel {
    /// b_safe: the bound for every change but an urgent mandatory one.
    pub normal_mps2: f64,
    /// b_safe,m: the bound for a mandatory change whose desire has reached 1.
    pub mandatory_mps2: f64,
}

impl SafeDecel {
    /// The bound for a change (`urgent`: mandatory with γ ≥ 1), positive m/s².
    #[inline]
    pub fn bound(&self, urgent: bool) -> f64 {
        if urgent {
            self.mandatory_mps2
        } else {
            self.normal_mps2
        }
    }
}

/// Is a change mandatory and urgent (γ ≥ 1: within E_min or T_min of its last point, or a
/// commanded change, spec 4.2), so that it may use b_safe,m?
#[inline]
pub fn urgent(mandatory: bool, gamma: f64) -> bool {
    mandatory && gamma >= 1.0
}

/// The safe-deceleration test of spec 9.1 on one acceleration (the new follower's `a_f` or the
/// changer's `a_ant`, m/s²): true when it asks for no braking harder than `bound_mps2`.
#[inline]
pub fn brakes_safely(accel: f64, bound_mps2: f64) -> bool {
    accel >= -bound_mps2
}

/// The target acceleration of a human (or hand-driven CAV) follower `h`, `lc` at speed `v_f`
/// with desired speed `v_des`, right after `changer` cut in ahead of it: its own law (spec
/// 2.4, before smoothing) with its own relaxation factors at the start of RCF (spec 4.6).
#[inline]
pub fn human_follower_accel(
    h: &HumanParams,
    lc: &LaneChangeParams,
    v_f: f64,
    v_des: f64,
    changer: Leader,
) -> f64 {
    human::target_accel(h, v_f, v_des, Some(changer), lcm::gap_relax(lc))
}

/// What an automated CAV follower's controller needs besides the changer (spec 3.9).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AutomatedFollower {
    pub v: f64,
    /// Its acceleration in the last step (the CACC error derivative uses it).
    pub a: f64,
    pub v_des: f64,
    /// Its effective time gap now and the target its transition moves toward (spec 3.5).
    pub time_gap_s: f64,
    pub target_gap_s: f64,
    pub family: Family,
    /// The changer is a CAV (CACC) or not (ACC).
    pub changer_is_cav: bool,
    /// The changer's acceleration, as its beacon carries it (the field law's feed-forward and
    /// approach; read only under `cav.cacc_law = "field"`), or as the radar estimates it (a
    /// human changer: the field law's approach under ACC).
    pub a_pred: f64,
}

/// The acceleration an automated CAV's controller would apply (spec 3.9: ACC behind a
/// non-CAV, CACC behind a CAV, the safety override and the limits) with `changer` as its new
/// leader, over a step `dt`, under `p.cacc_law` (under the field law the caller passes the
/// time gap after the cut-in reset, `cav::cut_in_time_gap`).
pub fn automated_follower_accel(
    p: &CavParams,
    f: &AutomatedFollower,
    changer: Leader,
    dt: f64,
) -> f64 {
    let leader = Some(changer).filter(|l| l.gap_m <= p.sensor_range_m);
    let cmd = match leader {
        None => cav::speed_regulation(p, f.v, f.v_des),
        Some(l) => {
            let tg = cav::ramp_time_gap(p, f.time_gap_s, f.target_gap_s, dt);
            if f.changer_is_cav {
                cav::cacc_by_law(p, f.v, f.a, f.a_pred, f.v_des, l, tg, f.family).accel
            } else {
                cav::acc_by_law(p, f.v, f.v_des, Some(l), f.a_pred, tg, f.family).accel
            }
        }
    };
    let a = cav::finalize(p, f.v, cmd, f.v_des, leader, dt);
    match leader {
        Some(l) if p.cacc_law == cav::CaccLaw::Field => bounded::min(a, field_need(p, f, l)),
        _ => a,
    }
}

/// What an automated follower under the field law needs behind a changer: its kinematic
/// approach (`cav::approach_accel`), not capped by the deceleration limit, over the gap that
/// is left once its braking has built up. That takes the response time t_r = τ + D / (2 J)
/// (the lag, then half the time to build the envelope's deceleration D at its jerk J; 1.0 s
/// at 25 m/s, 0.8 s at low speed), during which the gap closes by (v − v_l) t_r
/// (docs/cacc-field.md, cut-ins).
pub fn field_need(p: &CavParams, f: &AutomatedFollower, changer: Leader) -> f64 {
    let (decel, jerk) = cav::envelope(p, f.v);
    let t_r = p.effective_lag_s() + decel / (2.0 * jerk.max(0.1));
    let closing = (f.v - changer.v_mps).max(0.0) * t_r;
    let left = Leader {
        gap_m: changer.gap_m - closing,
        ..changer
    };
    cav::approach_accel(p, f.v, left, f.a_pred)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn safe() -> SafeDecel {
        SafeDecel {
            normal_mps2: 3.0,
            mandatory_mps2: 4.0,
        }
    }

    #[test]
    fn urgent_mandatory_changes_use_the_harder_bound() {
        assert_eq!(safe().bound(urgent(true, 1.0)), 4.0);
        assert_eq!(safe().bound(urgent(true, 0.99)), 3.0);
        assert_eq!(safe().bound(urgent(false, 1.0)), 3.0);
    }

    #[test]
    fn the_bound_is_inclusive() {
        assert!(brakes_safely(-3.0, 3.0));
        assert!(!brakes_safely(-3.0 - 1e-9, 3.0));
    }

    /// A cut-in 30 m ahead of a human follower at 30 m/s by a changer at 26 m/s: the published
    /// rule accepts it, yet the follower's own law asks for 6.2 m/s² (its Gipps term, spec 2.3);
    /// the safe rule refuses it. At equal speeds 25 m is accepted by both.
    #[test]
    fn a_cut_in_ahead_of_a_faster_follower_demands_hard_braking() {
        let (h, lc) = (HumanParams::default(), LaneChangeParams::default());
        let follower_after = |g: f64, v_changer: f64, v_f: f64| {
            let changer = Leader {
                gap_m: g,
                v_mps: v_changer,
            };
            human_follower_accel(&h, &lc, v_f, h.desired_speed, changer)
        };
        assert!(lcm::accept_lag_gap(&h, &lc, 30.0, 26.0, 30.0, 0.0));
        let a_f = follower_after(30.0, 26.0, 30.0);
        assert!(a_f < -6.0 && !brakes_safely(a_f, 3.0), "a_f = {a_f}");
        assert!(!brakes_safely(a_f, 4.0), "nor under the mandatory bound");
        assert!(lcm::accept_lag_gap(&h, &lc, 25.0, 30.0, 30.0, 0.0));
        let level = follower_after(25.0, 30.0, 30.0);
        assert!(brakes_safely(level, 3.0), "a_f = {level}");
        // The relaxation of the cut-in follower is its own (spec 4.6): unrelaxed it would
        // brake harder.
        let unrelaxed = human::target_accel(
            &h,
            30.0,
            h.desired_speed,
            Some(Leader {
                gap_m: 25.0,
                v_mps: 30.0,
            }),
            crate::Relax::NONE,
        );
        assert!(unrelaxed < level);
    }

    #[test]
    fn an_automated_follower_uses_its_controller_and_limits() {
        let p = CavParams {
            cacc_law: cav::CaccLaw::Spec,
            ..CavParams::default()
        };
        let f = AutomatedFollower {
            v: 30.0,
            a: 0.0,
            v_des: 30.0,
            time_gap_s: 1.1,
            target_gap_s: 1.1,
            family: Family::Gap,
            changer_is_cav: false,
            a_pred: 0.0,
        };
        let near = Leader {
            gap_m: 15.0,
            v_mps: 30.0,
        };
        // ACC collision avoidance, bounded at b (spec 3.3, 3.9).
        let a = automated_follower_accel(&p, &f, near, 0.1);
        assert_eq!(a, p.max_decel);
        let far = Leader {
            gap_m: 40.0,
            v_mps: 30.0,
        };
        assert!(automated_follower_accel(&p, &f, far, 0.1) > -3.0);
    }

    #[test]
    fn under_the_field_law_an_automated_follower_is_judged_by_its_need_not_its_limit() {
        let p = CavParams::default();
        assert_eq!(p.cacc_law, cav::CaccLaw::Field);
        // 20 m/s behind a vehicle that cut in standing 60 m ahead: its braking builds up in
        // t_r = 0.3 + 3.5 / (2 · 2.5) = 1.0 s, in which the gap closes by 20 m; stopping at
        // s_min then asks for 20² / (2 · 38.5) = 5.19 m/s², beyond b = 4, which is all that
        // finalize lets it apply.
        let f = AutomatedFollower {
            v: 20.0,
            a: 0.0,
            v_des: 30.0,
            time_gap_s: 0.6,
            target_gap_s: 0.6,
            family: Family::Speed,
            changer_is_cav: false,
            a_pred: 0.0,
        };
        let standing = Leader {
            gap_m: 60.0,
            v_mps: 0.0,
        };
        let a = automated_follower_accel(&p, &f, standing, 0.1);
        let need = -(20.0_f64 * 20.0) / (2.0 * (60.0 - 20.0 - p.standstill_gap_m));
        assert!((a - need).abs() < 1e-9, "a = {a}, need = {need}");
        assert!(!brakes_safely(a, 4.0));
        // Under the spec law the same follower is judged by what it applies.
        let spec = CavParams {
            cacc_law: cav::CaccLaw::Spec,
            ..p
        };
        let applied = automated_follower_accel(&spec, &f, standing, 0.1);
        assert!(applied >= p.max_decel - 1e-9, "applied = {applied}");
        assert!(brakes_safely(applied, 4.0));
    }
}
