//! Hand placement: put a vehicle on the road by hand, for tests and studies of small
//! situations (a cut-in, a cooperative gap, a join), before or between steps.

use crate::error::SimError;
use crate::events::Event;
use crate::sim::Simulation;
use crate::vehicle::Kind;
use crate::view::VehicleView;
use platoonsim_model::cav::{self, Family};

impl Simulation {
    /// Put a new vehicle of `kind` in `lane` (0 = rightmost) with its front at `x_m` (engine
    /// coordinate, 0 = the mainline entry) and speed `v_mps`. Its parameters are drawn from its
    /// own stream as for an arriving vehicle (a human-driven vehicle drawn where a CAV is asked
    /// for, or the reverse, takes the requested kind; a CAV then draws its t_C from the same
    /// stream). A CAV starts automated, in the gap family, at its own t_C behind a CAV and the
    /// ACC gap behind a human driver. Refused when the lane does not exist, the values are not
    /// finite or negative, or the vehicle would overlap one already there. Returns its id;
    /// [`Simulation::vehicle`] reads it back.
    pub fn place_vehicle(
        &mut self,
        kind: Kind,
        lane: usize,
        x_m: f64,
        v_mps: f64,
    ) -> Result<u64, SimError> {
        let bad = |m: String| Err(SimError::Command(m));
        if lane >= self.traffic.lanes.len() {
            return bad(format!(
                "place_vehicle: lane {lane} does not exist (0 to {})",
                self.traffic.lanes.len() - 1
            ));
        }
        if !(x_m.is_finite() && x_m >= 0.0 && v_mps.is_finite() && v_mps >= 0.0) {
            return bad(format!(
                "place_vehicle: x = {x_m} m and v = {v_mps} m/s must be finite and >= 0"
            ));
        }
        let t = self.clock.step as f64 * self.clock.dt;
        let id = self.traffic.next_id;
        let mut veh = crate::insert::create(&self.cfg, id, x_m, t, 0);
        if veh.kind != kind {
            veh.kind = kind;
            veh.cacc.gap_s = match kind {
                Kind::Cav => cav::draw_time_gap(&self.cfg.cav, veh.driver.rng.uniform()),
                Kind::Human => 0.0,
            };
        }
        let list = &self.traffic.lanes[lane];
        let vehicles = &self.traffic.vehicles;
        let j = list.partition_point(|&o| vehicles[o as usize].x > x_m);
        let ahead = (j > 0).then(|| &vehicles[list[j - 1] as usize]);
        let behind = list.get(j).map(|&o| &vehicles[o as usize]);
        let len = veh.driver.human.length_m;
        if ahead.is_some_and(|l| l.rear() <= x_m) || behind.is_some_and(|f| x_m - len <= f.x) {
            return bad(format!(
                "place_vehicle: a vehicle at x = {x_m} m in lane {lane} would overlap another"
            ));
        }
        self.traffic.next_id += 1;
        veh.lane = lane as u32;
        veh.x = x_m;
        veh.x_prev = x_m;
        veh.v = v_mps;
        veh.a = 0.0;
        if veh.is_cav() {
            veh.cacc.family = Family::Gap;
            veh.cacc.time_gap_s = match ahead {
                Some(l) if !l.is_cav() => self.cfg.cav.acc_time_gap_s,
                _ => veh.cacc.gap_s,
            };
        }
        veh.stats.entered_step = self.clock.step;
        veh.stats.measured = veh.stats.entered_step >= self.clock.warmup_step;
        veh.stats.reported = (veh.mode_label(), veh.cacc.regime);
        self.measures.metrics.entered += 1;
        if self.watch.observing {
            self.watch.events.push(Event::Entered {
                t_s: crate::record::step_time(self.clock.step, self.clock.dt),
                id,
                kind: veh.kind,
                entrance: 0,
                lane: veh.lane,
                x_m: x_m + self.origin_m(),
                v_mps,
            });
        }
        let s = self.traffic.alloc(veh);
        self.traffic.lanes[lane].insert(j, s);
        Ok(id)
    }

    /// The vehicle with id `id`, if it is on the road.
    pub fn vehicle(&self, id: u64) -> Option<VehicleView<'_>> {
        self.traffic
            .slot_of(id)
            .map(|s| VehicleView::new(&self.traffic.vehicles[s as usize]))
    }
}
