//! The lane-change decision procedure (spec 4.2, 4.3, 4.7), rule by rule, as pure functions.
//! The engine's decide phase (`crates/sim/src/decide.rs`) gathers the inputs from the
//! neighbourhood and calls these in the documented order; each rule is unit-tested here.
//!
//! | rule | function | spec / docs/model-choices.md |
//! |---|---|---|
//! | no desire within the minimum interval after a change | [`too_soon_after_change`] | 4.2 anti-oscillation |
//! | no quick return to the lane just left (γ < 1) | [`quick_return`] | 4.2 anti-oscillation |
//! | γ = γ_m + κ γ_d on the mandatory side, else the larger γ_d (left on a tie) | [`combine`] | 4.2 |
//! | organizing: toward the organized lane, none in it | [`toward`] | 4.7 |
//! | a change needs γ above the threshold | [`wants_change`] | 4.2 |
//! | the lead gap: discretionary changes must not brake behind the new leader | [`lead_acceptable`] | 4.3, 6.22 |
//! | the safe rule: nobody brakes harder than b_safe by its own law | [`crate::safegap`] | 9.1 |
//! | only a platoon leader changes: a follower splits first | [`change_now`] | 3.6.4 |
//! | BLC-Sync, BLC-Slow, discretionary sync | [`blc_target`] | 4.3 |
//! | the deadlock exceptions to BLC-Slow | [`keeps_pace`] | 4.3 \[D\] |
//! | a commanded change never brakes for it, and lets a faster follower pass | [`commanded_target`] | \[D\] (sim `command.rs`) |
//! | automation held back while the driver waits to organize | [`held_back`] | 6.20 `cav.organize_while_automated`, `cav.organize_hold` \[D\] |
//! | the whole before-lane-change step over a neighbourhood view | [`before_lane_change`] | 4.3 |
//!
//! | constant | unit | value | meaning |
//! |---|---|---|---|
//! | [`CREEP_SPEED_MPS`] | m/s | 2.23 | spec 4.3's 5 mph: BLC-Slow does not stop a vehicle beside faster traffic below it |

use crate::cav::OrganizeHold;
use crate::human::{self, HumanParams};
use crate::lanechange::{self as lcm, LaneChangeParams, Side};
use crate::safegap::{self, SafeDecel};
use crate::{Leader, Relax};

/// Creep speed of spec 4.3 (5 mph, m/s).
pub const CREEP_SPEED_MPS: f64 = 2.23;

/// The other side.
#[inline]
pub fn opposite(s: Side) -> Side {
    match s {
        Side::Left => Side::Right,
        Side::Right => Side::Left,
    }
}

/// Anti-oscillation, first part: no desire at all within the minimum interval after a change
/// (`since_s`: seconds since the last change).
#[inline]
pub fn too_soon_after_change(p: &LaneChangeParams, since_s: f64) -> bool {
    since_s < p.min_interval_s
}

/// Anti-oscillation, second part: a desire below 1 back toward the lane just left
/// (`last_side`: the side of the last change) within `return_factor` minimum intervals is
/// dropped.
#[inline]
pub fn quick_return(
    p: &LaneChangeParams,
    since_s: f64,
    gamma: f64,
    side: Side,
    last_side: Option<Side>,
) -> bool {
    gamma < 1.0 && last_side == Some(opposite(side)) && since_s < p.return_factor * p.min_interval_s
}

/// γ from the mandatory desire (if any) and the discretionary desires [left, right]:
/// γ = γ_m + κ γ_d on the mandatory side (the other side's discretionary desire is 0), else
/// the larger discretionary desire, left on a tie; `None` without any.
#[inline]
pub fn combine(
    mandatory: Option<(Side, f64)>,
    left: Option<f64>,
    right: Option<f64>,
    kappa: f64,
) -> Option<(Side, f64)> {
    match mandatory {
        Some((side, gm)) => {
            let gd = if side == Side::Left { left } else { right }.unwrap_or(0.0);
            Some((side, gm + kappa * gd))
        }
        None => match (left, right) {
            (None, None) => None,
            (Some(l), None) => Some((Side::Left, l)),
            (None, Some(r)) => Some((Side::Right, r)),
            (Some(l), Some(r)) => Some(if r > l {
                (Side::Right, r)
            } else {
                (Side::Left, l)
            }),
        },
    }
}

