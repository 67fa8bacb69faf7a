//! Phase 4 (lane changes): accepted changes are applied instantaneously (spec 4.4, 6.14),
//! front to back and lane by lane, each re-checked against the positions after integration
//! and after the changes already applied in this step; under the safe rule (spec 9.1) the
//! re-check includes the safe decelerations of both gaps.

use crate::config::Config;
use crate::events::Event;
use crate::state::NONE;
use crate::state::{Clock, RoadState, Scratch, Traffic, Watch};
use crate::vehicle::{Mode, Relaxation};
use platoonsim_model::cav::CavParams;
use platoonsim_model::cooperative as coop;
use platoonsim_model::human;
use platoonsim_model::lanechange::{self as lcm, Side};
use platoonsim_model::safegap;
use platoonsim_model::Leader;

/// Phase 4: reads the clock, the road and the decisions; writes the vehicles and lanes, the
/// lane-change bookkeeping and, with an observer, the step's events.
pub(crate) fn apply_lane_changes(
    cfg: &Config,
    clock: &Clock,
    origin_m: f64,
    road: &RoadState,
    traffic: &mut Traffic,
    scratch: &mut Scratch,
    watch: &mut Watch,
) {
    // Locals: a push does not make the loop reload the lane lists and the decisions.
    let Traffic { lanes, .. } = &*traffic;
    let Scratch {
        decisions,
        change_list,
        ..
    } = &mut *scratch;
    let decisions = &decisions[..];
    change_list.clear();
    for lane in lanes.iter() {
        for &s in lane {
            if let Some(side) = decisions[s as usize].change {
                change_list.push((s, side));
            }
        }
    }
    for i in 0..scratch.change_list.len() {
        let (s, side) = scratch.change_list[i];
        try_change(cfg, clock, origin_m, road, traffic, scratch, watch, s, side);
    }
}

/// One accepted change, re-checked on the current positions.
#[allow(clippy::too_many_arguments)]
fn try_change(
    cfg: &Config,
    clock: &Clock,
    origin_m: f64,
    road: &RoadState,
    traffic: &mut Traffic,
    scratch: &mut Scratch,
    watch: &mut Watch,
    s: u32,
    side: Side,
) {
    let step = clock.step;
    let v = &traffic.vehicles[s as usize];
    let from = v.lane as usize;
    let to = match side {
        Side::Left => from + 1,
        Side::Right => from.wrapping_sub(1),
    };
    if to >= traffic.lanes.len() || !road.geom.can_enter(to as u32, v.x) {
        return;
    }
    // Position in the target lane: first vehicle not strictly ahead.
    let target = &traffic.lanes[to];
    let j = target.partition_point(|&o| traffic.vehicles[o as usize].x > v.x);
    let tl = if j > 0 { target[j - 1] } else { NONE };
    let tf = target.get(j).copied().unwrap_or(NONE);
    // No change next to a vehicle that has just changed lanes (spec 4.2).
    for o in [tl, tf] {
        if o != NONE && scratch.changed_this_step[o as usize] == step {
            return;
        }
    }
    let lead = (tl != NONE).then(|| {
        let l = &traffic.vehicles[tl as usize];
        Leader {
            gap_m: l.rear() - v.x,
            v_mps: l.v,
        }
    });
    if let Some(l) = lead {
        if !lcm::accept_lead_gap(&v.driver.human, &v.driver.lc, l.gap_m, v.v, l.v_mps) {
            return;
        }
    }
    // spec 9.1: the bound of this change under the safe rule.
    let bound =
        crate::decide::safe_decel(cfg).map(|b| b.bound(scratch.decisions[s as usize].urgent));
    if tf != NONE || (bound.is_some() && lead.is_some()) {
        let a_ant = human::target_accel(
            &v.driver.human,
            v.v,
            road.desired_speed_in(
                v.driver.human.desired_speed,
                to,
                scratch.sensed[s as usize].here.right,
            ),
            lead,
            lcm::gap_relax(&v.driver.lc),
        );
        if let Some(b) = bound {
            if lead.is_some() && !safegap::brakes_safely(a_ant, b) {
                return;
            }
        }
        if tf != NONE {
            let f = &traffic.vehicles[tf as usize];
            let changer = Leader {
                gap_m: v.rear() - f.x,
                v_mps: v.v,
            };
            if !lcm::accept_lag_gap(
                &v.driver.human,
                &v.driver.lc,
                changer.gap_m,
                v.v,
                f.v,
                a_ant,
            ) {
                return;
            }
            if let Some(b) = bound {
                let a_f = crate::decide::follower_accel_after(
                    cfg,
                    road,
                    &scratch.sensed,
                    clock.dt,
                    f,
                    tf,
                    v,
                    changer,
                );
                if !safegap::brakes_safely(a_f, b) {
                    return;
                }
            }
        }
    }
    // A cooperative change (spec 9.2) stays safe by construction on the updated positions:
    // neither new pair needs braking harder than b_co under its own automated law.
    let cooperative = scratch.decisions[s as usize].coop;
    if cooperative && !coop_still_safe(&cfg.cav, clock.dt, road, traffic, scratch, s, to, tl, tf) {
        return;
    }
    // Execute.
    let k = traffic.lanes[from]
        .iter()
        .position(|&o| o == s)
        .expect("vehicle is in its lane");
    traffic.lanes[from].remove(k);
    traffic.lanes[to].insert(j, s);
    scratch.changed_this_step[s as usize] = step;
    let v = &mut traffic.vehicles[s as usize];
    v.lane = to as u32;
    v.mode = Mode::Cf;
    if cooperative {
        // Under automation: no hand-over, no relaxation (spec 9.2).
        v.lcs.coop_count = v.lcs.coop_count.saturating_add(1);
    } else {
        v.lcs.relax = Relaxation::since(step + 1);
    }
    v.lcs.last_step = step;
    v.lcs.last_side = Some(side);
    v.lcs.count += 1;
    if watch.observing {
        let (id, kind, x) = (v.id, v.kind, v.x);
        watch.events.push(Event::LaneChange {
            t_s: crate::record::step_time(step + 1, clock.dt),
            id,
            kind,
            from: from as u32,
            to: to as u32,
            x_m: x + origin_m,
            reason: scratch.decisions[s as usize].why,
            cooperative,
        });
    }
    // The new follower relaxes (RCF), unless it is an automated CAV (spec 4.6); under the
    // field law an automated one resets its gap reference to the actual gap and reopens it
    // (`cav::cut_in_time_gap`; docs/cacc-field.md).
    if tf != NONE {
        let gap = traffic.vehicles[s as usize].rear() - traffic.vehicles[tf as usize].x;
        let f = &mut traffic.vehicles[tf as usize];
        if !f.automated() {
            f.lcs.relax = Relaxation::since(step + 1);
            if matches!(f.mode, Mode::Ycf { .. }) {
                f.mode = Mode::Cf;
            }
        } else {
            f.cacc.time_gap_s =
                platoonsim_model::cav::cut_in_time_gap(&cfg.cav, f.cacc.time_gap_s, gap, f.v);
        }
    }
}

