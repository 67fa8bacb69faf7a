//! Scenario files: every class of bad input gets an error naming the field, the value and
//! what is allowed; nothing panics.

mod common;

use common::*;
use platoonsim_scenario::{from_toml, load, load_with, to_toml, Overrides, ScenarioError};

// ---------------------------------------------------------------- structure errors

#[test]
fn unknown_key_in_a_section_names_it_and_the_allowed_keys() {
    let (path, msg) = structure(parse(&SMALL.replace("lanes = 2", "lanes = 2\nfoo = 1")));
    assert_eq!(path, "road.foo");
    assert_eq!(
        msg,
        "unknown field 'foo' in [road]; allowed keys: lanes, length_m, control_start_m, control_end_m"
    );
}

#[test]
fn unknown_top_level_key() {
    let (path, msg) = structure(parse(&format!("colour = \"red\"\n{SMALL}")));
    assert_eq!(path, "colour");
    assert!(
        msg.starts_with(
            "unknown key 'colour' at the top level; allowed keys: name, description, model, run"
        ),
        "{msg}"
    );
}

#[test]
fn unknown_section() {
    let (path, msg) = structure(parse(&format!("{SMALL}\n[ramps]\nx = 1\n")));
    assert_eq!(path, "ramps");
    assert!(msg.contains("unknown key 'ramps'"), "{msg}");
}

#[test]
fn unknown_key_in_a_detector_and_in_a_model_section() {
    let (path, msg) = structure(parse(
        &SMALL.replace("position_m = 2600", "position_m = 2600\nlane = 1"),
    ));
    assert_eq!(path, "detectors[1].lane");
    assert!(
        msg.contains("unknown field 'lane' in [detectors[1]]; allowed keys: name, position_m"),
        "{msg}"
    );

    let (path, msg) = structure(parse(&format!("{SMALL}\n[human]\nbuffer = 0.2\n")));
    assert_eq!(path, "human.buffer");
    assert!(
        msg.contains("allowed keys:") && msg.contains("buffer_s"),
        "{msg}"
    );

    let (path, msg) = structure(parse(&format!(
        "{SMALL}\n[human.headway_s]\nmedian = 1.2\n"
    )));
    assert_eq!(path, "human.headway_s.median");
    assert_eq!(
        msg,
        "unknown field 'median' in [human.headway_s]; allowed keys: mean, sd, min, max"
    );

    let (path, _) = structure(parse(&format!("{SMALL}\n[cav]\nkp = 0.45\n")));
    assert_eq!(path, "cav.kp");
    let (path, _) = structure(parse(&format!("{SMALL}\n[lane_change]\npolite = 0.5\n")));
    assert_eq!(path, "lane_change.polite");
}

#[test]
fn malformed_number_gives_line_and_column() {
    let e = parse(&SMALL.replace("length_m = 3000", "length_m = 3_000.0.0")).unwrap_err();
    assert!(matches!(e, ScenarioError::Syntax { .. }), "{e}");
    let msg = e.to_string();
    assert!(msg.contains("test.toml") && msg.contains("line 5"), "{msg}");
    assert!(msg.contains("column"), "{msg}");
}

#[test]
fn wrong_types_name_the_key_and_the_value() {
    let (path, msg) = structure(parse(&SMALL.replace("lanes = 2", "lanes = \"two\"")));
    assert_eq!(path, "road.lanes");
    assert!(msg.contains("\"two\""), "{msg}");
    let (path, msg) = structure(parse(&SMALL.replace("lanes = 2", "lanes = 2.5")));
    assert_eq!(path, "road.lanes");
    assert!(msg.contains("2.5"), "{msg}");
    let (path, msg) = structure(parse(&SMALL.replace("lanes = 2", "lanes = -2")));
    assert_eq!(path, "road.lanes");
    assert!(msg.contains("-2"), "{msg}");
    let (path, _) = structure(parse(&format!("{SMALL}\n[run]\nseed = -1\n")));
    assert_eq!(path, "run.seed");
    let (path, msg) = structure(parse("name = \"x\"\ndemand = 5\n"));
    assert_eq!(path, "demand");
    assert!(msg.contains("integer"), "{msg}");
    let (path, msg) = structure(parse("name = \"x\"\ndetectors = 3\n"));
    assert_eq!(path, "detectors");
    assert!(msg.contains("array of tables"), "{msg}");
}

