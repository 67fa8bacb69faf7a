//! Section behaviour (`[[network.behaviour]]`, issue 45 item 1): defaults, checks, write-back,
//! and the calibration example's corridor that uses it.

mod common;

use common::*;
use platoonsim_scenario::{load, to_toml};

const SMALL_CORRIDOR: &str = include_str!("fixtures/small_corridor.toml");

fn corridor_problems(sets: &[&str]) -> Vec<String> {
    problems(with_set(SMALL_CORRIDOR, sets))
}

#[test]
fn section_behaviour_is_off_by_default_checked_and_written_back() {
    // Issue 45 item 1: `[[network.behaviour]]`, corridor coordinates in the file, engine
    // coordinates (x − start_m) inside; factors default to 1.
    let c = parse(SMALL_CORRIDOR).unwrap();
    assert!(c.road.network.as_ref().unwrap().behaviour.is_empty());
    assert!(!to_toml(&c).contains("behaviour"));
    let set = "network.behaviour=[{from_m = 500, to_m = 1500, buffer_factor = 1.3}, \
               {from_m = 2000, to_m = 3000, speed_factor = 0.9}]";
    let c = with_set(SMALL_CORRIDOR, &[set]).unwrap();
    let b = &c.road.network.as_ref().unwrap().behaviour;
    assert_eq!(b.len(), 2);
    assert_eq!(
        (
            b[0].from_m,
            b[0].to_m,
            b[0].buffer_factor,
            b[0].speed_factor
        ),
        (700.0, 1700.0, 1.3, 1.0)
    );
    assert_eq!(
        (
            b[1].from_m,
            b[1].to_m,
            b[1].buffer_factor,
            b[1].speed_factor
        ),
        (2200.0, 3200.0, 1.0, 0.9)
    );
    let back = parse(&to_toml(&c)).unwrap();
    assert_eq!(back.road.network.as_ref().unwrap().behaviour, *b);
    // One key of a stretch, as `calibrate` fits it.
    let c = with_set(
        SMALL_CORRIDOR,
        &[set, "network.behaviour[1].speed_factor=0.8"],
    )
    .unwrap();
    assert_eq!(
        c.road.network.as_ref().unwrap().behaviour[1].speed_factor,
        0.8
    );
}

#[test]
fn section_behaviour_stretches_are_refused_when_they_overlap_or_leave_their_ranges() {
    let p = corridor_problems(&["network.behaviour=[{from_m = 500, to_m = 1500}, \
         {from_m = 1400, to_m = 2000, buffer_factor = 5.5, speed_factor = 0}]"]);
    assert_eq!(
        p,
        vec![
            "network.behaviour[1].from_m = 1400: must be at or after network.behaviour[0].to_m \
             = 1500: the stretches must be in order and not overlap",
            "network.behaviour[1].buffer_factor = 5.5: must be in [0, 5] (1 = as elsewhere)",
            "network.behaviour[1].speed_factor = 0: must be in [0.5, 1.5] (1 = as elsewhere)",
        ]
    );
    let p = corridor_problems(&["network.behaviour=[{from_m = -500, to_m = 100}, \
         {from_m = 900, to_m = 800}, {to_m = 2900, buffer_factor = nan}]"]);
    assert_eq!(
        p,
        vec![
            "network.behaviour[0].from_m = -500: the stretch [-500, 100) must lie inside the \
             corridor [network.start_m, network.end_m) = [-200, 3000)",
            "network.behaviour[1].to_m = 800: must be > network.behaviour[1].from_m = 900",
            "network.behaviour[2].from_m = (missing): required: start of the stretch (m)",
            "network.behaviour[2].buffer_factor = nan: must be in [0, 5] (1 = as elsewhere)",
        ]
    );
}

#[test]
fn the_calibration_example_corridor_loads_with_its_stretch() {
    let c = load(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/calibrate/corridor.toml"
    ))
    .unwrap();
    let n = c.road.network.as_ref().unwrap();
    assert_eq!(n.behaviour.len(), 1);
    assert_eq!(
        (n.behaviour[0].from_m, n.behaviour[0].to_m),
        (1000.0, 3000.0)
    );
    assert_eq!(c.clock_start_s, Some(7 * 3600));
}
