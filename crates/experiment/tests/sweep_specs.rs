//! The sweep files shipped in `sweeps/` reproduce the experiments they stand for: every run's
//! metrics (and the run's key, the hash of its configuration) equal those of `experiment
//! sensitivity` and `experiment flow-aware`, and the paired differences equal the
//! experiments' derived metrics. Shortened to 2 seeds of 300 s with a 100 s warm-up (the
//! same shortening on both sides), so that the test takes seconds; the full runs differ only
//! in `run.duration_s`, `run.warmup_s` and the seed count.

use platoonsim_experiment::{experiments, run_experiment, ExperimentName, Settings};
use platoonsim_runs::sweep::{self, spec::Spec};
use std::path::{Path, PathBuf};
use toml::Value;

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "platoonsim-sweep-specs-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn shipped(file: &str) -> Spec {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../sweeps")
        .join(file);
    let mut spec = Spec::from_file(&path).unwrap();
    spec.seeds = vec![1, 2];
    for (k, v) in &mut spec.set {
        match k.as_str() {
            "run.duration_s" => *v = Value::Float(300.0),
            "run.warmup_s" => *v = Value::Float(100.0),
            _ => {}
        }
    }
    spec
}

fn same_runs(name: ExperimentName, file: &str, derived: &[(&str, &str)]) {
    let dir = scratch(file);
    let settings = Settings {
        out: dir.join("experiment"),
        seeds: 2,
        jobs: Some(2),
        duration_s: 300.0,
        warmup_s: 100.0,
        ..Settings::default()
    };
    let exp = run_experiment(name, &settings).unwrap();
    let spec = shipped(file);
    let opts = sweep::Options {
        out: dir.join("sweep"),
        jobs: Some(2),
        ..sweep::Options::default()
    };
    let done = sweep::run(&spec, &opts).unwrap();
    assert_eq!(done.computed, exp.outcomes.len());
    let runs = std::fs::read(dir.join("sweep/runs.csv")).unwrap();
    let mut r = csv::Reader::from_reader(&runs[..]);
    let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    let rows: Vec<Vec<String>> = r
        .records()
        .map(|x| x.unwrap().iter().map(String::from).collect())
        .collect();
    assert_eq!(rows.len(), exp.outcomes.len());
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    for o in &exp.outcomes {
        let labels = &exp.cells[o.cell].labels;
        let demand = labels.get("demand_vphpl").unwrap();
        let strategy = labels.get("strategy").unwrap();
        let row = rows
            .iter()
            .find(|x| {
                x[col("seed")] == o.seed.to_string()
                    && x[col("strategy.kind")] == strategy
                    && header
                        .iter()
                        .position(|h| h == "demand.vph_per_lane")
                        .is_none_or(|c| x[c] == demand)
            })
            .unwrap_or_else(|| panic!("no sweep run for {labels:?} seed {}", o.seed));
        assert_eq!(row[col("key")], o.key, "{labels:?}");
        let value = |name: &str| -> Option<f64> {
            let t = &row[col(name)];
            (!t.is_empty()).then(|| t.parse().unwrap())
        };
        for (m, v) in &o.fields.0 {
            if m == "platoon_length_ratio" {
                // L̄_PO / L̄_B per seed pair: the sweep gives the same pair as a percentage.
                let pct = value("avg_platoon_length_pct");
                match pct {
                    Some(p) => assert!(
                        (1.0 + p / 100.0 - v).abs() <= 1e-12 * v.abs(),
                        "{labels:?} seed {} {m}: {v} vs {p} %",
                        o.seed
                    ),
                    None => assert!(v.is_nan(), "{labels:?} seed {} {m}: {v} vs empty", o.seed),
                }
                continue;
            }
            if matches!(
                m.as_str(),
                "discharge_change_organized_lane_pct" | "discharge_change_other_lanes_pct"
            ) {
                // The experiment's split of ΔQ by lane (its mechanism section) has no sweep
                // column: the sweep gives the by-lane flows it is made of.
                continue;
            }
            let theirs = derived
                .iter()
                .find(|(e, _)| e == m)
                .map_or(m.as_str(), |(_, s)| s);
            match value(theirs) {
                Some(x) => assert_eq!(x, *v, "{labels:?} seed {} {m}", o.seed),
                None => assert!(v.is_nan(), "{labels:?} seed {} {m}: {v} vs empty", o.seed),
            }
        }
    }
}

#[test]
fn sensitivity_spec_gives_the_experiments_runs() {
    same_runs(
        experiments::get("sensitivity"),
        "sensitivity.toml",
        &[("discharge_change_pct", "discharge_flow_vphpl_pct")],
    );
}

#[test]
fn flow_aware_spec_gives_the_experiments_runs() {
    same_runs(
        experiments::get("flow-aware"),
        "flow-aware.toml",
        &[
            ("discharge_change_pct", "discharge_flow_vphpl_pct"),
            ("platoon_length_gain", "avg_platoon_length_diff"),
        ],
    );
}

/// `sweeps/flow-aware-sr99.toml`, the corridor's own threshold calibration (issue 43): one
/// baseline per penetration and every (rho_q, rho_v) pair of Flow-Aware, 84 cells, each at its
/// penetration's demand scale with its thresholds.
#[test]
fn the_sr99_threshold_calibration_plans_one_baseline_and_every_pair_per_penetration() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../sweeps/flow-aware-sr99.toml");
    let spec = Spec::from_file(&path).unwrap();
    let cells = sweep::plan::cells(&spec).unwrap();
    assert_eq!(cells.len(), 4 * (1 + 5 * 4));
    let baselines: Vec<_> = cells
        .iter()
        .filter(|c| c.config.strategy.kind.as_str() == "none")
        .map(|c| c.config.penetration)
        .collect();
    assert_eq!(baselines, [0.2, 0.4, 0.6, 0.8]);
    let pairs: std::collections::BTreeSet<(u64, u64)> = cells
        .iter()
        .filter_map(|c| c.config.strategy.thresholds.as_ref())
        .map(|t| (t.flow_threshold_vphpl as u64, t.speed_threshold_kmh as u64))
        .collect();
    assert_eq!(pairs.len(), 20);
}
