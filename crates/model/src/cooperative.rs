//! Cooperative lane changes of automated CAVs (spec 9.2, an extension beyond the published
//! model): the request over V2V, the gap the target-lane CAV follower opens, and when the
//! change is safe under automation.
//!
//! Design: the join manoeuvre of Plexe (Segata et al. 2014, "PLEXE: a platooning extension
//! for Veins", IEEE VNC; join at the tail or in the middle of a platoon: the joiner asks, the
//! platoon member behind the joining position opens a gap by keeping a larger distance, the
//! joiner changes lanes under automation and the string forms behind it), with the follower's
//! speed adjustment of SUMO's LC2013 (Erdmann 2014, "SUMO's lane-changing model": the
//! target-lane follower of a blocked changer treats it as a leader and slows down within its
//! comfortable deceleration) and the enlarged gap after a cut-in of Milanés & Shladover (2016,
//! "Handling cut-in vehicles in strings of CACC vehicles"). Equations (g = net gap, b_co the
//! cooperative deceleration, positive):
//!
//! ```text
//! request:    an automated CAV R with a mandatory or organizing desire asks the CAV F that
//!             follows it in the target lane (never a human driver); the request is live for
//!             asked steps k = 1 .. n_T (n_T = t_T / Δt), then R falls back to the published
//!             behaviour for n_T steps, then asks again                       [`asking`, `next_ask`]
//! opening:    F (automated, no own desire) follows R as a virtual leader with its own law
//!             (CACC toward a CAV) at the time gap t_o = max(t_A, t_join):
//!             a_F = min(a_auto, max(a_law(R; t_o), −b_co))                   [`open_gap_accel`]
//!             t_join = t_C of F, or the inter-platoon gap when the joined string would
//!             exceed its size limit (spec 3.6.6)
//! matching:   once F answers, R follows the target-lane leader L the same way (CACC toward a
//!             CAV, ACC toward a human driver, t_o = max(t_A, own gap)), and never accelerates
//!             beyond that: a_R = min(a_auto, max(a_law(L; t_o), −b_co))
//! change:     both gaps pass the gap acceptance of spec 4.3 (the engine's rule of the day),
//!             and the change is safe by construction: after it, F's own law behind R and
//!             R's own law behind L (each at its current effective time gap, with the safety
//!             override of spec 3.4) need no braking harder than b_co      [`join_safe`]
//! after:      R stays automated (no hand-over, no relaxation) and links to L's string if it
//!             has room; F links to R under the sticky memberships of spec 3.6
//! ```
//!
//! | symbol | field | default | unit | source |
//! |---|---|---|---|---|
//! | – | `cooperative_lane_change` | false | – | \[D\] spec 9.2 (off: the seed paper's manual, non-cooperative CAV changes) |
//! | b_co | `cooperative_gap_decel_mps2` | 2.0 | m/s² (positive) | the comfortable deceleration b_c = 0.5 b_f of spec 4.3 [P15-doc], which a yielding driver uses (spec 4.5) |
//! | t_T | `cooperative_timeout_s` | 10 | s | \[D\] spec 9.2: a request lives t_T, then the published behaviour for t_T |

use crate::cav::{self, CavParams, Family};
use crate::Leader;

/// Is a request that has been out for `asked` steps live (1 ..= `timeout_steps`)? 0 means no
/// request.
#[inline]
pub fn asking(asked: u16, timeout_steps: u16) -> bool {
    asked >= 1 && asked <= timeout_steps
}

/// The request counter of the next step, from the previous one: it counts up while the
/// request lives, through the fallback period of as many steps, and starts over after it.
#[inline]
pub fn next_ask(prev: u16, timeout_steps: u16) -> u16 {
    let cycle = timeout_steps.saturating_mul(2).max(1);
    if prev >= cycle {
        1
    } else {
        prev + 1
    }
}

/// The time gap the opener keeps to the virtual leader: at least the ACC gap t_A (the joiner's
/// gap acceptance needs more than a CACC gap; Milanés & Shladover 2016 re-close a cut-in gap
/// from there), and the gap of the string it will join (`t_join`).
#[inline]
pub fn opening_time_gap(p: &CavParams, t_join: f64) -> f64 {
    p.acc_time_gap_s.max(t_join)
}

/// The automated law (CACC toward a CAV, ACC toward a human driver) toward `leader` at time
/// gap `t`, in the gap family (the law of a vehicle that must keep that gap).
#[inline]
fn law(p: &CavParams, v: f64, a: f64, v_des: f64, leader: Leader, cav_leader: bool, t: f64) -> f64 {
    if cav_leader {
        cav::cacc(p, v, a, v_des, leader, t, Family::Gap).accel
    } else {
        cav::acc(p, v, v_des, Some(leader), t, Family::Gap).accel
    }
}

