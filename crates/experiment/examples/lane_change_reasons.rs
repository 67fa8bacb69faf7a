//! Count lane changes by reason from the engine's events, and check them against the summary.
//!
//! ```sh
//! cargo run --release -p platoonsim-experiment --example lane_change_reasons -- sr99 0.4 pd
//! ```
//!
//! Arguments: a scenario (built-in name or file), the CAV share, the strategy (defaults:
//! `homogeneous`, 0.5, `pd`). The summary's `lane_changes_per_vehicle` counts the vehicles that
//! entered in the measurement window; the observer counts the same ones from their `Entered`
//! and `LaneChange` events.

use platoonsim_scenario::{load_with, Overrides};
use platoonsim_sim::{Config, Event, Kind, Observer, Output, Simulation};
use std::collections::{BTreeMap, HashMap, HashSet};

/// Lane changes by reason and kind, of the vehicles that entered at or after `from_s`.
#[derive(Clone, Debug, Default)]
pub struct LaneChangeCounter {
    pub from_s: f64,
    measured: HashSet<u64>,
    pub vehicles: BTreeMap<&'static str, u64>,
    pub by_reason: BTreeMap<(&'static str, &'static str), u64>,
    per_vehicle: HashMap<u64, (Kind, u64)>,
}

impl Observer for LaneChangeCounter {
    fn on_step(&mut self, step: &platoonsim_sim::StepView<'_>) {
        for e in step.events() {
            match *e {
                Event::Entered { t_s, id, kind, .. } if t_s >= self.from_s => {
                    self.measured.insert(id);
                    *self.vehicles.entry(kind.as_str()).or_default() += 1;
                }
                Event::LaneChange {
                    id, kind, reason, ..
                } if self.measured.contains(&id) => {
                    *self
                        .by_reason
                        .entry((kind.as_str(), reason.as_str()))
                        .or_default() += 1;
                    self.per_vehicle.entry(id).or_insert((kind, 0)).1 += 1;
                }
                _ => {}
            }
        }
    }
}

impl LaneChangeCounter {
    /// Lane changes per vehicle of `kind` (`None`: all), as the summary defines them.
    pub fn per_vehicle(&self, kind: Option<Kind>) -> f64 {
        let changes: u64 = self
            .per_vehicle
            .values()
            .filter(|(k, _)| kind.is_none_or(|want| *k == want))
            .map(|(_, n)| n)
            .sum();
        let vehicles: u64 = match kind {
            None => self.vehicles.values().sum(),
            Some(k) => self.vehicles.get(k.as_str()).copied().unwrap_or(0),
        };
        if vehicles == 0 {
            0.0
        } else {
            changes as f64 / vehicles as f64
        }
    }
}

/// Run `config` with a counter attached; the output and the counter.
pub fn run_counted(config: Config) -> (Output, LaneChangeCounter) {
    let from_s = config.warmup_s;
    let mut sim = Simulation::new(config).expect("a valid config");
    let counter = LaneChangeCounter {
        from_s,
        ..LaneChangeCounter::default()
    };
    sim.observe(Box::new(counter))
        .expect("before the first step");
    while !sim.finished() {
        sim.step().expect("no engine error");
    }
    let counter = sim
        .observer::<LaneChangeCounter>()
        .expect("attached")
        .clone();
    (sim.finish(0.0), counter)
}

#[allow(dead_code)]
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scenario = args.first().map_or("homogeneous", String::as_str);
    let o = Overrides {
        penetration: Some(args.get(1).and_then(|p| p.parse().ok()).unwrap_or(0.5)),
        strategy: Some(args.get(2).map_or("pd", String::as_str).parse().unwrap()),
        ..Overrides::default()
    };
    let config = load_with(scenario, &o).unwrap_or_else(|e| panic!("{e}"));
    let (out, counter) = run_counted(config);
    for ((kind, reason), n) in &counter.by_reason {
        println!("{kind:>5} {reason:<13} {n:>7}");
    }
    let s = &out.summary;
    println!(
        "per vehicle: events {:.4}, summary {:.4}",
        counter.per_vehicle(None),
        s.lane_changes_per_vehicle.unwrap()
    );
    assert_eq!(
        counter.per_vehicle(None),
        s.lane_changes_per_vehicle.unwrap()
    );
    assert_eq!(
        counter.per_vehicle(Some(Kind::Cav)),
        s.lane_changes_per_cav.unwrap()
    );
    assert_eq!(
        counter.per_vehicle(Some(Kind::Human)),
        s.lane_changes_per_human.unwrap()
    );
}
