//! Phase 4 (lane changes): accepted changes are applied instantaneously (spec 4.4, 6.14),
//! front to back and lane by lane, each re-checked against the positions after integration
//! and after the changes already applied in this step.

use crate::events::Event;
use crate::sense::NONE;
use crate::sim::Simulation;
use crate::vehicle::{Mode, Relaxation};
use platoonsim_model::human;
use platoonsim_model::lanechange::{self as lcm, Side};
use platoonsim_model::Leader;

impl Simulation {
    /// Phase 4.
    pub(crate) fn apply_lane_changes(&mut self) {
        // Locals: a push does not make the loop reload the lane lists and the decisions.
        let Simulation {
            lanes,
            decisions,
            change_list,
            ..
        } = self;
        let decisions = &decisions[..];
        change_list.clear();
        for lane in lanes.iter() {
            for &s in lane {
                if let Some(side) = decisions[s as usize].change {
                    change_list.push((s, side));
                }
            }
        }
        for i in 0..self.change_list.len() {
            let (s, side) = self.change_list[i];
            self.try_change(s, side);
        }
    }

    fn try_change(&mut self, s: u32, side: Side) {
        let step = self.step;
        let v = &self.vehicles[s as usize];
        let from = v.lane as usize;
        let to = match side {
            Side::Left => from + 1,
            Side::Right => from.wrapping_sub(1),
        };
        if to >= self.lanes.len() || !self.geom.can_enter(to as u32, v.x) {
            return;
        }
        // Position in the target lane: first vehicle not strictly ahead.
        let target = &self.lanes[to];
        let j = target.partition_point(|&o| self.vehicles[o as usize].x > v.x);
        let tl = if j > 0 { target[j - 1] } else { NONE };
        let tf = target.get(j).copied().unwrap_or(NONE);
        // No change next to a vehicle that has just changed lanes (spec 4.2).
        for o in [tl, tf] {
            if o != NONE && self.changed_this_step[o as usize] == step {
                return;
            }
        }
        let lead = (tl != NONE).then(|| {
            let l = &self.vehicles[tl as usize];
            Leader {
                gap_m: l.rear() - v.x,
                v_mps: l.v,
            }
        });
        if let Some(l) = lead {
            if !lcm::accept_lead_gap(&v.human, &v.lc, l.gap_m, v.v, l.v_mps) {
                return;
            }
        }
        if tf != NONE {
            let f = &self.vehicles[tf as usize];
            let a_ant = human::target_accel(
                &v.human,
                v.v,
                self.v_des_in(s, v, to),
                lead,
                lcm::gap_relax(&v.lc),
            );
            if !lcm::accept_lag_gap(&v.human, &v.lc, v.rear() - f.x, v.v, f.v, a_ant) {
                return;
            }
        }
        // Execute.
        let k = self.lanes[from]
            .iter()
            .position(|&o| o == s)
            .expect("vehicle is in its lane");
        self.lanes[from].remove(k);
        self.lanes[to].insert(j, s);
        self.changed_this_step[s as usize] = step;
        let v = &mut self.vehicles[s as usize];
        v.lane = to as u32;
        v.mode = Mode::Cf;
        v.relax = Relaxation::Since(step + 1);
        v.last_lc_step = step;
        v.last_lc_side = Some(side);
        v.lane_changes += 1;
        if self.observing {
            let (id, kind, x) = (v.id, v.kind, v.x);
            self.events.push(Event::LaneChange {
                t_s: crate::record::step_time(step + 1, self.dt),
                id,
                kind,
                from: from as u32,
                to: to as u32,
                x_m: x + self.cfg.road.network.as_ref().map_or(0.0, |n| n.origin_m),
                reason: self.decisions[s as usize].why,
            });
        }
        // The new follower relaxes (RCF), unless it is an automated CAV (spec 4.6).
        if tf != NONE {
            let f = &mut self.vehicles[tf as usize];
            if !f.automated() {
                f.relax = Relaxation::Since(step + 1);
                if matches!(f.mode, Mode::Ycf { .. }) {
                    f.mode = Mode::Cf;
                }
            }
        }
    }
}
