//! Runner and experiment tests on the SR-99 corridor, with runs shortened to a few simulated
//! minutes (`run.duration_s` overridden): detector files kept beside the run files and
//! reused like them.

use platoonsim_experiment::experiments::{self, run_experiment_with};
use platoonsim_experiment::Settings;
use platoonsim_runs::design::{keep_detectors, runs, seeds};
use platoonsim_runs::detectors::Scope;
use platoonsim_runs::runner::{bar, simulate};
use platoonsim_runs::{Cell, Labels, Runner};
use platoonsim_scenario::{demand_scale_set, load_with, Overrides, StrategyKind};
use platoonsim_sim::{Config, Output, SimError};
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("platoonsim-net-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// SR-99 at 40 % CAV under PD, 600 s.
fn short_sr99() -> Cell {
    let o = Overrides {
        penetration: Some(0.4),
        strategy: Some(StrategyKind::PD),
        seed: Some(1),
        set: vec![demand_scale_set(1.1), "run.duration_s=600".into()],
        ..Overrides::default()
    };
    Cell {
        labels: Labels::new().with("strategy", "pd"),
        config: load_with("sr99", &o).unwrap(),
    }
}

fn names(dir: &Path, suffix: &str) -> usize {
    fs::read_dir(dir)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .ends_with(suffix)
        })
        .count()
}

#[test]
fn detector_files_are_kept_for_the_selected_runs_and_reused() {
    let dir = scratch("detectors").join("runs");
    let count = AtomicUsize::new(0);
    let exec = |c: &Config| -> Result<Output, SimError> {
        count.fetch_add(1, Ordering::SeqCst);
        simulate(c)
    };
    let cells = vec![short_sr99()];
    let mut specs = runs(&cells, &seeds(2));
    keep_detectors(&mut specs, Scope::All, |_, seed| seed == 1);
    let runner = || Runner::new(dir.clone(), Some(2), bar(2, false, "t"), &exec);
    let (k1, k2) = (specs[0].key(), specs[1].key());

    runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 2);
    assert_eq!(
        (names(&dir, ".json"), names(&dir, ".detectors.csv")),
        (2, 1)
    );
    let recs = runner().detectors(&k1).unwrap();
    assert!(recs.iter().any(|r| r.lane == "1") && recs.iter().any(|r| r.lane == "all"));
    assert!(recs.iter().any(|r| r.detector == "OR11-up"));
    // The same records as the engine's.
    assert_eq!(recs, simulate(&specs[0].config).unwrap().detectors);
    assert!(runner().detectors(&k2).is_err());

    // Everything reused.
    let r = runner();
    r.run(&specs).unwrap();
    assert_eq!((count.swap(0, Ordering::SeqCst), r.reused()), (0, 2));

    // Seed 2 now wants its cross-section: only it is recomputed.
    keep_detectors(&mut specs, Scope::CrossSection, |_, seed| seed == 2);
    runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 1);
    let cross = runner().detectors(&k2).unwrap();
    assert!(!cross.is_empty() && cross.iter().all(|r| r.lane == "all"));
    // A narrower wish is covered by a wider file.
    keep_detectors(&mut specs, Scope::CrossSection, |_, seed| seed == 1);
    runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 0);

    // A changed or missing detector file makes its run recompute.
    let f1 = dir.join(format!("{k1}.detectors.csv"));
    let mut bytes = fs::read(&f1).unwrap();
    bytes.push(b'\n');
    fs::write(&f1, &bytes).unwrap();
    runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 1);
    fs::remove_file(&f1).unwrap();
    runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 1);
    assert_eq!(runner().detectors(&k1).unwrap(), recs);

    // A run recomputed without detectors leaves its old detector file behind; the new run
    // file names none, so the old file is not used.
    let plain = runs(&cells, &seeds(2));
    let mut r = runner();
    r.reuse = false;
    r.run(&plain).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 2);
    assert_eq!(names(&dir, ".detectors.csv"), 2);
    runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 2);
}

fn settings(out: &Path, seeds: u32) -> Settings {
    Settings {
        out: out.to_path_buf(),
        seeds,
        jobs: Some(2),
        network_duration_s: Some(600.0),
        network_penetrations: vec![0.0, 0.4],
        ..Settings::default()
    }
}