/// The acceleration toward a virtual leader while a gap opens (or the joiner matches its
/// speed): the automated law toward `virtual_leader` at time gap `t`, never braking harder than
/// `b_co` (positive). The engine takes the minimum with the vehicle's own automated command.
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn open_gap_accel(
    p: &CavParams,
    v: f64,
    a: f64,
    v_des: f64,
    virtual_leader: Leader,
    cav_leader: bool,
    t: f64,
    b_co: f64,
) -> f64 {
    law(p, v, a, v_des, virtual_leader, cav_leader, t).max(-b_co)
}

/// The change is safe by construction for the pair (follower, leader) it creates: the
/// follower's own automated law behind the new leader at its effective time gap `t`, with the
/// safety override and the limits (spec 3.4), asks for no braking harder than `b_co`, and the
/// gap keeps the standstill margin.
#[allow(clippy::too_many_arguments)]
pub fn join_safe(
    p: &CavParams,
    v: f64,
    a: f64,
    v_des: f64,
    leader: Leader,
    cav_leader: bool,
    t: f64,
    b_co: f64,
    dt: f64,
) -> bool {
    if leader.gap_m <= p.standstill_gap_m {
        return false;
    }
    let cmd = law(p, v, a, v_des, leader, cav_leader, t);
    cav::finalize(p, v, cmd, v_des, Some(leader), dt) >= -b_co
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p() -> CavParams {
        CavParams::default()
    }

    #[test]
    fn a_request_lives_its_timeout_then_rests_as_long_then_starts_over() {
        let t = 3;
        let mut k = 0;
        let mut seen = Vec::new();
        for _ in 0..8 {
            k = next_ask(k, t);
            seen.push((k, asking(k, t)));
        }
        assert_eq!(
            seen,
            vec![
                (1, true),
                (2, true),
                (3, true),
                (4, false),
                (5, false),
                (6, false),
                (1, true),
                (2, true)
            ]
        );
        assert!(!asking(0, t), "0 is no request");
    }

    #[test]
    fn the_opener_brakes_at_most_the_cooperative_deceleration() {
        let p = p();
        // The requester alongside (negative virtual gap): the law would brake at the limit.
        let l = Leader {
            gap_m: -2.0,
            v_mps: 30.0,
        };
        let raw = law(&p, 30.0, 0.0, 30.0, l, true, 1.1);
        assert!(raw < -2.0, "raw law {raw}");
        assert_eq!(open_gap_accel(&p, 30.0, 0.0, 30.0, l, true, 1.1, 2.0), -2.0);
        // Far ahead: no braking at all.
        let far = Leader {
            gap_m: 80.0,
            v_mps: 30.0,
        };
        assert!(open_gap_accel(&p, 30.0, 0.0, 30.0, far, true, 1.1, 2.0) >= 0.0);
    }

    #[test]
    fn the_opening_gap_is_at_least_the_acc_gap() {
        let p = p();
        assert_eq!(opening_time_gap(&p, 0.6), p.acc_time_gap_s);
        assert_eq!(opening_time_gap(&p, 1.5), 1.5);
    }

    #[test]
    fn a_join_is_safe_only_at_the_followers_gap() {
        let p = p();
        let (v, t) = (30.0, 0.6);
        // At the CACC equilibrium gap t v + s_min, equal speeds: no braking.
        let eq = t * v + p.standstill_gap_m;
        let at = |g: f64, vl: f64| Leader {
            gap_m: g,
            v_mps: vl,
        };
        assert!(join_safe(&p, v, 0.0, v, at(eq, v), true, t, 2.0, 0.1));
        // Two metres short, equal speeds: the CACC collision-avoidance gains ask for
        // 0.45 × 2 / 0.1 = 9 m/s² (cut to b): unsafe.
        assert!(!join_safe(
            &p,
            v,
            0.0,
            v,
            at(eq - 2.0, v),
            true,
            t,
            2.0,
            0.1
        ));
        // At the gap but closing at 5 m/s: unsafe (the override brakes).
        assert!(!join_safe(
            &p,
            v,
            0.0,
            v,
            at(eq, v - 5.0),
            true,
            t,
            2.0,
            0.1
        ));
        // Behind a human driver: the ACC law at its gap.
        let acc_eq = cav::acc_equilibrium_gap(&p, 1.1, v);
        assert!(join_safe(
            &p,
            v,
            0.0,
            v,
            at(acc_eq, v),
            false,
            1.1,
            2.0,
            0.1
        ));
        assert!(!join_safe(
            &p,
            v,
            0.0,
            v,
            at(0.5 * acc_eq, v),
            false,
            1.1,
            2.0,
            0.1
        ));
        // Never inside the standstill margin.
        assert!(!join_safe(
            &p,
            0.0,
            0.0,
            30.0,
            at(1.0, 0.0),
            true,
            t,
            2.0,
            0.1
        ));
    }
}
