//! Network scenarios (issue 4): the `[network]` section (the built-in `sr99` in sr99.rs), the
//! lane-index conversion, the generated detectors, round trips and every class of bad input.

mod common;

use common::*;
use platoonsim_scenario::{
    demand_scale_set, from_toml, load, load_with, to_toml, Overrides, ScenarioError,
};
use platoonsim_sim::config::DetectorKind;
use platoonsim_sim::StrategyKind;

const SMALL_CORRIDOR: &str = include_str!("fixtures/small_corridor.toml");
const SR99: &str = include_str!("../scenarios/sr99.toml");

// ---------------------------------------------------------------- the example corridor

#[test]
fn small_corridor_fixture_loads() {
    let c = parse(SMALL_CORRIDOR).unwrap();
    c.check().unwrap();
    assert_eq!(c.road.lanes, 4);
    assert_eq!(c.road.length_m, 3200.0);
    let n = c.road.network.as_ref().unwrap();
    assert_eq!(
        n.through_lanes,
        vec![
            ext(1, 1700.0, 3200.0),
            ext(2, 0.0, 3200.0),
            ext(3, 0.0, 3200.0)
        ]
    );
    let ramps: Vec<(&str, f64, f64)> = n
        .on_ramps
        .iter()
        .map(|r| (r.name.as_str(), r.x_m, r.accel_lane_m))
        .collect();
    assert_eq!(
        ramps,
        vec![
            ("OR1: First St", 200.0, 250.0),
            ("B: Second St", 1700.0, 250.0)
        ]
    );
    assert_eq!(n.off_ramps[0].name, "FR1: Exit Rd");
    assert_eq!(n.demand_scale, 1.0);
    let dets: Vec<(&str, f64, bool)> = c
        .detectors
        .iter()
        .map(|d| (d.name.as_str(), d.position_m, d.exit))
        .collect();
    assert_eq!(
        dets,
        vec![
            ("OR1-up", 150.0, false),
            ("OR1-down", 250.0, false),
            ("FR1-up", 1050.0, false),
            ("B-up", 1650.0, false),
            ("B-down", 1750.0, false),
            ("end", 3190.0, true),
            ("FR1-off", 1100.0, true),
        ]
    );
    assert_eq!(c.measurement_detector, 5);
    assert_eq!(c.strategy.kind, StrategyKind::PD);
    let pd = c.strategy.pd.as_ref().unwrap();
    assert_eq!(
        (pd.zone_start_m, pd.zone_end_m, pd.start_s),
        (0.0, 3200.0, 0.0)
    );
}

#[test]
fn lane_counts_become_lateral_indices_from_the_right() {
    // The toy corridor: 3 lanes, then 4 from the add point.
    let text = SMALL_CORRIDOR.replace("count = 2", "count = 3").replace(
        "count = 3\n\n[[network.on_ramps]]",
        "count = 4\n\n[[network.on_ramps]]",
    );
    let c = parse(&text).unwrap();
    assert_eq!(c.road.lanes, 5);
    assert_eq!(
        c.road.network.unwrap().through_lanes,
        vec![
            ext(1, 1700.0, 3200.0),
            ext(2, 0.0, 3200.0),
            ext(3, 0.0, 3200.0),
            ext(4, 0.0, 3200.0)
        ]
    );
    // A lane drop: 3 lanes, then 2; stretches of equal count merge into one extent.
    let text = format!(
        "{}\n[[network.lanes]]\nfrom_m = 3000\nto_m = 3500\ncount = 2\n",
        SMALL_CORRIDOR
            .replace("end_m = 3000.0", "end_m = 3500.0")
            .replace("count = 2", "count = 3")
    );
    let c = parse(&text).unwrap();
    assert_eq!(c.road.lanes, 4);
    assert_eq!(
        c.road.network.unwrap().through_lanes,
        vec![
            ext(1, 0.0, 3200.0),
            ext(2, 0.0, 3700.0),
            ext(3, 0.0, 3700.0)
        ]
    );
}

