//! Stations from a table, the selection report, and aggregation with missing intervals.

use std::path::{Path, PathBuf};

use platoonsim_field::aggregate::{self, Missing};
use platoonsim_field::{place, FieldError, Obs, Placed, StationKind};

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn obs(station: &str, start_s: u32, flow: f64, speed: Option<f64>, occ: Option<f64>) -> Obs {
    Obs {
        station: station.into(),
        start_s,
        interval_s: 300,
        flow_vph: flow,
        speed_kmh: speed,
        occupancy: occ,
    }
}

#[test]
fn a_table_places_stations_sorted_by_x() {
    let dir = tempfile::tempdir().unwrap();
    let text = "kind,x_m,station,name,lanes\n\
                OR,500,r1,\"Ramp, east\",1\n\
                ML,104.6,313190,Elk Grove Blvd,2\n\
                FF,500,f0,,\n";
    let placed = place::from_table(&write(dir.path(), "p.csv", text)).unwrap();
    let got: Vec<(&str, f64, StationKind, u32, &str)> = placed
        .iter()
        .map(|p| {
            (
                p.station.as_str(),
                p.x_m,
                p.kind.clone(),
                p.lanes,
                p.name.as_str(),
            )
        })
        .collect();
    assert_eq!(
        got,
        [
            ("313190", 104.6, StationKind::Mainline, 2, "Elk Grove Blvd"),
            ("f0", 500.0, StationKind::FreewayConnector, 0, ""),
            ("r1", 500.0, StationKind::OnRamp, 1, "Ramp, east"),
        ]
    );
    let minimal =
        place::from_table(&write(dir.path(), "q.csv", "station,x_m,kind\na,1,HV\n")).unwrap();
    assert_eq!(minimal[0].kind, StationKind::Hov);
}

#[test]
fn table_errors_name_file_line_field_and_value() {
    let dir = tempfile::tempdir().unwrap();
    let e = place::from_table(&write(dir.path(), "p.csv", "station,x,kind\na,1,ML\n")).unwrap_err();
    assert!(matches!(e, FieldError::Header { line: 1, .. }), "{e:?}");
    assert!(e.to_string().contains("no column x_m"), "{e}");
    for (row, field, value, allowed) in [
        ("a,1,XX", "kind", "XX", "ML, OR, FR, HV, FF"),
        ("a,1 km,ML", "x_m", "1 km", "metres"),
        ("a,1,ML,two", "lanes", "two", "whole number"),
        ("b,1,ML", "station", "b", "once"),
    ] {
        let text = format!("station,x_m,kind,lanes\nb,0,ML,\n{row}\n");
        let e = place::from_table(&write(dir.path(), "p.csv", &text)).unwrap_err();
        let msg = e.to_string();
        for part in ["p.csv", "line 3", field, value, allowed] {
            assert!(msg.contains(part), "{part:?} not in {msg:?}");
        }
    }
}

fn placed(id: &str) -> Placed {
    Placed {
        station: id.into(),
        x_m: 0.0,
        kind: StationKind::Mainline,
        lanes: 2,
        name: String::new(),
    }
}

#[test]
fn select_keeps_placed_rows_and_reports_the_rest() {
    let rows = [
        obs("z", 0, 1.0, None, None),
        obs("a", 0, 2.0, None, None),
        obs("y", 0, 3.0, None, None),
        obs("a", 300, 4.0, None, None),
    ];
    let sel = place::select(&rows, &[placed("a"), placed("held-out")]);
    assert_eq!(sel.obs, [rows[1].clone(), rows[3].clone()]);
    assert_eq!(sel.ignored_stations, ["y", "z"]);
    assert_eq!(sel.without_data, ["held-out"]);
    // Ignored stations are listed sorted, whatever the order of the rows.
    let many: Vec<Obs> = ["q", "d", "x", "b", "m", "c", "w", "e"]
        .iter()
        .map(|s| obs(s, 0, 1.0, None, None))
        .collect();
    let sel = place::select(&many, &[placed("m")]);
    assert_eq!(sel.ignored_stations, ["b", "c", "d", "e", "q", "w", "x"]);

    assert!(place::require(&[placed("a")], &["a"]).is_ok());
    let e = place::require(&[placed("a"), placed("b")], &["a", "q", "r"]).unwrap_err();
    assert!(matches!(e, FieldError::UnknownStation { .. }), "{e:?}");
    assert_eq!(
        e.to_string(),
        "station(s) q, r not in the stations placed on the corridor; known: a, b"
    );
}

