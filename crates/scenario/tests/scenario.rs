//! Scenario files: the built-in scenario's values, every error class, overrides, round trips.

mod common;

use common::*;
use platoonsim_model::safegap::GapRule;
use platoonsim_scenario::{
    builtin, from_toml, load, load_with, to_toml, Overrides, ScenarioError, StrategyKind, BUILTINS,
};
use platoonsim_sim::Strategy;

// ---------------------------------------------------------------- the built-in scenario

#[test]
fn homogeneous_has_the_papers_road() {
    let c = load("homogeneous").unwrap();
    assert_eq!(c.name, "homogeneous");
    assert_eq!(c.seed, 1);
    assert_eq!(c.dt_s, 0.1);
    assert_eq!(c.duration_s, 3600.0);
    assert_eq!(c.warmup_s, 1200.0);
    assert_eq!(c.penetration, 0.5);
    assert_eq!(c.road.lanes, 3);
    assert_eq!(c.road.length_m, 6500.0);
    assert_eq!(c.road.control_start_m, 5000.0);
    assert_eq!(c.road.control_end_m, 6000.0);
    assert_eq!(c.demand.vph_per_lane, 2500.0);
    let dets: Vec<(&str, f64)> = c
        .detectors
        .iter()
        .map(|d| (d.name.as_str(), d.position_m))
        .collect();
    assert_eq!(
        dets,
        vec![
            ("upstream", 4900.0),
            ("control_mid", 5500.0),
            ("discharge", 6100.0)
        ]
    );
    assert_eq!(c.detectors[c.measurement_detector].name, "discharge");
    assert_eq!(c.aggregation_s, 300.0);
    assert_eq!(c.strategy, Strategy::none());
    // Model sections: the spec defaults, 110 km/h desired speed.
    assert_eq!(c.human, Default::default());
    assert_eq!(c.human.desired_speed_kmh.mean, 110.0);
    assert_eq!(c.cav, Default::default());
    assert_eq!(c.lane_change, Default::default());
    c.check().unwrap();
}

#[test]
fn every_builtin_loads_and_is_listed_with_its_file() {
    for b in BUILTINS {
        let c = load(b.name).unwrap();
        assert_eq!(c.name, b.name);
        assert!(!b.description.is_empty());
    }
    assert_eq!(builtin("homogeneous").unwrap().toml, HOMOGENEOUS);
    assert!(builtin("nope").is_none());
}

#[test]
fn homogeneous_strategy_defaults_follow_the_road_and_the_run() {
    let pd = load_with(
        "homogeneous",
        &Overrides {
            strategy: Some(StrategyKind::PD),
            ..Overrides::default()
        },
    )
    .unwrap();
    assert_eq!(pd.strategy.kind, StrategyKind::PD);
    let pd = pd.strategy.pd.unwrap();
    assert_eq!((pd.zone_start_m, pd.zone_end_m), (5000.0, 6000.0));
    assert_eq!((pd.start_s, pd.end_s), (1200.0, 3600.0));

    let fa = load_with(
        "homogeneous",
        &Overrides {
            strategy: Some(StrategyKind::FLOW_AWARE),
            duration_s: Some(1800.0),
            warmup_s: Some(600.0),
            ..Overrides::default()
        },
    )
    .unwrap();
    assert_eq!(fa.strategy.kind, StrategyKind::FLOW_AWARE);
    let (pd, thresholds) = (fa.strategy.pd.unwrap(), fa.strategy.thresholds.unwrap());
    assert_eq!((pd.start_s, pd.end_s), (600.0, 1800.0));
    // Thresholds: the table homogeneous.toml names, at the run's penetration (50 %).
    assert_eq!(thresholds.flow_threshold_vphpl, 2750.0);
    assert_eq!(thresholds.speed_threshold_kmh, 97.0);
    assert_eq!(thresholds.radius_m, 1500.0);
    // Between calibrated rows the thresholds are interpolated; an explicit value wins.
    let at = |pen: f64, set: &[&str]| {
        let mut o = Overrides {
            strategy: Some(StrategyKind::FLOW_AWARE),
            penetration: Some(pen),
            ..Overrides::default()
        };
        o.set = set.iter().map(|s| s.to_string()).collect();
        let s = load_with("homogeneous", &o).unwrap().strategy;
        s.thresholds.unwrap().flow_threshold_vphpl
    };
    let (q25, q50, q75) = (at(0.25, &[]), at(0.5, &[]), at(0.75, &[]));
    assert_eq!(at(0.625, &[]), 0.5 * (q50 + q75));
    assert_eq!(at(0.0, &[]), q25);
    assert_eq!(at(0.5, &["strategy.flow_threshold_vphpl=1234"]), 1234.0);
}