#[test]
fn user_detectors_join_the_generated_ones() {
    let text = format!(
        "{SMALL_CORRIDOR}\n[[detectors]]\nname = \"mid\"\nposition_m = 2000\n\
         [measurement]\ndetector = \"mid\"\n"
    );
    let c = parse(&text).unwrap();
    assert_eq!(
        names(&c),
        vec!["OR1-up", "OR1-down", "FR1-up", "B-up", "B-down", "mid", "end", "FR1-off"]
    );
    let mid = &c.detectors[5];
    assert_eq!((mid.position_m, mid.exit), (2200.0, false));
    assert_eq!(c.measurement_detector, 5);
}

#[test]
fn ramp_stations_name_the_ramp_counters() {
    let c = with_set(
        SMALL_CORRIDOR,
        &[
            "network.on_ramps[1].station=314107",
            "network.off_ramps[0].station=312424",
        ],
    )
    .unwrap();
    assert_eq!(
        names(&c),
        vec!["OR1-up", "OR1-down", "FR1-up", "B-up", "B-down", "end", "312424", "314107"]
    );
    let on = &c.detectors[7];
    assert_eq!(
        (on.position_m, on.exit, on.kind),
        (1700.0, false, DetectorKind::OnRamp { ramp: 1 })
    );
    assert_eq!(c.detectors[6].kind, DetectorKind::OffRamp { ramp: 0 });
    // Written back and read again: the same configuration.
    let resolved = to_toml(&c);
    assert!(resolved.contains("station = \"314107\""), "{resolved}");
    let back = from_toml(&resolved, "resolved", "other", &Overrides::default()).unwrap();
    assert_eq!(back, c);

    let p = corridor_problems(&[
        "network.on_ramps[0].station=S1",
        "network.off_ramps[0].station=S1",
    ]);
    assert_eq!(
        p,
        vec!["network.off_ramps[0].station = \"S1\": duplicates network.on_ramps[0].station; a station names one ramp counter"]
    );
    let p = corridor_problems(&["network.on_ramps[0].station='a b'"]);
    assert_eq!(
        p,
        vec!["network.on_ramps[0].station = \"a b\": must be a non-empty id of letters, digits, '_', '-' and '.' (it names the ramp's counter)"]
    );
}

// ---------------------------------------------------------------- round trips

#[test]
fn resolved_network_files_load_back_to_the_same_config() {
    let user = "\n[[detectors]]\nname = \"mid\"\nposition_m = 2000\n";
    let cases = [
        (SR99.to_string(), vec![]),
        (
            SR99.to_string(),
            vec!["strategy.kind=flow-aware", "run.penetration=0.5"],
        ),
        (
            SR99.to_string(),
            vec![
                "network.detectors.upstream_of_ramps_m=80",
                "network.detectors.before_end_m=5",
            ],
        ),
        (SMALL_CORRIDOR.to_string(), vec![]),
        (
            SMALL_CORRIDOR.to_string(),
            vec!["network.lane_speed_limits_kmh=[93.6, 98.8, 104]"],
        ),
        (
            format!("{SMALL_CORRIDOR}{user}"),
            vec!["strategy.zone_start_m=500"],
        ),
    ];
    for (text, sets) in cases {
        let c = with_set(&text, &sets).unwrap();
        let resolved = to_toml(&c);
        let back = from_toml(&resolved, "resolved", "other", &Overrides::default())
            .unwrap_or_else(|e| panic!("{e}\n{resolved}"));
        assert_eq!(back, c, "{sets:?}\n{resolved}");
    }
    let resolved = to_toml(&load("sr99").unwrap());
    for section in [
        "[network]",
        "[[network.lanes]]",
        "[[network.on_ramps]]",
        "[[network.off_ramps]]",
    ] {
        assert!(resolved.contains(section), "{section}\n{resolved}");
    }
    assert!(
        !resolved.contains("[demand]") && !resolved.contains("[[detectors]]"),
        "{resolved}"
    );
    assert!(resolved.contains("name = \"Elk Grove Blvd\""), "{resolved}");
}

// ---------------------------------------------------------------- errors

