//! Phase 5b (arrivals and insertion), issue 2 item 3.
//!
//! Arrivals: a Poisson process per entrance at the demand rate (exponential headways from the
//! entrance's own stream); each arrival's type is a Bernoulli trial with P(CAV) = penetration
//! and its parameters are drawn once from its own vehicle stream (spec 1).
//!
//! Insertion (spec 1, [P15-code]): the head of the entrance's virtual queue enters at x = 0 at
//! its desired speed if that is a steady state behind the last vehicle of some lane (its model
//! asks for no braking: human target acceleration ≥ 0; CAV gap ≥ its ACC/CACC equilibrium gap
//! and within the safety bound); otherwise at the speed of that last vehicle if that is a steady
//! state; otherwise it waits in the queue. Among the lanes that admit the full desired speed one
//! is drawn at random; otherwise the lane with the highest admissible speed. At most one vehicle
//! enters a lane per step. So demand above capacity builds a measurable queue instead of being
//! lost or violating car following.

use crate::config::Config;
use crate::rng::{Purpose, Stream};
use crate::sim::Simulation;
use crate::vehicle::{Kind, Mode, Relaxation, Vehicle, NEVER};
use platoonsim_model::cav::{self, Family};
use platoonsim_model::human::{self, HUMAN_DRAWS};
use platoonsim_model::lanechange::LC_DRAWS;
use platoonsim_model::{Leader, Relax};
use std::collections::VecDeque;

/// An entrance: its arrival stream and virtual queue.
pub struct Entrance {
    rng: Stream,
    /// Arrival rate (veh/s) for the whole entrance.
    rate: f64,
    next_arrival_s: f64,
    queue: VecDeque<Vehicle>,
}

impl Entrance {
    pub fn new(cfg: &Config, index: u64) -> Entrance {
        let mut rng = Stream::new(cfg.seed, Purpose::Arrivals, index);
        let rate = cfg.demand.vph_per_lane * cfg.road.lanes as f64 / 3600.0;
        let first = rng.exponential(rate);
        Entrance {
            rng,
            rate,
            next_arrival_s: first,
            queue: VecDeque::new(),
        }
    }

    pub fn waiting(&self) -> usize {
        self.queue.len()
    }
}

/// Draw a new vehicle (type and parameters) from its own stream.
fn create(cfg: &Config, id: u64) -> Vehicle {
    let mut rng = Stream::new(cfg.seed, Purpose::Vehicle, id);
    let kind = if rng.uniform() < cfg.penetration {
        Kind::Cav
    } else {
        Kind::Human
    };
    let mut zh = [0.0; HUMAN_DRAWS];
    zh.iter_mut().for_each(|z| *z = rng.normal());
    let z_speed = rng.normal();
    let mut zl = [0.0; LC_DRAWS];
    zl.iter_mut().for_each(|z| *z = rng.normal());
    let u_gap = rng.uniform();
    let human = cfg.human.sample(&zh, cfg.human.desired_speed_mps(z_speed));
    let cacc_gap_s = match kind {
        Kind::Cav => cav::draw_time_gap(&cfg.cav, u_gap),
        Kind::Human => 0.0,
    };
    Vehicle {
        id,
        kind,
        entered_step: NEVER,
        measured: false,
        human,
        lc: cfg.lane_change.sample(&zl),
        cacc_gap_s,
        time_gap_s: 0.0,
        string_pred: NEVER,
        rng,
        x: 0.0,
        x_prev: 0.0,
        v: 0.0,
        a: 0.0,
        lane: 0,
        mode: Mode::Cf,
        relax: Relaxation::None,
        family: Family::Speed,
        last_lc_step: NEVER,
        last_lc_side: None,
        lane_changes: 0,
        max_platoon: 1,
        max_platoon_tg2: 1,
    }
}

