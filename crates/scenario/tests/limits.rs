//! Issue 18 items 5 and 6: the time-step range and the upper limits that keep any input from
//! hanging the program or exhausting memory. Every refusal names the field, the value and what
//! is allowed.

mod common;
use common::*;
use platoonsim_scenario::{limits, load, ScenarioError};
use platoonsim_sim::{Recording, TrajectorySpec};

const SR99: &str = include_str!("../scenarios/sr99.toml");

/// The single problem of a refused scenario.
fn only(r: Result<platoonsim_sim::Config, ScenarioError>) -> String {
    let p = problems(r);
    assert_eq!(p.len(), 1, "{p:?}");
    p[0].clone()
}

/// The single problem of `text` with `sets` applied, which must start with `start`.
#[track_caller]
fn only_starting(text: &str, sets: &[&str], start: &str) -> String {
    let p = only(with_set(text, sets));
    assert!(p.starts_with(start), "{p}");
    p
}

#[test]
fn dt_range_at_both_ends() {
    for good in ["0.05", "0.1", "0.075", "0.2"] {
        assert!(with_set(HOMOGENEOUS, &[&format!("run.dt_s={good}")]).is_ok());
    }
    for bad in ["0.049", "0.21", "0.25", "0.5", "1.0", "1e-300"] {
        let p = only(with_set(HOMOGENEOUS, &[&format!("run.dt_s={bad}")]));
        assert!(p.starts_with("run.dt_s = "), "{p}");
        assert!(p.contains("must be in [0.05, 0.2] s (the CACC law"), "{p}");
    }
    // The named constants are the range.
    assert_eq!((limits::DT_MIN_S, limits::DT_MAX_S), (0.05, 0.2));
}

#[test]
fn dt_must_divide_the_detector_interval() {
    // 0.07 s is in range, but 300 s is not a whole number of its steps.
    let p = only(with_set(HOMOGENEOUS, &["run.dt_s=0.07"]));
    assert_eq!(
        p,
        "measurement.aggregation_s = 300: must be a whole number of steps of run.dt_s = 0.07"
    );
    assert!(with_set(HOMOGENEOUS, &["run.dt_s=0.08"]).is_ok());
}

#[test]
fn engine_check_repeats_the_essential_limits() {
    let good = load("homogeneous").unwrap();
    type Edit = fn(&mut platoonsim_sim::Config);
    let cases: [(&str, Edit); 4] = [
        ("run.dt_s = 1: must be in [0.05, 0.2] s", |c| c.dt_s = 1.0),
        (
            "run.duration_s = 1000000000000: must be in [0, 604800]",
            |c| c.duration_s = 1e12,
        ),
        ("demand.vph_per_lane = 20000: must be in [0, 10000]", |c| {
            c.demand.vph_per_lane = 20_000.0
        }),
        ("road.length_m = 1000000: must be in [0, 200000]", |c| {
            c.road.length_m = 1e6
        }),
    ];
    for (start, f) in cases {
        let mut c = good.clone();
        f(&mut c);
        let e = c.check().unwrap_err().to_string();
        assert!(e.starts_with(start), "{e}");
        assert!(platoonsim_sim::run(&c, None).is_err());
    }
    // A network's ramp demand, after the demand scale.
    let mut c = load("sr99").unwrap();
    c.road.network.as_mut().unwrap().on_ramps[3].demand_vph[2] = 4294967296.0;
    let e = c.check().unwrap_err().to_string();
    assert!(
        e.starts_with("network.on_ramps[3].demand_vph[2] = 4294967296"),
        "{e}"
    );
}

#[test]
fn known_reproductions_are_clear_errors() {
    let p = only_starting(
        SR99,
        &["network.on_ramps[3].demand_vph=[4294967296, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]"],
        "network.on_ramps[3].demand_vph[0] = 4294967296: must be in [0, ",
    );
    assert!(p.contains("an on-ramp is one lane: 10000 veh/h"), "{p}");
    let p = only(with_set(HOMOGENEOUS, &["run.duration_s=1e12"]));
    assert_eq!(
        p,
        "run.duration_s = 1000000000000: must be in (0, 604800] s (at most 7 simulated days)"
    );
    let p = only(with_set(HOMOGENEOUS, &["demand.vph_per_lane=4294967296"]));
    assert_eq!(
        p,
        "demand.vph_per_lane = 4294967296: must be in [0, 10000] veh/h/lane"
    );
}

#[test]
fn network_demand_cap_follows_the_scale_and_the_entrance_lanes() {
    // The small corridor has 2 lanes at the entrance: 20,000 veh/h at scale 1, 10,000 at 2.
    let corridor = include_str!("fixtures/small_corridor.toml");
    assert!(with_set(corridor, &["network.mainline_vph=[20000, 0]"]).is_ok());
    only_starting(
        corridor,
        &["network.mainline_vph=[20000, 0]", "network.demand_scale=2"],
        "network.mainline_vph[0] = 20000: must be in [0, 10000] veh/h (10000 veh/h per lane open at the entrance × 2 lanes, divided by network.base_demand_multiplier × network.demand_scale = 2)",
    );
}

