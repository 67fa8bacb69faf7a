//! Platoon organization through the `Organizer` seam (issue 19): the dedicated lane, the PD
//! lane on another side, and an organizer of a library user's own.
//!
//! Homogeneous road, 50 % CAV, 1,500 veh/h/lane, 40 min with 20 min of warm-up (the strategies
//! apply in the measurement window, in the control section 5,000-6,000 m).

use platoonsim_scenario::{load_with, Overrides, StrategyKind};
use platoonsim_sim::network::Geometry;
use platoonsim_sim::vehicle::Kind;
use platoonsim_sim::VehicleView;
use platoonsim_sim::{
    run_recording, Advice, Config, Organizer, Output, Recording, Simulation, TrajectorySpec,
};

const WARMUP_S: f64 = 1200.0;

fn config(strategy: StrategyKind, seed: u64, set: &[&str]) -> Config {
    let o = Overrides {
        penetration: Some(0.5),
        demand_vphpl: Some(1500.0),
        duration_s: Some(2400.0),
        warmup_s: Some(WARMUP_S),
        seed: Some(seed),
        strategy: Some(strategy),
        set: set.iter().map(|s| s.to_string()).collect(),
    };
    load_with("homogeneous", &o).unwrap()
}

/// Trajectories every second over the last 500 m of the control section, in the window.
fn recording() -> Recording {
    Recording {
        trips: false,
        trajectories: Some(TrajectorySpec {
            period_s: 1.0,
            window_s: Some((WARMUP_S, 2400.0)),
            x_m: Some((5500.0, 6000.0)),
        }),
    }
}

fn run(c: &Config) -> Output {
    let out = run_recording(c, &recording(), None).unwrap();
    assert_eq!(
        out.summary.collisions, 0,
        "{}: a run with a collision",
        c.name
    );
    out
}

/// Share of the samples of `kind` that are in lane `lane` (engine index).
fn share_in_lane(out: &Output, kind: Kind, lane: u32) -> f64 {
    let rows = out.trajectories.as_ref().unwrap();
    let of_kind: Vec<_> = rows.iter().filter(|r| r.kind == kind).collect();
    assert!(of_kind.len() > 1000, "{} samples", of_kind.len());
    of_kind.iter().filter(|r| r.lane == lane).count() as f64 / of_kind.len() as f64
}

#[test]
fn the_dedicated_lane_keeps_humans_out_and_lengthens_platoons() {
    for seed in [1, 2] {
        let base = run(&config(StrategyKind::NONE, seed, &[]));
        let ded = run(&config(StrategyKind::DEDICATED, seed, &[]));
        let humans_base = share_in_lane(&base, Kind::Human, 2);
        let humans = share_in_lane(&ded, Kind::Human, 2);
        let cavs = share_in_lane(&ded, Kind::Cav, 2);
        let (lb, ld) = (
            base.summary.avg_platoon_length.unwrap(),
            ded.summary.avg_platoon_length.unwrap(),
        );
        println!(
            "seed {seed}: humans in the lane {:.2} % (baseline {:.1} %), CAVs {:.1} %, \
             L̄ {ld:.2} vs {lb:.2}",
            100.0 * humans,
            100.0 * humans_base,
            100.0 * cavs
        );
        assert!(humans <= 0.02, "humans in the dedicated lane: {humans}");
        assert!(
            humans_base > 0.2,
            "the baseline uses the lane: {humans_base}"
        );
        assert!(cavs > 0.5, "CAVs in the dedicated lane: {cavs}");
        assert!(ld > lb, "L̄ {ld} not above the baseline's {lb}");
        assert_eq!(ded.summary.strategy, "dedicated");
    }
}

#[test]
fn the_pd_lane_can_be_the_rightmost() {
    let left = run(&config(StrategyKind::PD, 1, &[]));
    let right = run(&config(
        StrategyKind::PD,
        1,
        &["strategy.lane=\"rightmost\""],
    ));
    let index = run(&config(StrategyKind::PD, 1, &["strategy.lane=1"]));
    let (l0, l2) = (
        share_in_lane(&left, Kind::Cav, 0),
        share_in_lane(&left, Kind::Cav, 2),
    );
    let (r0, r2) = (
        share_in_lane(&right, Kind::Cav, 0),
        share_in_lane(&right, Kind::Cav, 2),
    );
    println!("CAVs in lanes 1 / 3: leftmost PD {l0:.2} / {l2:.2}, rightmost PD {r0:.2} / {r2:.2}");
    assert!(l2 > 0.5 && r0 > 0.5, "{l2} {r0}");
    assert!(r0 > l0 + 0.3 && l2 > r2 + 0.3);
    // Lane number 1 is the rightmost lane: the same run.
    let without_wall = |o: &Output| platoonsim_sim::Summary {
        wall_seconds: 0.0,
        ..o.summary.clone()
    };
    assert_eq!(without_wall(&index), without_wall(&right));
    assert_eq!(index.detectors, right.detectors);
}

/// A user's organizer: CAVs keep to the lane right of the leftmost everywhere after 1 km.
#[derive(Debug)]
struct MiddleLane;

