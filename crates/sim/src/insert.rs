//! Phase 5b (arrivals and insertion), issue 2 item 3.
//!
//! Arrivals: a Poisson process per entrance at the demand rate (exponential headways from the
//! entrance's own stream); each arrival's type is a Bernoulli trial with P(CAV) = penetration
//! (an on-ramp's own `penetration` for its arrivals, if it has one)
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
use crate::events::Event;
use crate::meter::Gate;
use crate::network::NO_LANE;
use crate::record::Recorder;
use crate::rng::{Purpose, Stream};
use crate::state::Sensed;
use crate::state::{Clock, RoadState, Traffic, Watch};
use crate::vehicle::{
    AutoFlags, CaccState, Driver, Kind, LaneChangeState, Mode, ModeLabel, Relaxation, Route, Stats,
    Vehicle, NEVER, NO_EXIT,
};
use platoonsim_model::cav::{self, CaccLaw, Family};
use platoonsim_model::human::{self, HUMAN_DRAWS};
use platoonsim_model::lanechange::LC_DRAWS;
use platoonsim_model::{Leader, Relax};
use std::collections::VecDeque;

/// An entrance: its arrival stream and virtual queue. Entrance 0 is the mainline; entrance
/// i + 1 is on-ramp i of the network.
pub struct Entrance {
    rng: Stream,
    /// Arrival rate (veh/s) per demand interval for the whole entrance (one value: constant).
    rates: Vec<f64>,
    /// Demand interval length (s); ∞ for a constant rate.
    interval_s: f64,
    next_arrival_s: f64,
    pub(crate) queue: VecDeque<Vehicle>,
    /// On-ramp index (`None` for the mainline).
    pub(crate) ramp: Option<usize>,
}

impl Entrance {
    /// All entrances of a run: the mainline, then one per on-ramp.
    pub fn all(cfg: &Config) -> Vec<Entrance> {
        let Some(net) = &cfg.road.network else {
            let rate = cfg.demand.vph_per_lane * cfg.road.lanes as f64 / 3600.0;
            return vec![Entrance::new(cfg, 0, vec![rate], f64::INFINITY, None)];
        };
        let per_s =
            |v: &[f64]| -> Vec<f64> { v.iter().map(|q| q * net.demand_scale / 3600.0).collect() };
        let mut out = vec![Entrance::new(
            cfg,
            0,
            per_s(&net.mainline_vph),
            net.interval_s,
            None,
        )];
        for (i, r) in net.on_ramps.iter().enumerate() {
            out.push(Entrance::new(
                cfg,
                i as u64 + 1,
                per_s(&r.demand_vph),
                net.interval_s,
                Some(i),
            ));
        }
        out
    }

    fn new(
        cfg: &Config,
        index: u64,
        rates: Vec<f64>,
        interval_s: f64,
        ramp: Option<usize>,
    ) -> Entrance {
        let rng = Stream::new(cfg.seed, Purpose::Arrivals, index);
        let mut e = Entrance {
            rng,
            rates,
            interval_s,
            next_arrival_s: 0.0,
            queue: VecDeque::new(),
            ramp,
        };
        e.next_arrival_s = e.draw_after(0.0);
        e
    }

    fn rate_at(&self, t: f64) -> f64 {
        if self.rates.is_empty() {
            return 0.0;
        }
        let k = if self.interval_s.is_finite() {
            (t / self.interval_s).floor().max(0.0) as usize
        } else {
            0
        };
        self.rates[k.min(self.rates.len() - 1)]
    }

    /// The next arrival after `t` of a Poisson process whose rate is constant over each demand
    /// interval: an exponential headway at the current rate, redrawn from the boundary at the
    /// next interval's rate if it crosses one (exact, by memorylessness). A constant rate gives
    /// the same draws as a plain exponential sequence.
    fn draw_after(&mut self, mut t: f64) -> f64 {
        loop {
            let k = (t / self.interval_s).floor();
            let boundary = if self.interval_s.is_finite() {
                (k + 1.0) * self.interval_s
            } else {
                f64::INFINITY
            };
            let rate = self.rate_at(t);
            let last = !self.interval_s.is_finite() || k as usize + 1 >= self.rates.len();
            let h = self.rng.exponential(rate);
            if last || t + h < boundary {
                return t + h;
            }
            t = boundary;
        }
    }

