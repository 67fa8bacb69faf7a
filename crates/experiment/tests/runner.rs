//! Runner and experiment tests on short runs: resumability (only missing or unusable run
//! files are recomputed), atomic files, identical results whatever the thread count, the
//! shape of the output files.

use platoonsim_experiment::experiments::{self, run_experiment_with};
use platoonsim_experiment::Settings;
use platoonsim_runs::design::{runs, seeds};
use platoonsim_runs::runner::{bar, simulate};
use platoonsim_runs::{Cell, Labels, Runner};
use platoonsim_sim::{Config, Output, SimError};
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("platoonsim-exp-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// Two tiny cells (2 minutes of light traffic).
fn tiny_cells() -> Vec<Cell> {
    [0.0, 0.5]
        .iter()
        .map(|&p| Cell {
            labels: Labels::new().with("penetration", format!("{p}")),
            config: Config::homogeneous(p, 600.0, 120.0, 30.0, 1),
        })
        .collect()
}

fn run_files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn rerun_recomputes_only_missing_or_unusable_runs() {
    let dir = scratch("resume").join("runs");
    let count = AtomicUsize::new(0);
    let exec = |c: &Config| -> Result<Output, SimError> {
        count.fetch_add(1, Ordering::SeqCst);
        simulate(c)
    };
    let specs = runs(&tiny_cells(), &seeds(3));
    let runner = || Runner::new(dir.clone(), Some(2), bar(specs.len(), false, "t"), &exec);

    let first = runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 6);
    assert!(first.iter().all(|o| o.computed));
    let names = run_files(&dir);
    assert_eq!(names.len(), 6);
    assert!(
        names
            .iter()
            .all(|n| n.ends_with(".json") && n.len() == 16 + 5),
        "{names:?}"
    );

    // Everything reused.
    let r = runner();
    let second = r.run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 0);
    assert_eq!((r.computed(), r.reused()), (0, 6));
    assert!(second.iter().all(|o| !o.computed));
    let strip = |v: &[platoonsim_runs::Outcome]| {
        v.iter()
            .map(|o| (o.cell, o.seed, o.key.clone(), bits(&o.fields)))
            .collect::<Vec<_>>()
    };
    assert_eq!(strip(&first), strip(&second));

    // One file deleted, one cut in half, a stale temporary file: two runs recomputed, the
    // temporary file gone.
    let deleted = specs[1].key();
    let cut = specs[4].key();
    fs::remove_file(dir.join(format!("{deleted}.json"))).unwrap();
    let path = dir.join(format!("{cut}.json"));
    let bytes = fs::read(&path).unwrap();
    fs::write(&path, &bytes[..bytes.len() / 2]).unwrap();
    let stale = dir.join(format!("{}.json.tmp", specs[0].key()));
    fs::write(&stale, b"{\"half").unwrap();
    let hour_ago = std::time::SystemTime::now() - std::time::Duration::from_secs(3600);
    fs::File::options()
        .write(true)
        .open(&stale)
        .unwrap()
        .set_modified(hour_ago)
        .unwrap();
    // A fresh temporary file may be another process's write in progress (sweep shards share
    // the directory): it stays.
    let fresh = dir.join("another-shard.json.tmp");
    fs::write(&fresh, b"{").unwrap();
    let r = runner();
    let third = r.run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 2);
    assert_eq!((r.computed(), r.reused()), (2, 4));
    let recomputed: Vec<&str> = third
        .iter()
        .filter(|o| o.computed)
        .map(|o| o.key.as_str())
        .collect();
    assert_eq!(recomputed, [deleted.as_str(), cut.as_str()]);
    assert_eq!(strip(&first), strip(&third));
    assert!(fresh.exists(), "a fresh temporary file is left alone");
    fs::remove_file(&fresh).unwrap();
    assert_eq!(
        run_files(&dir).len(),
        6,
        "no stale .tmp left: {:?}",
        run_files(&dir)
    );

    // A file computed by another build of the engine is not reused.
    let path = dir.join(format!("{}.json", specs[2].key()));
    let text = fs::read_to_string(&path).unwrap();
    let id = platoonsim_runs::record::engine_id();
    assert!(text.contains(id));
    fs::write(&path, text.replace(id, "0123456789abcdef")).unwrap();
    let r = runner();
    r.run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 1);
    assert!(fs::read_to_string(&path).unwrap().contains(id));

    // Without reuse, everything is recomputed.
    let mut r = runner();
    r.reuse = false;
    r.run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 6);
}

