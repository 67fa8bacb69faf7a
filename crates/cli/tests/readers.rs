//! Bounded readers (issue 35 item 5): every input file that is not a regular file is refused
//! at once with a true message (a FIFO used to block forever, a device to read until memory
//! ran out, or to be called "no such file"), and a file of records with an endless line is
//! refused without echoing it.

mod common;

use common::*;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Run platoonsim, killing it (and failing) if it has not ended after 20 s.
fn bounded_run(args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_platoonsim"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(20) {
            child.kill().unwrap();
            panic!("{args:?} still running after 20 s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

#[cfg(unix)]
fn fifo(dir: &Path, name: &str) -> PathBuf {
    let p = dir.join(name);
    assert!(Command::new("mkfifo").arg(&p).status().unwrap().success());
    p
}

/// A short run with trajectories and trips, to break one file of.
fn run_dir(root: &Path) -> PathBuf {
    let out = root.join("run");
    let o = platoonsim(&[
        "run",
        "homogeneous",
        "--duration",
        "300",
        "--warmup",
        "0",
        "--trajectories",
        "1",
        "--trips",
        "--set",
        "run.clock_start=\"05:00\"",
        "-q",
        "--out",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    out
}

fn refused(o: &Output, path: &Path, what: &str) {
    assert_eq!(o.status.code(), Some(1), "{}", stderr(o));
    let e = stderr(o);
    assert!(
        e.contains(&format!("{}", path.display()))
            && e.contains(&format!("not a regular file (a {what})")),
        "{e}"
    );
    assert!(!e.contains("no such file"), "{e}");
}

#[cfg(unix)]
#[test]
fn a_fifo_is_refused_by_every_reader() {
    let root = scratch("fifo");
    let f = fifo(&root, "input");
    let fs = s(&f);
    refused(&bounded_run(&["show", fs]), &f, "FIFO");
    refused(
        &bounded_run(&["run", fs, "--out", s(&root.join("o"))]),
        &f,
        "FIFO",
    );
    refused(
        &bounded_run(&["sweep", fs, "--out", s(&root.join("o"))]),
        &f,
        "FIFO",
    );
    refused(&bounded_run(&["time-space", fs]), &f, "FIFO");
    let set = format!("strategy.thresholds_table={fs:?}");
    refused(
        &bounded_run(&["show", "homogeneous", "--set", &set]),
        &f,
        "FIFO",
    );
    refused(
        &bounded_run(&[
            "experiment",
            "sr99",
            "--demand-scale-table",
            fs,
            "--out",
            s(&root.join("e")),
        ]),
        &f,
        "FIFO",
    );
    // The run directory files of `view` and `compare`.
    let dir = run_dir(&root);
    for name in [
        "trips.csv",
        "detectors.csv",
        "trajectories.csv",
        "road.json",
    ] {
        let file = dir.join(name);
        let keep = dir.join(format!("{name}.keep"));
        std::fs::rename(&file, &keep).unwrap();
        let p = fifo(&dir, name);
        refused(&bounded_run(&["view", s(&dir)]), &p, "FIFO");
        std::fs::remove_file(&p).unwrap();
        std::fs::rename(&keep, &file).unwrap();
    }
    let field = fifo(&root, "field.txt");
    refused(
        &bounded_run(&[
            "compare",
            s(&dir),
            "--field",
            s(&field),
            "--out",
            s(&root.join("c")),
        ]),
        &field,
        "FIFO",
    );
}

#[cfg(unix)]
#[test]
fn a_device_is_refused_with_what_it_is() {
    let zero = Path::new("/dev/zero");
    refused(
        &bounded_run(&["show", "/dev/zero"]),
        zero,
        "character device",
    );
    refused(
        &bounded_run(&["sweep", "/dev/zero"]),
        zero,
        "character device",
    );
    refused(
        &bounded_run(&["time-space", "/dev/zero"]),
        zero,
        "character device",
    );
    let root = scratch("device");
    refused(
        &bounded_run(&[
            "experiment",
            "sr99",
            "--demand-scale-table",
            "/dev/zero",
            "--out",
            s(&root.join("e")),
        ]),
        zero,
        "character device",
    );
}

#[test]
fn an_endless_line_is_refused_without_echoing_it() {
    let root = scratch("long-line");
    let dir = run_dir(&root);
    // A 4 MB header without a line break: it used to be echoed whole in the header error.
    let junk = "x".repeat(4 << 20);
    std::fs::write(dir.join("trajectories.csv"), &junk).unwrap();
    let traj = dir.join("trajectories.csv");
    for args in [vec!["time-space", s(&traj)], vec!["view", s(&dir)]] {
        let o = bounded_run(&args);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        let e = stderr(&o);
        assert!(e.len() < 1000, "{args:?}: {} bytes of stderr", e.len());
        assert!(
            e.contains("line 1 is longer than 65536 bytes (not a file of records)"),
            "{args:?}: {e}"
        );
    }
}