// ---------------------------------------------------------------- validation errors

#[test]
fn penetration_outside_unit_interval() {
    let p = problems(with_set(HOMOGENEOUS, &["run.penetration=1.5"]));
    assert_eq!(p, vec!["run.penetration = 1.5: must be in [0, 1]"]);
    let p = problems(load_with(
        "homogeneous",
        &Overrides {
            penetration: Some(-0.1),
            ..Overrides::default()
        },
    ));
    assert_eq!(p, vec!["run.penetration = -0.1: must be in [0, 1]"]);
}

#[test]
fn clock_start_must_be_a_time_of_day() {
    for bad in ["5:00", "24:00", "05:60", "05:00:60", "05:00pm", "0500", ""] {
        let p = problems(with_set(
            HOMOGENEOUS,
            &[&format!("run.clock_start=\"{bad}\"")],
        ));
        assert_eq!(
            p,
            vec![format!(
                "run.clock_start = \"{bad}\": must be a clock time \"HH:MM\" or \"HH:MM:SS\" \
                 (00:00 to 23:59:59)"
            )]
        );
    }
    // A number is not a clock time: a structure error that names the key.
    let err = with_set(HOMOGENEOUS, &["run.clock_start=500"]).unwrap_err();
    assert!(err.to_string().contains("clock_start"), "{err}");
    let c = with_set(HOMOGENEOUS, &["run.clock_start=\"07:30:15\""]).unwrap();
    assert_eq!(c.clock_start_s, Some(7 * 3600 + 30 * 60 + 15));
}

#[test]
fn detector_off_the_road() {
    let p = problems(with_set(HOMOGENEOUS, &["detectors[2].position_m=7000"]));
    assert_eq!(
        p,
        vec!["detectors[2].position_m = 7000: must lie inside the road (0, 6500)"]
    );
    let p = problems(with_set(HOMOGENEOUS, &["detectors[0].position_m=0"]));
    assert!(
        has(
            &p,
            "detectors[0].position_m = 0: must lie inside the road (0, 6500)"
        ),
        "{p:?}"
    );
}

#[test]
fn negative_lengths() {
    let p = problems(with_set(HOMOGENEOUS, &["road.length_m=-6500"]));
    assert!(
        has(&p, "road.length_m = -6500: must be in (0, 200000] m"),
        "{p:?}"
    );
    let p = problems(with_set(HOMOGENEOUS, &["strategy.radius_m=-1"]));
    assert_eq!(p, vec!["strategy.radius_m = -1: must be in (0, 200000] m"]);
    let p = problems(with_set(HOMOGENEOUS, &["run.duration_s=-5"]));
    assert!(
        has(
            &p,
            "run.duration_s = -5: must be in (0, 604800] s (at most 7 simulated days)"
        ),
        "{p:?}"
    );
}

#[test]
fn dt_outside_its_range() {
    // Issue 18 item 5: only [0.05, 0.2] s, with the reason in the message.
    for bad in [
        "0", "-0.1", "0.049", "0.21", "0.5", "1", "1.0", "1.5", "nan", "1e-300",
    ] {
        let p = problems(with_set(HOMOGENEOUS, &[&format!("run.dt_s={bad}")]));
        let shown = if bad == "1.0" { "1" } else { bad };
        assert_eq!(
            p,
            vec![format!(
                "run.dt_s = {shown}: must be in [0.05, 0.2] s (the CACC law is tuned per 0.1 s \
                 step; at 0.5 s the built-in scenarios collide, docs/safety.md)"
            )],
            "{bad}"
        );
    }
    for good in [0.05, 0.1, 0.2] {
        let c = with_set(HOMOGENEOUS, &[&format!("run.dt_s={good}")]).unwrap();
        assert_eq!(c.dt_s, good);
        assert_eq!(c.check(), Ok(()));
    }
}

#[test]
fn warmup_not_before_the_end() {
    let p = problems(with_set(HOMOGENEOUS, &["run.warmup_s=3600"]));
    assert_eq!(
        p,
        vec!["run.warmup_s = 3600: must be >= 0 and < run.duration_s = 3600"]
    );
    // A default that no longer fits is shown as a default.
    let p = problems(parse(&format!("{SMALL}\n[run]\nduration_s = 600\n")));
    assert!(
        has(
            &p,
            "run.warmup_s = 1200 (default): must be >= 0 and < run.duration_s = 600"
        ),
        "{p:?}"
    );
}