#[test]
fn duplicate_runs_execute_once_and_failures_keep_the_others() {
    let dir = scratch("dup").join("runs");
    let count = AtomicUsize::new(0);
    let cells = tiny_cells();
    let twice = vec![cells[0].clone(), cells[0].clone()];
    let exec = |c: &Config| -> Result<Output, SimError> {
        count.fetch_add(1, Ordering::SeqCst);
        simulate(c)
    };
    let specs = runs(&twice, &seeds(2));
    let r = Runner::new(dir.clone(), Some(2), bar(4, false, "t"), &exec);
    let out = r.run(&specs).unwrap();
    assert_eq!(count.load(Ordering::SeqCst), 2);
    assert_eq!(out.len(), 4);
    assert_eq!(bits(&out[0].fields), bits(&out[2].fields));
    assert_eq!(out[0].cell, 0);
    assert_eq!(out[2].cell, 1);

    // A failing run: an error, but the successful ones are saved.
    let failing = |c: &Config| -> Result<Output, SimError> {
        if c.seed == 2 {
            Err(SimError::Config("boom".into()))
        } else {
            simulate(c)
        }
    };
    let dir2 = scratch("fail").join("runs");
    let specs = runs(&cells, &seeds(2));
    let r = Runner::new(dir2.clone(), Some(2), bar(4, false, "t"), &failing);
    let err = r.run(&specs).unwrap_err().to_string();
    assert!(err.contains("boom") && err.contains("seed 2"), "{err}");
    assert_eq!(run_files(&dir2).len(), 2);
}

fn settings(out: &Path, jobs: usize, seeds: u32) -> Settings {
    Settings {
        out: out.to_path_buf(),
        seeds,
        jobs: Some(jobs),
        duration_s: 600.0,
        warmup_s: 300.0,
        ..Settings::default()
    }
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let a = scratch("threads-1");
    let b = scratch("threads-2");
    let exec = &simulate;
    let one =
        run_experiment_with(experiments::get("flow-aware"), &settings(&a, 1, 2), exec).unwrap();
    let two =
        run_experiment_with(experiments::get("flow-aware"), &settings(&b, 2, 2), exec).unwrap();
    assert_eq!(one.computed, 6);
    assert_eq!(two.computed, 6);
    for f in ["runs.csv", "summary.csv"] {
        let x = fs::read(a.join("flow-aware").join(f)).unwrap();
        let y = fs::read(b.join("flow-aware").join(f)).unwrap();
        assert_eq!(x, y, "{f} differs between 1 and 2 threads");
    }
    // A rerun reuses everything and gives the same files.
    let again =
        run_experiment_with(experiments::get("flow-aware"), &settings(&a, 2, 2), exec).unwrap();
    assert_eq!((again.computed, again.reused), (0, 6));
    let x = fs::read(b.join("flow-aware/runs.csv")).unwrap();
    assert_eq!(fs::read(a.join("flow-aware/runs.csv")).unwrap(), x);
}