    pub fn waiting(&self) -> usize {
        self.queue.len()
    }
}

/// Smallest distance from the entry point to an off-ramp the vehicle may choose (m) [D]: a
/// ramp vehicle cannot merge and reach an exit just downstream of its merge point.
pub const MIN_TRIP_TO_EXIT_M: f64 = 200.0;

/// Draw a new vehicle (type and parameters) from its own stream; on a network it also chooses
/// its exit on entry at `x` and time `t` (issue 4 item 1): for each off-ramp downstream in turn
/// a Bernoulli trial with that ramp's exit fraction for the current interval; the first success
/// is its exit, none means the mainline end. `origin` is the entrance's index.
pub(crate) fn create(cfg: &Config, id: u64, x: f64, t: f64, origin: u32) -> Vehicle {
    let mut rng = Stream::new(cfg.seed, Purpose::Vehicle, id);
    // An on-ramp may have its own share of CAVs (entrance i + 1 is on-ramp i).
    let penetration = match (&cfg.road.network, origin.checked_sub(1)) {
        (Some(net), Some(r)) => net
            .on_ramps
            .get(r as usize)
            .and_then(|r| r.penetration)
            .unwrap_or(cfg.penetration),
        _ => cfg.penetration,
    };
    let kind = if rng.uniform() < penetration {
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
    let mut exit = NO_EXIT;
    if let Some(net) = &cfg.road.network {
        for (k, r) in net.off_ramps.iter().enumerate() {
            if r.x_m < x + MIN_TRIP_TO_EXIT_M {
                continue;
            }
            if rng.uniform() < net.at(&r.exit_fraction, t) {
                exit = k as u32;
                break;
            }
        }
    }
    let human = cfg.human.sample(&zh, cfg.human.desired_speed_mps(z_speed));
    let cacc_gap_s = match kind {
        Kind::Cav => cav::draw_time_gap(&cfg.cav, u_gap),
        Kind::Human => 0.0,
    };
    Vehicle {
        x: 0.0,
        v: 0.0,
        a: 0.0,
        x_prev: 0.0,
        id,
        lane: 0,
        kind,
        mode: Mode::Cf,
        cacc: CaccState {
            pred: NEVER,
            time_gap_s: 0.0,
            gap_s: cacc_gap_s,
            family: Family::Speed,
            regime: None,
            auto: AutoFlags::NONE,
            max_platoon: 1,
            max_platoon_tg2: 1,
            beacon_age: 0,
        },
        lcs: LaneChangeState {
            relax: Relaxation::NONE,
            last_step: NEVER,
            count: 0,
            last_side: None,
            coop_count: 0,
        },
        driver: Driver {
            human,
            lc: cfg.lane_change.sample(&zl),
            rng,
        },
        route: Route {
            exit,
            origin,
            planned_exit: exit,
        },
        hold_wait: 0,
        stats: Stats {
            entered_step: NEVER,
            conflict_step: NEVER,
            conflict_leader: NEVER,
            measured: false,
            reported: (ModeLabel::Cf, None),
        },
    }
}

/// Tests: put a vehicle of `kind` with the mean driver (spec 2.6, 4.9) in `lane` at `x` with
/// speed `v`, in steady state (a = 0), automated if a CAV; returns its id. The lane list stays
/// sorted front first.
#[cfg(test)]
pub(crate) fn place_for_test(
    sim: &mut crate::Simulation,
    kind: Kind,
    lane: usize,
    x: f64,
    v: f64,
) -> u64 {
    let id = sim.traffic.next_id;
    sim.traffic.next_id += 1;
    let mut veh = create(&sim.cfg, id, x, 0.0, 0);
    veh.kind = kind;
    veh.driver.human = sim.cfg.human.mean();
    veh.driver.lc = sim.cfg.lane_change.mean();
    veh.lane = lane as u32;
    veh.x = x;
    veh.x_prev = x;
    veh.v = v;
    if kind == Kind::Cav {
        veh.cacc.gap_s = sim.cfg.cav.acc_time_gap_s;
        veh.cacc.time_gap_s = sim.cfg.cav.acc_time_gap_s;
        veh.cacc.family = Family::Gap;
    }
    veh.stats.entered_step = sim.clock.step;
    let s = sim.traffic.alloc(veh);
    let list = &sim.traffic.lanes[lane];
    let at = list.partition_point(|&o| sim.traffic.vehicles[o as usize].x > x);
    sim.traffic.lanes[lane].insert(at, s);
    id
}

/// What the insertion phase reads and writes.
pub(crate) struct Inserting<'a> {
    pub cfg: &'a Config,
    pub clock: &'a Clock,
    pub road: &'a RoadState,
    /// Platoon positions from this step's sense phase (a CAV entering behind a full platoon
    /// keeps the inter-platoon gap).
    pub sensed: &'a [Sensed],
    pub entrances: &'a mut [Entrance],
    pub traffic: &'a mut Traffic,
    /// The statistics' count of vehicles entered.
    pub entered: &'a mut u64,
    /// The trip record (the arrival time at the entrance, for the queue delay).
    pub rec: &'a mut Recorder,
    pub watch: &'a mut Watch,
    /// The loop detectors: an on-ramp counter counts each vehicle placed from its ramp.
    pub detectors: &'a mut crate::state::Detectors,
    /// The ramp meters: a metered ramp's head goes only at a green.
    pub meters: &'a mut crate::meter::Meters,
}