#[test]
fn control_section_and_zone_on_the_road() {
    let p = problems(with_set(HOMOGENEOUS, &["road.control_end_m=7000"]));
    assert!(
        has(&p, "road.control_end_m = 7000: must be > road.control_start_m = 5000 and <= road.length_m = 6500"),
        "{p:?}"
    );
    let p = problems(with_set(
        HOMOGENEOUS,
        &["road.control_start_m=6600", "road.control_end_m=6700"],
    ));
    assert!(
        p[0].starts_with("road.control_start_m = 6600: must lie in [0, road.length_m = 6500)"),
        "{p:?}"
    );
    let p = problems(with_set(HOMOGENEOUS, &["strategy.zone_end_m=8000"]));
    assert_eq!(
        p,
        vec!["strategy.zone_end_m = 8000: must be > strategy.zone_start_m = 5000 (default) and <= road.length_m = 6500"]
    );
    let p = problems(with_set(HOMOGENEOUS, &["strategy.zone_start_m=-10"]));
    assert!(
        p[0].starts_with("strategy.zone_start_m = -10: must lie in [0, road.length_m = 6500)"),
        "{p:?}"
    );
    let p = problems(with_set(
        HOMOGENEOUS,
        &["strategy.start_s=3000", "strategy.end_s=2000"],
    ));
    assert_eq!(
        p,
        vec!["strategy.end_s = 2000: must be > strategy.start_s = 3000"]
    );
}

#[test]
fn unknown_measurement_detector() {
    let p = problems(with_set(HOMOGENEOUS, &["measurement.detector=exit"]));
    assert_eq!(
        p,
        vec!["measurement.detector = \"exit\": names no detector; defined: \"upstream\", \"control_mid\", \"discharge\""]
    );
    let p = problems(parse(&SMALL.replace("detector = \"b\"", "")));
    assert!(
        p[0].starts_with("measurement.detector = (missing): required"),
        "{p:?}"
    );
}

#[test]
fn bad_distributions() {
    let p = problems(with_set(
        HOMOGENEOUS,
        &["human.headway_s={ mean = 1.25, sd = 0.3, min = 1.5, max = 1.0 }"],
    ));
    assert_eq!(
        p,
        vec!["human.headway_s = { mean = 1.25, sd = 0.3, min = 1.5, max = 1 }: min = 1.5 must be <= max = 1"]
    );
    let p = problems(with_set(HOMOGENEOUS, &["human.desired_speed_kmh.mean=90"]));
    assert!(
        p[0].contains("mean = 90 must lie in [min, max] = [100, 120]"),
        "{p:?}"
    );
    let p = problems(with_set(
        HOMOGENEOUS,
        &["lane_change.cooperativeness.sd=-1"],
    ));
    assert!(
        p[0].starts_with("lane_change.cooperativeness = ")
            && p[0].ends_with("sd = -1 must be >= 0"),
        "{p:?}"
    );
    let p = problems(with_set(
        HOMOGENEOUS,
        &["human.max_decel={ mean = 4.0, min = 4.0, max = 4.0 }"],
    ));
    assert!(p[0].contains("decelerations are negative"), "{p:?}");
}

#[test]
fn time_gap_shares_must_sum_to_one() {
    let p = problems(with_set(
        HOMOGENEOUS,
        &["cav.time_gap_shares=[[0.6, 0.5], [1.1, 0.2]]"],
    ));
    assert_eq!(
        p,
        vec!["cav.time_gap_shares = [[0.6, 0.5], [1.1, 0.2]]: the shares must sum to 1 (they sum to 0.7)"]
    );
    let p = problems(with_set(HOMOGENEOUS, &["cav.time_gap_shares=[]"]));
    assert!(p[0].starts_with("cav.time_gap_shares = []"), "{p:?}");
    let p = problems(with_set(
        HOMOGENEOUS,
        &["cav.time_gap_shares=[[0.6, 1.0], [-1, 0]]"],
    ));
    assert!(
        p[0].starts_with("cav.time_gap_shares[1] = [-1, 0]"),
        "{p:?}"
    );
}