impl Organizer for MiddleLane {
    fn name(&self) -> &str {
        "middle-lane"
    }
    fn advise(&self, v: VehicleView<'_>, _t_s: f64, road: &Geometry) -> Advice {
        match road.leftmost_through(v.x()) {
            Some(left) if v.x() > 1000.0 && left > 0 => Advice::Join {
                lane: left - 1,
                strength: 1.0,
            },
            _ => Advice::Free,
        }
    }
}

#[test]
fn a_library_user_can_pass_an_organizer_of_their_own() {
    let c = config(StrategyKind::NONE, 1, &[]);
    let mut sim = Simulation::new(c.clone()).unwrap();
    sim.record(&recording()).unwrap();
    sim.set_organizer(Box::new(MiddleLane)).unwrap();
    while !sim.finished() {
        sim.step().unwrap();
    }
    let own = sim.finish(0.0);
    assert_eq!(own.summary.strategy, "middle-lane");
    assert_eq!(own.summary.collisions, 0);
    let base = run(&c);
    let (mid, mid_base) = (
        share_in_lane(&own, Kind::Cav, 1),
        share_in_lane(&base, Kind::Cav, 1),
    );
    println!("CAVs in the middle lane: {mid:.2} (baseline {mid_base:.2})");
    // Most CAVs (two in three or more) keep to the middle lane, against a third without it.
    assert!(mid > 0.67 && mid > mid_base + 0.3, "{mid} vs {mid_base}");
    // Too late once the run has started.
    let mut started = Simulation::new(c).unwrap();
    started.step().unwrap();
    assert!(started.set_organizer(Box::new(MiddleLane)).is_err());
}

// ---------------------------------------------------------------- events

#[path = "../examples/lane_change_reasons.rs"]
mod lane_change_reasons;

#[test]
fn lane_changes_counted_from_events_agree_with_the_summary() {
    use platoonsim_sim::{Kind as K, Summary};
    let sr99 = |p: f64, k: StrategyKind| {
        let o = Overrides {
            penetration: Some(p),
            strategy: Some(k),
            duration_s: Some(1800.0),
            warmup_s: Some(600.0),
            ..Overrides::default()
        };
        load_with("sr99", &o).unwrap()
    };
    for c in [
        config(StrategyKind::DEDICATED, 1, &[]),
        sr99(0.4, StrategyKind::PD),
    ] {
        let plain = platoonsim_sim::run(&c, None).unwrap().summary;
        let (out, n) = lane_change_reasons::run_counted(c.clone());
        // Observing does not change the run.
        let same = |s: &Summary| Summary {
            wall_seconds: 0.0,
            ..s.clone()
        };
        assert_eq!(same(&out.summary), same(&plain));
        let s = &out.summary;
        println!("{}: {:?}", c.name, n.by_reason);
        assert_eq!(n.per_vehicle(None), s.lane_changes_per_vehicle.unwrap());
        assert_eq!(n.per_vehicle(Some(K::Cav)), s.lane_changes_per_cav.unwrap());
        assert_eq!(
            n.per_vehicle(Some(K::Human)),
            s.lane_changes_per_human.unwrap()
        );
        let reason = |kind: &str, r: &str| n.by_reason.get(&(kind, r)).copied().unwrap_or(0);
        assert!(reason("cav", "organizing") > 50, "{:?}", n.by_reason);
        assert_eq!(reason("human", "organizing"), 0);
        assert!(reason("human", "mandatory") > 0, "{:?}", n.by_reason);
    }
}

/// Hard brakings and mode changes from the event stream.
#[derive(Debug, Default)]
struct SafetyCounter {
    warmup_s: f64,
    brakings: [u64; 2],
    yields: u64,
    regimes: u64,
    last_t: f64,
}

impl platoonsim_sim::Observer for SafetyCounter {
    fn on_step(&mut self, step: &platoonsim_sim::StepView<'_>) {
        use platoonsim_sim::{Event, ModeLabel};
        for e in step.events() {
            assert!(e.t_s() >= self.last_t, "events in time order");
            assert_eq!(e.t_s(), step.time_s(), "stamped with the end of the step");
            self.last_t = e.t_s();
            match e {
                Event::HardBraking { t_s, kind, .. } if *t_s > self.warmup_s => {
                    self.brakings[*kind as usize] += 1;
                }
                Event::ModeChange {
                    to: ModeLabel::Ycf, ..
                } => self.yields += 1,
                Event::ModeChange {
                    regime_from,
                    regime_to,
                    ..
                } if regime_from.is_some() && regime_to.is_some() => self.regimes += 1,
                _ => {}
            }
        }
    }
}

#[test]
fn hard_brakings_and_mode_changes_come_as_events() {
    let c = config(StrategyKind::DEDICATED, 2, &[]);
    let mut sim = Simulation::new(c.clone()).unwrap();
    sim.observe(Box::new(SafetyCounter {
        warmup_s: c.warmup_s,
        ..SafetyCounter::default()
    }))
    .unwrap();
    while !sim.finished() {
        sim.step().unwrap();
    }
    let n = sim.observer::<SafetyCounter>().unwrap();
    let (brakings, yields, regimes) = (n.brakings, n.yields, n.regimes);
    let s = sim.finish(0.0).summary;
    println!("brakings {brakings:?}, yields {yields}, regime changes {regimes}");
    let hard = s.counted.get("hard_brakings").unwrap();
    assert_eq!(brakings, [hard.human, hard.cav]);
    assert!(yields > 10 && regimes > 100, "{yields} {regimes}");
}
