//! The road sketch from the engine's geometry: a network with a lane drop, acceleration lanes,
//! a lane add, an off-ramp and a PD zone (the expectations of the viewer's own derivation,
//! which this replaced), the organized lane of each `strategy.pd.lane`, and the homogeneous
//! road.

use super::*;
use platoonsim_sim::config::{DetectorSpec, LaneExtent, Network, OffRamp, OnRamp, PdConfig};
use platoonsim_sim::Strategy;

fn piece(lane: u32, from_m: f64, to_m: f64) -> LanePiece {
    LanePiece { lane, from_m, to_m }
}

fn segment(lane: u32, from_m: f64, to_m: f64, accel: bool, ends: bool) -> Segment {
    Segment {
        lane,
        from_m,
        to_m,
        accel,
        ends,
    }
}

fn homogeneous() -> Config {
    platoonsim_scenario::load("homogeneous").unwrap()
}

fn on_ramp(name: &str, x_m: f64) -> OnRamp {
    OnRamp {
        name: name.into(),
        x_m,
        accel_lane_m: 250.0,
        ramp_length_m: 300.0,
        demand_vph: vec![100.0],
        meter: None,
        penetration: None,
    }
}

/// A corridor of `lanes` lateral positions over [0, 3000) engine metres, output coordinate
/// −500 at its entrance, with these through lanes `(engine index, from, to)` and ramps.
fn network(lanes: u32, through: &[(u32, f64, f64)], on: Vec<OnRamp>, off: Vec<OffRamp>) -> Config {
    let mut c = homogeneous();
    c.road.lanes = lanes;
    c.road.length_m = 3000.0;
    c.road.control_start_m = 0.0;
    c.road.control_end_m = 3000.0;
    c.road.network = Some(Network {
        origin_m: -500.0,
        through_lanes: through
            .iter()
            .map(|&(lane, from_m, to_m)| LaneExtent { lane, from_m, to_m })
            .collect(),
        on_ramps: on,
        off_ramps: off,
        interval_s: 900.0,
        mainline_vph: vec![1000.0],
        demand_scale: 1.0,
        ramp_speed_kmh: 90.0,
        lane_speed_limits_kmh: Vec::new(),
        cross_lane_friction: None,
        behaviour: Vec::new(),
    });
    c.detectors = vec![DetectorSpec::mainline("d", 100.0)];
    c.measurement_detector = 0;
    c
}

fn pd(zone_start_m: f64, zone_end_m: f64, lane: LaneChoice) -> Strategy {
    Strategy::pd(PdConfig {
        zone_start_m,
        zone_end_m,
        start_s: 0.0,
        end_s: 60.0,
        lane,
    })
}

#[test]
fn network_lanes_ramps_and_coordinates() {
    // Output lanes 2-4 from the entrance, lane 4 dropped at engine 2000 m, lane 1 added at
    // 2500 m by OR2; OR1 at 1000 m has an acceleration lane.
    let mut c = network(
        4,
        &[
            (1, 0.0, 3000.0),
            (2, 0.0, 3000.0),
            (3, 0.0, 2000.0),
            (0, 2500.0, 3000.0),
        ],
        vec![on_ramp("OR1: A St", 1000.0), on_ramp("OR2: B St", 2500.0)],
        vec![OffRamp {
            name: "FR1: C St".into(),
            x_m: 1500.0,
            exit_fraction: vec![0.1],
        }],
    );
    c.strategy = pd(0.0, 3000.0, LaneChoice::Leftmost);
    c.human.length_m.mean = 4.5;
    let r = road_sketch(&c).unwrap();
    assert_eq!(r.lanes, 4);
    // The leftmost through lane: output lane 4 until its drop at engine 2000 m, then 3.
    assert_eq!(
        r.organized,
        vec![piece(4, -500.0, 1500.0), piece(3, 1500.0, 2500.0)]
    );
    assert_eq!((r.origin_m, r.start_m, r.end_m), (-500.0, -500.0, 2500.0));
    // The lane drop of engine lane 3 (output 4) at 2000 m.
    assert!(r
        .segments
        .contains(&segment(4, -500.0, 1500.0, false, true)));
    // OR1: an acceleration lane at engine index 0 (output lane 1), 250 m long.
    assert!(r.segments.contains(&segment(1, 500.0, 750.0, true, true)));
    // The lane OR2 adds runs to the end, without a wall.
    assert!(r
        .segments
        .contains(&segment(1, 2000.0, 2500.0, false, false)));
    assert_eq!(r.segments.len(), 5, "{:?}", r.segments);
    assert_eq!(r.on_ramps[0].name, "OR1");
    assert_eq!((r.on_ramps[0].lane, r.on_ramps[0].end_m), (1, 750.0));
    assert!(!r.on_ramps[0].adds_lane);
    // OR2 adds the lane that starts at its merge point.
    assert!(r.on_ramps[1].adds_lane);
    assert_eq!((r.on_ramps[1].lane, r.on_ramps[1].end_m), (1, 2000.0));
    let off = &r.off_ramps[0];
    assert_eq!((off.name.as_str(), off.lane, off.x_m), ("FR1", 2, 1000.0));
    assert_eq!((off.end_m, off.adds_lane), (1000.0, false));
    assert_eq!(r.detectors[0].x_m, -400.0);
    assert_eq!(r.detectors[0].kind, DetectorKind::Mainline);
    assert_eq!(r.control_m, [-500.0, 2500.0]);
    assert_eq!(r.strategy, "pd");
    assert_eq!(r.pd_zone_m, Some([-500.0, 2500.0]));
    assert_eq!(r.pd_window_s, Some([0.0, 60.0]));
    assert_eq!(r.vehicle_length_m, 4.5);
}