#[test]
fn non_finite_model_values() {
    let p = problems(with_set(
        HOMOGENEOUS,
        &["human.buffer_s=nan", "cav.acc_reg_gains=[inf, 0.07]"],
    ));
    assert!(
        has(&p, "human.buffer_s = nan: must be a finite number"),
        "{p:?}"
    );
    assert!(
        has(&p, "cav.acc_reg_gains[0] = inf: must be a finite number"),
        "{p:?}"
    );
}

#[test]
fn other_ranges() {
    let cases: &[(&str, &str)] = &[
        (
            "road.lanes=0",
            "road.lanes = 0: must be an integer from 1 to 8",
        ),
        (
            "road.lanes=9",
            "road.lanes = 9: must be an integer from 1 to 8",
        ),
        (
            "demand.vph_per_lane=-1",
            "demand.vph_per_lane = -1: must be in [0, 10000] veh/h/lane",
        ),
        (
            "strategy.kind=platoons",
            "strategy.kind = \"platoons\": must be one of \"none\", \"pd\", \"flow-aware\", \"dedicated\"",
        ),
        (
            "strategy.lane=0",
            "strategy.lane = 0: must be \"leftmost\", \"rightmost\" or a lane number 1 to 3 (the road's lanes; 1 = the rightmost lane)",
        ),
        (
            "strategy.lane=4",
            "strategy.lane = 4: must be \"leftmost\", \"rightmost\" or a lane number 1 to 3 (the road's lanes; 1 = the rightmost lane)",
        ),
        (
            "strategy.lane=\"middle\"",
            "strategy.lane = \"middle\": must be \"leftmost\", \"rightmost\" or a lane number 1 to 3 (the road's lanes; 1 = the rightmost lane)",
        ),
        (
            "measurement.aggregation_s=0.01",
            "measurement.aggregation_s = 0.01: must be a whole number of steps of run.dt_s = 0.1",
        ),
        (
            "measurement.aggregation_s=300.05",
            "measurement.aggregation_s = 300.05: must be a whole number of steps of run.dt_s = 0.1",
        ),
        (
            "detectors[1].name=upstream",
            "detectors[1].name = \"upstream\": duplicates detectors[0].name; names must be unique",
        ),
        (
            "cav.max_platoon=0",
            "cav.max_platoon = 0: must be 1 to 100 vehicles",
        ),
        (
            "human.smoothing=0.5",
            "human.smoothing = 0.5: must be >= 1 (1 = no smoothing)",
        ),
        (
            "lane_change.relax_jam=0",
            "lane_change.relax_jam = 0: must be in (0, 1]",
        ),
        ("name=''", "name = \"\": must be a non-empty string"),
        (
            "lane_change.min_speed_gain_mps=-1",
            "lane_change.min_speed_gain_mps = -1: must be >= 0",
        ),
        (
            "cav.time_gap_ramp_per_s=-0.5",
            "cav.time_gap_ramp_per_s = -0.5: must be >= 0",
        ),
        (
            "cav.cooperative_gap_decel_mps2=-2",
            "cav.cooperative_gap_decel_mps2 = -2: must be in (0, 4] m/s² (positive, at most -cav.max_decel)",
        ),
        (
            "cav.cooperative_gap_decel_mps2=5",
            "cav.cooperative_gap_decel_mps2 = 5: must be in (0, 4] m/s² (positive, at most -cav.max_decel)",
        ),
        (
            "cav.cooperative_timeout_s=0",
            "cav.cooperative_timeout_s = 0: must be in (0, 600] s",
        ),
        // spec 9.3: the CACC realism keys.
        (
            "cav.actuator_lag_s=-0.1",
            "cav.actuator_lag_s = -0.1: must be in [0, 10] s",
        ),
        (
            "cav.comm_delay_s=11",
            "cav.comm_delay_s = 11: must be in [0, 10] s",
        ),
        (
            "cav.beacon_timeout_s=-1",
            "cav.beacon_timeout_s = -1: must be in [0, 10] s",
        ),
        (
            "cav.packet_loss=1.5",
            "cav.packet_loss = 1.5: must be in [0, 1] (a probability; 1 = no V2V)",
        ),
        (
            "cav.packet_loss=-0.1",
            "cav.packet_loss = -0.1: must be in [0, 1] (a probability; 1 = no V2V)",
        ),
        (
            "cav.max_automated_decel_mps2=-5",
            "cav.max_automated_decel_mps2 = -5: must be > 0 m/s² (a braking magnitude, positive)",
        ),
        (
            "cav.field_low_level_lag_s=-0.3",
            "cav.field_low_level_lag_s = -0.3: must be in [0, 10] s",
        ),
        (
            "cav.cacc_field_gains=[0, 0.7]",
            "cav.cacc_field_gains = [0, 0.7]: must be [k_p > 0 (1/s²), k_d >= 0 (1/s)]",
        ),
        (
            "cav.cacc_feedforward=1.5",
            "cav.cacc_feedforward = 1.5: must be in [0, 1] (0 = no feed-forward, 1 = the predecessor's whole acceleration)",
        ),
        (
            "cav.envelope_speeds_mps=[20, 5]",
            "cav.envelope_speeds_mps = [20, 5]: must be [low, high] with 0 <= low < high (m/s)",
        ),
        (
            "cav.envelope_decel_mps2=[12.5, 3.5]",
            "cav.envelope_decel_mps2 = [12.5, 3.5]: must be [at low speed, at high speed], both > 0 m/s², at most 12 (about 1.2 g)",
        ),
        (
            "cav.envelope_jerk_mps3=[5, 0]",
            "cav.envelope_jerk_mps3 = [5, 0]: must be [at low speed, at high speed], both > 0 m/s³",
        ),
        (
            "lane_change.safe_follower_decel_mps2=-3",
            "lane_change.safe_follower_decel_mps2 = -3: must be > 0 m/s² (a deceleration, written positive)",
        ),
        (
            "lane_change.mandatory_safe_decel_mps2=2.5",
            "lane_change.mandatory_safe_decel_mps2 = 2.5: must be >= lane_change.safe_follower_decel_mps2 = 3 m/s² (positive)",
        ),
    ];
    for (set, expected) in cases {
        let p = problems(with_set(HOMOGENEOUS, &[set]));
        assert_eq!(p, vec![expected.to_string()], "--set {set}");
    }
    // Whole numbers of steps, and longer than the run, are fine.
    for ok in [
        "measurement.aggregation_s=60",
        "measurement.aggregation_s=0.3",
        "measurement.aggregation_s=7200",
        "cav.actuator_lag_s=0.5",
        "cav.comm_delay_s=0.2",
        "cav.packet_loss=1",
        "cav.beacon_timeout_s=0",
    ] {
        with_set(HOMOGENEOUS, &[ok]).unwrap_or_else(|e| panic!("{ok}: {e}"));
    }
}