fn corridor_problems(sets: &[&str]) -> Vec<String> {
    problems(with_set(SMALL_CORRIDOR, sets))
}

#[test]
fn lane_stretches_must_tile_the_corridor() {
    let p = corridor_problems(&["network.lanes[1].from_m=1600"]);
    assert_eq!(
        p,
        vec!["network.lanes[1].from_m = 1600: must equal network.lanes[0].to_m = 1500 (a gap; the stretches must tile [network.start_m, network.end_m) in order, without gaps or overlaps)"]
    );
    let p = corridor_problems(&["network.lanes[1].from_m=1400"]);
    assert!(p[0].contains("(an overlap;"), "{p:?}");
    let p = corridor_problems(&["network.lanes[0].from_m=-100"]);
    assert!(
        p[0].starts_with(
            "network.lanes[0].from_m = -100: must equal network.start_m = -200 (a gap;"
        ),
        "{p:?}"
    );
    let p = corridor_problems(&["network.lanes[1].to_m=2900"]);
    assert_eq!(
        p,
        vec!["network.lanes[1].to_m = 2900: must equal network.end_m = 3000 (the stretches must tile [network.start_m, network.end_m) in order, without gaps or overlaps)"]
    );
    let p = corridor_problems(&["network.lanes[0].to_m=-300"]);
    assert!(
        has(
            &p,
            "network.lanes[0].to_m = -300: must be > network.lanes[0].from_m = -200"
        ),
        "{p:?}"
    );
    for bad in ["0", "8"] {
        let p = corridor_problems(&[&format!("network.lanes[0].count={bad}")]);
        assert_eq!(
            p,
            vec![format!(
                "network.lanes[0].count = {bad}: must be an integer from 1 to 7"
            )]
        );
    }
    let p = corridor_problems(&["network.lanes=[]"]);
    assert!(
        has(&p, "network.lanes = []: at least one [[network.lanes]] stretch (from_m, to_m, count) is required"),
        "{p:?}"
    );
}

#[test]
fn ramps_inside_the_corridor_and_in_order() {
    let p = corridor_problems(&["network.on_ramps[0].x_m=-200"]);
    assert_eq!(
        p,
        vec!["network.on_ramps[0].x_m = -200: must lie inside the corridor (network.start_m, network.end_m) = (-200, 3000)"]
    );
    let p = corridor_problems(&["network.off_ramps[0].x_m=3000"]);
    assert!(
        p[0].starts_with("network.off_ramps[0].x_m = 3000: must lie inside the corridor"),
        "{p:?}"
    );
    let p = corridor_problems(&["network.on_ramps[1].x_m=-50"]);
    assert_eq!(
        p,
        vec!["network.on_ramps[1].x_m = -50: must be > network.on_ramps[0].x_m = 0 (on-ramps are listed in downstream order)"]
    );
    let p = corridor_problems(&["network.on_ramps[0].x_m=nan"]);
    assert_eq!(
        p,
        vec!["network.on_ramps[0].x_m = nan: must be a finite number in [-10000000, 10000000] m"]
    );
}

#[test]
fn lane_speed_caps_are_off_by_default_and_checked() {
    // Spec 2.7: optional; none unless given, and every cap a positive speed.
    let c = parse(SMALL_CORRIDOR).unwrap();
    assert!(c
        .road
        .network
        .as_ref()
        .unwrap()
        .lane_speed_limits_kmh
        .is_empty());
    assert!(!to_toml(&c).contains("lane_speed_limits_kmh"));
    let c = with_set(SMALL_CORRIDOR, &["network.lane_speed_limits_kmh=[90, 100]"]).unwrap();
    assert_eq!(
        c.road.network.as_ref().unwrap().lane_speed_limits_kmh,
        vec![90.0, 100.0]
    );
    let p = corridor_problems(&["network.lane_speed_limits_kmh=[90, -1, nan]"]);
    assert_eq!(
        p,
        vec![
            "network.lane_speed_limits_kmh[1] = -1: must be in (0, 1000] km/h",
            "network.lane_speed_limits_kmh[2] = nan: must be in (0, 1000] km/h",
        ]
    );
}

