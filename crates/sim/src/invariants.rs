//! Phase 7 (invariants and safety): over each lane's (leader, follower) pairs, collisions,
//! the surrogate safety measures and finiteness.

use crate::error::SimError;
use crate::safety::Safety;
use crate::state::{Clock, Traffic};
use crate::summary::CollisionKind;
use crate::vehicle::Vehicle;

/// A rear-end collision starts when the pair (follower in slot `f`, leader in slot `ld`)
/// overlaps and did not at the end of the previous step (phase 7).
#[cold]
#[inline(never)]
fn overlap(
    safety: &mut Safety,
    vehicles: &[Vehicle],
    ld: u32,
    f: u32,
    lane: usize,
    t: f64,
    origin: f64,
) {
    let (lead, fol) = (&vehicles[ld as usize], &vehicles[f as usize]);
    let pair = (fol.id, lead.id);
    if !safety.collisions.overlapping.contains(&pair) {
        let gap = lead.rear() - fol.x;
        safety.collide(
            t,
            CollisionKind::RearEnd,
            lane,
            fol.x + origin,
            fol,
            Some(lead),
            -gap,
        );
    }
    safety.collisions.overlapping_now.push(pair);
}

/// A non-finite state is an engine error (phase 7).
#[inline(always)]
fn check_finite(v: &Vehicle, lane: usize, t: f64) -> Result<(), SimError> {
    // The sum is finite exactly when the three are: they are bounded far below overflow (a
    // road of at most 200 km, speeds and accelerations of vehicles), and ∞ − ∞ is NaN.
    if (v.x + v.v + v.a).is_finite() {
        return Ok(());
    }
    Err(non_finite(v, lane, t))
}

#[cold]
#[inline(never)]
fn non_finite(v: &Vehicle, lane: usize, t: f64) -> SimError {
    SimError::NonFinite {
        vehicle: v.id,
        lane: lane + 1,
        t_s: t,
        x_m: v.x,
        v_mps: v.v,
        a_mps2: v.a,
    }
}

/// Phase 7: finiteness, collisions and the surrogate safety measures (`safety.rs`), over
/// each lane's (leader, follower) pairs at the end of the step. A pair whose follower's
/// front is past its leader's rear is a collision when it starts (it was not overlapping at
/// the end of the previous step). Keeps each lane sorted even after a collision.
#[inline]
pub(crate) fn check_invariants(
    clock: &Clock,
    origin: f64,
    traffic: &mut Traffic,
    safety: &mut Safety,
) -> Result<(), SimError> {
    let step = clock.step;
    let t = crate::record::step_time(step, clock.dt);
    let dt = clock.dt;
    let in_window = step > clock.warmup_step;
    let Traffic {
        lanes, vehicles, ..
    } = traffic;
    // Outside the measurement window only an overlapping pair passes the test below, and
    // `on_close` ignores it there.
    safety.exposure.in_window = in_window;
    let mut horizon = if in_window {
        safety.exposure.ttc_horizon_s
    } else {
        0.0
    };
    std::mem::swap(
        &mut safety.collisions.overlapping,
        &mut safety.collisions.overlapping_now,
    );
    safety.collisions.overlapping_now.clear();
    for (l, lane) in lanes.iter_mut().enumerate() {
        let mut sorted = true;
        let Some((&first, rest)) = lane.split_first() else {
            continue;
        };
        // Each record is looked up once: what the next pair needs of the follower (then its
        // leader) is kept in locals.
        let v0 = &vehicles[first as usize];
        check_finite(v0, l, t)?;
        let (mut li, mut lead_rear, mut lead_x, mut lead_v) = (first, v0.rear(), v0.x, v0.v);
        for &s in rest.iter() {
            let fol = &vehicles[s as usize];
            check_finite(fol, l, t)?;
            let (fx, fv, frear) = (fol.x, fol.v, fol.rear());
            let gap = lead_rear - fx;
            if gap < 0.0 {
                overlap(safety, vehicles, li, s, l, t, origin);
                if fx > lead_x {
                    sorted = false;
                }
            }
            // TTC = g / closing, divided out only when it is below the threshold or the
            // smallest so far (`ttc_horizon_s`, the larger of the two).
            // One comparison per pair: a pair that is not closing in gives a bound ≤ 0,
            // which only an overlap passes (`on_close` then finds no TTC).
            if gap < (fv - lead_v) * horizon {
                let lead_id = vehicles[li as usize].id;
                safety.on_close(&mut vehicles[s as usize], lead_id, gap, lead_v, step, dt);
                horizon = safety.exposure.ttc_horizon_s;
            }
            (li, lead_rear, lead_x, lead_v) = (s, frear, fx, fv);
        }
        if !sorted {
            lane.sort_by(|&a, &b| vehicles[b as usize].x.total_cmp(&vehicles[a as usize].x));
        }
    }
    Ok(())
}