#[test]
fn missing_sections_are_all_reported_at_once() {
    let p = problems(parse("name = \"empty\"\n"));
    for field in [
        "road.lanes",
        "road.length_m",
        "road.control_start_m",
        "road.control_end_m",
        "demand.vph_per_lane",
    ] {
        assert!(
            p.iter()
                .any(|l| l.starts_with(&format!("{field} = (missing): required"))),
            "{field}: {p:?}"
        );
    }
    assert!(
        has(
            &p,
            "detectors = []: at least one [[detectors]] entry (name, position_m) is required"
        ),
        "{p:?}"
    );
}

#[test]
fn error_message_lists_problems_under_the_origin() {
    let e = with_set(HOMOGENEOUS, &["run.penetration=2", "road.lanes=0"]).unwrap_err();
    let msg = e.to_string();
    assert_eq!(
        msg,
        "test.toml: invalid scenario:\n  run.penetration = 2: must be in [0, 1]\n  road.lanes = 0: must be an integer from 1 to 8"
    );
}

// ---------------------------------------------------------------- override errors

#[test]
fn bad_set_arguments() {
    let cases = [
        ("run.seed", "expected KEY=VALUE"),
        ("=3", "the key is empty"),
        ("run..seed=3", "is not a key"),
        ("run.se ed=3", "is not a key"),
        ("detectors[9].position_m=1", "index 9 is out of range"),
        ("detectors[x].position_m=1", "is not a non-negative integer"),
        ("run.seed.low=1", "'run.seed' is a integer, not a table"),
        ("road[0]=1", "'road' is a table, not an array"),
    ];
    for (arg, expected) in cases {
        match with_set(HOMOGENEOUS, &[arg]) {
            Err(e @ ScenarioError::Override { .. }) => {
                let msg = e.to_string();
                assert!(msg.contains(expected), "--set {arg}: {msg}");
                assert!(msg.contains(arg), "--set {arg}: {msg}");
            }
            other => panic!("--set {arg}: {other:?}"),
        }
    }
    // Setting an unknown key is an ordinary unknown-key error.
    let (path, _) = structure(with_set(HOMOGENEOUS, &["road.foo=1"]));
    assert_eq!(path, "road.foo");
    // A seed TOML cannot hold.
    let e = load_with(
        "homogeneous",
        &Overrides {
            seed: Some(u64::MAX),
            ..Overrides::default()
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("--seed"), "{e}");
}

// ---------------------------------------------------------------- never panic

#[test]
fn no_value_in_any_key_makes_loading_panic() {
    let resolved = to_toml(&load("homogeneous").unwrap());
    let doc: toml::Table = resolved.parse().unwrap();
    let mut keys = Vec::new();
    for (k, v) in &doc {
        match v {
            toml::Value::Table(t) => {
                for (kk, vv) in t {
                    keys.push(format!("{k}.{kk}"));
                    if let toml::Value::Table(inner) = vv {
                        keys.extend(inner.keys().map(|x| format!("{k}.{kk}.{x}")));
                    }
                }
            }
            toml::Value::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    if let toml::Value::Table(t) = item {
                        keys.extend(t.keys().map(|x| format!("{k}[{i}].{x}")));
                    }
                }
            }
            _ => keys.push(k.clone()),
        }
    }
    assert!(keys.len() > 60, "{}", keys.len());
    let values = [
        "-1",
        "0",
        "1e300",
        "-1e300",
        "nan",
        "inf",
        "-inf",
        "\"text\"",
        "[]",
        "[[1, 2]]",
        "{}",
        "true",
        "1979-05-27",
        "9223372036854775807",
    ];
    for key in &keys {
        for value in values {
            // Ok or Err, never a panic.
            let _ = from_toml(
                &resolved,
                "fuzz",
                "fuzz",
                &Overrides {
                    set: vec![format!("{key}={value}")],
                    ..Overrides::default()
                },
            );
        }
    }
}