#[test]
fn sensitivity_files_have_the_expected_shape() {
    let out = scratch("shape");
    let res = run_experiment_with(
        experiments::get("sensitivity"),
        &settings(&out, 2, 2),
        &simulate,
    )
    .unwrap();
    let dir = out.join("sensitivity");
    let mut names = run_files(&dir);
    names.retain(|n| n != "runs");
    assert_eq!(
        names,
        [
            "braking.png",
            "braking.svg",
            "run.json",
            "runs.csv",
            "sensitivity.png",
            "sensitivity.svg",
            "summary.csv",
            "summary.md"
        ]
    );
    assert!(fs::read(dir.join("sensitivity.png"))
        .unwrap()
        .starts_with(b"\x89PNG"));
    // The drawn title names the model it ran under (here the default preset).
    let svg = fs::read_to_string(dir.join("sensitivity.svg")).unwrap();
    assert!(svg.contains("platform defaults"), "no model in the title");
    assert!(!svg.contains("the paper&apos;s model") && !svg.contains("the paper's model"));
    // The Table 3 panels and the braking histogram (issue 29).
    assert_eq!(res.figures.len(), 2);
    assert_eq!(res.figures[1].stem, "braking");
    // 4 demands × 3 strategies (none, pd, dedicated) × 2 seeds.
    assert_eq!(run_files(&dir.join("runs")).len(), 24);

    // runs.csv: header + 24 rows, every row as wide as the header.
    let text = fs::read_to_string(dir.join("runs.csv")).unwrap();
    let mut r = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(
        &header[..5],
        ["penetration", "demand_vphpl", "strategy", "seed", "key"]
    );
    for col in [
        "lane_changes_per_vehicle",
        "lane_changes_per_cav",
        "lane_changes_per_human",
        "avg_platoon_length",
        "platooning_probability",
        "discharge_flow_vphpl",
        "max_sustained_flow_vphpl",
        "discharge_change_pct",
    ] {
        assert!(
            header.iter().any(|h| h == col),
            "{col} missing in {header:?}"
        );
    }
    assert!(!header.iter().any(|h| h == "wall_seconds"));
    let rows: Vec<csv::StringRecord> = r.records().map(|x| x.unwrap()).collect();
    assert_eq!(rows.len(), 24);
    assert!(rows.iter().all(|x| x.len() == header.len()));
    let dq = header
        .iter()
        .position(|h| h == "discharge_change_pct")
        .unwrap();
    for row in &rows {
        // ΔQ only on the organizing rows (PD and dedicated), against the baseline.
        assert_eq!(row[2] != *"none", !row[dq].is_empty(), "{row:?}");
    }

    // summary.csv: a row per cell and metric; Table 3 values on the right rows.
    let text = fs::read_to_string(dir.join("summary.csv")).unwrap();
    let mut r = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(
        header,
        [
            "penetration",
            "demand_vphpl",
            "strategy",
            "metric",
            "mean",
            "sd",
            "n",
            "ci_low",
            "ci_high",
            "paper",
            "difference",
            "relative_difference_pct",
            "paper_source",
            "runs_with_collisions"
        ]
    );
    let rows: Vec<csv::StringRecord> = r.records().map(|x| x.unwrap()).collect();
    let with_paper = rows.iter().filter(|x| !x[9].is_empty()).count();
    assert_eq!(with_paper, 4 * 9);
    let dq2500 = rows
        .iter()
        .find(|x| &x[1] == "2500" && &x[3] == "discharge_change_pct")
        .unwrap();
    assert_eq!(
        (&dq2500[6], &dq2500[9], &dq2500[12]),
        ("2", "-9.54", "Table 3")
    );
    assert_eq!(res.rows.len(), rows.len());

    let md = fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(md.starts_with("# Platoon organization at various demands (paper Table 3)"));
    for part in [
        "| 2500 | ours |",
        "| paper |",
        "-9.54",
        "## Against the paper",
        "## Checks",
    ] {
        assert!(md.contains(part), "{part} missing in summary.md:\n{md}");
    }

    let prov: serde_json::Value =
        serde_json::from_slice(&fs::read(dir.join("run.json")).unwrap()).unwrap();
    assert_eq!(prov["experiment"], "sensitivity");
    assert_eq!(prov["seeds"], serde_json::json!([1, 2]));
    assert_eq!(prov["cells"].as_array().unwrap().len(), 12);
    assert_eq!(prov["cells"][10]["labels"]["strategy"], "pd");
    assert_eq!(prov["cells"][10]["scenario"]["strategy"]["kind"], "pd");
    assert_eq!(
        prov["cells"][11]["scenario"]["strategy"]["kind"],
        "dedicated"
    );
    assert_eq!(prov["cells"][11]["keys"].as_array().unwrap().len(), 2);
    assert!(prov["version"].is_string());
}

