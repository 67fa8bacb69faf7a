//! Room for a vehicle at merge points and lane ends, and the warnings for legal geometry known
//! to collide (issue 35 item 4).

mod common;

use common::*;
use platoonsim_scenario::validate::warnings;

const CORRIDOR: &str = include_str!("fixtures/small_corridor.toml");

/// The small corridor with `old` replaced by `new` (which must occur).
fn patched(old: &str, new: &str) -> String {
    assert!(CORRIDOR.contains(old), "{old}");
    CORRIDOR.replacen(old, new, 1)
}

const FIRST_RAMP: &str = "x_m = 0.0\nramp_length_m = 300.0            # accel_lane_m defaults to 250\ndemand_vph = [400, 600]\n";

/// First St with an acceleration lane of `accel` m, then a ramp "Close" at `x` m.
fn with_close_ramp(accel: f64, x: f64) -> String {
    patched(
        FIRST_RAMP,
        &format!(
            "x_m = 0.0\nramp_length_m = 300.0\naccel_lane_m = {accel}\ndemand_vph = [400, 600]\n\n\
             [[network.on_ramps]]\nid = \"C\"\nname = \"Close\"\nx_m = {x}\nramp_length_m = 100.0\n\
             demand_vph = [300, 300]\n"
        ),
    )
}

#[test]
fn merge_points_closer_than_a_vehicle_are_refused() {
    let p = problems(parse(&with_close_ramp(250.0, 3.0)));
    assert_eq!(
        p,
        vec![
            "network.on_ramps[1].x_m = 3: must be at least 4 m (the longest vehicle, \
             human.length_m.max) downstream of network.on_ramps[0].x_m = 0: merge points closer \
             than a vehicle leave no room to enter"
        ]
    );
    // A vehicle length apart is accepted.
    parse(&with_close_ramp(250.0, 4.0)).unwrap();
}

#[test]
fn a_merge_point_just_after_the_end_of_its_lane_is_refused() {
    // First St's acceleration lane ends at 60 m; Close merges into the same lateral lane 3 m on.
    let p = problems(parse(&with_close_ramp(60.0, 63.0)));
    assert_eq!(
        p,
        vec![
            "network.on_ramps[1].x_m = 63: must be at least 4 m (the longest vehicle, \
             human.length_m.max) downstream of the end of the lane it enters (lateral lane 1, \
             ending at 60 m): a vehicle waiting at that end reaches into the merge point"
        ]
    );
    parse(&with_close_ramp(60.0, 64.0)).unwrap();
}

#[test]
fn an_acceleration_lane_shorter_than_a_vehicle_is_refused() {
    let text = patched(
        FIRST_RAMP,
        "x_m = 0.0\nramp_length_m = 300.0\naccel_lane_m = 2\ndemand_vph = [400, 600]\n",
    );
    let p = problems(parse(&text));
    assert_eq!(
        p,
        vec![
            "network.on_ramps[0].accel_lane_m = 2: must be at least 4 m (the longest vehicle, \
             human.length_m.max): a shorter acceleration lane leaves an entering vehicle no room"
        ]
    );
}

#[test]
fn a_lane_open_over_less_than_a_vehicle_is_refused() {
    let text = patched(
        "from_m = -200.0\nto_m = 1500.0\ncount = 2\n",
        "from_m = -200.0\nto_m = 1000.0\ncount = 2\n\n[[network.lanes]]\nfrom_m = 1000.0\n\
         to_m = 1002.0\ncount = 3\n\n[[network.lanes]]\nfrom_m = 1002.0\nto_m = 1500.0\ncount = 2\n",
    );
    let p = problems(parse(&text));
    assert_eq!(p.len(), 1, "{p:?}");
    assert!(
        p[0].starts_with(
            "network.lanes = lateral lane 1 open over [1000, 1002) m: a lane that ends \
                          must be open over at least 4 m"
        ),
        "{p:?}"
    );
}

#[test]
fn a_lane_drop_after_an_on_ramp_and_a_short_acceleration_lane_are_warned_about() {
    assert_eq!(warnings(&parse(CORRIDOR).unwrap()), Vec::<String>::new());
    // Three lanes to 100 m (one dropped 100 m after First St), First St's lane 30 m long.
    let text = patched(
        "from_m = -200.0\nto_m = 1500.0\ncount = 2\n",
        "from_m = -200.0\nto_m = 100.0\ncount = 3\n\n[[network.lanes]]\nfrom_m = 100.0\n\
         to_m = 1500.0\ncount = 2\n",
    )
    .replacen(
        "ramp_length_m = 300.0            # accel_lane_m defaults to 250",
        "ramp_length_m = 300.0\naccel_lane_m = 30",
        1,
    );
    let w = warnings(&parse(&text).unwrap());
    assert_eq!(
        w,
        vec![
            "network.on_ramps[0] (OR1: First St) merges at 0 m, 100 m upstream of a lane drop \
             (lateral lane 1 ends at 100 m): a lane drop within 300 m downstream of an on-ramp \
             is known to collide; move one of them",
            "network.on_ramps[0] (OR1: First St) at 0 m: an acceleration lane of 30 m (under \
             50 m) gives merging vehicles little room and is known to collide"
        ]
    );
}