#[test]
fn an_on_ramps_share_of_cavs_is_optional_and_checked() {
    // None unless given (the run's penetration, and nothing written); given, in [0, 1] and
    // written back.
    let c = parse(SMALL_CORRIDOR).unwrap();
    let net = c.road.network.as_ref().unwrap();
    assert!(net.on_ramps.iter().all(|r| r.penetration.is_none()));
    assert!(!to_toml(&c).contains("penetration = 0.0"));
    let c = with_set(SMALL_CORRIDOR, &["network.on_ramps[0].penetration=0"]).unwrap();
    assert_eq!(
        c.road.network.as_ref().unwrap().on_ramps[0].penetration,
        Some(0.0)
    );
    let back = from_toml(&to_toml(&c), "resolved", "other", &Overrides::default()).unwrap();
    assert_eq!(back, c);
    let p = corridor_problems(&["network.on_ramps[0].penetration=1.5"]);
    assert_eq!(
        p,
        vec!["network.on_ramps[0].penetration = 1.5: must be in [0, 1] (the share of CAVs among the ramp's arrivals)"]
    );
}

#[test]
fn cross_lane_friction_is_off_by_default_and_checked() {
    // Spec 2.7: optional; none unless given, c_fr in (0, 1], written back when given.
    let c = parse(SMALL_CORRIDOR).unwrap();
    assert_eq!(c.road.network.as_ref().unwrap().cross_lane_friction, None);
    assert!(!to_toml(&c).contains("cross_lane_friction"));
    let c = with_set(SMALL_CORRIDOR, &["network.cross_lane_friction=0.3"]).unwrap();
    assert_eq!(
        c.road.network.as_ref().unwrap().cross_lane_friction,
        Some(0.3)
    );
    let back = parse(&to_toml(&c)).unwrap();
    assert_eq!(
        back.road.network.as_ref().unwrap().cross_lane_friction,
        Some(0.3)
    );
    for (value, shown) in [("0", "0"), ("1.5", "1.5"), ("-0.2", "-0.2"), ("nan", "nan")] {
        let p = corridor_problems(&[&format!("network.cross_lane_friction={value}")]);
        assert_eq!(
            p,
            vec![format!(
                "network.cross_lane_friction = {shown}: must be in (0, 1] (1 = off)"
            )]
        );
    }
}

#[test]
fn series_are_checked_value_by_value_and_by_length() {
    let p = corridor_problems(&["network.mainline_vph=[3000, -1]"]);
    assert_eq!(
        p,
        vec!["network.mainline_vph[1] = -1: must be in [0, 20000] veh/h (10000 veh/h per lane open at the entrance × 2 lanes)"]
    );
    let p = corridor_problems(&["network.on_ramps[1].demand_vph=[300, inf]"]);
    assert_eq!(
        p,
        vec!["network.on_ramps[1].demand_vph[1] = inf: must be in [0, 10000] veh/h (an on-ramp is one lane: 10000 veh/h)"]
    );
    let p = corridor_problems(&["network.off_ramps[0].exit_fraction=[0.1, 1.5]"]);
    assert_eq!(
        p,
        vec!["network.off_ramps[0].exit_fraction[1] = 1.5: must be in [0, 1]"]
    );
    let p = corridor_problems(&["network.on_ramps[0].demand_vph=[400, 600, 700]"]);
    assert_eq!(
        p,
        vec!["network.on_ramps[0].demand_vph = (3 values): must have 2 intervals, as many as network.mainline_vph (one per network.interval_s)"]
    );
    let p = corridor_problems(&["network.off_ramps[0].exit_fraction=[0.1]"]);
    assert!(
        p[0].starts_with("network.off_ramps[0].exit_fraction = (1 values): must have 2 intervals"),
        "{p:?}"
    );
    let p = corridor_problems(&["network.mainline_vph=[]"]);
    assert_eq!(
        p,
        vec!["network.mainline_vph = []: must have at least one interval"]
    );
    let p = corridor_problems(&["network.demand_scale=-1", "network.interval_s=0"]);
    assert!(
        has(
            &p,
            "network.demand_scale = -1: must be a finite number >= 0"
        ),
        "{p:?}"
    );
    assert!(
        has(&p, "network.interval_s = 0: must be in [1, 604800] s"),
        "{p:?}"
    );
}