#[test]
fn calibration_writes_the_tradeoff_and_the_thresholds() {
    let out = scratch("calibrate");
    let table = out.join("written").join("flow_aware_thresholds.toml");
    fs::create_dir_all(table.parent().unwrap()).unwrap();
    let s = Settings {
        flow_thresholds: vec![1250.0, 2750.0],
        speed_thresholds: vec![0.0],
        write_table: Some(table.clone()),
        ..settings(&out, 2, 1)
    };
    assert_eq!(
        experiments::get("calibrate-flow-aware").total_runs(&s),
        3 * 4 * 3
    );
    let res = run_experiment_with(experiments::get("calibrate-flow-aware"), &s, &simulate).unwrap();
    assert_eq!(res.outcomes.len(), 36);
    let dir = out.join("calibrate-flow-aware");
    for f in [
        "runs.csv",
        "summary.csv",
        "summary.md",
        "run.json",
        "tradeoff.csv",
        "thresholds.toml",
        "tradeoff.png",
        "tradeoff.svg",
    ] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    let tradeoff = fs::read_to_string(dir.join("tradeoff.csv")).unwrap();
    assert_eq!(tradeoff.lines().count(), 1 + 3 * 2);
    let toml = fs::read_to_string(dir.join("thresholds.toml")).unwrap();
    assert_eq!(toml.matches("[[penetration]]").count(), 3);
    // --write-table: the same file where the Flow-Aware defaults are read from, in a form the
    // scenario crate reads back: every feasible row with a pair of the grid.
    assert_eq!(fs::read_to_string(&table).unwrap(), toml);
    let rows = platoonsim_scenario::thresholds::parse(&toml).unwrap();
    assert_eq!(rows.len(), toml.matches("feasible = true").count());
    for r in &rows {
        assert!([0.25, 0.5, 0.75].contains(&r.penetration), "{r:?}");
        assert!([1250.0, 2750.0].contains(&r.flow_threshold_vphpl), "{r:?}");
        assert_eq!(r.speed_threshold_kmh, 0.0);
    }
    let runs = fs::read_to_string(dir.join("runs.csv")).unwrap();
    let header = runs.lines().next().unwrap();
    assert!(header.starts_with(
        "penetration,demand_vphpl,strategy,flow_threshold_vphpl,speed_threshold_kmh,seed,key,"
    ));
    let md = fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(md.contains("## Chosen thresholds"), "{md}");
}

#[test]
fn capacity_baseline_mean_discharge_leaves_out_the_filling_road() {
    let out = scratch("capacity");
    let s = Settings {
        duration_s: 900.0,
        ..settings(&out, 2, 1)
    };
    let res = run_experiment_with(experiments::get("capacity"), &s, &simulate).unwrap();
    // 5 baseline cells, 4 PD and 4 dedicated cells, 1 seed.
    assert_eq!(res.outcomes.len(), 13);
    for o in res.outcomes.iter().filter(|o| o.cell < 5) {
        // Stage 1: a steady entrance queue discharges evenly, so the mean flow over the
        // window is close to its highest 5-min flow. With the filling first 5 min in the
        // window (about 530 veh/h/lane) the mean would be about three quarters of it.
        let mean = o.fields.get("discharge_flow_vphpl").unwrap();
        let max = o.fields.get("max_sustained_flow_vphpl").unwrap();
        assert!(
            mean <= max && mean > 0.97 * max,
            "cell {}: {mean} vs {max}",
            o.cell
        );
        assert!(max > 1800.0, "cell {}: capacity {max}", o.cell);
    }
    let md = fs::read_to_string(out.join("capacity/summary.md")).unwrap();
    for part in [
        "Baseline mean discharge",
        "PD mean discharge",
        "With the mean discharge instead of the highest 5-min flow",
    ] {
        assert!(md.contains(part), "{part} missing in summary.md:\n{md}");
    }
}

/// A run's metrics bit for bit: a statistic that does not apply (null, read as NaN) equals
/// itself.
fn bits(f: &platoonsim_runs::record::Fields) -> Vec<(String, u64)> {
    f.0.iter().map(|(k, v)| (k.clone(), v.to_bits())).collect()
}
