//! The built-in `sr99-field` (issue 30 item 4): SR-99 at clock time with no shift, a detector
//! at every PeMS mainline station of the metadata inside the corridor named by its ID, every
//! ramp with a PeMS station counted under that ID.

use platoonsim_field::{pems, place, StationKind};
use platoonsim_scenario::{load, load_with, Overrides};
use platoonsim_sim::config::DetectorKind;
use std::path::PathBuf;

fn meta() -> Vec<platoonsim_field::StationMeta> {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/pems-sr99/d03_text_meta_2014_09_18.txt");
    pems::read_meta(&p).unwrap()
}

#[test]
fn sr99_field_runs_at_clock_time_without_a_shift() {
    let c = load("sr99-field").unwrap();
    c.check().unwrap();
    assert_eq!(c.clock_start_s, Some(5 * 3600));
    assert_eq!(
        (c.duration_s, c.warmup_s, c.penetration),
        (18000.0, 0.0, 0.0)
    );
    let n = c.road.network.as_ref().unwrap();
    // 20 intervals of 15 min, read as written (an offset would refine the interval).
    assert_eq!((n.interval_s, n.mainline_vph.len()), (900.0, 20));
    assert_eq!(n.demand_scale, 1.0);
    // The geometry is sr99's.
    let s = load("sr99").unwrap();
    let sn = s.road.network.as_ref().unwrap();
    assert_eq!(n.through_lanes, sn.through_lanes);
    let xs = |n: &platoonsim_sim::Network| -> Vec<f64> {
        n.on_ramps
            .iter()
            .map(|r| r.x_m)
            .chain(n.off_ramps.iter().map(|r| r.x_m))
            .collect()
    };
    assert_eq!(xs(n), xs(sn));
    // The paper's demand scale by penetration, as sr99.
    let o = Overrides {
        penetration: Some(0.6),
        ..Overrides::default()
    };
    let at60 = load_with("sr99-field", &o).unwrap();
    assert_eq!(at60.road.network.unwrap().demand_scale, 1.17);
}

#[test]
fn every_pems_mainline_station_in_the_corridor_has_a_detector_named_by_its_id() {
    let c = load("sr99-field").unwrap();
    let origin = c.road.network.as_ref().unwrap().origin_m;
    let placed = place::by_postmile(&meta(), 287.230, -500.0, 17160.0);
    let mainline: Vec<_> = placed
        .iter()
        .filter(|p| p.kind == StationKind::Mainline)
        .collect();
    assert_eq!(mainline.len(), 28);
    for p in mainline {
        let d = c
            .detectors
            .iter()
            .find(|d| d.name == p.station)
            .unwrap_or_else(|| panic!("no detector {}", p.station));
        assert_eq!(d.kind, DetectorKind::Mainline);
        // Positions in the file are rounded to 0.1 m.
        assert!(
            (d.position_m + origin - p.x_m).abs() <= 0.05,
            "{}: {} vs {}",
            p.station,
            d.position_m + origin,
            p.x_m
        );
    }
    // Ramp counters: 16 on-ramps and 7 off-ramps have a PeMS station.
    let on = c
        .detectors
        .iter()
        .filter(|d| matches!(d.kind, DetectorKind::OnRamp { .. }))
        .count();
    let named_off = c
        .detectors
        .iter()
        .filter(|d| matches!(d.kind, DetectorKind::OffRamp { .. }) && !d.name.ends_with("-off"))
        .count();
    assert_eq!((on, named_off), (16, 7));
    assert!(c
        .detectors
        .iter()
        .any(|d| d.name == "314107" && d.kind == DetectorKind::OnRamp { ramp: 0 }));
}
