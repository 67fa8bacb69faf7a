//! An on-ramp just downstream of the end of another acceleration lane of the same index
//! (issue 35 item 4): a vehicle waiting at that lane's end reaches with its body towards the
//! next merge point, and the insertion there must see it.

use platoonsim_sim::{run, Config, LaneExtent, Network, OnRamp};

/// Two through lanes (indices 1-2) over 3 km; on-ramp A at 1,000 m with a 20 m acceleration
/// lane (its vehicles wait at the wall at 1,020 m for a gap in a busy lane), on-ramp B at
/// 1,023 m entering the same lane index: B's vehicles (4 m long) would overlap A's.
fn close_ramps(seed: u64) -> Config {
    let mut cfg = Config::homogeneous(0.0, 0.0, 600.0, 0.0, seed);
    cfg.name = "close-ramps".into();
    cfg.road.lanes = 3;
    cfg.road.length_m = 3000.0;
    cfg.road.control_start_m = 0.0;
    cfg.road.control_end_m = 3000.0;
    let ramp = |name: &str, x: f64, accel: f64| OnRamp {
        name: name.into(),
        x_m: x,
        accel_lane_m: accel,
        ramp_length_m: 300.0,
        demand_vph: vec![900.0],
        meter: None,
        penetration: None,
    };
    cfg.road.network = Some(Network {
        origin_m: 0.0,
        through_lanes: (1..=2)
            .map(|lane| LaneExtent {
                lane,
                from_m: 0.0,
                to_m: 3000.0,
            })
            .collect(),
        on_ramps: vec![ramp("A", 1000.0, 20.0), ramp("B", 1023.0, 250.0)],
        off_ramps: Vec::new(),
        interval_s: 900.0,
        mainline_vph: vec![3600.0],
        demand_scale: 1.0,
        ramp_speed_kmh: 60.0,
        lane_speed_limits_kmh: Vec::new(),
        cross_lane_friction: None,
        behaviour: Vec::new(),
    });
    cfg.detectors = vec![platoonsim_sim::DetectorSpec::mainline("end", 2900.0)];
    cfg.measurement_detector = 0;
    cfg
}

#[test]
fn an_on_ramp_sees_a_vehicle_waiting_at_the_end_of_the_lane_before_it() {
    for seed in 1..=3 {
        let out = run(&close_ramps(seed), None).unwrap();
        assert_eq!(out.summary.collisions, 0, "seed {seed}");
        assert!(out.summary.vehicles_entered > 300, "seed {seed}");
    }
}
