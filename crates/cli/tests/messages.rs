//! The messages of common mistakes: each names the flag or file, the value and what to do, and
//! a failed command leaves nothing behind.

mod common;
use common::{platoonsim, s, scratch, stderr};

/// A negative number reaches the range check instead of clap's "use '-- -1'" tip.
#[test]
fn negative_seed_and_demand_get_the_range() {
    let o = platoonsim(&["run", "homogeneous", "--seed", "-1"]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(!e.contains("tip:"), "{e}");
    assert!(e.contains("'-1' for '--seed <N>'"), "{e}");
    assert!(e.contains("from 0 to 18446744073709551615"), "{e}");

    let o = platoonsim(&["run", "homogeneous", "--demand", "-5"]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(!e.contains("tip:"), "{e}");
    assert!(
        e.contains("demand.vph_per_lane = -5: must be in [0, 10000] veh/h/lane"),
        "{e}"
    );
}

/// `--duration` shorter than the scenario's 1,200 s warm-up: the message says to add
/// `--warmup`, with a value that works.
#[test]
fn short_duration_suggests_warmup() {
    let o = platoonsim(&["run", "homogeneous", "--duration", "600"]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.contains("run.warmup_s = 1200"), "{e}");
    assert!(e.contains("--duration 600 --warmup 200"), "{e}");
    // With --warmup set by the user, the scenario's check speaks alone.
    let o = platoonsim(&["run", "homogeneous", "--duration", "600", "--warmup", "700"]);
    let e = stderr(&o);
    assert!(e.contains("run.warmup_s = 700"), "{e}");
    assert!(!e.contains("shorten the warm-up"), "{e}");
}

/// The suggested flags do give a valid run (and one that is not empty).
#[test]
fn the_suggested_warmup_runs() {
    let dir = scratch("suggested");
    let o = platoonsim(&[
        "run",
        "homogeneous",
        "--duration",
        "600",
        "--warmup",
        "200",
        "--out",
        s(&dir),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(v["collisions"], 0);
    assert!(v["vehicle_updates"].as_u64().unwrap() > 0, "{v}");
}

#[test]
fn a_directory_is_named_as_one() {
    let dir = scratch("directory");
    let o = platoonsim(&["run", s(&dir)]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.contains("is a directory, not a scenario file"), "{e}");
    assert!(!e.contains("no such file"), "{e}");
}

/// A JSON scenario (e.g. the scenario.json a run writes) is named as JSON, with the way to a
/// TOML one, rather than a TOML parser's complaint at line 1.
#[test]
fn a_json_scenario_points_to_toml() {
    let dir = scratch("json");
    let file = dir.join("scenario.json");
    std::fs::write(&file, "{\"run\": {\"seed\": 1}}\n").unwrap();
    let o = platoonsim(&["run", s(&file)]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.contains("scenario files are TOML"), "{e}");
    assert!(e.contains("show NAME --format toml"), "{e}");
    assert!(!e.contains("TOML parse error"), "{e}");
    // The same text under another name is recognised by its opening brace.
    let other = dir.join("s.toml");
    std::fs::write(&other, "{\"run\": {\"seed\": 1}}\n").unwrap();
    assert!(stderr(&platoonsim(&["run", s(&other)])).contains("scenario files are TOML"));
}

/// `experiment capacity --duration 300`: refused before the output folder exists, naming the
/// warm-up.
#[test]
fn experiment_checks_the_warmup_before_creating_anything() {
    let dir = scratch("experiment");
    let out = dir.join("out");
    let o = platoonsim(&[
        "experiment",
        "capacity",
        "--duration",
        "300",
        "--out",
        s(&out),
    ]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.contains("--warmup 1200"), "{e}");
    assert!(e.contains("--duration 300 --warmup 100"), "{e}");
    assert!(!out.exists(), "{} was created", out.display());
    // The suggested warm-up still meets capacity's fixed 300 s fill time: named too.
    let o = platoonsim(&[
        "experiment",
        "capacity",
        "--duration",
        "300",
        "--warmup",
        "100",
        "--out",
        s(&out),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("longer than 300 s"), "{}", stderr(&o));
    assert!(!out.exists());
}

/// An interrupted run's `.tmp` files of the run's outputs are removed by the next run into the
/// directory (others are left), and `summary.json` is written after every other file.
#[test]
fn a_run_cleans_stale_tmp_files_and_writes_the_summary_last() {
    let dir = scratch("tmp");
    std::fs::write(dir.join("trajectories.csv.tmp"), "time_s,id\n0,").unwrap();
    std::fs::write(dir.join("summary.json.tmp"), "{").unwrap();
    std::fs::write(dir.join("detectors.csv.4242-7.tmp"), "detector").unwrap();
    std::fs::write(dir.join("notes.txt.tmp"), "mine").unwrap();
    let o = platoonsim(&[
        "run",
        "homogeneous",
        "--duration",
        "300",
        "--warmup",
        "100",
        "--trips",
        "--trajectories",
        "10",
        "--view",
        "--out",
        s(&dir),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!dir.join("trajectories.csv.tmp").exists());
    assert!(!dir.join("summary.json.tmp").exists());
    assert!(!dir.join("detectors.csv.4242-7.tmp").exists());
    assert!(dir.join("notes.txt.tmp").exists(), "not a file of the run");
    let modified = |name: &str| {
        std::fs::metadata(dir.join(name))
            .unwrap()
            .modified()
            .unwrap()
    };
    let summary = modified("summary.json");
    for name in [
        "scenario.json",
        "scenario.toml",
        "road.json",
        "detectors.csv",
        "trips.csv",
        "trajectories.csv",
        "view.html",
    ] {
        assert!(
            modified(name) <= summary,
            "{name} written after summary.json"
        );
    }
}

/// Geometry that is legal but known to collide (issue 35 item 4) gets a warning naming the
/// elements, on stderr, before anything runs; the command goes on.
#[test]
fn a_lane_drop_just_after_an_on_ramp_is_warned_about() {
    let dir = scratch("lane-drop-warning");
    let file = dir.join("drop.toml");
    let text = include_str!("../../scenario/tests/fixtures/small_corridor.toml").replacen(
        "from_m = -200.0\nto_m = 1500.0\ncount = 2\n",
        "from_m = -200.0\nto_m = 100.0\ncount = 3\n\n[[network.lanes]]\nfrom_m = 100.0\n\
         to_m = 1500.0\ncount = 2\n",
        1,
    );
    std::fs::write(&file, text).unwrap();
    let o = platoonsim(&["show", s(&file)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        "warning: network.on_ramps[0] (OR1: First St) merges at 0 m, 100 m upstream of a lane \
         drop (lateral lane 1 ends at 100 m): a lane drop within 300 m downstream of an on-ramp \
         is known to collide; move one of them\n"
    );
}

/// Terminal escapes in a scenario name (issue 35 item 8) are printed as escapes, never raw: the
/// name in the file clears the screen and sets the window title.
#[test]
fn control_characters_in_a_scenario_name_are_printed_escaped() {
    let dir = scratch("escapes");
    let file = dir.join("evil.toml");
    let text = include_str!("../../scenario/scenarios/homogeneous.toml").replacen(
        "name = \"homogeneous\"",
        "name = \"evil\\u001b]0;pwned\\u0007\\u001b[2J\"",
        1,
    );
    std::fs::write(&file, text).unwrap();
    let out = dir.join("out");
    for args in [
        vec![
            "run",
            s(&file),
            "--duration",
            "30",
            "--warmup",
            "0",
            "--out",
            s(&out),
        ],
        vec!["show", s(&file)],
    ] {
        let o = platoonsim(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let text = String::from_utf8_lossy(&o.stdout).into_owned() + &stderr(&o);
        assert!(
            !text.contains(['\u{1b}', '\u{7}']),
            "{args:?}: a raw control character in {text:?}"
        );
        assert!(
            text.contains("evil\\u{1b}]0;pwned\\u{7}\\u{1b}[2J"),
            "{args:?}: {text}"
        );
    }
}

/// `experiment sr99` and `sr99-demand` simulate the paper's 4-hour morning: --duration and
/// --warmup are refused, naming the flag, rather than silently ignored (issue 35 item 6).
#[test]
fn the_sr99_experiments_refuse_duration_and_warmup() {
    let dir = scratch("sr99-duration");
    for name in ["sr99", "sr99-demand"] {
        for flag in ["--duration", "--warmup"] {
            let o = platoonsim(&["experiment", name, flag, "600", "--out", s(&dir)]);
            assert_eq!(o.status.code(), Some(1));
            assert_eq!(
                stderr(&o),
                format!(
                    "error: experiment {name} does not take {flag}: it simulates the paper's \
                     SR-99 morning, 05:00-09:00 (14400 s), with the scenario's own warm-up; \
                     --duration and --warmup apply to the homogeneous-road experiments\n"
                )
            );
        }
    }
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "nothing created"
    );
}

/// The exit status with standard output closed by its reader before the command writes.
fn with_closed_stdout(args: &[&str]) -> Option<i32> {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_platoonsim"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    child.wait().unwrap().code()
}

/// Issue 35 item 9: `--help | true` exits like every command whose reader went away (141), and
/// a run with collisions keeps its 3 when nobody reads its summary.
#[test]
fn a_closed_stdout_keeps_the_collision_status_and_help_reports_the_pipe() {
    let dir = scratch("closed-stdout");
    let out = dir.join("out");
    let run = [
        "run",
        "homogeneous",
        "--duration",
        "60",
        "--warmup",
        "0",
        "--penetration",
        "0.5",
        "--set",
        "cav.sensor_range_m=1",
        "--out",
        s(&out),
    ];
    assert_eq!(with_closed_stdout(&run), Some(3));
    // Help is written at once: the reader may still be there (0), but a closed pipe is 141.
    let codes: Vec<Option<i32>> = (0..20).map(|_| with_closed_stdout(&["--help"])).collect();
    assert!(
        codes.iter().all(|c| matches!(c, Some(0) | Some(141))),
        "{codes:?}"
    );
    assert!(codes.contains(&Some(141)), "{codes:?}");
}

/// `--tolerance nan` and `--trajectories 1e-300` (issue 35 item 9): refused, with a short
/// message.
#[test]
fn nan_tolerance_and_a_tiny_period_get_short_refusals() {
    let o = platoonsim(&["experiment", "calibrate-flow-aware", "--tolerance", "nan"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("a finite number >= 0"),
        "{}",
        stderr(&o)
    );
    let o = platoonsim(&["run", "homogeneous", "--trajectories", "1e-300"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr(&o),
        "error: invalid --trajectories 1e-300: the sampling period (s) must be a positive \
         multiple of the time step run.dt_s = 0.1 s\n"
    );
}

/// A syntax error quotes at most 200 characters of the offending line (issue 35 item 9: a
/// 200 KB line of brackets was echoed whole).
#[test]
fn a_syntax_error_quotes_a_long_line_cut_short() {
    let dir = scratch("long-syntax");
    let file = dir.join("nested.toml");
    std::fs::write(
        &file,
        format!("a = {}{}\n", "[".repeat(100_000), "]".repeat(100_000)),
    )
    .unwrap();
    let o = platoonsim(&["show", s(&file)]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.len() < 1000, "{} bytes", e.len());
    assert!(e.contains("not valid TOML") && e.contains("…"), "{e}");
    let long = format!("run.seed={}", "[".repeat(50_000));
    let o = platoonsim(&["show", "homogeneous", "--set", &long]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).len() < 1000, "{} bytes", stderr(&o).len());
}

#[test]
fn a_huge_or_hostile_id_in_an_error_is_bounded_and_escaped() {
    // Issue 48 D10, D11: a 10 MB unknown id printed a 20 MB error; control and bidirectional
    // characters from the files reached the terminal raw.
    let dir = scratch("huge_id");
    let id = "x".repeat(10_000_000);
    let net = format!(
        "<net>\n<edge id=\"a\" from=\"A\" to=\"B\"><lane id=\"a_0\" index=\"0\" speed=\"30\" \
         length=\"100\"/></edge>\n<connection from=\"a\" to=\"{id}\u{202e}\" fromLane=\"0\" \
         toLane=\"0\"/>\n</net>"
    );
    let path = dir.join("n.net.xml");
    std::fs::write(&path, net).unwrap();
    let o = platoonsim(&["import", "sumo", s(&path), "--out", s(&dir.join("n.toml"))]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{}", &err[..200.min(err.len())]);
    assert!(err.len() < 5_000, "{} bytes", err.len());
    assert!(err.contains("characters left out"), "{err}");
    assert!(
        err.contains("\\u{202e}") && !err.contains('\u{202e}'),
        "{err}"
    );
}
