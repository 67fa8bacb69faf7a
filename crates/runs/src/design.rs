//! Experiments as data. A [`Cell`] is one point of an experiment's grid: its labels (the
//! fields that tell cells apart in the tables: penetration, demand, strategy, …) and the
//! resolved [`Config`] it runs. A run is a cell with one seed ([`RunSpec`]); the seeds are
//! 1..=N.

use crate::detectors::Scope;
use crate::hash::config_key;
use crate::Error;
use platoonsim_scenario::{load_with, Overrides, StrategyKind};
use platoonsim_sim::Config;
use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};

/// Ordered (name, value) labels of a cell; values are text as written in the CSV files
/// (numbers in their shortest round-trip form, see [`num`]).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Labels(pub Vec<(String, String)>);

impl Labels {
    pub fn new() -> Labels {
        Labels(Vec::new())
    }

    /// Add a label (builder style).
    pub fn with(mut self, name: &str, value: impl Into<String>) -> Labels {
        self.0.push((name.to_string(), value.into()));
        self
    }

    pub fn get(&self, name: &str) -> Option<&str> {
        self.0
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// Whether every (name, value) of `wanted` is among these labels.
    pub fn matches(&self, wanted: &[(&str, &str)]) -> bool {
        wanted.iter().all(|(k, v)| self.get(k) == Some(*v))
    }
}

impl Serialize for Labels {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.len()))?;
        for (k, v) in &self.0 {
            m.serialize_entry(k, v)?;
        }
        m.end()
    }
}

/// A number as label text: the shortest form that reads back to the same value
/// (`0.5`, `2500`, `1234.5`).
pub fn num(v: f64) -> String {
    format!("{v}")
}

/// One point of an experiment: labels and the resolved configuration (its seed is replaced
/// by each run's).
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    pub labels: Labels,
    pub config: Config,
}

/// One run: cell index, seed, the configuration with that seed, and which detector records
/// the run keeps beside its run file (none unless an experiment asks, see [`keep_detectors`]).
#[derive(Clone, Debug, PartialEq)]
pub struct RunSpec {
    pub cell: usize,
    pub seed: u64,
    pub config: Config,
    pub detectors: Scope,
}

impl RunSpec {
    /// The run's key: the stable hash of its configuration (which includes the seed).
    pub fn key(&self) -> String {
        config_key(&self.config)
    }
}

/// Seeds 1..=n.
pub fn seeds(n: u32) -> Vec<u64> {
    (1..=u64::from(n)).collect()
}

/// Every run of `cells`, cell by cell, seed by seed (the order of every result table).
pub fn runs(cells: &[Cell], seeds: &[u64]) -> Vec<RunSpec> {
    let mut out = Vec::with_capacity(cells.len() * seeds.len());
    for (i, cell) in cells.iter().enumerate() {
        for &seed in seeds {
            let mut config = cell.config.clone();
            config.seed = seed;
            out.push(RunSpec {
                cell: i,
                seed,
                config,
                detectors: Scope::None,
            });
        }
    }
    out
}

/// Keep the detector records of `scope` for the runs that `wanted(cell, seed)` selects.
pub fn keep_detectors(specs: &mut [RunSpec], scope: Scope, wanted: impl Fn(usize, u64) -> bool) {
    for s in specs.iter_mut().filter(|s| wanted(s.cell, s.seed)) {
        s.detectors = s.detectors.max(scope);
    }
}

/// A point on the built-in homogeneous road: what the experiments vary.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub penetration: f64,
    pub demand_vphpl: f64,
    pub strategy: StrategyKind,
    pub duration_s: f64,
    pub warmup_s: f64,
    /// Further `KEY=VALUE` scenario overrides (as `platoonsim run --set`).
    pub set: Vec<String>,
}

/// The built-in `homogeneous` scenario with the point's overrides, resolved and validated
/// exactly as `platoonsim run homogeneous --penetration … --demand … --strategy …` does
/// (PD zone = control section, PD window = [warm-up, end], Flow-Aware thresholds from the
/// scenario).
pub fn homogeneous(p: &Point) -> Result<Config, Error> {
    let overrides = Overrides {
        penetration: Some(p.penetration),
        demand_vphpl: Some(p.demand_vphpl),
        duration_s: Some(p.duration_s),
        warmup_s: Some(p.warmup_s),
        seed: Some(1),
        strategy: Some(p.strategy),
        set: p.set.clone(),
    };
    Ok(load_with("homogeneous", &overrides)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_are_cell_major_with_their_seed_in_the_config() {
        let base = Config::homogeneous(0.5, 1000.0, 300.0, 60.0, 1);
        let cells = vec![
            Cell {
                labels: Labels::new().with("strategy", "none"),
                config: base.clone(),
            },
            Cell {
                labels: Labels::new().with("strategy", "pd"),
                config: base,
            },
        ];
        let r = runs(&cells, &seeds(3));
        let order: Vec<(usize, u64)> = r.iter().map(|s| (s.cell, s.seed)).collect();
        assert_eq!(order, [(0, 1), (0, 2), (0, 3), (1, 1), (1, 2), (1, 3)]);
        assert!(r.iter().all(|s| s.config.seed == s.seed));
        assert_ne!(r[0].key(), r[1].key());
        // Same config and seed, same key, whatever the cell.
        assert_eq!(r[0].key(), r[3].key());
    }

    #[test]
    fn labels() {
        let l = Labels::new()
            .with("penetration", num(0.5))
            .with("demand_vphpl", num(2500.0));
        assert_eq!(l.get("demand_vphpl"), Some("2500"));
        assert!(l.matches(&[("penetration", "0.5")]));
        assert!(!l.matches(&[("penetration", "0.25")]));
        assert_eq!(
            serde_json::to_string(&l).unwrap(),
            r#"{"penetration":"0.5","demand_vphpl":"2500"}"#
        );
    }

    #[test]
    fn homogeneous_point_resolves_the_strategy() {
        let p = Point {
            penetration: 0.25,
            demand_vphpl: 1800.0,
            strategy: StrategyKind::PD,
            duration_s: 600.0,
            warmup_s: 200.0,
            set: vec![],
        };
        let c = homogeneous(&p).unwrap();
        assert_eq!(c.penetration, 0.25);
        assert_eq!(c.demand.vph_per_lane, 1800.0);
        assert_eq!(c.strategy.kind, StrategyKind::PD);
        let pd = c.strategy.pd.as_ref().unwrap();
        assert_eq!((pd.zone_start_m, pd.zone_end_m), (5000.0, 6000.0));
        assert_eq!((pd.start_s, pd.end_s), (200.0, 600.0));
    }
}
