//! The `platoonsim` binary end to end. The engine-backed tests run real (short) simulations;
//! the others fail (or succeed) before any simulation starts. The per-vehicle records and the
//! time-space diagram are tested in records.rs.

mod common;

use common::{platoonsim, s, scratch, stderr, stdout, summary_without_wall_time};
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------- help and listing

#[test]
fn help_lists_the_commands() {
    let o = platoonsim(&["--help"]);
    assert!(o.status.success());
    let text = stdout(&o);
    for cmd in ["run", "bench", "scenarios", "show", "time-space", "--quiet"] {
        assert!(text.contains(cmd), "{cmd} missing from --help:\n{text}");
    }
}

#[test]
fn run_help_explains_every_flag() {
    let o = platoonsim(&["run", "--help"]);
    assert!(o.status.success());
    let text = stdout(&o);
    for flag in [
        "<SCENARIO-NAME-OR-FILE>",
        "--penetration <P>",
        "--demand <VEH_PER_H_PER_LANE>",
        "--duration <S>",
        "--warmup <S>",
        "--seed <N>",
        "--strategy <STRATEGY>",
        "flow-aware",
        "--set <KEY=VALUE>",
        "--demand-scale <F>",
        "--out <DIR>",
        "out/run",
        "--trips",
        "--trajectories <PERIOD_S>",
        "--trajectory-window <T0,T1>",
        "--trajectory-x <X0,X1>",
        "tens of millions of rows",
    ] {
        assert!(
            text.contains(flag),
            "{flag} missing from run --help:\n{text}"
        );
    }
}

#[test]
fn bench_and_show_help_explain_their_flags() {
    let text = stdout(&platoonsim(&["bench", "--help"]));
    for flag in ["--duration <S>", "--repeat <N>", "--seed <N>", "--json"] {
        assert!(
            text.contains(flag),
            "{flag} missing from bench --help:\n{text}"
        );
    }
    let text = stdout(&platoonsim(&["show", "--help"]));
    for flag in ["--format", "toml", "json", "--set <KEY=VALUE>"] {
        assert!(
            text.contains(flag),
            "{flag} missing from show --help:\n{text}"
        );
    }
}

#[test]
fn scenarios_lists_the_builtins() {
    let o = platoonsim(&["scenarios"]);
    assert!(o.status.success());
    assert!(stdout(&o).starts_with("homogeneous "), "{}", stdout(&o));
    assert!(stdout(&o).contains("\nsr99 "), "{}", stdout(&o));
}

// ---------------------------------------------------------------- show

