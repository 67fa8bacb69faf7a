//! A sweep on a real scheduler (issue 21): HyperQueue's server and a worker are started on this
//! machine (the `hyperqueue` package from PyPI embeds both; `tests/hq/submit.py` drives it),
//! the acceptance sweep of `tests/sweep.rs` is submitted as 4 shard tasks that read their
//! index from `HQ_TASK_ID` plus a collect task depending on them, and the collected
//! `runs.csv` and `summary.csv` must equal a local unsharded sweep byte for byte. Likewise a
//! calibration (`tests/calibrate.rs`' small one): 2 shard tasks that wait for each other's runs
//! generation by generation, then an unsharded task that computes nothing and writes the
//! outputs, whose `trace.csv` and `calibrated.toml` must equal a local unsharded calibration's.
//!
//! `.ci/run` installs the package. Outside CI, a machine without it skips the test with a
//! message; under CI (`CI=true`) a missing package fails it.

mod common;

use common::{platoonsim, s, scratch, stderr};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

const SHARDS: usize = 4;

/// Whether HyperQueue is missing (the test is then skipped, with a message); under CI a
/// missing package fails the test instead.
fn hyperqueue_missing(test: &str) -> bool {
    let Err(why) = common::python_imports("hyperqueue.cluster") else {
        return false;
    };
    let ci = std::env::var("CI").is_ok_and(|v| v == "true" || v == "1");
    assert!(
        !ci,
        "CI=true but HyperQueue is missing: {why}; .ci/run installs it with \
         `python3 -m pip install hyperqueue==0.27.0`"
    );
    eprintln!(
        "SKIPPED {test}: {why}. Install it with `python3 -m pip install hyperqueue==0.27.0` (CI \
         does)."
    );
    true
}

#[test]
fn sweep_on_hyperqueue_equals_the_local_sweep() {
    if hyperqueue_missing("sweep_on_hyperqueue_equals_the_local_sweep") {
        return;
    }
    let dir = scratch("hq");
    let tests = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let spec = tests.join("sweep/sweep.toml");

    let local = dir.join("local");
    let o = platoonsim(&["-q", "sweep", s(&spec), "--out", s(&local)]);
    assert!(o.status.success(), "{}", stderr(&o));

    let out = dir.join("hq-out");
    let work = dir.join("hq-work");
    let start = Instant::now();
    let o = Command::new("python3")
        .arg(tests.join("hq/submit.py"))
        .args([env!("CARGO_BIN_EXE_platoonsim"), s(&spec), s(&out)])
        .arg(SHARDS.to_string())
        .arg(&work)
        .output()
        .unwrap();
    let wall = start.elapsed().as_secs_f64();
    assert!(
        o.status.success(),
        "HyperQueue job failed:\n{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    // Each task ran its own share, found from HQ_TASK_ID.
    let mut handled = 0;
    for i in 0..SHARDS {
        let log = std::fs::read_to_string(work.join(format!("shard{i}.out"))).unwrap();
        let want = format!("shard {}/{SHARDS}: ", i + 1);
        assert!(log.contains(&want), "task {i}: {log}");
        let n: usize = log[log.find(&want).unwrap() + want.len()..]
            .split_whitespace()
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!(
            log.contains(&format!("({n} computed, 0 reused)")),
            "task {i}: {log}"
        );
        handled += n;
    }
    assert_eq!(handled, 18);
    let collect = std::fs::read_to_string(work.join("collect.out")).unwrap();
    assert!(
        collect.contains("18 runs (0 computed, 18 reused)"),
        "{collect}"
    );
    for f in ["runs.csv", "summary.csv"] {
        assert!(
            std::fs::read(out.join(f)).unwrap() == std::fs::read(local.join(f)).unwrap(),
            "{f} differs between HyperQueue and the local sweep"
        );
    }
    eprintln!(
        "HyperQueue: server, worker, {SHARDS} shard tasks and the collect task in {wall:.1} s"
    );
}

#[test]
fn calibration_on_hyperqueue_equals_the_local_one() {
    if hyperqueue_missing("calibration_on_hyperqueue_equals_the_local_one") {
        return;
    }
    let dir = scratch("hq-calibrate");
    let tests = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let field = common::calibrate::field(&dir);
    let scenario = common::calibrate::scenario();
    let params = tests.join("calibrate/small.toml");
    let command = [
        "calibrate",
        &scenario,
        "--field",
        s(&field),
        "--params",
        s(&params),
    ];
    let local = dir.join("local");
    let mut args = vec!["-q"];
    args.extend(command);
    args.extend(["--out", s(&local)]);
    let o = platoonsim(&args);
    assert!(o.status.success(), "{}", stderr(&o));

    let out = dir.join("hq-out");
    let work = dir.join("hq-work");
    let start = Instant::now();
    let o = Command::new("python3")
        .arg(tests.join("hq/submit.py"))
        .args([
            env!("CARGO_BIN_EXE_platoonsim"),
            "-",
            s(&out),
            "2",
            s(&work),
        ])
        .args(command)
        .output()
        .unwrap();
    let wall = start.elapsed().as_secs_f64();
    assert!(
        o.status.success(),
        "HyperQueue job failed:\n{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    // Each task computed its own half of every generation's runs, found from HQ_TASK_ID.
    for i in 0..2 {
        let log = std::fs::read_to_string(work.join(format!("shard{i}.out"))).unwrap();
        let want = format!(
            "shard {}/2: 13 candidates, 13 runs (13 computed, 0 reused)",
            i + 1
        );
        assert!(log.contains(&want), "task {i}: {log}");
    }
    let collect = std::fs::read_to_string(work.join("collect.out")).unwrap();
    assert!(
        collect.contains("26 runs (0 computed, 26 reused)"),
        "{collect}"
    );
    for f in ["trace.csv", "calibrated.toml"] {
        assert!(
            std::fs::read(out.join("small").join(f)).unwrap()
                == std::fs::read(local.join("small").join(f)).unwrap(),
            "{f} differs between HyperQueue and the local calibration"
        );
    }
    eprintln!("HyperQueue: server, worker, 2 calibration shards and the final task in {wall:.1} s");
}