#[test]
fn readme_example_scenario_is_valid() {
    let readme = include_str!("../../../docs/scenario-files.md");
    let start = readme
        .find("```toml\n")
        .expect("docs/scenario-files.md has a TOML example")
        + "```toml\n".len();
    let len = readme[start..].find("```").unwrap();
    let c = parse(&readme[start..start + len]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(c.name, "two_lane_test");
    assert_eq!(c.strategy.kind, platoonsim_sim::StrategyKind::PD);
}

// ---------------------------------------------------------------- braking limits and [safety]

const CAV_B_E: &str = "must be in (4, 12] m/s²: positive (a deceleration, as SUMO's \
                       emergencyDecel), harder than the normal limit -cav.max_decel = 4, at \
                       most about 1.2 g";
const HUMAN_B_E: &str = "must be in (4, 12] m/s²: positive (a deceleration, as SUMO's \
                         emergencyDecel), harder than the hardest normal limit a driver \
                         draws, -human.max_decel.min = 4, at most about 1.2 g";

#[test]
fn a_negative_emergency_deceleration_is_refused() {
    // Accepted before issue 29: every CAV then accelerated at 9 m/s².
    let p = problems(with_set(HOMOGENEOUS, &["cav.emergency_decel_mps2=-9"]));
    assert_eq!(p, vec![format!("cav.emergency_decel_mps2 = -9: {CAV_B_E}")]);
    let p = problems(with_set(HOMOGENEOUS, &["human.emergency_decel_mps2=-9"]));
    assert_eq!(
        p,
        vec![format!("human.emergency_decel_mps2 = -9: {HUMAN_B_E}")]
    );
    let p = problems(with_set(HOMOGENEOUS, &["cav.emergency_decel_mps2=0"]));
    assert_eq!(p, vec![format!("cav.emergency_decel_mps2 = 0: {CAV_B_E}")]);
    // Above the physical bound, and tiny values (issue 35 item 2).
    for v in ["12.5", "1e-9"] {
        let p = problems(with_set(
            HOMOGENEOUS,
            &[&format!("human.emergency_decel_mps2={v}")],
        ));
        assert_eq!(p.len(), 1, "{v}: {p:?}");
        assert!(p[0].starts_with("human.emergency_decel_mps2 = "), "{p:?}");
    }
}

#[test]
fn an_emergency_limit_equal_to_the_normal_one_is_refused() {
    // Issue 35 item 2: b_e = |max_decel| hides every emergency braking (none exceeds b).
    let p = problems(with_set(HOMOGENEOUS, &["cav.emergency_decel_mps2=4"]));
    assert_eq!(p, vec![format!("cav.emergency_decel_mps2 = 4: {CAV_B_E}")]);
    let p = problems(with_set(HOMOGENEOUS, &["human.emergency_decel_mps2=4"]));
    assert_eq!(
        p,
        vec![format!("human.emergency_decel_mps2 = 4: {HUMAN_B_E}")]
    );
    assert!(with_set(HOMOGENEOUS, &["human.emergency_decel_mps2=4.01"]).is_ok());
    assert!(with_set(HOMOGENEOUS, &["cav.emergency_decel_mps2=12"]).is_ok());
}

#[test]
fn an_emergency_limit_weaker_than_the_normal_one_is_refused() {
    let p = problems(with_set(HOMOGENEOUS, &["cav.emergency_decel_mps2=3.5"]));
    assert_eq!(
        p,
        vec![format!("cav.emergency_decel_mps2 = 3.5: {CAV_B_E}")]
    );
    let p = problems(with_set(HOMOGENEOUS, &["human.emergency_decel_mps2=3.5"]));
    assert_eq!(
        p,
        vec![format!("human.emergency_decel_mps2 = 3.5: {HUMAN_B_E}")]
    );
    // A normal limit raised to 7 m/s² needs b_e > 7.
    let p = problems(with_set(
        HOMOGENEOUS,
        &["cav.max_decel=-7", "cav.emergency_decel_mps2=6"],
    ));
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(
        p[0].starts_with("cav.emergency_decel_mps2 = 6: must be in (7, 12] m/s²")
            && p[0].contains("-cav.max_decel = 7"),
        "{p:?}"
    );
    // A human driver may draw a normal limit down to human.max_decel.min.
    let p = problems(with_set(
        HOMOGENEOUS,
        &[
            "human.max_decel={mean = -4.0, sd = 1.0, min = -7.0, max = -3.0}",
            "human.emergency_decel_mps2=6",
        ],
    ));
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(
        p[0].starts_with("human.emergency_decel_mps2 = 6: must be in (7, 12] m/s²"),
        "{p:?}"
    );
    // Just above the normal limit, and the findings' 6 m/s² with b = 4, are fine.
    for ok in [
        &[
            "cav.emergency_decel_mps2=4.5",
            "human.emergency_decel_mps2=4.5",
        ][..],
        &["cav.emergency_decel_mps2=6", "human.emergency_decel_mps2=6"],
        &["cav.emergency_decel_mps2=12"],
    ] {
        with_set(HOMOGENEOUS, ok).unwrap_or_else(|e| panic!("{ok:?}: {e}"));
    }
}

#[test]
fn an_emergency_limit_beyond_tyre_friction_is_refused() {
    let p = problems(with_set(HOMOGENEOUS, &["cav.emergency_decel_mps2=20"]));
    assert_eq!(p, vec![format!("cav.emergency_decel_mps2 = 20: {CAV_B_E}")]);
    let p = problems(with_set(HOMOGENEOUS, &["human.emergency_decel_mps2=12.5"]));
    assert_eq!(
        p,
        vec![format!("human.emergency_decel_mps2 = 12.5: {HUMAN_B_E}")]
    );
}

#[test]
fn the_ttc_threshold_is_positive_and_bounded() {
    for bad in ["0", "-1.5", "10.5"] {
        let p = problems(with_set(
            HOMOGENEOUS,
            &[&format!("safety.ttc_threshold_s={bad}")],
        ));
        assert_eq!(
            p,
            vec![format!(
                "safety.ttc_threshold_s = {bad}: must be in (0, 10] s (FHWA SSAM uses 1.5 s)"
            )],
        );
    }
    let c = with_set(HOMOGENEOUS, &["safety.ttc_threshold_s=3"]).unwrap();
    assert_eq!(c.safety.ttc_threshold_s, 3.0);
    assert_eq!(parse(HOMOGENEOUS).unwrap().safety.ttc_threshold_s, 1.5);
}