#[test]
fn show_prints_a_scenario_file_that_loads_back() {
    let dir = scratch("show");
    let o = platoonsim(&[
        "show",
        "homogeneous",
        "--penetration",
        "0.25",
        "--set",
        "human.buffer_s=0.2",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let file = dir.join("resolved.toml");
    std::fs::write(&file, stdout(&o)).unwrap();

    let from_file = platoonsim(&["show", s(&file), "--format", "json"]);
    assert!(from_file.status.success(), "{}", stderr(&from_file));
    let direct = platoonsim(&[
        "show",
        "homogeneous",
        "--penetration",
        "0.25",
        "--set",
        "human.buffer_s=0.2",
        "--format",
        "json",
    ]);
    assert_eq!(stdout(&from_file), stdout(&direct));
    let json: serde_json::Value = serde_json::from_str(&stdout(&direct)).unwrap();
    assert_eq!(json["penetration"], 0.25);
    assert_eq!(json["human"]["buffer_s"], 0.2);
    assert_eq!(json["road"]["lanes"], 3);
    assert_eq!(json["strategy"]["kind"], "none");
}

#[test]
fn show_sr99_prints_the_network_and_takes_the_run_flags() {
    let dir = scratch("show-sr99");
    let flags = [
        "--penetration",
        "0.6",
        "--strategy",
        "pd",
        "--seed",
        "4",
        "--demand-scale",
        "1.2",
    ];
    let mut args = vec!["show", "sr99"];
    args.extend_from_slice(&flags);
    let o = platoonsim(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    for part in [
        "[network]",
        "[[network.on_ramps]]",
        "name = \"Elk Grove Blvd\"",
    ] {
        assert!(text.contains(part), "{part} missing:\n{text}");
    }
    let file = dir.join("sr99.toml");
    std::fs::write(&file, &text).unwrap();
    let from_file = platoonsim(&["show", s(&file), "--format", "json"]);
    assert!(from_file.status.success(), "{}", stderr(&from_file));
    args.extend_from_slice(&["--format", "json"]);
    let direct = platoonsim(&args);
    assert_eq!(stdout(&from_file), stdout(&direct));
    let json: serde_json::Value = serde_json::from_str(&stdout(&direct)).unwrap();
    assert_eq!(json["penetration"], 0.6);
    assert_eq!(json["seed"], 4);
    assert_eq!(json["strategy"]["kind"], "pd");
    assert_eq!(json["road"]["lanes"], 6);
    // --demand-scale times the calibrated base multiplier 1.10 of sr99.
    let scale = json["road"]["network"]["demand_scale"].as_f64().unwrap();
    assert!((scale - 1.10 * 1.2).abs() < 1e-12, "{scale}");
    assert_eq!(json["road"]["network"]["origin_m"], -500.0);
    assert_eq!(
        json["road"]["network"]["on_ramps"]
            .as_array()
            .unwrap()
            .len(),
        16
    );
}

// ---------------------------------------------------------------- argument errors (no engine)

/// The run fails with exit code 1, says `expected` on stderr, and creates no output.
fn assert_run_fails(test: &str, extra: &[&str], expected: &str) {
    let dir = scratch(test);
    let out = dir.join("out");
    let mut args = vec!["run"];
    args.extend_from_slice(extra);
    args.extend_from_slice(&["--out", s(&out)]);
    let o = platoonsim(&args);
    assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains(expected),
        "{args:?}: expected {expected:?} in:\n{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    assert!(stdout(&o).is_empty(), "{}", stdout(&o));
    assert!(!out.exists(), "output directory created for a failed run");
}

#[test]
fn run_rejects_a_bad_penetration() {
    assert_run_fails(
        "bad-penetration",
        &["homogeneous", "--penetration", "1.5"],
        "run.penetration = 1.5: must be in [0, 1]",
    );
}

#[test]
fn run_rejects_bad_set_arguments() {
    assert_run_fails(
        "bad-set-form",
        &["homogeneous", "--set", "run.seed"],
        "invalid override 'run.seed': expected KEY=VALUE",
    );
    assert_run_fails(
        "bad-set-key",
        &["homogeneous", "--set", "road.foo=1"],
        "road.foo: unknown field 'foo' in [road]; allowed keys: lanes, length_m, control_start_m, control_end_m",
    );
    assert_run_fails(
        "bad-set-type",
        &["homogeneous", "--set", "run.dt_s=fast"],
        "run.dt_s: invalid type: string \"fast\"",
    );
    assert_run_fails(
        "bad-set-detector",
        &["homogeneous", "--set", "detectors[2].position_m=7000"],
        "detectors[2].position_m = 7000: must lie inside the road (0, 6500)",
    );
}

#[test]
fn demand_scale_needs_a_network_and_demand_a_homogeneous_road() {
    assert_run_fails(
        "demand-scale-homogeneous",
        &["homogeneous", "--demand-scale", "1.1"],
        "invalid --demand-scale 1.1: the scenario has no [network] section",
    );
    assert_run_fails(
        "demand-on-sr99",
        &["sr99", "--demand", "2000"],
        "demand.vph_per_lane = 2000: must be left out with [network]",
    );
    assert_run_fails(
        "negative-demand-scale",
        &["sr99", "--demand-scale=-1"],
        "network.demand_scale = -1: must be a finite number >= 0",
    );
}

#[test]
fn run_rejects_bad_trajectory_flags() {
    assert_run_fails(
        "trajectories-zero",
        &["homogeneous", "--trajectories", "0"],
        "invalid --trajectories 0: the sampling period (s) must be a positive multiple of the \
         time step run.dt_s = 0.1 s",
    );
    assert_run_fails(
        "trajectories-off-step",
        &["homogeneous", "--trajectories", "0.15"],
        "invalid --trajectories 0.15: the sampling period (s) must be a positive multiple of the \
         time step run.dt_s = 0.1 s",
    );
    // The step is the scenario's, after the overrides.
    assert_run_fails(
        "trajectories-dt",
        &[
            "homogeneous",
            "--set",
            "run.dt_s=0.2",
            "--trajectories",
            "0.1",
        ],
        "invalid --trajectories 0.1: the sampling period (s) must be a positive multiple of the \
         time step run.dt_s = 0.2 s",
    );
    assert_run_fails(
        "trajectory-window-reversed",
        &[
            "homogeneous",
            "--trajectories",
            "1",
            "--trajectory-window",
            "5,1",
        ],
        "invalid --trajectory-window 5,1: expected T0,T1 with 0 <= T0 < T1 (seconds of simulated \
         time)",
    );
    assert_run_fails(
        "trajectory-x-reversed",
        &["sr99", "--trajectories", "1", "--trajectory-x", "300,200"],
        "invalid --trajectory-x 300,200: expected X0,X1 with X0 < X1",
    );
    assert_run_fails(
        "trajectory-x-off-road",
        &["sr99", "--trajectories", "1", "--trajectory-x=-3000,-1000"],
        "invalid --trajectory-x -3000,-1000: the range must overlap the road, which spans -500 to \
         17160 m in this coordinate",
    );
    // A window without --trajectories, or one that is not numbers: clap refuses it.
    for (extra, expected) in [
        (
            &["--trajectory-window", "1,2"][..],
            "--trajectories <PERIOD_S>",
        ),
        (
            &["--trajectories", "1", "--trajectory-window", "a,2"],
            "invalid value 'a' for '--trajectory-window <T0,T1>'",
        ),
    ] {
        let mut args = vec!["run", "homogeneous"];
        args.extend_from_slice(extra);
        let o = platoonsim(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(stderr(&o).contains(expected), "{args:?}: {}", stderr(&o));
    }
}

#[test]
fn run_rejects_an_unknown_scenario_file() {
    assert_run_fails(
        "unknown-file",
        &["no/such/scenario.toml"],
        "unknown scenario 'no/such/scenario.toml'",
    );
    assert_run_fails("unknown-name", &["homogenous"], "built-ins: homogeneous");
}

#[test]
fn run_reports_a_malformed_file_with_line_and_column() {
    let dir = scratch("malformed");
    let file = dir.join("bad.toml");
    std::fs::write(
        &file,
        "name = \"bad\"\n[road]\nlanes = 3\nlength_m = 6_500.0.0\n",
    )
    .unwrap();
    assert_run_fails("malformed-run", &[s(&file)], "line 4, column");
}

#[test]
fn clap_rejects_an_unknown_strategy() {
    let o = platoonsim(&["run", "homogeneous", "--strategy", "platoons"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("possible values: none, pd, flow-aware, dedicated"),
        "{}",
        stderr(&o)
    );
}

// ---------------------------------------------------------------- with the engine

// These run the simulation; un-ignore them once platoonsim_sim::run is implemented.

/// A 10-minute run (the flags in `extra` may not repeat these).
const SHORT: &[&str] = &["--duration", "600", "--quiet"];

fn short_run(test: &str, extra: &[&str]) -> PathBuf {
    let out = scratch(test).join("out");
    let mut args = vec!["run", "homogeneous"];
    args.extend_from_slice(SHORT);
    if !extra.contains(&"--warmup") {
        args.extend_from_slice(&["--warmup", "300"]);
    }
    args.extend_from_slice(extra);
    args.extend_from_slice(&["--out", s(&out)]);
    let o = platoonsim(&args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    assert!(
        stdout(&o).contains("vehicles") || stdout(&o).contains("Vehicles"),
        "{}",
        stdout(&o)
    );
    out
}

#[test]
fn run_writes_summary_detectors_and_scenario() {
    let out = short_run(
        "files",
        &["--seed", "3", "--penetration", "0.5", "--demand", "1500"],
    );
    let names: Vec<String> = {
        let mut n: Vec<String> = std::fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        n.sort();
        n
    };
    assert_eq!(
        names,
        [
            "detectors.csv",
            "road.json",
            "scenario.json",
            "scenario.toml",
            "summary.json"
        ]
    );

    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    for key in [
        "scenario",
        "penetration",
        "demand_vphpl",
        "seed",
        "vehicles_entered",
        "vehicles_exited",
        "vehicles_in_network",
        "vehicles_waiting",
        "lane_changes_per_vehicle",
        "avg_platoon_length",
        "platooning_probability",
        "discharge_flow_vphpl",
        "max_sustained_flow_vphpl",
        "collisions",
        "vehicle_updates",
        "wall_seconds",
    ] {
        assert!(summary.get(key).is_some(), "summary.json lacks {key}");
    }
    assert_eq!(summary["seed"], 3);
    assert_eq!(summary["demand_vphpl"], 1500.0);
    assert_eq!(summary["collisions"], 0);
    let n = |k: &str| summary[k].as_u64().unwrap();
    assert_eq!(
        n("vehicles_entered"),
        n("vehicles_exited") + n("vehicles_in_network")
    );

    let csv = std::fs::read_to_string(out.join("detectors.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("detector,kind,position_m,lane,interval_start_s,interval_s,count,cav_count,flow_vph,speed_kmh,occupancy")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    // 3 detectors x (3 lanes + "all") per five-minute interval.
    assert!(!rows.is_empty(), "{csv}");
    assert_eq!(rows.len() % (3 * 4), 0, "{csv}");
    assert!(rows.iter().all(|r| r.len() == 11));
    assert!(rows
        .iter()
        .any(|r| r[0] == "discharge" && r[1] == "mainline" && r[3] == "all"));

    let scenario: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("scenario.json")).unwrap()).unwrap();
    assert_eq!(scenario["seed"], 3);
    assert_eq!(scenario["duration_s"], 600.0);
    // The written scenario.toml reruns the same configuration.
    let again = platoonsim(&["show", s(&out.join("scenario.toml")), "--format", "json"]);
    let again: serde_json::Value = serde_json::from_slice(&again.stdout).unwrap();
    assert_eq!(again, scenario);
    assert!(!std::fs::read_dir(&out).unwrap().any(|e| e
        .unwrap()
        .file_name()
        .to_string_lossy()
        .ends_with(".tmp")));
}

#[test]
fn same_seed_is_bit_identical_and_another_seed_differs() {
    let a = short_run("seed-a", &["--seed", "11"]);
    let b = short_run("seed-b", &["--seed", "11"]);
    let c = short_run("seed-c", &["--seed", "12"]);
    let csv = |d: &Path| std::fs::read(d.join("detectors.csv")).unwrap();
    assert_eq!(csv(&a), csv(&b));
    assert_eq!(summary_without_wall_time(&a), summary_without_wall_time(&b));
    assert_ne!(csv(&a), csv(&c));
}

#[test]
fn strategies_run() {
    for strategy in ["pd", "flow-aware"] {
        let out = short_run(
            &format!("strategy-{strategy}"),
            &["--strategy", strategy, "--warmup", "120"],
        );
        let summary: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
        assert_eq!(summary["strategy"], strategy);
    }
}

#[test]
fn bench_reports_updates_per_second() {
    let o = platoonsim(&["bench", "--duration", "120", "--repeat", "2", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["penetration"], 0.5);
    assert_eq!(v["demand_vphpl"], 2500.0);
    let reps = v["repetitions"].as_array().unwrap();
    assert_eq!(reps.len(), 2);
    for r in reps {
        assert!(r["updates_per_second"].as_f64().unwrap() > 0.0);
        assert_eq!(r["steps"], 1200);
        assert!(r["vehicles_entered"].as_u64().unwrap() > 0);
    }
    let text = platoonsim(&["bench", "--duration", "60"]);
    assert!(text.status.success(), "{}", stderr(&text));
    assert!(
        stdout(&text).contains("vehicle updates per second"),
        "{}",
        stdout(&text)
    );
}