/// [`try_change`]'s re-check of a cooperative change (spec 9.2) on the current positions: the
/// new follower `tf` (it must still be an automated CAV) behind the changer `s`, and the changer
/// behind the new leader `tl` within sensor range, each under its own automated law at its
/// effective time gap, need no braking harder than b_co (`cooperative::join_safe`).
#[allow(clippy::too_many_arguments)]
fn coop_still_safe(
    cav: &CavParams,
    dt: f64,
    road: &RoadState,
    traffic: &Traffic,
    scratch: &Scratch,
    s: u32,
    to: usize,
    tl: u32,
    tf: u32,
) -> bool {
    let gap = |v: &crate::vehicle::Vehicle| {
        if v.cacc.time_gap_s > 0.0 {
            v.cacc.time_gap_s
        } else {
            v.cacc.gap_s
        }
    };
    let b_co = cav.cooperative_gap_decel_mps2;
    let v = &traffic.vehicles[s as usize];
    if tf != NONE {
        let f = &traffic.vehicles[tf as usize];
        if !f.automated() {
            return false;
        }
        let f_des = road.desired_speed_in(
            f.driver.human.desired_speed,
            to,
            scratch.sensed[tf as usize].here.right,
        );
        let lag = Leader {
            gap_m: v.rear() - f.x,
            v_mps: v.v,
        };
        if !coop::join_safe(cav, f.v, f.a, f_des, lag, true, gap(f), b_co, dt) {
            return false;
        }
    }
    if tl != NONE {
        let l = &traffic.vehicles[tl as usize];
        let lead = Leader {
            gap_m: l.rear() - v.x,
            v_mps: l.v,
        };
        if lead.gap_m <= cav.sensor_range_m {
            let v_des = road.desired_speed_in(
                v.driver.human.desired_speed,
                to,
                scratch.sensed[s as usize].here.right,
            );
            if !coop::join_safe(cav, v.v, v.a, v_des, lead, l.is_cav(), gap(v), b_co, dt) {
                return false;
            }
        }
    }
    true
}