#[test]
fn demand_offset_reads_every_series_later() {
    let net = |sets: &[&str]| {
        with_set(SMALL_CORRIDOR, sets)
            .unwrap()
            .road
            .network
            .unwrap()
    };
    // Whole intervals: the first ones are dropped and the last one holds past the end.
    let n = net(&["network.demand_offset_s=1800"]);
    assert_eq!(n.interval_s, 1800.0);
    assert_eq!(n.mainline_vph, vec![3600.0]);
    assert_eq!(n.on_ramps[0].demand_vph, vec![600.0]);
    assert_eq!(n.on_ramps[1].demand_vph, vec![500.0]);
    assert_eq!(n.off_ramps[0].exit_fraction, vec![0.15]);
    assert_eq!(
        (n.at(&n.mainline_vph, 0.0), n.at(&n.mainline_vph, 3000.0)),
        (3600.0, 3600.0)
    );
    // Part of an interval: the series are refined to gcd(1800, 600) = 600 s and stay exact.
    let n = net(&["network.demand_offset_s=600"]);
    assert_eq!(n.interval_s, 600.0);
    assert_eq!(n.mainline_vph, vec![3000.0, 3000.0, 3600.0, 3600.0, 3600.0]);
    assert_eq!(
        n.off_ramps[0].exit_fraction,
        vec![0.1, 0.1, 0.15, 0.15, 0.15]
    );
    for t in [0.0, 599.0, 1199.0, 1200.0, 2500.0, 4000.0] {
        let expect = if t + 600.0 < 1800.0 { 3000.0 } else { 3600.0 };
        assert_eq!(n.at(&n.mainline_vph, t), expect, "t = {t}");
    }
    // 0 (the default) leaves the series as written.
    let plain = net(&[]);
    assert_eq!(net(&["network.demand_offset_s=0"]), plain);
    assert_eq!(plain.mainline_vph, vec![3000.0, 3600.0]);
}

#[test]
fn demand_offset_is_checked() {
    let span = "(the span of the demand series: 2 intervals of network.interval_s = 1800 s)";
    for (v, shown) in [
        ("-900", "-900"),
        ("3600", "3600"),
        ("1e9", "1000000000"),
        ("nan", "nan"),
    ] {
        let set = format!("network.demand_offset_s={v}");
        let p = corridor_problems(&[set.as_str()]);
        assert_eq!(
            p,
            vec![format!(
                "network.demand_offset_s = {shown}: must be in [0, 3600) s {span}"
            )]
        );
    }
    let p = corridor_problems(&["network.demand_offset_s=0.5"]);
    assert_eq!(
        p,
        vec![format!(
            "network.demand_offset_s = 0.5: must be a whole number of seconds or a multiple of network.interval_s = 1800 s, in [0, 3600) s {span}"
        )]
    );
    // A bad interval is reported once; the offset is then only checked for its sign.
    let p = corridor_problems(&["network.interval_s=0", "network.demand_offset_s=-1"]);
    assert!(
        has(&p, "network.interval_s = 0: must be in [1, 604800] s"),
        "{p:?}"
    );
    assert!(
        has(
            &p,
            "network.demand_offset_s = -1: must be a finite number >= 0"
        ),
        "{p:?}"
    );
    // On a scenario without a network the key is unknown like every network key.
    assert!(with_set(common::SMALL, &["network.demand_offset_s=900"]).is_err());
}

