//! Safety in the experiment outputs (issue 18): the safety measures flow into runs.csv and
//! summary.csv (a null minimum TTC as an empty cell, left out of the statistics), the runs
//! with collisions mark their cells in summary.csv, summary.md and the report, and a run file
//! of an older engine without the new fields still reads.

use platoonsim_experiment::experiments::{self, run_experiment_with};
use platoonsim_experiment::report::{self, ReportInput};
use platoonsim_experiment::{table, Settings};
use platoonsim_runs::record::{self, Fields};
use platoonsim_runs::runner::simulate;
use platoonsim_runs::{safety, Cell, Labels, Outcome};
use platoonsim_sim::{Config, Output, SimError};
use std::fs;
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("platoonsim-safety-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn cells() -> Vec<Cell> {
    let c = Config::homogeneous(0.5, 1000.0, 300.0, 60.0, 1);
    ["none", "pd"]
        .iter()
        .map(|k| Cell {
            labels: Labels::new()
                .with("demand_vphpl", "1000")
                .with("strategy", *k),
            config: c.clone(),
        })
        .collect()
}

/// A run with the safety fields; `min_ttc` NaN stands for a null in the run file.
fn outcome(cell: usize, seed: u64, collisions: f64, brakings: f64, min_ttc: f64) -> Outcome {
    Outcome {
        cell,
        seed,
        key: format!("k{cell}{seed}"),
        fields: Fields(vec![
            ("discharge_flow_vphpl".into(), 1000.0),
            ("collisions".into(), collisions),
            ("max_deceleration_mps2".into(), 4.5),
            ("vehicle_km".into(), 200.0),
            ("hard_brakings".into(), brakings),
            ("hard_brakings_per_100vkm".into(), brakings / 2.0),
            ("hard_brakings_per_100vkm_human".into(), brakings / 2.0),
            ("severe_brakings_per_100vkm".into(), 0.5),
            ("brakings_at_limit_per_100vkm".into(), 0.0),
            ("rear_end_conflicts_per_100vkm".into(), 1.0),
            ("lane_change_conflicts_per_100vkm".into(), 0.5),
            ("tet_s".into(), 1.3),
            ("tit_s2".into(), 0.5),
            ("min_ttc_s".into(), min_ttc),
        ]),
        computed: true,
    }
}

fn synthetic() -> (Vec<Cell>, Vec<Outcome>) {
    let outcomes = vec![
        outcome(0, 1, 0.0, 3.0, 1.5),
        outcome(0, 2, 0.0, 3.0, f64::NAN),
        outcome(1, 1, 0.0, 5.0, 0.5),
        outcome(1, 2, 2.0, 7.0, 1.5),
    ];
    (cells(), outcomes)
}

#[test]
fn failed_cells_and_the_warning() {
    let (cells, outcomes) = synthetic();
    let failed = safety::failed_cells(&cells, &outcomes);
    assert_eq!(
        failed,
        [safety::Failed {
            cell: 1,
            seeds: vec![2],
            runs: 2
        }]
    );
    let w = safety::warning_md(&cells, &outcomes);
    assert!(
        w.starts_with("> **Warning: 1 run with collisions — these results are invalid.**"),
        "{w}"
    );
    assert!(
        w.ends_with("> - demand_vphpl 1000, strategy pd: 1 of 2 runs (seed 2)\n\n"),
        "{w}"
    );
    // No collision, no warning.
    assert_eq!(safety::warning_md(&cells, &outcomes[..3]), "");
}

#[test]
fn the_safety_table_has_every_cell_side_by_side() {
    let (cells, outcomes) = synthetic();
    let md = safety::section_md(&cells, &outcomes, &["demand_vphpl"]);
    assert!(md.starts_with("## Safety\n\n"), "{md}");
    assert!(
        md.contains("time to collision below TTC* = 1.5 s;"),
        "the TTC* used: {md}"
    );
    let lines: Vec<&str> = md.lines().filter(|l| l.starts_with('|')).collect();
    assert_eq!(
        lines,
        [
            "| Demand (veh/h/lane) | Strategy | Runs with collisions (runs) | Vehicle-km (veh·km) | Hard brakings > 4 m/s² (per 100 veh-km) | Severe brakings ≥ 6 m/s² (per 100 veh-km) | Brakings at the limit b_e (per 100 veh-km) | Rear-end conflicts (per 100 veh-km) | Lane-change conflicts (per 100 veh-km) | TET (s) | TIT (s²) | Min TTC (s) | Max deceleration (m/s²) |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
            // Min TTC: one run had none (null), left out of the mean.
            "| 1000 | none | 0 of 2 | 200 ± 0 | 1.500 ± 0.000 | 0.500 ± 0.000 | 0.000 ± 0.000 | 1.00 ± 0.00 | 0.50 ± 0.00 | 1.3 ± 0.0 | 0.5 ± 0.0 | 1.50 (n = 1) | 4.50 ± 0.00 |",
            // 3 ± t(0.975, 1) · (1 / √2) / √2 = 3 ± 6.3531; TTC 1 ± 6.3531.
            "| 1000 | pd | **1 of 2** (invalid) | 200 ± 0 | 3.000 ± 6.353 | 0.500 ± 0.000 | 0.000 ± 0.000 | 1.00 ± 0.00 | 0.50 ± 0.00 | 1.3 ± 0.0 | 0.5 ± 0.0 | 1.00 ± 6.35 | 4.50 ± 0.00 |",
            // By kind: only the human hard-braking rate is in the synthetic runs.
            "| Demand (veh/h/lane) | Strategy | Hard brakings, human-driven (per 100 veh-km) | Hard brakings, CAV (per 100 veh-km) | Severe brakings, human-driven (per 100 veh-km) | Severe brakings, CAV (per 100 veh-km) | Lane-change conflicts, human-driven (per 100 veh-km) | Lane-change conflicts, CAV (per 100 veh-km) |",
            "|---|---|---|---|---|---|---|---|",
            "| 1000 | none | 1.500 ± 0.000 | – | – | – | – | – |",
            "| 1000 | pd | 3.000 ± 6.353 | – | – | – | – | – |",
        ]
    );
}