#[test]
fn three_5_minute_intervals_make_one_15_minute_interval() {
    // 07:00-07:15: 100, 50 and 0 vehicles in 5 min (1200, 600, 0 veh/h).
    let rows = [
        obs("a", 25_500, 600.0, Some(60.0), Some(0.2)),
        obs("a", 25_200, 1200.0, Some(90.0), Some(0.1)),
        obs("a", 25_800, 0.0, None, Some(0.0)),
    ];
    let q = aggregate::to_interval(&rows, 900);
    assert_eq!(q.len(), 1);
    assert_eq!(
        (q[0].station.as_str(), q[0].start_s, q[0].interval_s),
        ("a", 25_200, 900)
    );
    assert_eq!(q[0].flow_vph, 600.0);
    // Flow-weighted: (1200 × 90 + 600 × 60) / 1800 = 80 (the plain mean would be 75).
    assert_eq!(q[0].speed_kmh, Some(80.0));
    assert!((q[0].occupancy.unwrap() - 0.1).abs() < 1e-15);
    assert!(aggregate::missing(&rows, 25_200, 26_100, 900).is_empty());
}

#[test]
fn speed_falls_back_to_the_plain_mean_without_vehicles_and_needs_every_speed() {
    let idle = [
        obs("a", 0, 0.0, Some(100.0), None),
        obs("a", 300, 0.0, Some(70.0), None),
    ];
    let q = aggregate::to_interval(&idle, 600);
    assert_eq!(q[0].speed_kmh, Some(85.0));
    assert_eq!(q[0].occupancy, None);
    let unknown = [
        obs("a", 0, 600.0, Some(100.0), None),
        obs("a", 300, 60.0, None, None),
    ];
    let q = aggregate::to_interval(&unknown, 600);
    assert_eq!(q[0].speed_kmh, None);
    assert_eq!(q[0].flow_vph, 330.0);
}

#[test]
fn a_missing_sub_interval_makes_no_aggregate_and_is_listed() {
    // b lacks 07:05; a is complete over 07:00-07:15 but lacks 07:15-07:30.
    let rows = [
        obs("b", 25_200, 100.0, Some(80.0), Some(0.1)),
        obs("a", 25_200, 100.0, Some(80.0), Some(0.1)),
        obs("a", 25_500, 100.0, Some(80.0), Some(0.1)),
        obs("a", 25_800, 100.0, Some(80.0), Some(0.1)),
        obs("b", 25_800, 100.0, Some(80.0), Some(0.1)),
    ];
    let q = aggregate::to_interval(&rows, 900);
    let got: Vec<(&str, u32)> = q.iter().map(|o| (o.station.as_str(), o.start_s)).collect();
    assert_eq!(got, [("a", 25_200)]);
    let miss = |station: &str, start_s: u32| Missing {
        station: station.into(),
        start_s,
    };
    assert_eq!(
        aggregate::missing(&rows, 25_200, 27_000, 900),
        [miss("a", 26_100), miss("b", 25_200), miss("b", 26_100)]
    );
    // At 5 min: b's 07:05 and every 5-minute interval of 07:15-07:30.
    assert_eq!(
        aggregate::missing(&rows, 25_200, 27_000, 300),
        [
            miss("a", 26_100),
            miss("a", 26_400),
            miss("a", 26_700),
            miss("b", 25_500),
            miss("b", 26_100),
            miss("b", 26_400),
            miss("b", 26_700),
        ]
    );
    // Only intervals that end by the window's end are asked for (07:15-07:20 ends after 26 399),
    // from the first multiple of the interval at or after its start.
    assert_eq!(
        aggregate::missing(&rows, 25_001, 26_399, 300),
        [miss("b", 25_500)]
    );
    // A missing last sub-interval (d has 07:00 and 07:05 only) makes no aggregate either.
    let head = [
        obs("d", 25_200, 1.0, None, None),
        obs("d", 25_500, 1.0, None, None),
    ];
    assert!(aggregate::to_interval(&head, 900).is_empty());
    assert_eq!(
        aggregate::missing(&head, 25_200, 26_100, 900),
        [miss("d", 25_200)]
    );
    // Misaligned rows (07:02) never tile an aligned interval.
    let off = [
        obs("c", 25_320, 1.0, None, None),
        obs("c", 25_620, 1.0, None, None),
        obs("c", 25_920, 1.0, None, None),
    ];
    assert!(aggregate::to_interval(&off, 900).is_empty());
    assert_eq!(
        aggregate::missing(&off, 25_200, 26_100, 900),
        [miss("c", 25_200)]
    );
}