#[test]
fn ramp_ids_must_be_unique_and_valid() {
    let p = corridor_problems(&["network.on_ramps[1].id=FR1"]);
    assert_eq!(
        p,
        vec!["network.off_ramps[0].id = \"FR1\" (default): duplicates network.on_ramps[1].id; ramp ids must be unique (they name the detectors)"]
    );
    let p = corridor_problems(&["network.off_ramps[0].id='a b'"]);
    assert_eq!(
        p,
        vec!["network.off_ramps[0].id = \"a b\": must be a non-empty id of letters, digits, '_', '-' and '.' (it names the ramp's detectors)"]
    );
    let p = corridor_problems(&["network.on_ramps[0].name=' '"]);
    assert_eq!(
        p,
        vec!["network.on_ramps[0].name = \" \": must be a non-empty string"]
    );
}

#[test]
fn road_and_demand_keys_clash_with_a_network() {
    let p = corridor_problems(&[
        "road.lanes=3",
        "road.length_m=3200",
        "demand.vph_per_lane=1000",
    ]);
    assert!(
        p.iter()
            .any(|l| l.starts_with("road.lanes = 3: must be left out with [network]")),
        "{p:?}"
    );
    assert!(
        p.iter()
            .any(|l| l.starts_with("road.length_m = 3200: must be left out with [network]")),
        "{p:?}"
    );
    assert!(
        p.iter().any(|l| l
            .starts_with("demand.vph_per_lane = 1000: must be left out with [network]")
            && l.contains("--demand-scale")),
        "{p:?}"
    );
    let p = problems(load_with(
        "sr99",
        &Overrides {
            demand_vphpl: Some(2000.0),
            ..Overrides::default()
        },
    ));
    assert!(
        p[0].starts_with("demand.vph_per_lane = 2000: must be left out"),
        "{p:?}"
    );
}

#[test]
fn missing_network_keys_are_all_reported() {
    let p = problems(parse("[network]\n"));
    for field in ["network.start_m", "network.end_m", "network.mainline_vph"] {
        assert!(
            p.iter()
                .any(|l| l.starts_with(&format!("{field} = (missing): required"))),
            "{field}: {p:?}"
        );
    }
    assert!(
        !p.iter().any(|l| l.starts_with("road.")
            || l.starts_with("demand.")
            || l.starts_with("detectors")),
        "{p:?}"
    );
    let p = corridor_problems(&["network.end_m=-300"]);
    assert!(
        has(&p, "network.end_m = -300: must be > network.start_m = -200"),
        "{p:?}"
    );
    let p = problems(parse(&SMALL_CORRIDOR.replace("ramp_length_m = 300.0", "")));
    assert_eq!(
        p,
        vec!["network.on_ramps[0].ramp_length_m = (missing): required: the ramp roadway length upstream of the merge point (m)"]
    );
}

#[test]
fn detectors_on_a_network() {
    let user = |name: &str, pos: &str| {
        format!("{SMALL_CORRIDOR}\n[[detectors]]\nname = \"{name}\"\nposition_m = {pos}\n")
    };
    let p = problems(parse(&user("end", "100")));
    assert!(
        p[0].starts_with(
            "detectors[0].name = \"end\": duplicates a detector generated for the network"
        ),
        "{p:?}"
    );
    let p = problems(parse(&user("x", "-250")));
    assert_eq!(
        p,
        vec!["detectors[0].position_m = -250: must lie inside the corridor (-200, 3000)"]
    );
    let p = corridor_problems(&["network.detectors.before_end_m=4000"]);
    assert_eq!(
        p,
        vec!["network.detectors.before_end_m = 4000: must be > 0 and < the corridor length network.end_m − network.start_m = 3200"]
    );
    let p = corridor_problems(&["network.detectors.upstream_of_ramps_m=-1"]);
    assert_eq!(
        p,
        vec!["network.detectors.upstream_of_ramps_m = -1: must be in [0, 200000] m"]
    );
    let p = corridor_problems(&["measurement.detector=nope"]);
    assert_eq!(
        p,
        vec!["measurement.detector = \"nope\": names no detector; defined: \"OR1-up\", \"OR1-down\", \"FR1-up\", \"B-up\", \"B-down\", \"end\", \"FR1-off\""]
    );
    let p = problems(with_set(SR99, &["measurement.detector=nope"]));
    assert!(
        p[0].ends_with("… (55 in all; `platoonsim show` lists them)"),
        "{p:?}"
    );
    let p = corridor_problems(&["road.control_start_m=-300"]);
    assert!(
        p[0].starts_with("road.control_start_m = -300: must lie in [network.start_m = -200, network.end_m = 3000)"),
        "{p:?}"
    );
    let p = corridor_problems(&["strategy.zone_end_m=3500"]);
    assert_eq!(
        p,
        vec!["strategy.zone_end_m = 3500: must be > strategy.zone_start_m = -200 (default) and <= network.end_m = 3000"]
    );
}