/// The side from `lane` toward `target` (lanes counted from the right), `None` when there.
#[inline]
pub fn toward(lane: u32, target: u32) -> Option<Side> {
    match lane.cmp(&target) {
        std::cmp::Ordering::Less => Some(Side::Left),
        std::cmp::Ordering::Greater => Some(Side::Right),
        std::cmp::Ordering::Equal => None,
    }
}

/// A desire leads to a lane-change attempt only above the driver's threshold.
#[inline]
pub fn wants_change(p: &LaneChangeParams, gamma: f64) -> bool {
    gamma > p.threshold
}

/// The lead gap is acceptable: the gap rule holds (`gap_ok`, `accept_lead_gap`) and, for a
/// discretionary change, the driver need not brake behind the new leader (`a_ant` ≥ 0). A
/// mandatory change, and an organizing one when `regardless` (`cav.organize_regardless_of_speed`),
/// skip the second part.
#[inline]
pub fn lead_acceptable(gap_ok: bool, mandatory: bool, regardless: bool, a_ant: f64) -> bool {
    gap_ok && (mandatory || regardless || a_ant >= 0.0)
}

/// Change in this step: both gaps acceptable and not a CACC follower (a follower splits first).
#[inline]
pub fn change_now(lead_ok: bool, lag_ok: bool, follower: bool) -> bool {
    lead_ok && lag_ok && !follower
}

/// The target acceleration in BLC (before the change; `a_cur` behind the current leader,
/// `a_ant` behind the target-lane leader with relaxed gaps, `comfort` the comfortable
/// deceleration, negative): changing now or nothing to adapt, `a_cur`; mandatory with the lag
/// gap open, BLC-Sync min(a_cur, max(a_ant, comfort)); mandatory with the lag gap closed and
/// `slow` (γ above the slow-down desire and no exception), BLC-Slow min(a_cur, comfort);
/// discretionary with only the lead gap closed, the sync without braking, min(a_cur,
/// max(a_ant, 0)).
#[inline]
#[allow(clippy::too_many_arguments)]
pub fn blc_target(
    a_cur: f64,
    a_ant: f64,
    comfort: f64,
    change: bool,
    mandatory: bool,
    lead_ok: bool,
    lag_ok: bool,
    slow: bool,
) -> f64 {
    if change {
        a_cur
    } else if mandatory {
        if lag_ok {
            a_cur.min(a_ant.max(comfort))
        } else if slow {
            a_cur.min(comfort)
        } else {
            a_cur
        }
    } else if lag_ok && !lead_ok {
        a_cur.min(a_ant.max(0.0))
    } else {
        a_cur
    }
}

/// The exceptions to BLC-Slow \[D\]: the target-lane follower is yielding to this vehicle
/// (slowing down too would leave both waiting for the other), or it is faster (it passes by
/// itself) and this vehicle is in an acceleration lane or already below the creep speed.
#[inline]
pub fn keeps_pace(follower_yields: bool, follower_v: f64, v: f64, in_accel_lane: bool) -> bool {
    follower_yields || (follower_v > v && (v < CREEP_SPEED_MPS || in_accel_lane))
}

/// A commanded change (`commanded`) never brakes for the change: BLC-Sync and BLC-Slow may
/// not take `target` below min(a_cur, 0), the driver's own car following; and while a faster
/// target-lane follower (`follower_faster`) closes the lag gap it holds its speed,
/// min(a_cur, 0), so that the follower goes by instead of running alongside \[D\] (sim
/// `command.rs`). Other changes: `target` unchanged.
#[inline]
pub fn commanded_target(
    target: f64,
    a_cur: f64,
    commanded: bool,
    lag_ok: bool,
    follower_faster: bool,
) -> f64 {
    if !commanded {
        target
    } else if !lag_ok && follower_faster {
        a_cur.min(0.0)
    } else {
        target.max(a_cur.min(0.0))
    }
}

