//! Phase 5a (boundaries, first half): vehicles leave the road at its end or by their
//! off-ramp; and [`Departures`], how any departure reaches the statistics, the trip record
//! and the observers.

use crate::detector::Detector;
use crate::energy::EnergyMeter;
use crate::events::{Departure, Event, Observer};
use crate::metrics::Metrics;
use crate::record::Recorder;
use crate::state::{Clock, RoadState, Traffic, Watch};
use crate::vehicle::{Vehicle, NO_EXIT};
use crate::view::VehicleView;

/// Who hears of a departure: the paper's statistics, the trip record, the energy meter, the
/// user's observers (and the step's event list), in that order.
pub(crate) struct Departures<'a> {
    pub clock: &'a Clock,
    /// Output coordinate of engine x = 0.
    pub origin_m: f64,
    pub metrics: &'a mut Metrics,
    pub rec: &'a mut Recorder,
    pub watch: &'a mut Watch,
    /// The energy meter, when `energy.enabled`.
    pub energy: &'a mut Option<Box<EnergyMeter>>,
}

impl Departures<'_> {
    /// `v` leaves the road as `how` in this step (or is still on it at the end of the run).
    #[inline(never)]
    pub fn leave(&mut self, v: &Vehicle, how: Departure) {
        // A departure happens in the step under way; a vehicle still on the road is reported
        // at the end of the run (after the last step).
        let step = match how {
            Departure::OnRoad => self.clock.step,
            _ => self.clock.step + 1,
        };
        let t = crate::record::step_time(step, self.clock.dt);
        let view = VehicleView::new(v);
        self.metrics.on_exit(view, how, t);
        if self.rec.trips.is_some() {
            self.rec.on_exit(view, how, t);
        }
        if let Some(e) = self.energy.as_mut() {
            e.on_exit(view, how, t);
        }
        if self.watch.observing {
            for o in &mut self.watch.observers {
                o.on_exit(view, how, t);
            }
            if how != Departure::OnRoad {
                self.watch.events.push(Event::Exited {
                    t_s: t,
                    id: v.id,
                    kind: v.kind,
                    how,
                    x_m: v.x + self.origin_m,
                    v_mps: v.v,
                });
            }
        }
    }
}

/// Phase 5a: vehicles whose front passed the road end (`end_m`) leave; on a network,
/// vehicles that reach their off-ramp in its lane leave by it (counted by the ramp's detector,
/// `exit_detector` per off-ramp), and those that reach it in another lane miss it and drive on
/// to the end [D] (counted in `missed_exits`). `exit_due`: integrate saw a vehicle at or past
/// its off-ramp in this step (reset here).
#[allow(clippy::too_many_arguments)]
pub(crate) fn exits(
    end_m: f64,
    road: &RoadState,
    traffic: &mut Traffic,
    exit_due: &mut bool,
    detectors: &mut [Detector],
    exit_detector: &[Option<usize>],
    missed_exits: &mut u64,
    out: &mut Departures<'_>,
) {
    for l in 0..traffic.lanes.len() {
        while let Some(&s) = traffic.lanes[l].first() {
            if traffic.vehicles[s as usize].x < end_m {
                break;
            }
            traffic.lanes[l].remove(0);
            out.leave(&traffic.vehicles[s as usize], Departure::RoadEnd);
            traffic.free.push(s);
        }
    }
    // Only when integrate saw a vehicle at or past its off-ramp (x and exits do not change
    // between the two phases; vehicles inserted after this phase are integrated first).
    if !std::mem::take(exit_due) {
        return;
    }
    for l in 0..traffic.lanes.len() {
        let mut k = 0;
        while k < traffic.lanes[l].len() {
            let s = traffic.lanes[l][k];
            let v = &mut traffic.vehicles[s as usize];
            if v.route.exit == NO_EXIT {
                k += 1;
                continue;
            }
            let ramp = &road.geom.off_ramps[v.route.exit as usize];
            if v.x < ramp.x {
                k += 1;
                continue;
            }
            if v.lane != ramp.lane {
                v.route.exit = NO_EXIT;
                *missed_exits += 1;
                k += 1;
                continue;
            }
            let (exit, speed, cav) = (v.route.exit as usize, v.v, v.is_cav());
            traffic.lanes[l].remove(k);
            if let Some(d) = exit_detector[exit] {
                detectors[d].count_exit(speed, cav);
            }
            out.leave(&traffic.vehicles[s as usize], Departure::OffRamp(exit));
            traffic.free.push(s);
        }
    }
}
