//! What a scenario gets from the tables by penetration: only what it names. A corridor of the
//! user's own runs at demand scale 1 and has no Flow-Aware thresholds; the built-ins name
//! their tables (sr99.rs and scenario.rs check the values they give).

mod common;

use common::*;
use platoonsim_scenario::{from_toml, load_with, Overrides, StrategyKind};
use platoonsim_sim::Strategy;

const SMALL_CORRIDOR: &str = include_str!("fixtures/small_corridor.toml");

/// The small corridor without its `demand_scale` line, at penetration `p`.
fn corridor_at(
    p: f64,
    sets: &[&str],
) -> Result<platoonsim_sim::Config, platoonsim_scenario::ScenarioError> {
    let text: String = SMALL_CORRIDOR
        .lines()
        .filter(|l| !l.starts_with("demand_scale"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(!text.contains("demand_scale ="));
    let mut set = vec![format!("run.penetration={p}")];
    set.extend(sets.iter().map(|s| s.to_string()));
    let set: Vec<&str> = set.iter().map(String::as_str).collect();
    with_set(&text, &set)
}

fn flow_aware(sets: &[&str]) -> Result<platoonsim_sim::Config, platoonsim_scenario::ScenarioError> {
    let mut all = vec!["strategy.kind=flow-aware"];
    all.extend_from_slice(sets);
    with_set(SMALL, &all)
}

#[test]
fn a_corridor_of_ones_own_runs_at_demand_scale_one_at_any_penetration() {
    for p in [0.0, 0.4, 0.6, 1.0] {
        let c = corridor_at(p, &[]).unwrap();
        assert_eq!(c.road.network.unwrap().demand_scale, 1.0, "penetration {p}");
    }
}

#[test]
fn a_corridor_that_names_a_demand_scale_table_gets_its_scale() {
    let scale = |p: f64, sets: &[&str]| {
        corridor_at(p, sets)
            .unwrap()
            .road
            .network
            .unwrap()
            .demand_scale
    };
    let sr99 = "network.demand_scale_table=sr99_demand_scales";
    assert_eq!(scale(0.6, &[sr99]), 1.17);
    assert_eq!(scale(1.0, &[sr99]), 1.27);
    // An explicit scale wins over the table.
    assert_eq!(scale(0.6, &[sr99, "network.demand_scale=1.05"]), 1.05);
}

#[test]
fn a_table_that_cannot_be_used_is_an_error_at_its_key() {
    let p = problems(corridor_at(0.5, &["network.demand_scale_table=sr98"]));
    assert_eq!(
        p,
        vec![
            "network.demand_scale_table = \"sr98\": must name a table of demand scales by \
             penetration: no built-in table 'sr98' (built-in tables: sr99_demand_scales, \
             flow_aware_thresholds, flow_aware_thresholds_sr99) and not a path (a path contains '/' or ends in .toml)"
        ]
    );
    // A thresholds table has no demand-scale column.
    let p = problems(corridor_at(
        0.5,
        &["network.demand_scale_table=flow_aware_thresholds"],
    ));
    assert_eq!(
        p,
        vec![
            "network.demand_scale_table = \"flow_aware_thresholds\": must name a table of demand \
             scales by penetration: the table has no feasible row with penetration, demand_scale"
        ]
    );
}

#[test]
fn flow_aware_without_thresholds_says_which_keys_to_set_and_where_the_tables_are() {
    let p = problems(flow_aware(&[]));
    let why = "strategy.kind = \"flow-aware\" needs both thresholds: set \
               strategy.flow_threshold_vphpl (veh/h/lane) and strategy.speed_threshold_kmh \
               (km/h), or strategy.thresholds_table = \"flow_aware_thresholds\" (the built-in \
               table calibrated on the homogeneous road, \
               crates/scenario/scenarios/flow_aware_thresholds.toml) or the path of a table \
               file in its format";
    assert_eq!(
        p,
        vec![
            format!("strategy.flow_threshold_vphpl = (missing): {why}"),
            format!("strategy.speed_threshold_kmh = (missing): {why}"),
        ]
    );
    // One given: only the other is missing.
    let p = problems(flow_aware(&["strategy.speed_threshold_kmh=80"]));
    assert_eq!(
        p,
        vec![format!("strategy.flow_threshold_vphpl = (missing): {why}")]
    );
    // Other strategies need no thresholds.
    for kind in ["none", "pd"] {
        with_set(SMALL, &[&format!("strategy.kind={kind}")]).unwrap();
    }
}

#[test]
fn flow_aware_takes_thresholds_from_the_file_or_the_table_it_names() {
    let thresholds = |c: platoonsim_sim::Config| match c.strategy {
        Strategy {
            kind: StrategyKind::FLOW_AWARE,
            thresholds: Some(t),
            ..
        } => (t.flow_threshold_vphpl, t.speed_threshold_kmh),
        other => panic!("{other:?}"),
    };
    let given = flow_aware(&[
        "strategy.flow_threshold_vphpl=1900",
        "strategy.speed_threshold_kmh=85",
    ]);
    assert_eq!(thresholds(given.unwrap()), (1900.0, 85.0));
    // SMALL is at the default penetration, 0.5: the built-in table's row there.
    let table = flow_aware(&["strategy.thresholds_table=flow_aware_thresholds"]);
    assert_eq!(thresholds(table.unwrap()), (2750.0, 97.0));
    let mixed = flow_aware(&[
        "strategy.thresholds_table=flow_aware_thresholds",
        "strategy.speed_threshold_kmh=60",
    ]);
    assert_eq!(thresholds(mixed.unwrap()), (2750.0, 60.0));
    // The same as the built-in homogeneous road, which names the table.
    let homogeneous = load_with(
        "homogeneous",
        &Overrides {
            strategy: Some(StrategyKind::FLOW_AWARE),
            ..Overrides::default()
        },
    );
    assert_eq!(thresholds(homogeneous.unwrap()), (2750.0, 97.0));
    // A table's value out of range is reported as from the table (default).
    let dir = scratch_dir("range");
    std::fs::write(
        dir.join("t.toml"),
        "[[penetration]]\npenetration = 0\nflow_threshold_vphpl = 0\nspeed_threshold_kmh = 90\n",
    )
    .unwrap();
    let table = format!("strategy.thresholds_table={}", dir.join("t.toml").display());
    assert_eq!(
        problems(flow_aware(&[&table])),
        vec!["strategy.flow_threshold_vphpl = 0 (default): must be in (0, 10000] veh/h/lane"]
    );
}

#[test]
fn relative_table_paths_are_read_from_the_scenario_files_directory() {
    let dir = scratch_dir("relative");
    std::fs::create_dir_all(dir.join("tables")).unwrap();
    std::fs::write(
        dir.join("tables/scales.toml"),
        "[[penetration]]\npenetration = 0\ndemand_scale = 1.0\n\
         [[penetration]]\npenetration = 1\ndemand_scale = 1.4\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("tables/thresholds.toml"),
        "[[penetration]]\npenetration = 0.5\nflow_threshold_vphpl = 2100\nspeed_threshold_kmh = 88\n",
    )
    .unwrap();
    let text = SMALL_CORRIDOR
        .replace(
            "demand_scale = 1.0",
            "demand_scale_table = \"tables/scales.toml\"",
        )
        .replace(
            "kind = \"pd\"",
            "kind = \"flow-aware\"\nthresholds_table = \"tables/thresholds.toml\"",
        );
    let file = dir.join("corridor.toml");
    std::fs::write(&file, text.as_bytes()).unwrap();
    let c = load_with(&file.display().to_string(), &Overrides::default()).unwrap();
    assert!((c.road.network.as_ref().unwrap().demand_scale - 1.2).abs() < 1e-12);
    assert_eq!(c.strategy.kind, StrategyKind::FLOW_AWARE);
    let Some(thresholds) = c.strategy.thresholds else {
        panic!("{:?}", c.strategy)
    };
    assert_eq!(
        (
            thresholds.flow_threshold_vphpl,
            thresholds.speed_threshold_kmh
        ),
        (2100.0, 88.0)
    );
    // The same text without its directory does not find the tables.
    let e = from_toml(&text, "text", "t", &Overrides::default()).unwrap_err();
    let p: Vec<String> = e.problems().iter().map(|p| p.field.clone()).collect();
    assert_eq!(
        p,
        vec!["network.demand_scale_table", "strategy.thresholds_table"]
    );
}

fn scratch_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "platoonsim-scenario-tables-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
