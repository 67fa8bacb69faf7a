//! The built-in `sr99` corridor (issue 4): its geometry, ramps, demand and detectors against
//! the data folder, the demand scale by penetration, and its strategy defaults.

mod common;

use common::*;
use platoonsim_scenario::{
    demand_scale_set, demand_scales, from_toml, load_with, Overrides, StrategyKind,
};
use platoonsim_sim::config::DetectorKind;
use platoonsim_sim::Strategy;

const SR99: &str = include_str!("../scenarios/sr99.toml");

#[test]
fn sr99_is_the_corridor_of_the_data() {
    let c = load_with("sr99", &Overrides::default()).unwrap();
    c.check().unwrap();
    assert_eq!(c.name, "sr99");
    assert_eq!(
        (c.duration_s, c.warmup_s, c.penetration),
        (14400.0, 0.0, 0.0)
    );
    assert_eq!(c.road.lanes, 6);
    assert_eq!(c.road.length_m, 17660.0);
    assert_eq!(
        (c.road.control_start_m, c.road.control_end_m),
        (0.0, 17660.0)
    );
    assert_eq!(c.demand.vph_per_lane, 0.0);
    let n = c.road.network.as_ref().unwrap();
    assert_eq!(n.origin_m, -500.0);
    assert_eq!(n.on_ramps.len(), 16);
    assert_eq!(n.off_ramps.len(), 11);
    // The field's 16 intervals from 05:00, read 30 min later (network.demand_offset_s = 1800):
    // the run starts with the 05:30 interval and holds the last one (08:45) past 08:30.
    assert_eq!(n.interval_s, 900.0);
    assert_eq!(n.mainline_vph.len(), 14);
    assert_eq!(n.mainline_vph[0], 2100.0);
    assert_eq!(n.mainline_vph[13], 2390.0);
    // Calibrated base multiplier 1.10 (docs/calibration.md) × the paper's scale 1.00 at 0 %.
    assert_eq!(n.demand_scale, 1.1);
    assert_eq!(n.ramp_speed_kmh, 90.0);
    // HOV lane open to all: 3 lanes, 4 from the Calvine WB on-ramp, 5 from the Fruitridge WB one.
    assert_eq!(
        n.through_lanes,
        vec![
            ext(1, 15552.0, 17660.0),
            ext(2, 6234.0, 17660.0),
            ext(3, 0.0, 17660.0),
            ext(4, 0.0, 17660.0),
            ext(5, 0.0, 17660.0),
        ]
    );
    let or1 = &n.on_ramps[0];
    assert_eq!(or1.name, "OR1: Elk Grove Blvd");
    assert_eq!(
        (or1.x_m, or1.accel_lane_m, or1.ramp_length_m),
        (500.0, 250.0, 320.7)
    );
    assert_eq!(n.on_ramps[6].x_m, 6234.0); // Calvine Rd WB: the lane add
                                           // 250 m everywhere except the two lengths read from the PATH composite lane numbers.
    let accel: Vec<f64> = n.on_ramps.iter().map(|r| r.accel_lane_m).collect();
    let mut expected = vec![250.0; 16];
    expected[10] = 440.0; // OR11 Florin Rd WB
    expected[13] = 346.0; // OR14 Fruitridge Rd EB: auxiliary lane into the lane add
    assert_eq!(accel, expected);
    assert!(n.on_ramps.iter().all(|r| r.demand_vph.len() == 14));
    assert_eq!(n.on_ramps[0].demand_vph[0], 270.0); // OR1 at 05:30
    assert_eq!(n.off_ramps[0].name, "FR1: Laguna Blvd/Bond Rd");
    assert_eq!(n.off_ramps[0].x_m, 1700.0);
    assert_eq!(n.off_ramps[0].exit_fraction[0], 0.026); // FR1 at 05:30
    assert!(n.off_ramps.iter().all(|r| r.exit_fraction.len() == 14));

    // Detectors: up/down around every ramp, end, and one per off-ramp.
    let exits: Vec<&str> = c
        .detectors
        .iter()
        .filter(|d| d.exit)
        .map(|d| d.name.as_str())
        .collect();
    assert_eq!(exits.len(), 12);
    assert_eq!(exits[0], "end");
    assert_eq!(exits[1], "FR1-off");
    let off: Vec<usize> = c
        .detectors
        .iter()
        .filter_map(|d| match d.kind {
            DetectorKind::OffRamp { ramp } => Some(ramp),
            DetectorKind::Mainline | DetectorKind::OnRamp { .. } => None,
        })
        .collect();
    assert_eq!(off, (0..11).collect::<Vec<_>>());
    let mainline: Vec<_> = c
        .detectors
        .iter()
        .filter(|d| d.kind == DetectorKind::Mainline)
        .collect();
    // 16 × 2 + 11 up + end, no coincident positions on this corridor.
    assert_eq!(mainline.len(), 16 * 2 + 11 + 1);
    assert!(mainline
        .windows(2)
        .all(|w| w[0].position_m < w[1].position_m));
    assert_eq!(
        names(&c)[..5],
        ["OR1-up", "OR1-down", "FR1-up", "OR2-up", "OR2-down"]
    );
    let pos = |name: &str| {
        c.detectors
            .iter()
            .find(|d| d.name == name)
            .unwrap()
            .position_m
    };
    assert_eq!(pos("OR1-up"), 450.0);
    assert_eq!(pos("OR3-down"), 2548.0);
    assert_eq!(pos("FR2-up"), 3427.0);
    assert_eq!(pos("end"), 17650.0);
    assert_eq!(c.detectors[c.measurement_detector].name, "end");
    assert_eq!(c.aggregation_s, 300.0);
    assert_eq!(c.strategy, Strategy::none());
}