#[test]
fn runs_and_summary_csv_carry_the_safety_fields() {
    let (cells, outcomes) = synthetic();
    let runs = String::from_utf8(table::runs_csv(&cells, &outcomes).unwrap()).unwrap();
    let lines: Vec<&str> = runs.lines().collect();
    assert_eq!(
        lines[0],
        "demand_vphpl,strategy,seed,key,discharge_flow_vphpl,collisions,max_deceleration_mps2,\
         vehicle_km,hard_brakings,hard_brakings_per_100vkm,hard_brakings_per_100vkm_human,\
         severe_brakings_per_100vkm,brakings_at_limit_per_100vkm,rear_end_conflicts_per_100vkm,\
         lane_change_conflicts_per_100vkm,tet_s,tit_s2,min_ttc_s"
    );
    // The null minimum TTC is an empty cell (pandas reads NaN, the column stays float);
    // counts are integers, every other number has a decimal point.
    assert_eq!(
        lines[2],
        "1000,none,2,k02,1000.0,0,4.5,200.0,3,1.5,1.5,0.5,0.0,1.0,0.5,1.3,0.5,"
    );
    assert_eq!(
        lines[4],
        "1000,pd,2,k12,1000.0,2,4.5,200.0,7,3.5,3.5,0.5,0.0,1.0,0.5,1.3,0.5,1.5"
    );

    let rows = table::summarize("sensitivity", &cells, &outcomes);
    let ttc = rows
        .iter()
        .find(|r| r.cell == 0 && r.metric == "min_ttc_s")
        .unwrap();
    assert_eq!((ttc.stats.n, ttc.stats.mean), (1, 1.5));
    let summary = String::from_utf8(table::summary_csv(&cells, &rows).unwrap()).unwrap();
    let mut r = csv::Reader::from_reader(summary.as_bytes());
    let header = r.headers().unwrap().clone();
    assert_eq!(&header[header.len() - 1], "runs_with_collisions");
    let recs: Vec<csv::StringRecord> = r.records().map(|x| x.unwrap()).collect();
    // 14 metrics of two cells.
    assert_eq!(recs.len(), 28);
    for rec in &recs {
        let expected = if &rec[1] == "pd" { "1" } else { "0" };
        assert_eq!(&rec[rec.len() - 1], expected, "{rec:?}");
    }
    let ttc_row = recs
        .iter()
        .find(|x| &x[1] == "none" && &x[2] == "min_ttc_s")
        .unwrap();
    // mean 1.5 over n = 1 (the null left out); no sd or interval.
    assert_eq!(
        (&ttc_row[3], &ttc_row[4], &ttc_row[5], &ttc_row[6]),
        ("1.5", "", "1", "")
    );
}

#[test]
fn an_old_run_file_without_the_safety_fields_still_reads() {
    // The summary of a run file from before issue 18 (collisions only).
    let old = br#"{"config_hash":"k","seed":1,"version":"0.1.0","engine":"e",
        "summary":{"scenario":"homogeneous","vehicles_entered":10,"discharge_flow_vphpl":900.5,
        "collisions":0,"vehicle_updates":100,"steps":10,"wall_seconds":0.1}}"#;
    let fields = record::decode(old, "k", 1, Some("e")).unwrap();
    assert_eq!(fields.get("min_ttc_s"), None);
    assert_eq!(fields.get("discharge_flow_vphpl"), Some(900.5));
    let cells = cells();
    let outcomes = vec![Outcome {
        cell: 0,
        seed: 1,
        key: "k".into(),
        fields,
        computed: false,
    }];
    let md = safety::section_md(&cells[..1], &outcomes, &[]);
    assert!(
        md.contains("| 1000 | none | 0 of 1 | – | – | – | – | – | – | – | – | – | – |"),
        "{md}"
    );
    // A null minimum TTC reads as NaN, not as an error.
    let new = br#"{"config_hash":"k","seed":1,"engine":"e",
        "summary":{"discharge_flow_vphpl":1.0,"min_ttc_s":null}}"#;
    let f = record::decode(new, "k", 1, Some("e")).unwrap();
    assert!(f.get("min_ttc_s").unwrap().is_nan());
}