impl Simulation {
    /// Phase 5b.
    pub(crate) fn insert(&mut self) {
        let t_end = (self.step + 1) as f64 * self.dt;
        while self.entrance.next_arrival_s <= t_end {
            let v = create(&self.cfg, self.next_id);
            self.next_id += 1;
            self.entrance.queue.push_back(v);
            let h = self.entrance.rng.exponential(self.entrance.rate);
            self.entrance.next_arrival_s += h;
        }
        let n_lanes = self.lanes.len();
        let mut used = 0u32; // bit per lane
        while let Some(head) = self.entrance.queue.front() {
            let v_des = head.human.desired_speed;
            let mut full: u32 = 0;
            let mut n_full = 0usize;
            let mut best: Option<(usize, f64)> = None;
            for l in 0..n_lanes {
                if used & (1 << l) != 0 {
                    continue;
                }
                if let Some(v) = self.insertion_speed(head, l) {
                    if v >= v_des {
                        full |= 1 << l;
                        n_full += 1;
                    } else if best.is_none_or(|(_, b)| v > b) {
                        best = Some((l, v));
                    }
                }
            }
            let (lane, speed) = if n_full > 0 {
                let head = self.entrance.queue.front_mut().expect("queue has a head");
                let pick = head.rng.index(n_full);
                let lane = (0..n_lanes)
                    .filter(|l| full & (1 << l) != 0)
                    .nth(pick)
                    .expect("pick < n_full");
                (lane, v_des)
            } else if let Some(b) = best {
                b
            } else {
                break;
            };
            let mut veh = self.entrance.queue.pop_front().expect("queue has a head");
            veh.lane = lane as u32;
            veh.x = 0.0;
            veh.x_prev = 0.0;
            veh.v = speed;
            veh.a = 0.0;
            veh.entered_step = self.step + 1;
            veh.measured = veh.entered_step >= self.warmup_step;
            if veh.is_cav() {
                veh.time_gap_s = veh.cacc_gap_s;
                if let Some(&ld) = self.lanes[lane].last() {
                    veh.time_gap_s = self.entry_time_gap(&veh, ld);
                    if self.vehicles[ld as usize].rear() < 2.0 * speed.max(1.0) {
                        veh.family = Family::Gap;
                    }
                }
            }
            self.metrics.entered += 1;
            let s = self.alloc(veh);
            self.lanes[lane].push(s);
            used |= 1 << lane;
        }
    }

    /// The time gap a CAV entering behind slot `ld` keeps (spec 3.6): its own t_C behind a CAV
    /// whose platoon has room, the inter-platoon gap behind a full one, t_A behind a human.
    fn entry_time_gap(&self, veh: &Vehicle, ld: u32) -> f64 {
        let p = &self.cfg.cav;
        if !self.vehicles[ld as usize].is_cav() {
            p.acc_time_gap_s
        } else if self.platoon_pos.get(ld as usize).copied().unwrap_or(1) >= p.max_platoon {
            p.inter_platoon_gap_s
        } else {
            veh.cacc_gap_s
        }
    }

    /// The speed at which `veh` may enter `lane` at x = 0 in steady state, if any.
    fn insertion_speed(&self, veh: &Vehicle, lane: usize) -> Option<f64> {
        let v_des = veh.human.desired_speed;
        let Some(&ld) = self.lanes[lane].last() else {
            return Some(v_des);
        };
        let l = &self.vehicles[ld as usize];
        let leader = Leader {
            gap_m: l.rear(),
            v_mps: l.v,
        };
        if leader.gap_m <= 0.0 {
            return None;
        }
        let ok = |v: f64| -> bool {
            match veh.kind {
                Kind::Human => {
                    human::target_accel(&veh.human, v, v_des, Some(leader), Relax::NONE) >= 0.0
                }
                Kind::Cav => {
                    let p = &self.cfg.cav;
                    if leader.gap_m > p.sensor_range_m {
                        return true;
                    }
                    let t = self.entry_time_gap(veh, ld);
                    let eq = if l.is_cav() {
                        cav::cacc_equilibrium_gap(p, t, v)
                    } else {
                        cav::acc_equilibrium_gap(p, t, v)
                    };
                    leader.gap_m >= eq && cav::safe_speed(p, leader.gap_m, l.v) >= v
                }
            }
        };
        if ok(v_des) {
            Some(v_des)
        } else {
            let v = l.v.min(v_des);
            ok(v).then_some(v)
        }
    }
}