// ---------------------------------------------------------------- round trips

#[test]
fn resolved_toml_loads_back_to_the_same_config() {
    let lanes = ["\"leftmost\"", "\"rightmost\"", "2"];
    for (kind, lane) in StrategyKind::all().flat_map(|k| lanes.map(|l| (k, l))) {
        let o = Overrides {
            strategy: Some(kind),
            set: vec![
                "human.buffer_s=0.2".into(),
                "strategy.radius_m=2000".into(),
                format!("strategy.lane={lane}"),
            ],
            ..Overrides::default()
        };
        let c = load_with("homogeneous", &o).unwrap();
        let text = to_toml(&c);
        let back = from_toml(&text, "resolved", "other", &Overrides::default())
            .unwrap_or_else(|e| panic!("{e}\n{text}"));
        assert_eq!(back, c, "{text}");
    }
}

#[test]
fn the_clock_start_round_trips_and_only_sr99_names_one() {
    let sr99 = load("sr99").unwrap();
    assert_eq!(sr99.clock_start_s, Some(5 * 3600));
    let text = to_toml(&sr99);
    assert!(text.contains("clock_start = \"05:00:00\""), "{text}");
    let back = from_toml(&text, "resolved", "sr99", &Overrides::default()).unwrap();
    assert_eq!(back.clock_start_s, Some(5 * 3600));
    let homogeneous = load("homogeneous").unwrap();
    assert_eq!(homogeneous.clock_start_s, None);
    assert!(!to_toml(&homogeneous).contains("clock_start"));
}

#[test]
fn resolved_toml_lists_every_section() {
    let text = to_toml(&load("homogeneous").unwrap());
    for section in [
        "[run]",
        "[road]",
        "[demand]",
        "[[detectors]]",
        "[measurement]",
        "[strategy]",
        "[human]",
        "[cav]",
        "[lane_change]",
    ] {
        assert!(text.contains(section), "{section} missing in\n{text}");
    }
    assert!(
        text.contains("desired_speed_kmh = { mean = 110.0"),
        "{text}"
    );
    assert!(text.parse::<toml::Table>().is_ok());
}

#[test]
fn set_round_trips() {
    let c = with_set(
        HOMOGENEOUS,
        &[
            "run.seed=3",
            "human.buffer_s=0.2",
            "cav.time_gap_shares=[[0.6,1.0]]",
            "strategy.kind=flow-aware",
            "detectors[0].position_m=4800",
            "human.desired_speed_kmh.mean=115",
            "lane_change.threshold={ mean = 0.3, sd = 0.1, min = 0.2, max = 0.5 }",
            "lane_change.gap_rule=published",
            "lane_change.safe_follower_decel_mps2=3.5",
            "name=renamed",
        ],
    )
    .unwrap();
    assert_eq!(c.lane_change.gap_rule, GapRule::Published);
    assert_eq!(c.lane_change.safe_follower_decel_mps2, 3.5);
    assert_eq!(c.seed, 3);
    assert_eq!(c.human.buffer_s, 0.2);
    assert_eq!(c.cav.time_gap_shares, vec![(0.6, 1.0)]);
    assert_eq!(c.strategy.kind, StrategyKind::FLOW_AWARE);
    assert_eq!(c.detectors[0].position_m, 4800.0);
    // A single field of a distribution: the other fields keep their defaults.
    assert_eq!(c.human.desired_speed_kmh.mean, 115.0);
    assert_eq!(c.human.desired_speed_kmh.min, 100.0);
    assert_eq!(c.lane_change.threshold.mean, 0.3);
    assert_eq!(c.name, "renamed");
    // And the result survives the trip through the resolved file.
    let back = from_toml(&to_toml(&c), "resolved", "x", &Overrides::default()).unwrap();
    assert_eq!(back, c);
}