#[test]
fn acceleration_lanes_end_where_the_engine_ends_them() {
    // Ramps a (300 m) and b (500 m) overlap: one auxiliary lane [300, 750) ending in a wall,
    // for both ramps. Ramp c (1200 m) runs on into the through lane of its index that starts
    // at 1300 m: no wall. (The viewer's own derivation drew a at [300, 550) with a bar at 550.)
    let c = network(
        3,
        &[(1, 0.0, 3000.0), (2, 0.0, 3000.0), (0, 1300.0, 3000.0)],
        vec![
            on_ramp("a", 300.0),
            on_ramp("b", 500.0),
            on_ramp("c", 1200.0),
        ],
        vec![],
    );
    let r = road_sketch(&c).unwrap();
    let accel: Vec<&Segment> = r.segments.iter().filter(|s| s.accel).collect();
    assert_eq!(
        accel,
        [
            &segment(1, -200.0, 250.0, true, true),
            &segment(1, 700.0, 800.0, true, false)
        ]
    );
    let ends: Vec<f64> = r.on_ramps.iter().map(|r| r.end_m).collect();
    assert_eq!(ends, [250.0, 250.0, 800.0]);
    assert!(r.off_ramps.is_empty() && r.organized.is_empty());
    assert_eq!((r.strategy.as_str(), r.pd_zone_m), ("none", None));
}

#[test]
fn the_organized_lane_follows_strategy_pd_lane() {
    // Output lanes 1 and 2 everywhere, 3 from engine 1000 m; the zone [500, 2000).
    let mut c = network(
        3,
        &[(0, 0.0, 3000.0), (1, 0.0, 3000.0), (2, 1000.0, 3000.0)],
        vec![],
        vec![],
    );
    let organized = |c: &mut Config, lane| {
        c.strategy = pd(500.0, 2000.0, lane);
        road_sketch(c).unwrap().organized
    };
    assert_eq!(
        organized(&mut c, LaneChoice::Rightmost),
        vec![piece(1, 0.0, 1500.0)]
    );
    assert_eq!(
        organized(&mut c, LaneChoice::Leftmost),
        vec![piece(2, 0.0, 500.0), piece(3, 500.0, 1500.0)]
    );
    // Engine index 2 (output lane 3), held within the through lanes: lane 2 before lane 3
    // opens.
    assert_eq!(
        organized(&mut c, LaneChoice::Index(2)),
        vec![piece(2, 0.0, 500.0), piece(3, 500.0, 1500.0)]
    );
    // Engine index 1 is open throughout: one piece.
    assert_eq!(
        organized(&mut c, LaneChoice::Index(1)),
        vec![piece(2, 0.0, 1500.0)]
    );
}

#[test]
fn the_homogeneous_road_is_its_lanes_over_its_length() {
    let mut c = homogeneous();
    // A zone past the road's end is drawn to the end only.
    c.strategy = pd(5000.0, 9000.0, LaneChoice::Leftmost);
    let r = road_sketch(&c).unwrap();
    let n = c.road.lanes;
    let length = c.road.length_m;
    assert_eq!((r.origin_m, r.start_m, r.end_m), (0.0, 0.0, length));
    assert_eq!(r.lanes, n);
    let want: Vec<Segment> = (1..=n)
        .map(|l| segment(l, 0.0, length, false, false))
        .collect();
    assert_eq!(r.segments, want);
    assert!(r.on_ramps.is_empty() && r.off_ramps.is_empty());
    assert_eq!(r.organized, vec![piece(n, 5000.0, length)]);
    assert_eq!(r.pd_zone_m, Some([5000.0, 9000.0]));
    assert_eq!(r.control_m, [c.road.control_start_m, c.road.control_end_m]);
    let names: Vec<&str> = r.detectors.iter().map(|d| d.name.as_str()).collect();
    let want: Vec<&str> = c.detectors.iter().map(|d| d.name.as_str()).collect();
    assert_eq!(names, want);
    assert_eq!((r.name.as_str(), r.seed), (c.name.as_str(), c.seed));
    assert_eq!(r.vehicle_length_m, 4.0);
}

#[test]
fn sr99_sketches_its_corridor() {
    let c = platoonsim_scenario::load("sr99").unwrap();
    let r = road_sketch(&c).unwrap();
    let n = c.road.network.as_ref().unwrap();
    assert_eq!(r.on_ramps.len(), n.on_ramps.len());
    assert_eq!(r.off_ramps.len(), n.off_ramps.len());
    assert_eq!(r.lanes, c.road.lanes);
    assert_eq!(r.origin_m, n.origin_m);
    assert!(r.on_ramps.iter().all(|r| r.name.starts_with("OR")));
    // Every stretch lies on the road, and every off-ramp counter is an off-ramp detector.
    for s in &r.segments {
        assert!(s.from_m >= r.start_m && s.from_m < s.to_m, "{s:?}");
        assert!(s.accel || s.to_m <= r.end_m, "{s:?}");
    }
    assert!(r
        .detectors
        .iter()
        .any(|d| d.kind == DetectorKind::OffRamp && d.name.ends_with("-off")));
}