#[test]
fn lengths_counts_and_arrays_are_bounded() {
    let p = only(with_set(HOMOGENEOUS, &["road.length_m=1e7"]));
    assert_eq!(p, "road.length_m = 10000000: must be in (0, 200000] m");
    let shares = format!(
        "cav.time_gap_shares=[{}]",
        vec!["[1.0, 0.005]"; 200].join(",")
    );
    let p = only(with_set(HOMOGENEOUS, &[&shares]));
    assert_eq!(
        p,
        "cav.time_gap_shares = (200 pairs): at most 100 [time_gap_s, share] pairs"
    );
    only_starting(
        HOMOGENEOUS,
        &["cav.max_platoon=4000000000"],
        "cav.max_platoon = 4000000000: must be in [-1000000, 1000000]",
    );
    let p = problems(with_set(SR99, &["network.end_m=500000"]));
    assert!(
        p[0].starts_with("network.end_m = 500000: must be at most network.start_m + 200000"),
        "{p:?}"
    );
    let p = only(with_set(SR99, &["network.interval_s=0.001"]));
    assert_eq!(p, "network.interval_s = 0.001: must be in [1, 604800] s");
    let p = only(with_set(SR99, &["network.on_ramps[0].ramp_length_m=1e9"]));
    assert_eq!(
        p,
        "network.on_ramps[0].ramp_length_m = 1000000000: must be in [0, 10000] m"
    );
    only_starting(
        HOMOGENEOUS,
        &["measurement.aggregation_s=0.1", "run.duration_s=604800"],
        "measurement.aggregation_s = 0.1: gives 72576000 detector records",
    );
    let detectors: Vec<String> = (0..1001)
        .map(|i| format!("[[detectors]]\nname = \"d{i}\"\nposition_m = 100\n"))
        .collect();
    let text = format!("{SMALL}\n{}", detectors.join(""));
    let p = problems(parse(&text));
    assert!(
        has(
            &p,
            "detectors = (1003 entries): at most 1000 [[detectors]] entries"
        ),
        "{p:?}"
    );
}

#[test]
fn files_and_set_values_over_a_mebibyte_are_refused_before_parsing() {
    // sr99.toml, the largest built-in, fits comfortably.
    assert!(SR99.len() * 50 < limits::MAX_FILE_BYTES);
    // A 25-million-element array would take gigabytes; refused by its size alone.
    let big = format!("{SMALL}\n# {}\n", "x".repeat(limits::MAX_FILE_BYTES));
    let e = parse(&big).unwrap_err();
    assert!(matches!(e, ScenarioError::TooLarge { .. }), "{e}");
    assert!(
        e.to_string().contains("must be at most 1048576 bytes"),
        "{e}"
    );
    let dir = std::env::temp_dir().join(format!("platoonsim-limits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("big.toml");
    std::fs::write(&path, &big).unwrap();
    let e = load(path.to_str().unwrap()).unwrap_err();
    assert!(matches!(e, ScenarioError::TooLarge { .. }), "{e}");
    std::fs::remove_dir_all(&dir).ok();
    let set = format!("cav.time_gap_shares=[{}]", vec!["[1,0]"; 300_000].join(","));
    let e = with_set(HOMOGENEOUS, &[&set]).unwrap_err();
    assert!(
        e.to_string()
            .contains("a --set argument must be at most 1048576 bytes"),
        "{e}"
    );
}

#[test]
fn trajectory_memory_is_estimated_and_refused_above_4_gib() {
    let c = load("sr99").unwrap();
    let rec = |period_s, window_s, x_m| Recording {
        trips: false,
        trajectories: Some(TrajectorySpec {
            period_s,
            window_s,
            x_m,
        }),
    };
    // The whole 4-hour corridor every 0.1 s: far too much.
    let e = rec(0.1, None, None).check(&c).unwrap_err().to_string();
    assert!(
        e.starts_with("--trajectories 0.1 s: the recording could hold up to"),
        "{e}"
    );
    assert!(
        e.contains("--trajectory-window T0,T1, --trajectory-x X0,X1 or a longer period"),
        "{e}"
    );
    // The example of docs/commands.md fits.
    rec(1.0, Some((3600.0, 4500.0)), Some((0.0, 6000.0)))
        .check(&c)
        .unwrap();
}

#[test]
fn the_vehicles_a_run_brings_are_bounded() {
    // Every rate and the duration in range, but 8 lanes at 10,000 veh/h for 7 days bring
    // 13.4 million vehicles, most of them waiting in the entry queue.
    let p = only(with_set(
        HOMOGENEOUS,
        &[
            "road.lanes=8",
            "demand.vph_per_lane=10000",
            "run.duration_s=604800",
        ],
    ));
    assert_eq!(
        p,
        "run.duration_s = 604800: with this demand the run brings about 13440000 vehicles; at \
         most 10000000 (a vehicle waiting at an entrance is held in memory): shorten the run or \
         lower the demand"
    );
    assert!(with_set(HOMOGENEOUS, &["run.duration_s=604800"]).is_ok());
    // A network: the series integrated over the run, the last value holding past its end.
    assert!(with_set(SR99, &["run.duration_s=86400"]).is_ok());
}
