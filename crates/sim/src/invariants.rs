//! Phase 7 (invariants and safety): over each lane's (leader, follower) pairs, collisions,
//! the surrogate safety measures and finiteness.

use crate::error::SimError;
use crate::events::CollisionKind;
use crate::safety::Safety;
use crate::state::{Clock, Traffic};
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
                let ld = &vehicles[li as usize];
                let lead_id = ld.id;
                // The pair was formed by a lane change in this step (phase 4 ran at step − 1).
                let changed = |v: &Vehicle| v.lcs.last_step.wrapping_add(1) == step;
                let lane_change = changed(ld) || changed(&vehicles[s as usize]);
                safety.on_close(
                    &mut vehicles[s as usize],
                    lead_id,
                    gap,
                    lead_v,
                    lane_change,
                    step,
                    dt,
                );
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;
    use crate::safety::Counted;
    use crate::vehicle::Kind;

    /// One lane, hand-placed: a follower (human, 30 m/s, front at 100 m) and, `gap` metres
    /// ahead of it, a vehicle at 24 m/s that changed into the lane in the step that just ran
    /// if `cut_in`. Returns the (rear-end, lane-change) conflicts after the invariant phase of
    /// that step and of the next one (positions unchanged: the pair stays in conflict).
    fn conflicts_after(gap: f64, cut_in: bool) -> (u64, u64) {
        let cfg = Config::homogeneous(0.0, 1000.0, 60.0, 0.0, 1);
        let mut safety = Safety::new(&cfg);
        let mut traffic = Traffic {
            lanes: vec![vec![]],
            ..Traffic::default()
        };
        let step = 10;
        let mut changer = crate::insert::create(&cfg, 1, 0.0, 0.0, 0);
        let mut fol = crate::insert::create(&cfg, 2, 0.0, 0.0, 0);
        fol.kind = Kind::Human;
        fol.x = 100.0;
        fol.v = 30.0;
        changer.x = 100.0 + gap + changer.driver.human.length_m;
        changer.v = 24.0;
        if cut_in {
            // Phase 4 of the step that just ran (the invariant phase sees step + 1).
            changer.lcs.last_step = step - 1;
        }
        let c = traffic.alloc(changer);
        let f = traffic.alloc(fol);
        traffic.lanes[0] = vec![c, f];
        let mut clock = Clock {
            dt: 0.1,
            step,
            total_steps: 100,
            warmup_step: 0,
            agg_steps: 10,
        };
        check_invariants(&clock, 0.0, &mut traffic, &mut safety).unwrap();
        clock.step += 1;
        check_invariants(&clock, 0.0, &mut traffic, &mut safety).unwrap();
        let n = |w| safety.counts.get(w).human;
        (
            n(Counted::RearEndConflicts),
            n(Counted::LaneChangeConflicts),
        )
    }

    #[test]
    fn a_close_cut_in_is_one_lane_change_conflict() {
        // TTC = 8 / 6 = 1.33 s < 1.5 s: one conflict episode over both steps, a lane-change one.
        assert_eq!(conflicts_after(8.0, true), (0, 1));
        // The same pair without a lane change is a rear-end conflict.
        assert_eq!(conflicts_after(8.0, false), (1, 0));
    }

    #[test]
    fn a_roomy_change_is_no_conflict() {
        // TTC = 40 / 6 = 6.7 s.
        assert_eq!(conflicts_after(40.0, true), (0, 0));
        // Just above TTC* (9.3 / 6 = 1.55 s).
        assert_eq!(conflicts_after(9.3, true), (0, 0));
    }
}
