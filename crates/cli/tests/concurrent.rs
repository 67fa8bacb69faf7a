//! Concurrent writers of one `--out` directory (issue 35 item 3): the second process is
//! refused with a clear error while the first holds the directory's lock, so the directory
//! always holds one run's (or one sweep's) complete files, never a mix.

mod common;

use common::*;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const LOCKED: &str = "another platoonsim process is writing";

fn spawn(args: &[&str]) -> std::process::Child {
    Command::new(env!("CARGO_BIN_EXE_platoonsim"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("cannot start platoonsim")
}

fn run_args<'a>(seed: &'a str, out: &'a str) -> Vec<&'a str> {
    vec![
        "run",
        "homogeneous",
        "--duration",
        "240",
        "--warmup",
        "0",
        "--seed",
        seed,
        "-q",
        "--out",
        out,
    ]
}

/// What identifies a run directory's contents (the wall time left out).
fn run_files(dir: &Path) -> (serde_json::Value, Vec<u8>, Vec<u8>) {
    (
        summary_without_wall_time(dir),
        std::fs::read(dir.join("detectors.csv")).unwrap(),
        std::fs::read(dir.join("scenario.json")).unwrap(),
    )
}

fn sweep_spec(dir: &Path) -> PathBuf {
    let spec = dir.join("spec.toml");
    std::fs::write(
        &spec,
        "scenario = \"homogeneous\"\nseeds = 2\nmetrics = [\"discharge_flow_vphpl\"]\n\
         [set]\n\"run.duration_s\" = 120\n\"run.warmup_s\" = 0\n\
         [axes]\n\"run.penetration\" = [0.2, 0.6]\n",
    )
    .unwrap();
    spec
}

fn sweep_files(dir: &Path) -> (Vec<u8>, Vec<u8>) {
    (
        std::fs::read(dir.join("runs.csv")).unwrap(),
        std::fs::read(dir.join("summary.csv")).unwrap(),
    )
}

/// Both finished: each exited 0, or was refused naming the directory; at least one wrote.
fn check_pair(outs: &[Output], dir: &Path, trial: usize) -> usize {
    let mut ok = 0;
    for o in outs {
        if o.status.success() {
            ok += 1;
        } else {
            let e = stderr(o);
            assert!(
                e.contains(&format!("{LOCKED} {}", dir.display())),
                "trial {trial}: {e}"
            );
            assert_eq!(o.status.code(), Some(1), "trial {trial}: {e}");
        }
    }
    assert!(ok >= 1, "trial {trial}: both refused");
    ok
}

#[test]
fn a_directory_being_written_is_refused_naming_it() {
    use fs4::FileExt;
    let root = scratch("held");
    let out = root.join("out");
    std::fs::create_dir_all(&out).unwrap();
    // This test process plays the other writer: it holds the lock a `run` would take.
    let held = std::fs::File::open(&out).unwrap();
    FileExt::try_lock(&held).unwrap();
    let o = platoonsim(&run_args("1", s(&out)));
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(
        stderr(&o).lines().next().unwrap(),
        format!(
            "error: {LOCKED} {}: wait for it to end or choose another --out (only the shards of \
             one sweep or calibration, --shard I/N, may write a directory together)",
            out.display()
        )
    );
    assert_eq!(
        std::fs::read_dir(&out).unwrap().count(),
        0,
        "nothing written"
    );
    // A sweep, sharded or not, is refused too.
    let spec = sweep_spec(&root);
    for shard in [&[][..], &["--shard", "1/2"]] {
        let mut args = vec!["sweep", s(&spec), "-q", "--out", s(&out)];
        args.extend_from_slice(shard);
        let o = platoonsim(&args);
        assert!(stderr(&o).contains(LOCKED), "{shard:?}: {}", stderr(&o));
    }
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 0);
    // Released, the directory is written.
    drop(held);
    let o = platoonsim(&run_args("1", s(&out)));
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn two_runs_and_two_sweeps_on_one_directory_never_mix_20_of_20() {
    let root = scratch("pairs");
    // The references, each written alone.
    let (ref_a, ref_b) = (root.join("ref-a"), root.join("ref-b"));
    for (seed, dir) in [("1", &ref_a), ("2", &ref_b)] {
        assert!(platoonsim(&run_args(seed, s(dir))).status.success());
    }
    let refs = [run_files(&ref_a), run_files(&ref_b)];
    let spec = sweep_spec(&root);
    let ref_sweep = root.join("ref-sweep");
    assert!(
        platoonsim(&["sweep", s(&spec), "-q", "--out", s(&ref_sweep)])
            .status
            .success()
    );
    let ref_sweep = sweep_files(&ref_sweep);

    let (mut both_runs, mut both_sweeps) = (0, 0);
    for trial in 0..20 {
        // Two runs with different seeds at once: the directory holds one of them, whole.
        let dir = root.join(format!("run-{trial}"));
        let d = s(&dir);
        let children = [spawn(&run_args("1", d)), spawn(&run_args("2", d))];
        let outs: Vec<Output> = children
            .into_iter()
            .map(|c| c.wait_with_output().unwrap())
            .collect();
        both_runs += usize::from(check_pair(&outs, &dir, trial) == 2);
        let got = run_files(&dir);
        assert!(refs.contains(&got), "trial {trial}: a mix of two runs");

        // Two identical sweeps at once: one sweep's complete tables.
        let dir = root.join(format!("sweep-{trial}"));
        let d = s(&dir);
        let args = ["sweep", s(&spec), "-q", "--out", d];
        let children = [spawn(&args), spawn(&args)];
        let outs: Vec<Output> = children
            .into_iter()
            .map(|c| c.wait_with_output().unwrap())
            .collect();
        both_sweeps += usize::from(check_pair(&outs, &dir, trial) == 2);
        assert_eq!(sweep_files(&dir), ref_sweep, "trial {trial}");
    }
    // Both may succeed only when one ended before the other locked; that is the exception.
    eprintln!("both succeeded (one after the other): runs {both_runs}/20, sweeps {both_sweeps}/20");
}
