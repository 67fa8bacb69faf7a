//! Phase 1 (sense): neighbours, CACC links, platoon positions and platoon statistics.

use crate::state::{RoadState, Scratch, Sensed, Traffic, NONE};
use crate::vehicle::Vehicle;
use platoonsim_model::cav::CavParams;

/// Phase 1: reads the vehicles and lanes and the road's tables, writes the scratch (sensed
/// neighbours, step-start x and v) and the vehicles' string memberships and platoon
/// statistics.
pub(crate) fn sense(p: &CavParams, traffic: &mut Traffic, road: &RoadState, scratch: &mut Scratch) {
    let n = traffic.vehicles.len();
    if scratch.sensed.len() < n {
        scratch.sensed.resize(n, Sensed::default());
        scratch.changed_this_step.resize(n, u64::MAX);
    }
    let n_lanes = traffic.lanes.len();
    scratch.lane_xv.resize(n_lanes, Vec::new());
    let range = p.sensor_range_m;
    let t_far = p.cacc_tg_band_s[1];
    let slack = p.standstill_gap_m + p.speed_control_min_gap_m;
    // Pass A, per lane back to front: (x, v) copy, own-lane neighbours, CAV ahead, the
    // candidate CACC link to the leader (`linked` holds it until pass B) and the size of
    // the sub-string each vehicle leads under the previous memberships.
    // Local slices: the loop reads and writes these arrays once per vehicle.
    let Traffic {
        lanes, vehicles, ..
    } = &*traffic;
    let Scratch {
        lane_xv, sensed, ..
    } = &mut *scratch;
    let vehicles = &vehicles[..];
    // As long as `vehicles` (resized above): a slot that indexes `vehicles` indexes this
    // too, so the compiler drops the second bounds check.
    let sensed = &mut sensed[..vehicles.len()];
    for (lane, xv) in lanes.iter().zip(lane_xv.iter_mut()) {
        let n = lane.len();
        xv.clear();
        // Sentinels behind every position: the merge sweeps below stop on the first one
        // without a length check, and read up to two entries beyond the cursor.
        xv.resize(n + SENTINELS, (f64::NEG_INFINITY, 0.0));
        // The vehicles' part, as long as the lane (no bounds check on `xv[k]`).
        let xv = &mut xv[..n];
        let mut follower = NONE;
        let mut f_pred = crate::vehicle::NEVER;
        let mut f_cand = false;
        let mut f_size = 0u32;
        for k in (0..n).rev() {
            let s = lane[k];
            let ld = if k > 0 { lane[k - 1] } else { NONE };
            let v = &vehicles[s as usize];
            xv[k] = (v.x, v.v);
            let lv = (k > 0).then(|| &vehicles[ld as usize]);
            let ahead = lv.is_some_and(|lv| lv.is_cav() && lv.rear() - v.x <= range);
            let cand = ahead
                && v.automated()
                && lv.is_some_and(|lv| lv.rear() - v.x <= t_far * v.v + slack);
            let size = if f_cand && f_pred == v.id {
                1 + f_size
            } else {
                1
            };
            let t = &mut sensed[s as usize];
            t.nb.idx = k as u32;
            t.nb.leader = ld;
            t.nb.follower = follower;
            t.cav_ahead = ahead;
            t.linked = cand;
            t.sub_size = size;
            follower = s;
            f_pred = v.cacc.pred;
            f_cand = cand;
            f_size = size;
        }
    }
    platoons(p, traffic, road, scratch);
}

