//! `run` with collisions (collisions.csv, exit code 3, --allow-collisions, the safety line of
//! the summary) and standard output that fails: a closed pipe exits quietly with 141, a full
//! device with `error: …`, never a panic.

mod common;

use common::{num, platoonsim, read_csv, s, scratch, stderr, stdout};
use std::process::{Command, Output, Stdio};

/// The arguments of a quiet run of the homogeneous road for `duration` s with `warmup` s of
/// warm-up, then `options`, written to `out`.
fn homogeneous_run<'a>(
    duration: &'a str,
    warmup: &'a str,
    options: &[&'a str],
    out: &'a str,
) -> Vec<&'a str> {
    let mut args = vec![
        "run",
        "homogeneous",
        "--duration",
        duration,
        "--warmup",
        warmup,
    ];
    args.extend_from_slice(options);
    args.extend_from_slice(&["--out", out, "-q"]);
    args
}

/// 50 % CAV whose CAVs see only 1 m ahead: the controllers notice their leader too late and
/// run into it.
const BLIND_CAVS: [&str; 4] = ["--penetration", "0.5", "--set", "cav.sensor_range_m=1"];

/// A minute of the homogeneous road with [`BLIND_CAVS`] (15 collisions on this branch).
fn colliding(out: &str, extra: &[&str]) -> Output {
    let mut args = homogeneous_run("60", "0", &BLIND_CAVS, out);
    args.extend_from_slice(extra);
    platoonsim(&args)
}

const COLUMNS: &str =
    "t_s,kind,lane,x_m,vehicle,vehicle_kind,v_mps,other,other_kind,other_v_mps,overlap_m";

#[test]
fn a_run_with_collisions_writes_them_and_exits_with_3() {
    let dir = scratch("collide");
    let o = colliding(s(&dir), &[]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(3), "{err}");
    assert!(err.starts_with("warning: "), "{err}");
    assert!(err.contains("the first: t = "), "{err}");
    assert!(err.contains("collisions.csv"), "{err}");
    assert!(!err.contains("panicked"), "{err}");

    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("summary.json")).unwrap()).unwrap();
    let n = summary["collisions"].as_u64().unwrap();
    assert!(n > 0);
    let text = std::fs::read_to_string(dir.join("collisions.csv")).unwrap();
    assert_eq!(text.lines().next(), Some(COLUMNS));
    let rows = read_csv(&dir.join("collisions.csv"));
    assert_eq!(rows.len() as u64, n);
    let mut last_t = 0.0;
    for r in &rows {
        let t = num(r, "t_s");
        assert!(t >= last_t && t <= 60.0, "time order: {r:?}");
        last_t = t;
        assert!(
            ["rear-end", "lane-end"].contains(&r["kind"].as_str()),
            "{r:?}"
        );
        assert!(r["lane"].parse::<u32>().unwrap() >= 1);
        r["vehicle"].parse::<u64>().unwrap();
        assert!(
            ["human", "cav"].contains(&r["vehicle_kind"].as_str()),
            "{r:?}"
        );
        assert!(num(r, "v_mps") >= 0.0 && num(r, "overlap_m") >= 0.0);
        if r["kind"] == "rear-end" {
            r["other"].parse::<u64>().unwrap();
            assert!(
                ["human", "cav"].contains(&r["other_kind"].as_str()),
                "{r:?}"
            );
            num(r, "other_v_mps");
        } else {
            assert!(r["other"].is_empty() && r["other_kind"].is_empty());
        }
    }
    let first = &rows[0];
    assert!(
        err.contains(&format!(
            "t = {} s, {} in lane {}",
            first["t_s"], first["kind"], first["lane"]
        )),
        "{err}"
    );
    let paragraph = stdout(&o).replace('\n', " ");
    assert!(
        paragraph.contains(&format!("Collisions: {n}.")),
        "{paragraph}"
    );
    assert!(
        paragraph.contains("scenario.toml, road.json, collisions.csv."),
        "{paragraph}"
    );

    // --allow-collisions: the same files and warning, exit 0.
    let o = colliding(s(&dir), &["--allow-collisions"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stderr(&o).starts_with("warning: "));
    assert_eq!(
        std::fs::read_to_string(dir.join("collisions.csv")).unwrap(),
        text
    );

    // A run without collisions in the same directory removes the stale file.
    let o = platoonsim(&homogeneous_run("120", "30", &[], s(&dir)));
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stderr(&o), "");
    assert!(!dir.join("collisions.csv").exists());
    let p = stdout(&o).replace('\n', " ");
    assert!(p.contains("Collisions: 0."), "{p}");
    assert!(p.contains("Safety after the warm-up, over "), "{p}");
    assert!(p.contains("hard brakings beyond 4 m/s² ("), "{p}");
    assert!(p.contains(" severe (6 m/s² or more; "), "{p}");
    assert!(
        p.contains("lane-change conflicts (TTC below 1.5 s), TET "),
        "{p}"
    );
    assert!(p.contains("largest deceleration "), "{p}");
}

/// `platoonsim ARGS` with its standard output the write end of a pipe whose read end is
/// already closed: every write fails with EPIPE.
fn into_closed_pipe(args: &[&str]) -> Output {
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    Command::new(env!("CARGO_BIN_EXE_platoonsim"))
        .args(args)
        .stdout(writer)
        .stderr(Stdio::piped())
        .output()
        .unwrap()
}

#[test]
fn a_closed_pipe_exits_quietly_with_141() {
    let dir = scratch("pipe");
    let run = homogeneous_run("60", "0", &[], s(&dir));
    for args in [
        &["show", "sr99"][..],
        &["show", "homogeneous", "--format", "json"],
        &["scenarios"],
        &run,
    ] {
        let o = into_closed_pipe(args);
        assert_eq!(o.status.code(), Some(141), "{args:?}: {}", stderr(&o));
        assert_eq!(stderr(&o), "", "{args:?}");
    }
    // The run's files were written before the summary was printed.
    assert!(dir.join("summary.json").is_file());

    // Stderr into the same closed pipe: the collision warning cannot be written either, and
    // that is no panic; the run keeps its failure status 3 (issue 35 item 9: it exited 141,
    // and a script piping the summary lost the collision).
    let (reader, writer) = std::io::pipe().unwrap();
    drop(reader);
    let o = Command::new(env!("CARGO_BIN_EXE_platoonsim"))
        .args(homogeneous_run("60", "0", &BLIND_CAVS, s(&dir)))
        .stdout(writer.try_clone().unwrap())
        .stderr(writer)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(3));
    assert!(dir.join("collisions.csv").is_file());
}

#[test]
fn a_full_device_is_an_error() {
    if !std::path::Path::new("/dev/full").exists() {
        return; // Linux only
    }
    for args in [&["show", "homogeneous"][..], &["scenarios"]] {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let o = Command::new(env!("CARGO_BIN_EXE_platoonsim"))
            .args(args)
            .stdout(full)
            .output()
            .unwrap();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.starts_with("error: cannot write to standard output: No space left on device"),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
}

/// The TTC threshold of the conflict measures is SSAM's 1.5 s by default, and `show` says so
/// (issue 29).
#[test]
fn show_homogeneous_states_the_ttc_threshold() {
    let o = platoonsim(&["show", "homogeneous"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    let section = text
        .split("\n[safety]\n")
        .nth(1)
        .unwrap_or_else(|| panic!("no [safety] section: {text}"));
    assert!(
        section
            .lines()
            .any(|l| l.trim_start().starts_with("ttc_threshold_s = 1.5")),
        "{section}"
    );
}