/// What an automated CAV whose driver waits for a gap toward its organized lane sees of its
/// wait (6.20, `cav.organize_hold`): the inputs of [`held_back`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HoldView {
    /// The lag gap is acceptable (spec 4.3).
    pub lag_ok: bool,
    /// The anticipated acceleration behind the target-lane leader (m/s²).
    pub a_ant: f64,
    /// The target-lane leader's rear is ahead of the CAV's front, or there is none.
    pub leader_ahead: bool,
    /// Own speed (m/s).
    pub v: f64,
    /// How long (s) the CAV has waited below [`CREEP_SPEED_MPS`] in this wait.
    pub waited_slow_s: f64,
}

/// An automated CAV whose driver waits for a gap toward its organized lane: the driver's
/// discretionary synchronization of spec 4.3 through the automation, i.e. with the lag gap
/// open, no acceleration beyond what the target-lane leader allows (`a_ant`), never braking
/// for it. `hold` says when it applies (docs/model-choices.md 6.20):
///
/// | `hold` | applies while the lag gap is acceptable and |
/// |---|---|
/// | `Off` | never (the automation drives on) |
/// | `Always` | always (6.20 as first built; can deadlock at standstill) |
/// | `LeaderAhead` | the target-lane leader's rear is ahead of the CAV's front (the 2026-12 fix: released beside an overlapping leader at every speed) |
/// | `Narrow` | at or above the creep speed always; below it only with the leader ahead, and for at most `timeout_s` of waiting below it |
///
/// `Narrow` cannot hold a CAV still for more than `timeout_s`: a mutual wait (the target-lane
/// leader waiting for the CAV's own lag gap) ends when the CAV drives on.
#[inline]
pub fn held_back(a_auto: f64, hold: OrganizeHold, w: &HoldView, timeout_s: f64) -> f64 {
    let applies = w.lag_ok
        && match hold {
            OrganizeHold::Off => false,
            OrganizeHold::Always => true,
            OrganizeHold::LeaderAhead => w.leader_ahead,
            OrganizeHold::Narrow => {
                w.v >= CREEP_SPEED_MPS || (w.leader_ahead && w.waited_slow_s < timeout_s)
            }
        };
    if applies {
        a_auto.min(w.a_ant.max(0.0))
    } else {
        a_auto
    }
}

/// What a driver with a lane-change desire sees (spec 4.3): itself, the way ahead in its lane,
/// the gap in the target lane. Assembled by the engine's decide phase.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlcView {
    /// Own speed (m/s) and the acceleration of the last step (m/s²).
    pub v: f64,
    pub a: f64,
    /// Own desired speed in the current lane and in the target lane (m/s).
    pub v_des: f64,
    pub v_des_target: f64,
    /// The leader in the current lane, or the end of the lane as a standing leader.
    pub leader: Option<Leader>,
    /// Car-following relaxation in force (spec 4.6).
    pub relax: Relax,
    /// The target lane's leader: gap from own front to its rear (m), its speed.
    pub target_leader: Option<Leader>,
    /// The target lane's follower, if any.
    pub target_follower: Option<TargetFollower>,
    /// The desire: its side is implied; mandatory or not, and its strength γ.
    pub mandatory: bool,
    pub gamma: f64,
    /// An organizing move that accepts the lead gap regardless of the speed difference
    /// (`cav.organize_regardless_of_speed`, docs/model-choices.md 6.22).
    pub organize_regardless: bool,
    /// A CACC follower must split from its string before it changes (spec 3.6.4).
    pub must_split: bool,
    /// The vehicle is in an acceleration lane.
    pub in_accel_lane: bool,
    /// A commanded change (`sim::Command::ChangeLane`): like a merge from an acceleration
    /// lane, it never drops back (BLC-Slow) behind a faster target-lane follower.
    pub commanded: bool,
    /// The safe rule's decelerations (spec 9.1); `None` under the published rule (spec 4.3).
    pub safe: Option<SafeDecel>,
}

/// The target lane's follower as the lag-gap rule sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TargetFollower {
    /// Gap from its front to own rear (m).
    pub gap_m: f64,
    pub v_mps: f64,
    /// It is yielding to this vehicle.
    pub yields: bool,
    /// Its acceleration by its own law with this vehicle as its new leader (spec 9.1); only
    /// read under the safe rule (the engine computes it only then).
    pub a_after: f64,
}

