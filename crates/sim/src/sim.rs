//! The simulation state and the step.

use crate::config::{Config, DetectorKind};
use crate::detector::Detector;
use crate::error::SimError;
use crate::events::CollisionKind;
use crate::events::{Departure, Event, Observer, StepView};
use crate::here::HereTables;
use crate::insert::Entrance;
use crate::metrics::Metrics;
use crate::network::Geometry;
use crate::organize::{self, Organizer};
use crate::record::{Recorder, Recording, TrajectoryRecorder};
use crate::safety::Safety;
use crate::state::{Clock, Control, Detectors, Measures, RoadState, Scratch, Traffic, Watch};
use crate::summary::{Output, Summary};
use crate::view::VehicleView;

/// Steps between two renumberings of the vehicle slots (`Simulation::compact`).
const COMPACT_EVERY_STEPS: u64 = 600;

/// The whole simulation state.
pub struct Simulation {
    pub(crate) cfg: Config,
    pub(crate) clock: Clock,
    pub(crate) traffic: Traffic,
    pub(crate) road: RoadState,
    /// Mainline entrance first, then one per on-ramp.
    pub(crate) entrances: Vec<Entrance>,
    /// Section behaviour (`behaviour.rs`); `None` without stretches.
    pub(crate) sections: Option<crate::behaviour::Sections>,
    pub(crate) scratch: Scratch,
    pub(crate) detectors: Detectors,
    pub(crate) measures: Measures,
    pub(crate) control: Control,
    /// Optional trip and trajectory records (`record.rs`); off unless [`Simulation::record`].
    pub(crate) rec: Recorder,
    pub(crate) watch: Watch,
    /// Fuel and electricity per vehicle (`energy.rs`); only with `energy.enabled`.
    pub(crate) energy: Option<Box<crate::energy::EnergyMeter>>,
    /// The ramp meters (`meter.rs`); empty without any.
    pub(crate) meters: crate::meter::Meters,
    /// The mechanism measures (`mechanism.rs`); only with `measurement.mechanism`.
    pub(crate) mechanism: Option<Box<crate::mechanism::Mechanism>>,
}