#[test]
fn later_set_wins_and_typed_flags_win_over_set() {
    let o = Overrides {
        penetration: Some(0.25),
        set: vec![
            "run.penetration=0.75".into(),
            "run.seed=5".into(),
            "run.seed=6".into(),
        ],
        ..Overrides::default()
    };
    let c = from_toml(HOMOGENEOUS, "t", "t", &o).unwrap();
    assert_eq!(c.penetration, 0.25);
    assert_eq!(c.seed, 6);
}

#[test]
fn typed_overrides_reach_the_config() {
    let o = Overrides {
        penetration: Some(1.0),
        demand_vphpl: Some(1000.0),
        duration_s: Some(600.0),
        warmup_s: Some(120.0),
        seed: Some(42),
        strategy: Some(StrategyKind::PD),
        set: vec![],
    };
    let c = load_with("homogeneous", &o).unwrap();
    assert_eq!(c.penetration, 1.0);
    assert_eq!(c.demand.vph_per_lane, 1000.0);
    assert_eq!(c.duration_s, 600.0);
    assert_eq!(c.warmup_s, 120.0);
    assert_eq!(c.seed, 42);
    assert_eq!(c.strategy.kind, StrategyKind::PD);
}

// ---------------------------------------------------------------- files and names

fn temp_file(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("platoonsim-scenario-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_file_loads_and_its_name_defaults_to_the_file_stem() {
    let text = SMALL.replace("name = \"small\"", "");
    let path = temp_file("my_road.toml", &text);
    let c = load(path.to_str().unwrap()).unwrap();
    assert_eq!(c.name, "my_road");
    assert_eq!(c.road.lanes, 2);
    assert_eq!(c.measurement_detector, 1);
    // Defaults of [run] and [measurement].
    assert_eq!(
        (c.seed, c.dt_s, c.duration_s, c.warmup_s, c.penetration),
        (1, 0.1, 3600.0, 1200.0, 0.5)
    );
    assert_eq!(c.aggregation_s, 300.0);
}

#[test]
fn unknown_scenario_names_the_builtins() {
    let e = load("no_such_scenario").unwrap_err();
    assert!(matches!(e, ScenarioError::UnknownScenario { .. }));
    let msg = e.to_string();
    assert!(
        msg.contains("'no_such_scenario'") && msg.contains("homogeneous"),
        "{msg}"
    );
    let e = load("missing/dir/file.toml").unwrap_err();
    assert!(matches!(e, ScenarioError::UnknownScenario { .. }), "{e}");
}

/// The homogeneous road has one definition, `scenarios/homogeneous.toml`; the engine keeps a
/// mirror of it for its own tests and benchmarks (`Config::homogeneous`), which must equal the
/// file loaded with the same values, field by field (the models' parameters included).
#[test]
fn homogeneous_config_mirrors_the_scenario_file() {
    for (pen, demand, duration, warmup, seed) in [
        (0.5, 2500.0, 3600.0, 1200.0, 1),
        (0.0, 1000.0, 600.0, 0.0, 7),
        (0.25, 1800.0, 1800.0, 600.0, 3),
        (1.0, 2200.0, 900.0, 300.0, 42),
    ] {
        let mirror = platoonsim_sim::Config::homogeneous(pen, demand, duration, warmup, seed);
        let overrides = |strategy| Overrides {
            penetration: Some(pen),
            demand_vphpl: Some(demand),
            duration_s: Some(duration),
            warmup_s: Some(warmup),
            seed: Some(seed),
            strategy,
            ..Overrides::default()
        };
        let file = load_with("homogeneous", &overrides(None)).unwrap();
        assert_eq!(file, mirror);
        let pd = load_with("homogeneous", &overrides(Some(StrategyKind::PD))).unwrap();
        assert_eq!(pd, mirror.with_pd());
    }
}