/// The outcome of the before-lane-change step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Blc {
    /// The acceleration to apply (smoothed, spec 2.4), m/s².
    pub accel: f64,
    /// Change lanes in this step.
    pub change: bool,
    /// The lead and lag gaps are acceptable.
    pub lead_ok: bool,
    pub lag_ok: bool,
    /// The anticipated acceleration behind the target-lane leader (m/s²).
    pub a_ant: f64,
    /// The target-lane leader's rear is ahead of the own front (or there is none).
    pub target_ahead: bool,
}

/// The before-lane-change step (spec 4.3), in order: the acceleration behind the current
/// leader and, with relaxed gaps, behind the target-lane leader; gap acceptance
/// ([`lead_acceptable`], the lag rule; under the safe rule both also need
/// [`safegap::brakes_safely`], spec 9.1); [`change_now`]; BLC-Slow only for a mandatory desire
/// above the slow-down threshold with the lag gap closed and no [`keeps_pace`] exception;
/// the target from [`blc_target`], smoothed.
pub fn before_lane_change(h: &HumanParams, lc: &LaneChangeParams, w: &BlcView) -> Blc {
    let a_cur = human::target_accel(h, w.v, w.v_des, w.leader, w.relax);
    let a_ant = human::target_accel(h, w.v, w.v_des_target, w.target_leader, lcm::gap_relax(lc));
    // spec 9.1: the bound of this change, if the safe rule applies.
    let bound = w
        .safe
        .map(|s| s.bound(safegap::urgent(w.mandatory, w.gamma)));
    let lead_ok = match w.target_leader {
        None => true,
        Some(l) => lead_acceptable(
            lcm::accept_lead_gap(h, lc, l.gap_m, w.v, l.v_mps)
                && bound.is_none_or(|b| safegap::brakes_safely(a_ant, b)),
            w.mandatory,
            w.organize_regardless,
            a_ant,
        ),
    };
    let lag_ok = match w.target_follower {
        None => true,
        Some(f) => {
            lcm::accept_lag_gap(h, lc, f.gap_m, w.v, f.v_mps, a_ant)
                && bound.is_none_or(|b| safegap::brakes_safely(f.a_after, b))
        }
    };
    let change = change_now(lead_ok, lag_ok, w.must_split);
    let slow = w.mandatory
        && !lag_ok
        && w.gamma > lc.slow_down_desire
        && !w
            .target_follower
            .is_some_and(|f| keeps_pace(f.yields, f.v_mps, w.v, w.in_accel_lane || w.commanded));
    let target = blc_target(
        a_cur,
        a_ant,
        h.comfort_decel,
        change,
        w.mandatory,
        lead_ok,
        lag_ok,
        slow,
    );
    let faster = w.target_follower.is_some_and(|f| f.v_mps > w.v);
    let target = commanded_target(target, a_cur, w.commanded, lag_ok, faster);
    Blc {
        accel: human::smooth_accel(w.a, target, h.smoothing),
        change,
        lead_ok,
        lag_ok,
        a_ant,
        target_ahead: w.target_leader.is_none_or(|l| l.gap_m > 0.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Side::{Left, Right};

    fn p() -> LaneChangeParams {
        LaneChangeParams::default()
    }

    #[test]
    fn no_desire_within_the_minimum_interval() {
        let p = p();
        assert!(too_soon_after_change(&p, 0.9 * p.min_interval_s));
        assert!(!too_soon_after_change(&p, p.min_interval_s));
    }

    #[test]
    fn no_quick_return_below_full_desire() {
        let (p, t) = (p(), p().min_interval_s * 1.01);
        assert!(quick_return(&p, t, 0.5, Left, Some(Right)));
        assert!(
            !quick_return(&p, t, 1.0, Left, Some(Right)),
            "γ = 1 returns"
        );
        assert!(
            !quick_return(&p, t, 0.5, Left, Some(Left)),
            "same side again"
        );
        assert!(!quick_return(
            &p,
            p.return_factor * p.min_interval_s,
            0.5,
            Left,
            Some(Right)
        ));
    }

    #[test]
    fn mandatory_adds_the_discretionary_part_of_its_side() {
        assert_eq!(
            combine(Some((Left, 0.5)), Some(0.4), Some(0.9), 0.5),
            Some((Left, 0.7))
        );
        assert_eq!(
            combine(Some((Right, 0.5)), Some(0.4), None, 0.5),
            Some((Right, 0.5))
        );
    }

    #[test]
    fn discretionary_takes_the_larger_side_left_on_a_tie() {
        assert_eq!(combine(None, Some(0.3), Some(0.4), 0.5), Some((Right, 0.4)));
        assert_eq!(combine(None, Some(0.4), Some(0.4), 0.5), Some((Left, 0.4)));
        assert_eq!(combine(None, None, Some(0.2), 0.5), Some((Right, 0.2)));
        assert_eq!(combine(None, None, None, 0.5), None);
    }

    #[test]
    fn organizing_moves_toward_the_lane_and_stops_in_it() {
        assert_eq!(toward(0, 2), Some(Left));
        assert_eq!(toward(2, 0), Some(Right));
        assert_eq!(toward(1, 1), None);
    }

    #[test]
    fn a_desire_must_pass_the_threshold() {
        let p = p();
        assert!(wants_change(&p, p.threshold + 1e-9));
        assert!(!wants_change(&p, p.threshold));
    }

    #[test]
    fn discretionary_changes_do_not_brake_behind_the_new_leader() {
        assert!(!lead_acceptable(true, false, false, -0.1));
        assert!(lead_acceptable(true, true, false, -0.1), "mandatory");
        assert!(
            lead_acceptable(true, false, true, -0.1),
            "organizing regardless"
        );
        assert!(
            !lead_acceptable(false, true, true, 1.0),
            "the gap rule always holds"
        );
    }

    #[test]
    fn a_cacc_follower_splits_before_it_changes() {
        assert!(change_now(true, true, false));
        assert!(!change_now(true, true, true));
        assert!(!change_now(true, false, false));
    }

    #[test]
    fn blc_sync_slow_and_discretionary_sync() {
        let blc = |change, mandatory, lead_ok, lag_ok, slow| {
            blc_target(1.0, -3.0, -2.0, change, mandatory, lead_ok, lag_ok, slow)
        };
        assert_eq!(blc(true, true, true, true, true), 1.0, "changing: a_cur");
        assert_eq!(
            blc(false, true, false, true, false),
            -2.0,
            "sync, no harder than comfort"
        );
        assert_eq!(
            blc(false, true, false, false, true),
            -2.0,
            "slow: drop back"
        );
        assert_eq!(blc(false, true, false, false, false), 1.0, "no slow: a_cur");
        assert_eq!(
            blc(false, false, false, true, false),
            0.0,
            "discretionary sync: no braking"
        );
        assert_eq!(
            blc(false, false, true, false, true),
            1.0,
            "discretionary, lag closed"
        );
    }

    #[test]
    fn blc_slow_spares_a_yielded_to_or_creeping_driver() {
        assert!(keeps_pace(true, 0.0, 5.0, false), "the follower yields");
        assert!(
            keeps_pace(false, 3.0, 2.0, false),
            "below creep speed, faster follower"
        );
        assert!(keeps_pace(false, 9.0, 8.0, true), "in an acceleration lane");
        assert!(!keeps_pace(false, 9.0, 8.0, false));
        assert!(!keeps_pace(false, 1.0, 2.0, true), "a slower follower");
    }

    fn hold(lag_ok: bool, a_ant: f64, leader_ahead: bool, v: f64, waited: f64) -> HoldView {
        HoldView {
            lag_ok,
            a_ant,
            leader_ahead,
            v,
            waited_slow_s: waited,
        }
    }

    #[test]
    fn automation_holds_back_for_the_target_lane_without_braking() {
        use OrganizeHold::*;
        for h in [Always, LeaderAhead, Narrow] {
            assert_eq!(
                held_back(1.0, h, &hold(true, 0.5, true, 20.0, 0.0), 10.0),
                0.5
            );
            assert_eq!(
                held_back(1.0, h, &hold(true, -2.0, true, 20.0, 0.0), 10.0),
                0.0
            );
            // Never braking for it, and no hold with the lag gap closed.
            assert_eq!(
                held_back(-1.0, h, &hold(true, -2.0, true, 20.0, 0.0), 10.0),
                -1.0
            );
            assert_eq!(
                held_back(1.0, h, &hold(false, -2.0, true, 20.0, 0.0), 10.0),
                1.0
            );
        }
        assert_eq!(
            held_back(1.0, Off, &hold(true, -2.0, true, 20.0, 0.0), 10.0),
            1.0
        );
    }

    #[test]
    fn the_narrow_hold_is_released_only_near_standstill() {
        use OrganizeHold::*;
        // A target-lane leader alongside at speed: held, as first built (`Always`); the
        // 2026-12 fix (`LeaderAhead`) released it at every speed.
        let alongside = hold(true, -2.0, false, 10.0, 0.0);
        assert_eq!(held_back(1.0, Always, &alongside, 10.0), 0.0);
        assert_eq!(held_back(1.0, LeaderAhead, &alongside, 10.0), 1.0);
        assert_eq!(held_back(1.0, Narrow, &alongside, 10.0), 0.0);
        // Below the creep speed, beside it: released.
        let creeping = hold(true, -2.0, false, 1.0, 0.0);
        assert_eq!(held_back(1.0, Narrow, &creeping, 10.0), 1.0);
        assert_eq!(held_back(1.0, Always, &creeping, 10.0), 0.0);
        // Below the creep speed with the leader ahead: held until the timeout, then not.
        assert_eq!(
            held_back(1.0, Narrow, &hold(true, -2.0, true, 0.0, 9.9), 10.0),
            0.0
        );
        assert_eq!(
            held_back(1.0, Narrow, &hold(true, -2.0, true, 0.0, 10.0), 10.0),
            1.0
        );
        assert_eq!(
            held_back(1.0, Always, &hold(true, -2.0, true, 0.0, 99.0), 10.0),
            0.0
        );
        // At speed the timeout does not apply.
        assert_eq!(
            held_back(1.0, Narrow, &hold(true, -2.0, true, 5.0, 99.0), 10.0),
            0.0
        );
    }

    /// A driver at 20 m/s wanting to move right: its lane clear ahead, a target-lane leader
    /// 40 m ahead at the same speed, and (unless changed) a follower `lag` m behind.
    fn blc_scene(lag: Option<f64>, mandatory: bool, gamma: f64) -> BlcView {
        BlcView {
            v: 20.0,
            a: 0.0,
            v_des: 25.0,
            v_des_target: 25.0,
            leader: None,
            relax: Relax::NONE,
            target_leader: Some(Leader {
                gap_m: 40.0,
                v_mps: 20.0,
            }),
            target_follower: lag.map(|g| TargetFollower {
                gap_m: g,
                v_mps: 20.0,
                yields: false,
                a_after: 0.0,
            }),
            mandatory,
            gamma,
            organize_regardless: false,
            must_split: false,
            in_accel_lane: false,
            commanded: false,
            safe: None,
        }
    }

    fn blc(w: &BlcView) -> Blc {
        before_lane_change(&HumanParams::default(), &p(), w)
    }

    #[test]
    fn blc_changes_at_once_when_both_gaps_are_open() {
        let out = blc(&blc_scene(Some(40.0), false, 0.5));
        assert!(out.change && out.lead_ok && out.lag_ok);
    }

    #[test]
    fn blc_a_cacc_follower_splits_before_it_changes() {
        let out = blc(&BlcView {
            must_split: true,
            ..blc_scene(Some(40.0), false, 0.5)
        });
        assert!(!out.change && out.lead_ok && out.lag_ok);
    }

    #[test]
    fn blc_slow_brakes_comfortably_for_a_closed_lag_gap() {
        let h = HumanParams::default();
        let out = blc(&blc_scene(Some(1.0), true, 1.0));
        assert!(!out.change && !out.lag_ok);
        assert_eq!(
            out.accel,
            human::smooth_accel(0.0, h.comfort_decel, h.smoothing)
        );
    }

    #[test]
    fn blc_slow_waits_when_the_follower_yields() {
        let mut w = blc_scene(Some(1.0), true, 1.0);
        w.target_follower = w
            .target_follower
            .map(|f| TargetFollower { yields: true, ..f });
        assert!(
            blc(&w).accel > 0.0,
            "no BLC-Slow: free acceleration toward v_des"
        );
    }

    #[test]
    fn blc_a_weak_mandatory_desire_does_not_slow_down() {
        let out = blc(&blc_scene(Some(1.0), true, 0.5 * p().slow_down_desire));
        assert!(!out.change && out.accel > 0.0);
    }

    /// spec 9.1: the same cut-in (a follower 30 m back at 30 m/s, the changer at 26 m/s, whose
    /// own law asks for more than 6 m/s² after the change) is made under the published rule
    /// and refused under the safe rule; a follower that need not brake hard is no obstacle.
    #[test]
    fn blc_the_safe_rule_refuses_a_cut_in_the_published_rule_accepts() {
        let h = HumanParams::default();
        let changer = Leader {
            gap_m: 30.0,
            v_mps: 26.0,
        };
        let a_after =
            crate::safegap::human_follower_accel(&h, &p(), 30.0, h.desired_speed, changer);
        let mut w = blc_scene(Some(30.0), false, 0.5);
        w.v = 26.0;
        w.target_leader = None;
        w.target_follower = Some(TargetFollower {
            gap_m: 30.0,
            v_mps: 30.0,
            yields: false,
            a_after,
        });
        let published = blc(&w);
        assert!(published.change && published.lag_ok);
        let safe = SafeDecel {
            normal_mps2: 3.0,
            mandatory_mps2: 4.0,
        };
        w.safe = Some(safe);
        let refused = blc(&w);
        assert!(!refused.change && !refused.lag_ok && refused.lead_ok);
        // The same follower when it would only need 2.9 m/s².
        w.target_follower = w
            .target_follower
            .map(|f| TargetFollower { a_after: -2.9, ..f });
        assert!(blc(&w).change);
        // The lead gap: the changer's own law behind its new leader (a_ant) is bounded too.
        let mut m = blc_scene(None, true, 0.5);
        m.target_leader = Some(Leader {
            gap_m: 30.0,
            v_mps: 14.0,
        });
        let open = blc(&m);
        assert!(open.change && open.a_ant < -3.0, "a_ant = {}", open.a_ant);
        m.safe = Some(safe);
        assert!(
            !blc(&m).lead_ok,
            "a mandatory desire below 1: b_safe = 3 m/s²"
        );
        m.gamma = 1.0;
        assert!(!blc(&m).lead_ok, "γ = 1: b_safe,m = 4 m/s² < 4.13");
    }

    /// A commanded change (mandatory, γ = 1) does not drop back behind a faster follower.
    #[test]
    fn blc_a_commanded_change_does_not_slow_for_a_faster_follower() {
        let mut w = blc_scene(Some(1.0), true, 1.0);
        w.target_follower = w
            .target_follower
            .map(|f| TargetFollower { v_mps: 30.0, ..f });
        assert!(blc(&w).accel < 0.0, "BLC-Slow");
        w.commanded = true;
        let out = blc(&w);
        assert!(
            !out.change && out.accel == 0.0,
            "holds its speed: {}",
            out.accel
        );
        assert_eq!(commanded_target(-2.0, 1.0, true, false, true), 0.0);
        assert_eq!(
            commanded_target(-2.0, -0.5, true, false, true),
            -0.5,
            "own law brakes"
        );
        assert_eq!(
            commanded_target(-2.0, 1.0, true, true, false),
            0.0,
            "no sync braking"
        );
        assert_eq!(commanded_target(0.5, 1.0, true, true, false), 0.5);
        assert_eq!(
            commanded_target(1.0, 1.0, true, false, true),
            0.0,
            "not alongside"
        );
        assert_eq!(
            commanded_target(-2.0, 1.0, false, false, true),
            -2.0,
            "not commanded"
        );
    }
}