#[test]
fn structure_errors_name_the_nested_key() {
    let (path, msg) = structure(parse(&SMALL_CORRIDOR.replace("count = 2", "count = 2.5")));
    assert_eq!(path, "network.lanes[0].count");
    assert!(msg.contains("2.5"), "{msg}");
    let (path, msg) = structure(parse(
        &SMALL_CORRIDOR.replace("x_m = 900.0", "x_m = 900.0\nlanes = 1"),
    ));
    assert_eq!(path, "network.off_ramps[0].lanes");
    assert!(msg.starts_with("unknown field 'lanes' in [network.off_ramps[0]]; allowed keys: id, name, x_m, exit_fraction"), "{msg}");
    let (path, _) = structure(with_set(SMALL_CORRIDOR, &["network.detectors.spacing=1"]));
    assert_eq!(path, "network.detectors.spacing");
    let (path, _) = structure(with_set(SMALL_CORRIDOR, &["network.speed=1"]));
    assert_eq!(path, "network.speed");
    let (path, msg) = structure(with_set(SMALL_CORRIDOR, &["network.on_ramps=3"]));
    assert_eq!(path, "network.on_ramps");
    assert!(msg.contains("array of tables"), "{msg}");
}

#[test]
fn network_overrides_need_a_network() {
    for o in [
        Overrides {
            set: vec![demand_scale_set(1.1)],
            ..Overrides::default()
        },
        Overrides {
            set: vec!["network.start_m=0".into()],
            ..Overrides::default()
        },
    ] {
        match load_with("homogeneous", &o) {
            Err(e @ ScenarioError::Override { .. }) => {
                let msg = e.to_string();
                assert!(msg.contains("has no [network] section"), "{msg}");
            }
            other => panic!("{other:?}"),
        }
    }
    assert_eq!(demand_scale_set(1.1), "network.demand_scale=1.1");
}

#[test]
fn no_value_in_any_network_key_makes_loading_panic() {
    fn walk(prefix: &str, v: &toml::Value, out: &mut Vec<String>) {
        match v {
            toml::Value::Table(t) => {
                for (k, vv) in t {
                    let p = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    out.push(p.clone());
                    walk(&p, vv, out);
                }
            }
            toml::Value::Array(items) => {
                for (i, item) in items.iter().enumerate().take(2) {
                    let p = format!("{prefix}[{i}]");
                    if item.is_table() {
                        walk(&p, item, out);
                    } else {
                        out.push(p);
                    }
                }
            }
            _ => {}
        }
    }
    let resolved = to_toml(&parse(SMALL_CORRIDOR).unwrap());
    let doc: toml::Table = resolved.parse().unwrap();
    let mut keys = Vec::new();
    walk(
        "",
        &toml::Value::Table(doc.get("network").unwrap().as_table().unwrap().clone()),
        &mut keys,
    );
    let keys: Vec<String> = keys.into_iter().map(|k| format!("network.{k}")).collect();
    assert!(keys.len() > 30, "{keys:?}");
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
        "[-1, nan]",
        "9223372036854775807",
    ];
    for key in &keys {
        for value in values {
            let _ = with_set(&resolved, &[&format!("{key}={value}")]);
        }
    }
}

#[test]
fn docs_example_is_the_fixture() {
    let doc = include_str!("../../../docs/network-scenarios.md");
    assert!(
        doc.contains(SMALL_CORRIDOR),
        "docs/network-scenarios.md must contain tests/fixtures/small_corridor.toml verbatim"
    );
}