impl Inserting<'_> {
    /// Phase 5b: arrivals at every entrance, then insertion from each virtual queue.
    pub(crate) fn insert(&mut self) {
        let t_end = (self.clock.step + 1) as f64 * self.clock.dt;
        for e in 0..self.entrances.len() {
            while self.entrances[e].next_arrival_s <= t_end {
                let t = self.entrances[e].next_arrival_s;
                let x = match self.entrances[e].ramp {
                    None => 0.0,
                    Some(r) => self.road.geom.on_ramps[r].x,
                };
                let v = create(self.cfg, self.traffic.next_id, x, t, e as u32);
                self.traffic.next_id += 1;
                if self.rec.trips.is_some() {
                    self.rec.arrived(v.id, t);
                }
                let ent = &mut self.entrances[e];
                ent.queue.push_back(v);
                ent.next_arrival_s = ent.draw_after(t);
            }
            match self.entrances[e].ramp {
                None => self.insert_mainline(e),
                Some(r) => self.insert_ramp(e, r),
            }
        }
    }

    /// The mainline entrance: any lane open at x = 0, several vehicles per step (one per lane).
    fn insert_mainline(&mut self, e: usize) {
        let mut used = 0u32; // bit per lane
        let n_entry = self.road.geom.entry_lanes.len();
        while let Some(head) = self.entrances[e].queue.front() {
            let mut full: u32 = 0;
            let mut lane_v_des = [0.0f64; 32];
            let mut n_full = 0usize;
            let mut best: Option<(usize, f64)> = None;
            for i in 0..n_entry {
                let l = self.road.geom.entry_lanes[i] as usize;
                if used & (1 << l) != 0 {
                    continue;
                }
                // The desired speed in that lane (spec 2.7 caps; v_F without them).
                let v_des = self.entry_desired_speed(head, l);
                lane_v_des[l] = v_des;
                if let Some(v) = self.insertion_speed_at(
                    head,
                    0.0,
                    self.traffic.lanes[l].last().copied(),
                    None,
                    v_des,
                ) {
                    if v >= v_des {
                        full |= 1 << l;
                        n_full += 1;
                    } else if best.is_none_or(|(_, b)| v > b) {
                        best = Some((l, v));
                    }
                }
            }
            let (lane, speed) = if n_full > 0 {
                let head = self.entrances[e]
                    .queue
                    .front_mut()
                    .expect("queue has a head");
                let pick = head.driver.rng.index(n_full);
                let lane = (0..32)
                    .filter(|l| full & (1 << l) != 0)
                    .nth(pick)
                    .expect("pick < n_full");
                (lane, lane_v_des[lane])
            } else if let Some(b) = best {
                b
            } else {
                break;
            };
            let veh = self.entrances[e]
                .queue
                .pop_front()
                .expect("queue has a head");
            let at = self.traffic.lanes[lane].len();
            self.place(veh, lane, 0.0, speed, at);
            used |= 1 << lane;
        }
    }

    /// An on-ramp: at most one vehicle per step enters its lane at the merge point, at most at
    /// the ramp speed limit, if that is a steady state behind the vehicle (or wall) ahead and
    /// leaves the vehicle behind (a lane add, or a merged auxiliary lane) a comfortable gap.
    fn insert_ramp(&mut self, e: usize, r: usize) {
        let now = (self.clock.step + 1) as f64 * self.clock.dt;
        let gate = match self.meters.of_ramp(r) {
            None => Gate::Free,
            Some(m) => self.meters.list[m].gate(now, self.entrances[e].queue.len()),
        };
        if gate == Gate::Red {
            return;
        }
        let Some(head) = self.entrances[e].queue.front() else {
            return;
        };
        let ramp = &self.road.geom.on_ramps[r];
        let (x, lane) = (ramp.x, ramp.lane as usize);
        let v_max = self
            .road
            .section_speed(head.driver.human.desired_speed, x)
            .min(self.road.ramp_speed_mps);
        let list = &self.traffic.lanes[lane];
        let j = list.partition_point(|&o| self.traffic.vehicles[o as usize].x > x);
        let ld = (j > 0).then(|| list[j - 1]);
        // The nearest vehicle behind the merge point must be clear of the new one's body even
        // when a wall stops it before the merge point (it waits at the end of an upstream
        // acceleration lane of the same index, issue 35 item 4).
        if let Some(&b) = list.get(j) {
            if self.traffic.vehicles[b as usize].x > x - head.driver.human.length_m {
                return;
            }
        }
        // The follower, unless a wall stops it before the merge point (the end of an
        // upstream acceleration lane of the same index).
        let fo = list.get(j).copied().filter(|&f| {
            let fx = self.traffic.vehicles[f as usize].x;
            self.road
                .geom
                .wall_ahead(lane as u32, fx)
                .is_none_or(|w| w >= x)
        });
        let wall = self.road.geom.wall_ahead(lane as u32, x);
        let Some(speed) = self.insertion_speed_at(head, x, ld, wall, v_max) else {
            return;
        };
        if let Some(fs) = fo {
            let f = &self.traffic.vehicles[fs as usize];
            let gap = x - head.driver.human.length_m - f.x;
            if gap <= 0.0 {
                return;
            }
            let view = Leader {
                gap_m: gap,
                v_mps: speed,
            };
            // An automated follower under the field law is judged by its own handling of the
            // insertion (its controller after the cut-in reset, as the safe gap rule judges
            // it); every other follower by the human model, as before.
            let a = if f.automated() && self.cfg.cav.cacc_law == CaccLaw::Field {
                crate::decide::automated_follower_after(
                    self.cfg,
                    self.clock.dt,
                    f,
                    f.driver.human.desired_speed,
                    head,
                    view,
                )
            } else {
                human::target_accel(
                    &f.driver.human,
                    f.v,
                    f.driver.human.desired_speed,
                    Some(view),
                    Relax::NONE,
                )
            };
            if a < f.driver.human.comfort_decel {
                return;
            }
        }
        let veh = self.entrances[e]
            .queue
            .pop_front()
            .expect("queue has a head");
        if let Some(m) = self.meters.of_ramp(r) {
            self.meters.list[m].released(gate, now, self.clock.dt);
        }
        if let Some(d) = self.detectors.entry_of_ramp[r] {
            self.detectors.list[d].count_exit(speed, veh.is_cav());
        }
        let len = veh.driver.human.length_m;
        self.place(veh, lane, x, speed, j);
        // The automated follower resets its gap reference to the actual gap (field law).
        if let Some(fs) = fo {
            let f = &mut self.traffic.vehicles[fs as usize];
            if f.automated() {
                f.cacc.time_gap_s =
                    cav::cut_in_time_gap(&self.cfg.cav, f.cacc.time_gap_s, x - len - f.x, f.v);
            }
        }
    }

    /// Put a vehicle on the road at list index `at` of `lane`.
    fn place(&mut self, mut veh: Vehicle, lane: usize, x: f64, speed: f64, at: usize) {
        veh.lane = lane as u32;
        veh.x = x;
        veh.x_prev = x;
        veh.v = speed;
        veh.a = 0.0;
        veh.stats.entered_step = self.clock.step + 1;
        veh.stats.measured = veh.stats.entered_step >= self.clock.warmup_step;
        if veh.is_cav() {
            veh.cacc.time_gap_s = veh.cacc.gap_s;
            if at > 0 {
                let ld = self.traffic.lanes[lane][at - 1];
                veh.cacc.time_gap_s = self.entry_time_gap(&veh, ld);
                if self.traffic.vehicles[ld as usize].rear() - x < 2.0 * speed.max(1.0) {
                    veh.cacc.family = Family::Gap;
                }
            }
        }
        *self.entered += 1;
        veh.stats.reported = (veh.mode_label(), veh.cacc.regime);
        if self.watch.observing {
            self.watch.events.push(Event::Entered {
                t_s: crate::record::step_time(self.clock.step + 1, self.clock.dt),
                id: veh.id,
                kind: veh.kind,
                entrance: veh.route.origin,
                lane: veh.lane,
                x_m: x + self.cfg.road.origin_m(),
                v_mps: speed,
            });
        }
        let s = self.traffic.alloc(veh);
        self.traffic.lanes[lane].insert(at, s);
    }

    /// The time gap a CAV entering behind slot `ld` keeps (spec 3.6): its own t_C behind a CAV
    /// whose platoon has room, the inter-platoon gap behind a full one, t_A behind a human.
    fn entry_time_gap(&self, veh: &Vehicle, ld: u32) -> f64 {
        let p = &self.cfg.cav;
        if !self.traffic.vehicles[ld as usize].is_cav() {
            p.acc_time_gap_s
        } else if self.sensed.get(ld as usize).map_or(1, |t| t.platoon_pos) >= p.max_platoon {
            p.inter_platoon_gap_s
        } else {
            veh.cacc.gap_s
        }
    }

    /// The desired speed of `veh` in entry `lane` at x = 0: v_F, capped by the lane's speed
    /// limit when the network has lane-based caps (spec 2.7, counted from the rightmost through
    /// lane there), so that it enters in steady state.
    fn entry_desired_speed(&self, veh: &Vehicle, lane: usize) -> f64 {
        let v_f = self.road.section_speed(veh.driver.human.desired_speed, 0.0);
        if self.road.lane_caps_mps.is_empty() {
            return v_f;
        }
        let right = self
            .road
            .geom
            .rightmost_through(0.0)
            .map_or(NO_LANE, |r| r as u8);
        self.road.lane_capped(v_f, lane, right)
    }

    /// The speed (at most `v_max`) at which `veh` may enter at `x` behind slot `ld` (and a wall
    /// at `wall`, a standing obstacle) in steady state, if any: `v_max` if it needs no braking
    /// there, otherwise the leader's speed if that does, otherwise none.
    fn insertion_speed_at(
        &self,
        veh: &Vehicle,
        x: f64,
        ld: Option<u32>,
        wall: Option<f64>,
        v_max: f64,
    ) -> Option<f64> {
        let v_des = self.road.section_speed(veh.driver.human.desired_speed, x);
        let section = self.road.section_human(&veh.driver.human, x);
        let hp = section.as_ref().unwrap_or(&veh.driver.human);
        let mut leader = ld.map(|ld| {
            let l = &self.traffic.vehicles[ld as usize];
            (
                Leader {
                    gap_m: l.rear() - x,
                    v_mps: l.v,
                },
                Some(l),
            )
        });
        if let Some(w) = wall {
            if leader.is_none_or(|(l, _)| w - x < l.gap_m) {
                leader = Some((
                    Leader {
                        gap_m: w - x,
                        v_mps: 0.0,
                    },
                    None,
                ));
            }
        }
        let Some((leader, lv)) = leader else {
            return Some(v_max);
        };
        if leader.gap_m <= 0.0 {
            return None;
        }
        let ok = |v: f64| -> bool {
            match (veh.kind, lv) {
                (Kind::Cav, Some(l)) => {
                    let p = &self.cfg.cav;
                    if leader.gap_m > p.sensor_range_m {
                        return true;
                    }
                    let t = self.entry_time_gap(veh, ld.expect("a vehicle leader"));
                    let eq = if l.is_cav() {
                        cav::cacc_equilibrium_gap(p, t, v)
                    } else {
                        cav::acc_equilibrium_gap(p, t, v)
                    };
                    leader.gap_m >= eq && cav::safe_speed(p, leader.gap_m, l.v) >= v
                }
                _ => human::target_accel(hp, v, v_des, Some(leader), Relax::NONE) >= 0.0,
            }
        };
        if ok(v_max) {
            Some(v_max)
        } else {
            let v = leader.v_mps.min(v_max);
            ok(v).then_some(v)
        }
    }
}
