//! Phase 3 (integrate): every vehicle moves by its decided acceleration, bounded by its
//! emergency limit (`safety.rs`); a vehicle past the end of its lane is a lane-end collision
//! and leaves the road (its removal, which reaches the records and the observers, is the cold
//! tail of `Simulation::integrate` in `sim.rs`, so that this phase does not import the step).

use crate::network::Geometry;
use crate::safety::Counted;
use crate::state::{Clock, Measures, Scratch, Traffic};
use crate::vehicle::{Relaxation, NO_EXIT};
use platoonsim_model::safety as law;

/// Phase 3 without its cold tail: every vehicle moves by its decided acceleration bounded by
/// its emergency limit; reads the clock, the geometry (walls, off-ramps) and the decisions,
/// writes the vehicles, the scratch flags (`exit_due`, `lanes_sorted`, `crashed`) and the
/// safety measures.
#[inline]
pub(crate) fn move_vehicles(
    clock: &Clock,
    geom: &Geometry,
    traffic: &mut Traffic,
    scratch: &mut Scratch,
    measures: &mut Measures,
) {
    let dt = clock.dt;
    let mut sorted = true;
    // Locals (the stores into the records cannot change them, so nothing is reloaded per
    // vehicle), and the slot-indexed arrays as long as `vehicles`: one bounds check per
    // vehicle for the three.
    let Traffic {
        lanes,
        vehicles,
        auto,
        ..
    } = traffic;
    let Scratch {
        decisions,
        sensed,
        exit_due,
        crashed,
        lanes_sorted,
        ..
    } = scratch;
    let Measures {
        vehicle_updates,
        safety,
        cacc_fallbacks,
        ..
    } = measures;
    let step = clock.step;
    let in_window = step >= clock.warmup_step;
    let plain = geom.plain;
    let off_ramps = &geom.off_ramps[..];
    let vehicles = &mut vehicles[..];
    let decisions = &decisions[..vehicles.len()];
    let sensed = &sensed[..vehicles.len()];
    // Metres driven in this step by kind (human, CAV): the vehicle-km of the rates.
    let mut driven = [0.0_f64; 2];
    for (l, lane) in lanes.iter().enumerate() {
        let mut ahead = f64::INFINITY;
        for &s in lane {
            let d = &decisions[s as usize];
            let veh = &mut vehicles[s as usize];
            veh.x_prev = veh.x;
            let a_prev = veh.a;
            let accel = law::braking_limited(d.accel, safety.limit(veh.kind));
            let v_new = veh.v + accel * dt;
            if v_new >= 0.0 {
                veh.x += 0.5 * (veh.v + v_new) * dt;
                veh.v = v_new;
                veh.a = accel;
            } else {
                // Stops within the step: travels v²/(2|a|).
                veh.x += 0.5 * veh.v * veh.v / (-accel);
                veh.a = -veh.v / dt;
                veh.v = 0.0;
            }
            driven[veh.kind as usize] += veh.x - veh.x_prev;
            safety.on_applied(veh, a_prev, veh.a, step, in_window);
            if !plain {
                // A wall is a standing obstacle (network.rs): passing it is a collision.
                // (`here` is at the step-start position: x_prev, in this lane.)
                if let Some(w) = sensed[s as usize].here.wall {
                    if veh.x > w {
                        crashed.push((s, l as u32, w));
                    }
                }
            }
            sorted &= veh.x <= ahead;
            ahead = veh.x;
            // As in exits: not `x < ramp.x` (a NaN position counts too).
            if veh.route.exit != NO_EXIT
                && off_ramps
                    .get(veh.route.exit as usize)
                    .is_some_and(|r| veh.x.partial_cmp(&r.x) != Some(std::cmp::Ordering::Less))
            {
                *exit_due = true;
            }
            veh.mode = d.mode;
            veh.cacc.family = d.family;
            veh.cacc.regime = d.regime;
            veh.cacc.time_gap_s = d.time_gap;
            // spec 9.3: AEB interventions and CACC fallbacks, as episodes, and the organizing
            // wait of 6.20 (rare: one branch).
            if !d.auto.union(veh.cacc.auto).is_none() {
                let (now, was) = (d.auto, veh.cacc.auto);
                if in_window {
                    if now.aeb() && !was.aeb() {
                        safety.counts.count(Counted::AebInterventions, veh.kind);
                    }
                    *cacc_fallbacks += u64::from(now.degraded() && !was.degraded());
                    if now.takeover() && !was.takeover() {
                        safety.counts.count(Counted::TakeoverRequests, veh.kind);
                    }
                }
                veh.hold_wait = if now.in_wait() {
                    veh.hold_wait.saturating_add(u32::from(now.wait_slow()))
                } else {
                    0
                };
                veh.cacc.auto = now;
            }
            if d.takeover {
                veh.lcs.relax = Relaxation::since(step);
            }
            if let Some(since) = veh.lcs.relax.started() {
                let elapsed = (step + 1 - since) as f64 * dt;
                if elapsed >= veh.driver.lc.relax_time_s {
                    veh.lcs.relax = Relaxation::NONE;
                }
            }
        }
        *vehicle_updates += lane.len() as u64;
    }
    *lanes_sorted = sorted;
    if in_window {
        let km = &mut safety.counts.vehicle_km;
        km.human += driven[0] / 1000.0;
        km.cav += driven[1] / 1000.0;
    }
    // spec 9.3: every vehicle's new speed is its V2V broadcast for the next step (only with
    // a broadcast log: its own pass, so that without one the loop above is unchanged).
    if let Some(b) = auto.beacons.as_mut() {
        for lane in lanes.iter() {
            for &s in lane {
                b.broadcast(s, step + 1, vehicles[s as usize].v);
            }
        }
    }
}
