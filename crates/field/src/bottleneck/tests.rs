use super::matching::all_within;
use super::*;

fn placed(station: &str, x_m: f64, kind: StationKind) -> Placed {
    Placed {
        station: station.into(),
        x_m,
        kind,
        lanes: 4,
        name: String::new(),
    }
}

const SIX: u32 = 6 * 3600;

/// 5-min speeds from 06:00 for 36 intervals; `f(k)` gives the speed of interval k.
fn series(station: &str, f: impl Fn(u32) -> Option<f64>) -> Vec<Obs> {
    (0..36)
        .map(|k| Obs {
            station: station.into(),
            start_s: SIX + 300 * k,
            interval_s: 300,
            flow_vph: 4000.0,
            speed_kmh: f(k),
            occupancy: Some(0.1),
        })
        .collect()
}

/// A, B upstream; C, D downstream. B is congested (40 km/h) 07:00-08:00 (k = 12..24) except
/// a 2-interval recovery (k = 16, 17), and for 2 intervals at k = 30, 31; A is congested
/// with it (no rise between A and B); C and D flow freely (100 km/h).
fn corridor() -> (Vec<Obs>, Vec<Placed>) {
    let jam = |k: u32| (12..24).contains(&k) && !(16..18).contains(&k) || (30..32).contains(&k);
    let obs = [
        series("A", |k| Some(if jam(k) { 45.0 } else { 100.0 })),
        series("B", |k| Some(if jam(k) { 40.0 } else { 100.0 })),
        series("C", |_| Some(100.0)),
        series("D", |_| Some(100.0)),
        series("R", |_| Some(10.0)),
    ]
    .concat();
    let places = vec![
        placed("D", 3000.0, StationKind::Mainline),
        placed("B", 1000.0, StationKind::Mainline),
        placed("R", 1500.0, StationKind::OnRamp),
        placed("C", 2000.0, StationKind::Mainline),
        placed("A", 0.0, StationKind::Mainline),
    ];
    (obs, places)
}

#[test]
fn chen_defaults_in_kmh() {
    let p = Params::default();
    assert!((p.upstream_max_kmh - 64.373_76).abs() < 1e-9);
    assert!((p.min_rise_kmh - 32.186_88).abs() < 1e-9);
}

#[test]
fn onset_and_clearance_on_a_synthetic_speed_field() {
    let (obs, places) = corridor();
    let b = identify(&obs, &places, &Params::default());
    assert_eq!(
        b,
        vec![Bottleneck {
            upstream: "B".into(),
            downstream: "C".into(),
            x_m: 1500.0,
            onset_s: 7 * 3600,
            clearance_s: 8 * 3600,
            // 12 intervals, 2 of them the bridged recovery.
            active_minutes: 50.0,
        }]
    );
}

#[test]
fn longer_gaps_split_and_short_episodes_are_dropped() {
    let (obs, places) = corridor();
    let p = Params {
        max_gap_intervals: 1,
        min_active_intervals: 2,
        ..Params::default()
    };
    let b = identify(&obs, &places, &p);
    let spans: Vec<(u32, u32)> = b.iter().map(|b| (b.onset_s, b.clearance_s)).collect();
    assert_eq!(
        spans,
        [
            (SIX + 12 * 300, SIX + 16 * 300),
            (SIX + 18 * 300, SIX + 24 * 300),
            (SIX + 30 * 300, SIX + 32 * 300)
        ]
    );
}

#[test]
fn thresholds_are_strict_below_and_inclusive_on_the_rise() {
    let p = Params {
        upstream_max_kmh: 60.0,
        min_rise_kmh: 30.0,
        min_active_intervals: 1,
        ..Params::default()
    };
    let places = [
        placed("U", 0.0, StationKind::Mainline),
        placed("D", 500.0, StationKind::Mainline),
    ];
    let run = |up: f64, down: f64| {
        let obs = [
            series("U", |k| Some(if k == 5 { up } else { 100.0 })),
            series("D", |_| Some(down)),
        ]
        .concat();
        identify(&obs, &places, &p).len()
    };
    assert_eq!(run(50.0, 80.0), 1);
    assert_eq!(run(50.0, 79.0), 0);
    assert_eq!(run(60.0, 95.0), 0);
    assert_eq!(run(59.0, 95.0), 1);
}

#[test]
fn a_standing_queue_counts_as_speed_zero_and_no_data_as_inactive() {
    let p = Params {
        min_active_intervals: 1,
        ..Params::default()
    };
    let places = [
        placed("U", 0.0, StationKind::Mainline),
        placed("D", 500.0, StationKind::Mainline),
    ];
    let mut up = series("U", |k| if k == 5 { None } else { Some(100.0) });
    let down = series("D", |_| Some(100.0));
    let obs = [up.clone(), down.clone()].concat();
    assert!(identify(&obs, &places, &p).is_empty());
    up[5].occupancy = Some(0.8);
    let obs = [up, down].concat();
    let b = identify(&obs, &places, &p);
    assert_eq!(b.len(), 1);
    assert_eq!(b[0].onset_s, SIX + 5 * 300);
}

fn bn(x_m: f64, onset_min: u32, clear_min: u32) -> Bottleneck {
    Bottleneck {
        upstream: "u".into(),
        downstream: "d".into(),
        x_m,
        onset_s: onset_min * 60,
        clearance_s: clear_min * 60,
        active_minutes: f64::from(clear_min - onset_min),
    }
}

#[test]
fn matching_by_place_and_time() {
    let p = MatchParams::default();
    let field = [bn(5000.0, 420, 480), bn(5000.0, 960, 1080)];
    // Morning within tolerance (+10, +5 min, 1 km away); evening onset 20 min late.
    let sim = [bn(6000.0, 430, 485), bn(5200.0, 980, 1080)];
    let pairs = compare(&sim, &field, &p);
    assert_eq!(pairs.len(), 2);
    assert_eq!(pairs[0].distance_m, Some(1000.0));
    assert_eq!(pairs[0].onset_diff_min, Some(10.0));
    assert_eq!(pairs[0].clearance_diff_min, Some(5.0));
    assert!(pairs[0].within);
    assert_eq!(pairs[1].onset_diff_min, Some(20.0));
    assert!(!pairs[1].within);
    assert!(!all_within(&pairs));
    assert!(all_within(&pairs[..1]));

    // Too far (1,600 m): both are left alone, and the fit fails.
    let pairs = compare(&[bn(6600.0, 420, 480)], &field[..1], &p);
    assert_eq!(pairs.len(), 2);
    assert!(pairs[0].field.is_some() && pairs[0].sim.is_none());
    assert!(pairs[1].sim.is_some() && pairs[1].field.is_none());
    assert!(!all_within(&pairs));
    // Nothing on either side agrees.
    assert!(all_within(&compare(&[], &[], &p)));
}

#[test]
fn the_nearest_candidate_wins() {
    let field = [bn(5000.0, 420, 480)];
    let sim = [bn(6200.0, 420, 480), bn(4700.0, 425, 480)];
    let pairs = compare(&sim, &field, &MatchParams::default());
    assert_eq!(pairs[0].distance_m, Some(-300.0));
    assert!(pairs[0].within);
    assert!(pairs[1].sim.is_some() && !pairs[1].within);
}