impl Simulation {
    /// Build a simulation from a validated config.
    pub fn new(cfg: Config) -> Result<Simulation, SimError> {
        cfg.check()?;
        let dt = cfg.dt_s;
        let n_lanes = cfg.road.lanes as usize;
        let steps = |s: f64| (s / dt).round() as u64;
        let geom = Geometry::new(&cfg)?;
        let origin = cfg.road.origin_m();
        let detectors = cfg
            .detectors
            .iter()
            .map(|d| {
                let mask = match d.kind {
                    DetectorKind::OffRamp { .. } | DetectorKind::OnRamp { .. } => 1,
                    DetectorKind::Mainline => (0..n_lanes as u32)
                        .filter(|&l| geom.through(l, d.position_m))
                        .fold(0u32, |m, l| m | (1 << l)),
                };
                let mut det = Detector::covering(&d.name, d.position_m, n_lanes, mask, origin);
                det.exit = d.exit;
                det.kind = match d.kind {
                    DetectorKind::Mainline => "mainline",
                    DetectorKind::OffRamp { .. } => "off-ramp",
                    DetectorKind::OnRamp { .. } => "on-ramp",
                };
                det
            })
            .collect::<Vec<_>>();
        let mut exit_detector = vec![None; geom.off_ramps.len()];
        let mut entry_detector = vec![None; geom.on_ramps.len()];
        for (i, d) in cfg.detectors.iter().enumerate() {
            match d.kind {
                DetectorKind::OffRamp { ramp } => exit_detector[ramp] = Some(i),
                DetectorKind::OnRamp { ramp } => entry_detector[ramp] = Some(i),
                DetectorKind::Mainline => {}
            }
        }
        let ramp_speed_mps = cfg
            .road
            .network
            .as_ref()
            .map_or(f64::INFINITY, |n| n.ramp_speed_kmh / 3.6);
        let lane_caps_mps = cfg.road.network.as_ref().map_or(Vec::new(), |n| {
            n.lane_speed_limits_kmh.iter().map(|c| c / 3.6).collect()
        });
        let meters = crate::meter::Meters::new(&cfg, &geom, n_lanes);
        let mut sim = Simulation {
            meters,
            clock: Clock {
                dt,
                step: 0,
                total_steps: steps(cfg.duration_s),
                warmup_step: steps(cfg.warmup_s),
                agg_steps: steps(cfg.aggregation_s).max(1),
            },
            traffic: Traffic {
                lanes: vec![Vec::new(); n_lanes],
                auto: crate::automation::Automation::new(&cfg),
                ..Traffic::default()
            },
            entrances: Entrance::all(&cfg),
            sections: cfg
                .road
                .network
                .as_ref()
                .and_then(|n| crate::behaviour::Sections::new(&n.behaviour)),
            scratch: Scratch {
                ramp_factor: vec![[1.0; 2]; geom.on_ramps.len()],
                ..Scratch::default()
            },
            road: RoadState {
                here_tables: HereTables::new(&geom),
                geom,
                ramp_speed_mps,
                lane_caps_mps,
                friction: cfg
                    .road
                    .network
                    .as_ref()
                    .and_then(|n| n.cross_lane_friction)
                    .filter(|&c| c < 1.0),
                behaviour: cfg
                    .road
                    .network
                    .as_ref()
                    .map_or(Vec::new(), |n| n.behaviour.clone()),
            },
            detectors: Detectors {
                list: detectors,
                hint: Vec::new(),
                exit_of_ramp: exit_detector,
                entry_of_ramp: entry_detector,
            },
            measures: Measures {
                metrics: Metrics::default(),
                safety: Safety::new(&cfg),
                vehicle_updates: 0,
                missed_exits: 0,
                cacc_fallbacks: 0,
            },
            control: Control {
                organizer: Box::new(crate::organize::NoOrganizer),
                advise: [false; 2],
                commands: Vec::new(),
            },
            rec: Recorder::default(),
            watch: Watch::default(),
            energy: cfg
                .energy
                .enabled
                .then(|| Box::new(crate::energy::EnergyMeter::new(&cfg))),
            mechanism: cfg
                .mechanism
                .then(|| Box::new(crate::mechanism::Mechanism::of(&cfg))),
            cfg,
        };
        let organizer = organize::build(&sim.cfg);
        sim.install(organizer);
        Ok(sim)
    }

    /// Organize platoons with `organizer` instead of the strategy the config names (a
    /// strategy of the library user's own; docs/organizers.md). The summary's `strategy` is
    /// then the organizer's name. Must be called before the first step.
    pub fn set_organizer(&mut self, organizer: Box<dyn Organizer>) -> Result<(), SimError> {
        if self.clock.step > 0 {
            return Err(SimError::AfterFirstStep("the organizer must be set"));
        }
        self.install(organizer);
        Ok(())
    }

    fn install(&mut self, organizer: Box<dyn Organizer>) {
        self.control.advise = [organizer.advises_humans(), organizer.advises_cavs()];
        self.control.organizer = organizer;
    }

    /// Also record what `recording` asks for (trips, trajectories); they come back in
    /// [`Output::trips`] and [`Output::trajectories`]. Recording reads the state and never
    /// changes the simulation. Must be called before the first step.
    pub fn record(&mut self, recording: &Recording) -> Result<(), SimError> {
        recording.check(&self.cfg)?;
        if self.clock.step > 0 {
            return Err(SimError::AfterFirstStep("recording must be enabled"));
        }
        let origin = self.origin_m();
        self.rec = Recorder {
            trips: recording.trips.then(Vec::new),
            trajectories: recording
                .trajectories
                .as_ref()
                .map(|t| TrajectoryRecorder::new(t, &self.cfg, origin)),
            entry_x: std::iter::once(0.0)
                .chain(self.road.geom.on_ramps.iter().map(|r| r.x))
                .collect(),
            arrived_s: Vec::new(),
            origin_m: origin,
            dt: self.clock.dt,
        };
        Ok(())
    }