/// Pass B, per lane front to back: leaders and followers in the adjacent lanes (merge
/// sweeps), `here` (the geometry's step function, here.rs), CACC memberships and platoon
/// positions, statistics.
///
/// CACC strings (spec 3.6) and platoon statistics (spec 5.1.6, 6.15).
///
/// A *candidate link* exists when an automated CAV follows a CAV within sensor range and is
/// not in speed regulation (time gap ≤ 2 s, spec 6.15). Membership is sticky [D]: a CAV
/// stays in the string of the predecessor it joined while the candidate link to that same
/// vehicle lasts; a new link is a *join*, allowed only if the predecessor's position plus
/// the size of the joining sub-string is at most `max_platoon`. Otherwise the CAV leads its
/// own string and keeps the inter-platoon gap. (Re-splitting merged strings at 10 by
/// recounting positions every step, spec 3.6.6, moved every follower behind a merge or a
/// broken link to a new gap at once; the resulting braking waves halved 100 % CAV
/// capacity.) A member's position is its predecessor's + 1; a string is a platoon.
///
/// Statistics (spec 5.1.6). Paper definition [S]: "when a CAV immediately follows
/// another CAV, it automatically starts to form a platoon", and P_P ≈ 1 − (1 − p)² "given
/// the subject vehicle is a CAV, its leader and/or follower is a CAV": a link is an
/// automated CAV directly behind a CAV within sensor range. Strict variant (spec 6.15):
/// only string members (not in speed regulation). Runs longer than `max` count as
/// platoons of at most `max`.
fn platoons(p: &CavParams, traffic: &mut Traffic, road: &RoadState, scratch: &mut Scratch) {
    let max = p.max_platoon.max(1);
    let Traffic {
        lanes, vehicles, ..
    } = traffic;
    let Scratch {
        lane_xv, sensed, ..
    } = scratch;
    let here_tables = &road.here_tables;
    let n_lanes = lanes.len();
    let vehicles = &mut vehicles[..];
    // As long as `vehicles` (see pass A).
    let sensed = &mut sensed[..vehicles.len()];
    for l in 0..n_lanes {
        let lane = &lanes[l];
        let xs = &lane_xv[l];
        let empty: &[u32] = &[];
        let no_xv: &[(f64, f64)] = &[(f64::NEG_INFINITY, 0.0); SENTINELS];
        let (llane, lx) = if l + 1 < n_lanes {
            (&lanes[l + 1][..], &lane_xv[l + 1][..])
        } else {
            (empty, no_xv)
        };
        let (rlane, rx) = if l > 0 {
            (&lanes[l - 1][..], &lane_xv[l - 1][..])
        } else {
            (empty, no_xv)
        };
        // Merge-sweep cursors: the first vehicle of the other lane that is not strictly
        // ahead.
        let (mut jl, mut jr) = (0u32, 0u32);
        // The geometry's step function along the lane (here.rs).
        let mut here = here_tables.walk(l);
        let (mut adj_start, mut tg2_start) = (0usize, 0usize);
        for (k, (&s, &(x, _))) in lane.iter().zip(xs).enumerate() {
            let si = s as usize;
            jl = sweep(lx, jl, x);
            jr = sweep(rx, jr, x);
            // Membership and position (`linked` holds the candidate link from pass A; the
            // leader's position is final: it comes first in the lane list).
            let mut pred_id = crate::vehicle::NEVER;
            let mut pos = 1;
            if sensed[si].linked {
                let ld = lane[k - 1] as usize;
                let lpos = sensed[ld].platoon_pos;
                let lid = vehicles[ld].id;
                let member = vehicles[si].cacc.pred == lid;
                if (member && lpos < max) || (!member && lpos + sensed[si].sub_size <= max) {
                    pred_id = lid;
                    pos = lpos + 1;
                }
            }
            let t = &mut sensed[si];
            // The leader there is at the cursor's index − 1 (none when the cursor is 0:
            // the index wraps past the end). One test instead of two.
            t.nb.left_leader = llane
                .get((jl as usize).wrapping_sub(1))
                .copied()
                .unwrap_or(NONE);
            t.nb.right_leader = rlane
                .get((jr as usize).wrapping_sub(1))
                .copied()
                .unwrap_or(NONE);
            t.nb.left_j = jl;
            t.nb.right_j = jr;
            t.here = here.at(x);
            t.platoon_pos = pos;
            let is_linked = pred_id != crate::vehicle::NEVER;
            t.linked = is_linked;
            let cav_ahead = t.cav_ahead;
            let v = &mut vehicles[si];
            let adjacent = cav_ahead && v.automated();
            v.cacc.pred = pred_id;
            if !adjacent || k - adj_start >= max as usize {
                close_run(vehicles, lane, adj_start, k, false);
                adj_start = k;
            }
            if !is_linked {
                close_run(vehicles, lane, tg2_start, k, true);
                tg2_start = k;
            }
        }
        close_run(vehicles, lane, adj_start, lane.len(), false);
        close_run(vehicles, lane, tg2_start, lane.len(), true);
    }
}

/// Entries (−∞, 0) after the vehicles in each `Simulation::lane_xv` list.
const SENTINELS: usize = 3;

/// The merge-sweep cursor of another lane for position `x`: from `j`, the index of the first
/// vehicle of `xv` (front first, ending in `SENTINELS` sentinels at −∞) that is not strictly
/// ahead of `x`.
///
/// Equal to `while xv[j].0 > x { j += 1 }`. The first two steps are taken without branching
/// (a step that stops leaves `j` where the loop would have stopped, and so does every later
/// one): the cursor usually moves by zero, one or two vehicles, at random, and a mispredicted
/// loop exit cost more than the steps. Longer runs (the other lane is denser here, or this
/// lane holds only a few vehicles, as an acceleration lane does) are galloped over and then
/// bisected: at the step start the lanes are sorted (descending x; `check_invariants` sorts
/// them, and its finiteness check covers every vehicle but the first, which the two steps have
/// passed by then), so "ahead of `x`" holds for a prefix of what is left.
///
/// The three reads `xv[j]`, `xv[j + b0]`, `xv[j + b0 + b1]` share one bounds check: the cursor
/// never passes the first sentinel (nothing is ahead of a sentinel), so the two entries after
/// it exist; `j` is a `u32`, so `j + SENTINELS` cannot wrap and the check is a single one.
#[inline]
fn sweep(xv: &[(f64, f64)], j: u32, x: f64) -> u32 {
    let j = j as usize;
    let w = &xv[j..j + SENTINELS];
    let b0 = usize::from(w[0].0 > x);
    let b1 = usize::from(w[b0].0 > x);
    let k = b0 + b1;
    if w[k].0 > x {
        // Galloping: `lo` is ahead, `hi` is not (the first sentinel is not).
        let last = xv.len() - SENTINELS;
        let (mut lo, mut step) = (j + k, 1);
        let hi = loop {
            let p = lo + step;
            if p >= last {
                break last;
            }
            if xv[p].0 > x {
                lo = p;
                step *= 2;
            } else {
                break p;
            }
        };
        return (lo + 1 + xv[lo + 1..hi].partition_point(|p| p.0 > x)) as u32;
    }
    (j + k) as u32
}

/// A statistical platoon ends: every CAV in it, `lane[start..end]`, records its size.
///
/// The size is tested before the run is sliced: most runs have one vehicle, and the slice's
/// bounds checks would come first otherwise.
#[inline]
fn close_run(vehicles: &mut [Vehicle], lane: &[u32], start: usize, end: usize, strict: bool) {
    if end - start < 2 {
        return;
    }
    let run = &lane[start..end];
    let size = run.len() as u32;
    for &s in run {
        let v = &mut vehicles[s as usize];
        let m = if strict {
            &mut v.cacc.max_platoon_tg2
        } else {
            &mut v.cacc.max_platoon
        };
        if *m < size {
            *m = size;
        }
    }
}