#[test]
fn sr99_writes_table4_and_the_three_figures() {
    let out = scratch("sr99");
    let s = settings(&out, 2);
    assert_eq!(experiments::get("sr99").total_runs(&s), 2 * 4);
    let res = run_experiment_with(experiments::get("sr99"), &s, &simulate).unwrap();
    assert_eq!(res.outcomes.len(), 8);
    let dir = out.join("sr99");
    for f in [
        "runs.csv",
        "summary.csv",
        "summary.md",
        "run.json",
        "sr99_contours.png",
        "sr99_contours.svg",
        "sr99_lanes.png",
        "sr99_lanes.svg",
        "sr99_bars.png",
        "sr99_bars.svg",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    // Detector files: every baseline run (cross-section), and seed 1 of PD and Flow-Aware at
    // 40 % (every lane).
    assert_eq!(names(&dir.join("runs"), ".detectors.csv"), 2 + 2 + 1 + 1);
    assert_eq!(names(&dir.join("runs"), ".json"), 8);

    let runs = fs::read_to_string(dir.join("runs.csv")).unwrap();
    let header = runs.lines().next().unwrap();
    assert!(header.starts_with("penetration,demand_scale,strategy,seed,key,"));
    for col in [
        "network_discharge_vph",
        "discharge_change_pct",
        "lane_changes_change_pct",
        "platoon_length_change_pct",
        "florin_congested_min",
    ] {
        assert!(header.contains(col), "{col} missing in {header}");
    }
    let summary = fs::read_to_string(dir.join("summary.csv")).unwrap();
    assert!(
        summary.contains(",Table 4 (SR-99)"),
        "paper values in summary.csv"
    );
    let md = fs::read_to_string(dir.join("summary.md")).unwrap();
    for part in [
        "## Table 4: ours vs the paper",
        "| 40 % | 1.10 / 1.10 | PD |",
        "11739.8",
        "## Change vs the baseline at the same penetration (%)",
        "| 40 % | Flow-Aware PD |",
        "-2.9",
        "## Recurrent bottlenecks",
        "In words:",
        "## Checks",
        "sr99_contours.png",
    ] {
        assert!(md.contains(part), "{part} missing in summary.md:\n{md}");
    }
    // The three SR-99 figures and the braking histogram (issue 29).
    assert_eq!(res.figures.len(), 4);
    assert_eq!(res.figures[3].stem, "braking");
    assert!(!res.checks.is_empty());

    // A rerun reuses every run, detector files included.
    let again = run_experiment_with(experiments::get("sr99"), &s, &simulate).unwrap();
    assert_eq!((again.computed, again.reused), (0, 8));
    assert_eq!(fs::read_to_string(dir.join("runs.csv")).unwrap(), runs);

    // sr99-demand at the table's scales runs sr99's baselines: reused from its directory.
    let check = Settings {
        scale_grid: vec![],
        ..s
    };
    let demand = run_experiment_with(experiments::get("sr99-demand"), &check, &simulate).unwrap();
    assert_eq!((demand.computed, demand.reused), (0, 4));
    assert_eq!(names(&out.join("sr99-demand/runs"), ".detectors.csv"), 4);
}

#[test]
fn sr99_demand_searches_the_grid_and_writes_the_table() {
    let out = scratch("demand");
    let table = out.join("written.toml");
    let s = Settings {
        scale_grid: vec![1.0, 1.4],
        network_penetrations: vec![0.2, 0.4],
        // In 10 min nothing jams at 60 km/h, but everything is below 200 km/h from the
        // first interval on: "active" at once if the criterion asks for 5 min.
        bottleneck_speed_kmh: 200.0,
        bottleneck_minutes: 5.0,
        write_table: Some(table.clone()),
        ..settings(&out, 1)
    };
    assert_eq!(experiments::get("sr99-demand").total_runs(&s), 4);
    let res = run_experiment_with(experiments::get("sr99-demand"), &s, &simulate).unwrap();
    // Found at the first scale: the grid stops there.
    assert_eq!(res.outcomes.len(), 2);
    let dir = out.join("sr99-demand");
    for f in [
        "demand_scales.toml",
        "demand_scales.png",
        "demand_contours.png",
        "summary.md",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    let written = fs::read_to_string(&table).unwrap();
    assert_eq!(
        written,
        fs::read_to_string(dir.join("demand_scales.toml")).unwrap()
    );
    let rows = platoonsim_scenario::demand_scales::parse(&written).unwrap();
    assert_eq!(rows.len(), 2);
    assert!(rows.iter().all(|r| r.demand_scale == 1.0));
    assert_eq!(names(&dir.join("runs"), ".detectors.csv"), 2);

    // With the real criterion, 10 min never shows a bottleneck: every scale is tried.
    let strict = Settings {
        write_table: None,
        network_penetrations: vec![0.4],
        ..settings(&out, 1)
    };
    let strict = Settings {
        scale_grid: vec![1.0, 1.4],
        ..strict
    };
    let res = run_experiment_with(experiments::get("sr99-demand"), &strict, &simulate).unwrap();
    assert_eq!(res.outcomes.len(), 2);
    let md = fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(md.contains("not reached (≤ 1.4)"), "{md}");
    let toml = fs::read_to_string(dir.join("demand_scales.toml")).unwrap();
    assert!(toml.contains("feasible = false"));

    // No grid: the table's scales are only checked.
    let check = Settings {
        scale_grid: vec![],
        ..strict
    };
    let res = run_experiment_with(experiments::get("sr99-demand"), &check, &simulate).unwrap();
    assert_eq!(res.outcomes.len(), 1);
    let md = fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(md.contains("**No search**"), "{md}");
    assert!(md.contains("| 40 % | 1.10: no | 1.10 |"), "{md}");
}