/// The engine, with a collision added to the PD run of seed 2 (what a run that collides
/// reports), so that the marking is tested without depending on which scenario collides.
fn with_a_collision(c: &Config) -> Result<Output, SimError> {
    let mut out = simulate(c)?;
    if c.strategy.kind == platoonsim_sim::StrategyKind::PD && c.seed == 2 {
        out.summary.collisions = 1;
    }
    Ok(out)
}

#[test]
fn an_experiment_marks_the_cells_that_collided() {
    let out = scratch("flow-aware");
    let s = Settings {
        out: out.clone(),
        seeds: 2,
        jobs: Some(2),
        duration_s: 600.0,
        warmup_s: 300.0,
        ..Settings::default()
    };
    let res = run_experiment_with(experiments::get("flow-aware"), &s, &with_a_collision).unwrap();
    let dir = out.join("flow-aware");
    let md = fs::read_to_string(dir.join("summary.md")).unwrap();
    let title = "# Flow-Aware strategy on the homogeneous road\n\n";
    assert!(
        md.starts_with(&format!(
            "{title}> **Warning: 1 run with collisions — these results are invalid.**"
        )),
        "{md}"
    );
    assert!(
        md.contains("> - penetration 0.5, demand_vphpl 2500, strategy pd: 1 of 2 runs (seed 2)"),
        "{md}"
    );
    assert!(md.contains("## Safety"), "{md}");
    // The braking histogram, as a figure.
    assert!(
        md.contains("![Hard-braking episodes by peak deceleration"),
        "{md}"
    );
    assert!(dir.join("braking.png").is_file() && dir.join("braking.svg").is_file());
    let safety_rows: Vec<&str> = md
        .split("## Safety")
        .nth(1)
        .unwrap()
        .split("By vehicle kind")
        .next()
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("| 0.5 |"))
        .collect();
    assert_eq!(safety_rows.len(), 3, "{md}");
    assert!(safety_rows[0].starts_with("| 0.5 | 2500 | none | 0 of 2 |"));
    assert!(safety_rows[1].starts_with("| 0.5 | 2500 | flow-aware | 0 of 2 |"));
    assert!(safety_rows[2].starts_with("| 0.5 | 2500 | pd | **1 of 2** (invalid) |"));
    let check = res.checks.last().unwrap();
    assert!(!check.passed);
    assert!(
        check.statement.contains("1 of 6 runs had collisions"),
        "{check:?}"
    );

    // runs.csv: the seed-2 PD run has collisions = 1, every safety field is numeric.
    let mut r = csv::Reader::from_path(dir.join("runs.csv")).unwrap();
    let header = r.headers().unwrap().clone();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    for rec in r.records() {
        let rec = rec.unwrap();
        let collided = &rec[col("strategy")] == "pd" && &rec[col("seed")] == "2";
        assert_eq!(&rec[col("collisions")], if collided { "1" } else { "0" });
        for f in [
            "max_deceleration_mps2",
            "vehicle_km",
            "hard_brakings",
            "severe_brakings_cav",
            "brakings_at_limit_human",
            "rear_end_conflicts",
            "lane_change_conflicts_human",
            "hard_brakings_per_100vkm",
            "lane_change_conflicts_per_100vkm_human",
            "braking_peaks_human_0",
            "braking_peaks_cav_5",
            "tet_s",
            "tit_s2",
        ] {
            rec[col(f)].parse::<f64>().unwrap();
        }
        let ttc = &rec[col("min_ttc_s")];
        assert!(ttc.is_empty() || ttc.parse::<f64>().is_ok(), "{ttc}");
    }

    // The report opens with the warning, naming the experiment and the cell.
    let outputs = [res];
    let input = ReportInput {
        outputs: &outputs,
        provenance: Default::default(),
        command: "test",
        seeds: 2,
        network_seeds: None,
        network_note: "",
        jobs: Some(2),
        wall_seconds: 1.0,
    };
    let report = report::markdown(&input);
    let warning = report.split("## At a glance").next().unwrap();
    assert!(
        warning.contains("> **Warning: 1 of 6 runs with collisions — these results are invalid.**"),
        "{warning}"
    );
    assert!(
        warning.contains(
            "> - flow-aware: penetration 0.5, demand_vphpl 2500, strategy pd: 1 of 2 runs (seed 2)"
        ),
        "{warning}"
    );
    assert!(
        report.contains("### Safety"),
        "the experiment's table in the report"
    );
    assert_eq!(report::collisions_warning(&[]), "");
}
