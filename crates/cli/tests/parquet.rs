//! `--format parquet` (issue 21): the Parquet tables of `run` (detectors, trips, trajectories),
//! `sweep` and `experiment` (runs, summary) hold exactly what the CSV files hold, checked
//! column by column by reading them back with pyarrow (`tests/parquet/compare.py`).
//! `.ci/run` installs pyarrow; outside CI a machine without it skips the test with a message,
//! under CI (`CI=true`) a missing pyarrow fails it.

mod common;

use common::{platoonsim, s, scratch, stderr, stdout};
use std::path::{Path, PathBuf};
use std::process::Command;

fn ok(args: &[&str]) -> String {
    let o = platoonsim(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    stdout(&o)
}

/// Compare each (CSV, Parquet) pair with pyarrow; returns its report.
fn compare(pairs: &[(PathBuf, PathBuf)]) -> String {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/parquet/compare.py");
    let mut cmd = Command::new("python3");
    cmd.arg(script);
    for (c, p) in pairs {
        cmd.arg(c).arg(p);
    }
    let o = cmd.output().unwrap();
    assert!(o.status.success(), "{}\n{}", stdout(&o), stderr(&o));
    stdout(&o)
}

#[test]
fn parquet_tables_equal_the_csv_tables() {
    if let Err(why) = common::python_imports("pyarrow.parquet") {
        let ci = std::env::var("CI").is_ok_and(|v| v == "true" || v == "1");
        assert!(
            !ci,
            "CI=true but pyarrow is missing: {why}; .ci/run installs it"
        );
        eprintln!("SKIPPED parquet_tables_equal_the_csv_tables: {why}. Install it with `python3 -m pip install pyarrow` (CI does).");
        return;
    }
    let dir = scratch("parquet");
    let tests = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let ramps = tests.join("sweep/ramps.toml");
    let mut pairs = Vec::new();

    // run: the same seed twice, CSV then Parquet.
    let (csv, pq) = (dir.join("run-csv"), dir.join("run-pq"));
    let base = [
        "run",
        s(&ramps),
        "--trips",
        "--trajectories",
        "1",
        "--strategy",
        "pd",
    ];
    ok(&[&base[..], &["--out", s(&csv)]].concat());
    let out = ok(&[&base[..], &["--out", s(&pq), "--format", "parquet"]].concat());
    assert!(out.contains("trajectories.parquet ("), "{out}");
    for t in ["detectors", "trips", "trajectories"] {
        assert!(!pq.join(format!("{t}.csv")).exists());
        pairs.push((
            csv.join(format!("{t}.csv")),
            pq.join(format!("{t}.parquet")),
        ));
    }

    // run: an overloaded entrance (rows of vehicles still queued, with empty cells) and a
    // clock start (the clock columns, as text).
    let (csv, pq) = (dir.join("queued-csv"), dir.join("queued-pq"));
    let base = [
        "run",
        "homogeneous",
        "--duration",
        "300",
        "--warmup",
        "60",
        "--demand",
        "4000",
        "--trips",
        "--set",
        "run.clock_start=\"05:00\"",
    ];
    ok(&[&base[..], &["--out", s(&csv)]].concat());
    ok(&[&base[..], &["--out", s(&pq), "--format", "parquet"]].concat());
    let trips = std::fs::read_to_string(csv.join("trips.csv")).unwrap();
    assert!(
        trips.contains(",queued,") && trips.contains(",05:00:"),
        "{trips}"
    );
    for t in ["detectors", "trips"] {
        pairs.push((
            csv.join(format!("{t}.csv")),
            pq.join(format!("{t}.parquet")),
        ));
    }

    // sweep: the tables of the same run files, collected as Parquet.
    let spec = tests.join("sweep/sweep.toml");
    let sweep = dir.join("sweep");
    ok(&["-q", "sweep", s(&spec), "--out", s(&sweep)]);
    for t in ["runs", "summary"] {
        std::fs::copy(
            sweep.join(format!("{t}.csv")),
            dir.join(format!("sweep-{t}.csv")),
        )
        .unwrap();
    }
    ok(&[
        "-q",
        "sweep",
        s(&spec),
        "--out",
        s(&sweep),
        "--collect",
        "--format",
        "parquet",
    ]);
    for t in ["runs", "summary"] {
        assert!(!sweep.join(format!("{t}.csv")).exists(), "a stale {t}.csv");
        pairs.push((
            dir.join(format!("sweep-{t}.csv")),
            sweep.join(format!("{t}.parquet")),
        ));
    }

    // experiment: flow-aware, shortened, in both formats.
    let exp = [
        "experiment",
        "flow-aware",
        "--seeds",
        "2",
        "--duration",
        "300",
        "--warmup",
        "100",
    ];
    let (ecsv, epq) = (dir.join("exp-csv"), dir.join("exp-pq"));
    ok(&[&["-q"][..], &exp, &["--out", s(&ecsv)]].concat());
    ok(&[
        &["-q"][..],
        &exp,
        &["--out", s(&epq), "--format", "parquet"],
    ]
    .concat());
    for t in ["runs", "summary"] {
        pairs.push((
            ecsv.join(format!("flow-aware/{t}.csv")),
            epq.join(format!("flow-aware/{t}.parquet")),
        ));
    }

    let report = compare(&pairs);
    eprintln!("{report}");
    assert_eq!(report.lines().count(), pairs.len(), "{report}");
    // The trajectories are large enough to matter; their types are the expected ones.
    let traj = report
        .lines()
        .find(|l| l.contains("trajectories.parquet"))
        .unwrap();
    assert!(
        traj.contains("10 columns") && traj.contains("3 string") && traj.contains("3 uint64"),
        "{traj}"
    );
    let runs = report
        .lines()
        .find(|l| l.contains("sweep/runs.parquet"))
        .unwrap();
    assert!(runs.contains("x 18 rows"), "{runs}");
}