    /// Attach an observer of the library user's own (events.rs; docs/library.md): it gets
    /// every step's events and the state after the step, and every vehicle as it leaves.
    /// Observers never change the simulation. Must be called before the first step.
    pub fn observe(&mut self, observer: Box<dyn Observer>) -> Result<(), SimError> {
        if self.clock.step > 0 {
            return Err(SimError::AfterFirstStep("observers must be attached"));
        }
        self.watch.observers.push(observer);
        self.watch.observing = true;
        self.measures.safety.braking.logging = true;
        Ok(())
    }

    /// The first attached observer of type `T` (to read what it gathered).
    pub fn observer<T: Observer + 'static>(&self) -> Option<&T> {
        self.watch
            .observers
            .iter()
            .find_map(|o| o.as_any().downcast_ref::<T>())
    }

    /// Output coordinate of engine x = 0 (the network origin; 0 on a plain road).
    pub(crate) fn origin_m(&self) -> f64 {
        self.cfg.road.origin_m()
    }

    /// Slot `s` leaves the road as `how` in this step (or is still on it at the end): the
    /// statistics, the trip record and the user's observers see it, in that order.
    pub(crate) fn leave(&mut self, s: u32, how: Departure) {
        let origin_m = self.origin_m();
        crate::exits::Departures {
            clock: &self.clock,
            origin_m,
            metrics: &mut self.measures.metrics,
            rec: &mut self.rec,
            watch: &mut self.watch,
            energy: &mut self.energy,
        }
        .leave(&self.traffic.vehicles[s as usize], how);
    }

    /// Simulated time (s), as the records print it (`record::step_time`: 12.3 rather than
    /// 12.300000000000001).
    pub fn time_s(&self) -> f64 {
        crate::record::step_time(self.clock.step, self.clock.dt)
    }

    /// True once the configured duration has been simulated.
    pub fn finished(&self) -> bool {
        self.clock.step >= self.clock.total_steps
    }

    /// The config this simulation runs.
    pub fn config(&self) -> &Config {
        &self.cfg
    }

    /// Vehicles on the road in `lane` (0 = rightmost), front first.
    pub fn lane_vehicles(&self, lane: usize) -> impl Iterator<Item = VehicleView<'_>> + '_ {
        crate::view::lane(&self.traffic.lanes[lane], &self.traffic.vehicles)
    }

    /// Number of vehicles on the road.
    pub fn vehicles_in_network(&self) -> usize {
        self.traffic.lanes.iter().map(Vec::len).sum()
    }

    /// Vehicles waiting in the virtual entry queue.
    pub fn vehicles_waiting(&self) -> usize {
        self.entrances.iter().map(Entrance::waiting).sum()
    }

    /// Collisions so far: vehicle pairs that started to overlap, vehicles that reached the end
    /// of their lane.
    pub fn collisions(&self) -> u64 {
        self.measures.safety.collisions.events.len() as u64
    }

    /// The paper's statistics so far (metrics.rs): counted as vehicles leave the road.
    pub fn metrics(&self) -> &crate::metrics::Metrics {
        &self.measures.metrics
    }

    /// The collisions so far, in time order.
    pub fn collision_events(&self) -> &[crate::events::CollisionEvent] {
        &self.measures.safety.collisions.events
    }

    /// Advance one step. Phases, in this order, each reading the state the previous one left:
    ///
    /// 1. **sense**: same-lane leaders and adjacent-lane leaders/followers (a merge sweep over
    ///    the position-sorted lanes); CACC links and platoon positions; platoon statistics.
    /// 2. **decide**: every vehicle, from the step-start state only (synchronous update):
    ///    lane-change desire and gap acceptance (spec 4), yielding, then the acceleration of
    ///    its mode (human model spec 2, or CAV control spec 3).
    /// 3. **integrate**: ballistic update, speeds never negative (spec 1).
    /// 4. **lane changes**: accepted changes are re-checked on the new positions and applied
    ///    instantaneously, front to back, lane by lane (spec 4.4).
    /// 5. **boundaries**: exits at the downstream end, then arrivals and insertion from the
    ///    virtual entry queue.
    /// 6. **detectors**: crossings and occupancy; interval close and broadcast.
    /// 7. **invariants**: no overlap (an overlap is counted as a collision), all states finite.
    pub fn step(&mut self) -> Result<(), SimError> {
        if let Some(sec) = &mut self.sections {
            sec.apply(&self.road.behaviour, &mut self.traffic);
        }
        if let Some(b) = &self.traffic.auto.beacons {
            b.receive(
                self.clock.step,
                &self.traffic.lanes,
                &mut self.traffic.vehicles,
            );
        }
        crate::sense::sense(
            &self.cfg.cav,
            &mut self.traffic,
            &self.road,
            &mut self.scratch,
        );
        crate::decide::decide(
            &self.cfg,
            &self.clock,
            &self.traffic,
            &self.road,
            &self.entrances,
            &mut self.control,
            &mut self.scratch,
        );
        self.integrate();
        let origin = self.origin_m();
        crate::execute::apply_lane_changes(
            &self.cfg,
            &self.clock,
            origin,
            &self.road,
            &mut self.traffic,
            &mut self.scratch,
            &mut self.watch,
        );
        let origin_m = self.origin_m();
        crate::exits::exits(
            self.cfg.road.length_m,
            &self.road,
            &mut self.traffic,
            &mut self.scratch.exit_due,
            &mut self.detectors.list,
            &self.detectors.exit_of_ramp,
            &mut self.measures.missed_exits,
            &mut crate::exits::Departures {
                clock: &self.clock,
                origin_m,
                metrics: &mut self.measures.metrics,
                rec: &mut self.rec,
                watch: &mut self.watch,
                energy: &mut self.energy,
            },
        );
        crate::insert::Inserting {
            cfg: &self.cfg,
            clock: &self.clock,
            road: &self.road,
            sensed: &self.scratch.sensed,
            entrances: &mut self.entrances,
            traffic: &mut self.traffic,
            entered: &mut self.measures.metrics.entered,
            rec: &mut self.rec,
            watch: &mut self.watch,
            detectors: &mut self.detectors,
            meters: &mut self.meters,
        }
        .insert();
        crate::detect::observe_detectors(
            self.clock.dt,
            &self.traffic,
            self.scratch.lanes_sorted,
            &mut self.detectors,
        );
        if !self.meters.list.is_empty() {
            self.meters
                .observe(self.clock.dt, &self.traffic, self.scratch.lanes_sorted);
        }
        self.clock.step += 1;
        if !self.meters.list.is_empty() {
            self.meters.control(self.clock.step, self.clock.dt);
        }
        if self.clock.step.is_multiple_of(COMPACT_EVERY_STEPS) {
            self.compact();
        }
        if self.clock.step.is_multiple_of(self.clock.agg_steps) {
            for d in &mut self.detectors.list {
                d.close_interval();
            }
            self.broadcast();
        }
        if self
            .rec
            .trajectories
            .as_ref()
            .is_some_and(|t| t.due(self.clock.step))
        {
            let origin_m = self.origin_m();
            self.rec
                .on_step(&step_view(&self.clock, origin_m, &self.traffic, &[]));
        }
        if let Some(e) = self.energy.as_mut() {
            let origin_m = self.cfg.road.origin_m();
            e.on_step(&step_view(&self.clock, origin_m, &self.traffic, &[]));
        }
        if let Some(m) = self.mechanism.as_mut() {
            let origin_m = self.cfg.road.origin_m();
            m.on_step(
                &step_view(&self.clock, origin_m, &self.traffic, &[]),
                &self.road.geom,
            );
        }
        let checked = crate::invariants::check_invariants(
            &self.clock,
            self.origin_m(),
            &mut self.traffic,
            &mut self.measures.safety,
        );
        if self.watch.observing {
            self.notify();
        }
        checked
    }

    /// Phase 3: the decided acceleration bounded by the vehicle's emergency limit
    /// (`safety.rs`), then v' = max(0, v + aΔt); x' = x + ½(v + v')Δt, or the stopping point
    /// when the speed would turn negative. A vehicle whose front passes the end of its lane
    /// has collided with it: the event is recorded and the vehicle leaves the road.
    pub(crate) fn integrate(&mut self) {
        crate::integrate::move_vehicles(
            &self.clock,
            &self.road.geom,
            &mut self.traffic,
            &mut self.scratch,
            &mut self.measures,
        );
        if self.watch.observing {
            self.log_brakings();
        }
        if !self.scratch.crashed.is_empty() {
            self.remove_crashed();
        }
    }

    /// The vehicles that ran past the end of their lane in this step: one collision each, and
    /// they leave the road (their trip ends as `collided`). Removing them keeps every lane
    /// sorted.
    #[cold]
    #[inline(never)]
    fn remove_crashed(&mut self) {
        let t = crate::record::step_time(self.clock.step + 1, self.clock.dt);
        let origin = self.origin_m();
        for (s, l, w) in std::mem::take(&mut self.scratch.crashed) {
            let v = &self.traffic.vehicles[s as usize];
            self.measures.safety.collide(
                t,
                CollisionKind::LaneEnd,
                l as usize,
                v.x + origin,
                v,
                None,
                v.x - w,
            );
            if self.watch.observing {
                self.log_collisions();
            }
            self.traffic.lanes[l as usize].retain(|&o| o != s);
            self.leave(s, Departure::Collided);
            self.traffic.free.push(s);
        }
    }

    /// Run to the end and produce the outputs.
    pub fn finish(mut self, wall_seconds: f64) -> Output {
        // Vehicles still on the road count with what they did so far (in id order, the
        // order of their trip records).
        let mut on_road: Vec<u32> = self.traffic.lanes.iter().flatten().copied().collect();
        on_road.sort_unstable_by_key(|&s| self.traffic.vehicles[s as usize].id);
        for s in on_road {
            self.leave(s, Departure::OnRoad);
        }
        let queued = self.rec.trips.is_some().then(|| {
            crate::record::queued_of(
                self.entrances.iter().flat_map(|e| e.queue.iter()),
                &self.rec.arrived_s,
                crate::record::step_time(self.clock.step, self.clock.dt),
            )
        });
        let mut trips = self.rec.trips.take();
        if let (Some(trips), Some(e)) = (trips.as_mut(), self.energy.as_ref()) {
            for t in trips {
                t.energy = e.trip(t.id, t.kind);
            }
        }
        let trajectories = self.rec.trajectories.take().map(|t| t.rows);
        let cfg = &self.cfg;
        let det = &self.detectors.list[cfg.measurement_detector];
        let lanes = det.covered_lanes() as f64;
        let interval = cfg.aggregation_s;
        let first = (cfg.warmup_s / interval).ceil() as usize;
        let mut window_count = 0u64;
        let mut window_intervals = 0usize;
        let mut max_flow: f64 = 0.0;
        for k in first..det.intervals() {
            let c = det.total_count(k);
            window_count += c;
            window_intervals += 1;
            max_flow = max_flow.max(c as f64 * 3600.0 / interval / lanes);
        }
        let window_h = window_intervals as f64 * interval / 3600.0;
        let network_discharge = cfg.road.network.as_ref().map(|_| {
            let n: u64 = self
                .detectors
                .list
                .iter()
                .filter(|d| d.exit)
                .map(|d| {
                    (first..d.intervals())
                        .map(|k| d.total_count(k))
                        .sum::<u64>()
                })
                .sum();
            if window_h > 0.0 {
                n as f64 / window_h
            } else {
                0.0
            }
        });
        let zero_flow_intervals = self
            .detectors
            .list
            .iter()
            .filter(|d| d.kind == "mainline")
            .map(|d| {
                (first..d.intervals())
                    .filter(|&k| d.total_count(k) == 0)
                    .count() as u64
            })
            .sum();
        let discharge = if window_h > 0.0 {
            window_count as f64 / window_h / lanes
        } else {
            0.0
        };
        let m = &self.measures.metrics;
        let sf = &self.measures.safety;
        let summary = Summary {
            scenario: cfg.name.clone(),
            penetration: cfg.penetration,
            demand_vphpl: cfg
                .road
                .network
                .is_none()
                .then_some(cfg.demand.vph_per_lane),
            demand_scale: cfg.road.network.as_ref().map(|n| n.demand_scale),
            strategy: self.control.organizer.name().to_string(),
            seed: cfg.seed,
            dt_s: cfg.dt_s,
            duration_s: cfg.duration_s,
            warmup_s: cfg.warmup_s,
            vehicles_entered: m.entered,
            vehicles_exited: m.exited,
            vehicles_in_network: self.vehicles_in_network() as u64,
            vehicles_waiting: self.vehicles_waiting() as u64,
            lane_changes_per_vehicle: m.lane_changes_per_vehicle(),
            lane_changes_per_cav: m.lane_changes_by_type().0,
            lane_changes_per_human: m.lane_changes_by_type().1,
            cooperative_lane_changes: m.cooperative_lane_changes,
            avg_platoon_length: m.avg_platoon_length(),
            platooning_probability: m.platooning_probability(),
            avg_platoon_length_tg2: m.platoon_stats_tg2().0,
            platooning_probability_tg2: m.platoon_stats_tg2().1,
            cavs_counted: m.cavs_counted,
            vehicles_counted: m.vehicles_counted,
            discharge_flow_vphpl: discharge,
            max_sustained_flow_vphpl: max_flow,
            network_discharge_vph: network_discharge,
            zero_flow_intervals,
            missed_exits: self.measures.missed_exits,
            collisions: self.measures.safety.collisions.events.len() as u64,
            max_deceleration_mps2: sf.braking.max_decel,
            vehicle_km: sf.counts.vehicle_km.total(),
            vehicle_km_cav: sf.counts.vehicle_km.cav,
            vehicle_km_human: sf.counts.vehicle_km.human,
            counted: sf.counted_measures(),
            braking_peaks: sf.braking_peaks(),
            tet_s: sf.exposure.tet_s.total(),
            tet_s_cav: sf.exposure.tet_s.cav,
            tet_s_human: sf.exposure.tet_s.human,
            tit_s2: sf.exposure.tit_s2.total(),
            tit_s2_cav: sf.exposure.tit_s2.cav,
            tit_s2_human: sf.exposure.tit_s2.human,
            min_ttc_s: sf
                .exposure
                .min_ttc_s
                .is_finite()
                .then_some(sf.exposure.min_ttc_s),
            cacc_fallbacks: self.measures.cacc_fallbacks,
            energy: self.energy.as_ref().map(|e| e.summary()),
            mechanism: self.mechanism.as_ref().map(|m| {
                let (lowest, counts) = det.lane_counts(first);
                m.summary_at(
                    det.position_m,
                    lowest,
                    &counts,
                    window_h,
                    &self.road.geom,
                    cfg.road.origin_m(),
                )
            }),
            meters: self.meters.summaries(self.clock.dt),
            vehicle_updates: self.measures.vehicle_updates,
            steps: self.clock.step,
            wall_seconds,
        };
        let mut detectors = Vec::new();
        for d in &self.detectors.list {
            d.records(interval, &mut detectors);
        }
        Output {
            summary,
            detectors,
            collision_events: std::mem::take(&mut self.measures.safety.collisions.events),
            trips,
            queued,
            trajectories,
        }
    }

    /// The hard brakings that started in this step's integrate phase, as events.
    #[cold]
    #[inline(never)]
    pub(crate) fn log_brakings(&mut self) {
        let t = crate::record::step_time(self.clock.step + 1, self.clock.dt);
        for (id, kind, decel) in self.measures.safety.braking.brakings.drain(..) {
            self.watch.events.push(Event::HardBraking {
                t_s: t,
                id,
                kind,
                decel_mps2: decel,
            });
        }
    }

    /// The collisions recorded since the last call, as events.
    #[cold]
    #[inline(never)]
    pub(crate) fn log_collisions(&mut self) {
        for c in &self.measures.safety.collisions.events[self.watch.collisions_reported..] {
            self.watch.events.push(Event::Collision(c.clone()));
        }
        self.watch.collisions_reported = self.measures.safety.collisions.events.len();
    }

    /// End of a step with observers attached: the rear-end collisions and the mode changes
    /// of the step become events, and every observer gets the step's events and the state.
    #[cold]
    #[inline(never)]
    fn notify(&mut self) {
        self.log_collisions();
        let t = crate::record::step_time(self.clock.step, self.clock.dt);
        let Traffic {
            lanes, vehicles, ..
        } = &mut self.traffic;
        let events = &mut self.watch.events;
        for lane in lanes.iter() {
            for &s in lane {
                let v = &mut vehicles[s as usize];
                let now = (v.mode_label(), v.cacc.regime);
                if v.stats.reported != now {
                    events.push(Event::ModeChange {
                        t_s: t,
                        id: v.id,
                        kind: v.kind,
                        from: v.stats.reported.0,
                        to: now.0,
                        regime_from: v.stats.reported.1,
                        regime_to: now.1,
                    });
                    v.stats.reported = now;
                }
            }
        }
        let Watch {
            observers, events, ..
        } = &mut self.watch;
        let origin_m = self.cfg.road.origin_m();
        let view = step_view(&self.clock, origin_m, &self.traffic, events);
        for o in observers.iter_mut() {
            o.on_step(&view);
        }
        events.clear();
    }

    /// At the end of an aggregation interval: the detectors' broadcasts to the organizer
    /// (the Flow-Aware condition is recomputed from them).
    fn broadcast(&mut self) {
        let interval = self.cfg.aggregation_s;
        let casts: Vec<_> = self
            .detectors
            .list
            .iter()
            // On-ramp counters say nothing of the mainline's condition (off-ramp counters
            // have always been read, as in the paper's runs).
            .filter(|d| d.kind != "on-ramp")
            .filter_map(|d| d.broadcast(interval).map(|b| (d.position_m, b)))
            .collect();
        self.control
            .organizer
            .on_broadcasts(&self.road.geom, &casts);
    }

    /// Renumber the slots in lane order, front first (memory locality only: neighbours in a
    /// lane become neighbours in memory). Nothing depends on slot numbers across steps: every
    /// slot-indexed array is rebuilt by the next sense phase before it is read, or renumbered
    /// here (the beacon log, the section behaviour's record of each vehicle); insertion reads
    /// `Sensed::platoon_pos` only of vehicles that were on the road at that phase: the mainline
    /// entrance inserts first and on-ramps are listed in downstream order; identities are vehicle ids,
    /// and no result is accumulated in slot order.
    fn compact(&mut self) {
        let on_road = self.vehicles_in_network();
        let mut packed = Vec::with_capacity(on_road.max(self.traffic.vehicles.len()));
        let logging = self.traffic.auto.beacons.is_some() || self.sections.is_some();
        let mut order = Vec::new();
        for lane in &mut self.traffic.lanes {
            for s in lane.iter_mut() {
                packed.push(self.traffic.vehicles[*s as usize].clone());
                if logging {
                    order.push(*s);
                }
                *s = (packed.len() - 1) as u32;
            }
        }
        self.traffic.vehicles = packed;
        if let Some(b) = &mut self.traffic.auto.beacons {
            b.renumber(&order);
        }
        if let Some(sec) = &mut self.sections {
            sec.renumber(&order);
        }
        self.traffic.free.clear();
        self.scratch.changed_this_step.fill(u64::MAX);
    }
}

/// The state after the last step as an observer sees it, with `events` as its events.
fn step_view<'a>(
    clock: &Clock,
    origin_m: f64,
    traffic: &'a Traffic,
    events: &'a [Event],
) -> StepView<'a> {
    StepView::new(
        clock.step,
        crate::record::step_time(clock.step, clock.dt),
        origin_m,
        &traffic.lanes,
        &traffic.vehicles,
        events,
    )
}