#[test]
fn sr99_demand_scale_follows_the_penetration_unless_given() {
    let at = |p: f64, scale: Option<f64>| {
        let mut o = Overrides {
            penetration: Some(p),
            ..Overrides::default()
        };
        if let Some(s) = scale {
            o.set.push(demand_scale_set(s));
        }
        load_with("sr99", &o)
            .unwrap()
            .road
            .network
            .unwrap()
            .demand_scale
    };
    // Engine scale = the calibrated base multiplier 1.10 × the run's scale.
    let base = 1.1;
    assert_eq!(at(0.4, None), base * 1.1);
    assert_eq!(at(1.0, None), base * 1.27);
    let table = demand_scales::embedded();
    assert_eq!(
        at(0.5, None),
        base * demand_scales::at(&table, 0.5, demand_scales::FALLBACK)
    );
    assert!((at(0.5, None) - base * 1.135).abs() < 1e-12);
    assert_eq!(at(0.5, Some(1.3)), base * 1.3);
    // The base multiplier multiplies the scale.
    let c = from_toml(
        &SR99.replace(
            "base_demand_multiplier = 1.10",
            "base_demand_multiplier = 1.5",
        ),
        "t",
        "t",
        &Overrides {
            penetration: Some(0.8),
            ..Overrides::default()
        },
    )
    .unwrap();
    assert_eq!(c.road.network.unwrap().demand_scale, 1.5 * 1.25);
}

#[test]
fn sr99_strategy_zone_and_window_default_to_the_whole_corridor_and_run() {
    for kind in [StrategyKind::PD, StrategyKind::FLOW_AWARE] {
        let c = load_with(
            "sr99",
            &Overrides {
                strategy: Some(kind),
                penetration: Some(0.5),
                ..Overrides::default()
            },
        )
        .unwrap();
        if let Some(thresholds) = &c.strategy.thresholds {
            assert_eq!(thresholds.radius_m, 1500.0);
        }
        let pd = c.strategy.pd.unwrap();
        assert_eq!((pd.zone_start_m, pd.zone_end_m), (0.0, 17660.0));
        assert_eq!((pd.start_s, pd.end_s), (0.0, 14400.0));
    }
    // Given in the corridor coordinate, converted.
    let c = with_set(
        SR99,
        &[
            "strategy.kind=pd",
            "strategy.zone_start_m=10000",
            "strategy.zone_end_m=12000",
        ],
    )
    .unwrap();
    let pd = c.strategy.pd.unwrap();
    assert_eq!((pd.zone_start_m, pd.zone_end_m), (10500.0, 12500.0));
}
