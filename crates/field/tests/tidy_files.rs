//! The tidy CSV: round trip, intervals from spacing, and its errors.

use std::path::{Path, PathBuf};

use platoonsim_field::{load, tidy, FieldError, Obs};

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn assert_names(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "{p:?} not in {msg:?}");
    }
}

fn obs(station: &str, start_s: u32, interval_s: u32, flow: f64) -> Obs {
    Obs {
        station: station.into(),
        start_s,
        interval_s,
        flow_vph: flow,
        speed_kmh: Some(0.1 + flow / 37.0),
        occupancy: Some(flow / 23_000.0),
    }
}

#[test]
fn write_then_read_gives_the_same_rows() {
    let mut rows = vec![
        obs("312425", 25_200, 300, 5316.0),
        obs("det, \"quoted\"", 25_200, 900, 1.0 / 3.0),
        obs("312425", 25_500, 300, 0.0),
        obs("single", 86_399, 1, 7.25),
    ];
    rows[2].speed_kmh = None;
    rows[2].occupancy = None;
    let mut bytes = Vec::new();
    tidy::write(&mut bytes, &rows).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    assert!(text.starts_with("station,time,flow_vph,speed_kmh,occupancy,interval_s\n"));
    assert!(text.contains("\n312425,07:05:00,0,,,300\n"), "{text}");
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "t.csv", &text);
    assert_eq!(tidy::read(&path).unwrap(), rows);
    assert_eq!(load::load(&[path]).unwrap(), rows);
}

#[test]
fn interval_comes_from_each_stations_spacing() {
    let dir = tempfile::tempdir().unwrap();
    // Columns in another order; a: 07:05 -> 07:15 is a gap, its interval the smallest spacing.
    let text = "time,station,flow_vph,speed_kmh,occupancy\n\
                07:00,a,1200,100.5,0.05\n\
                07:00,b,600,,\n\
                07:05,a,1300,99,0.06\n\
                07:15,a,1250,98,0.055\n\
                07:15,b,650,80,0.1\n";
    let rows = tidy::read(&write(dir.path(), "s.csv", text)).unwrap();
    let got: Vec<(&str, u32, u32)> = rows
        .iter()
        .map(|o| (o.station.as_str(), o.start_s, o.interval_s))
        .collect();
    assert_eq!(
        got,
        [
            ("a", 25_200, 300),
            ("b", 25_200, 900),
            ("a", 25_500, 300),
            ("a", 26_100, 300),
            ("b", 26_100, 900)
        ]
    );
    assert_eq!(rows[1].speed_kmh, None);
    // load tells a tidy file by its column names, in any order.
    assert_eq!(
        load::load(&[write(dir.path(), "s.csv", text)]).unwrap(),
        rows
    );
    assert_eq!(rows[0].speed_kmh, Some(100.5));

    // A station with one row takes the interval the others share...
    let shared = format!(
        "{}07:30,c,10,90,0.01\n",
        text.replace(",b,", ",a2,").replace("07:15,a2", "07:05,a2")
    );
    let rows = tidy::read(&write(dir.path(), "s.csv", &shared)).unwrap();
    assert!(rows.iter().all(|o| o.interval_s == 300), "{rows:?}");
    // ... and is an error when they do not share one.
    let e = tidy::read(&write(
        dir.path(),
        "s.csv",
        &format!("{text}07:30,c,10,90,0.01\n"),
    ))
    .unwrap_err();
    assert!(matches!(e, FieldError::Value { line: 7, .. }), "{e:?}");
    assert_names(
        &e.to_string(),
        &[
            "s.csv",
            "line 7",
            "time",
            "07:30:00",
            "station c",
            "interval_s",
        ],
    );
}

#[test]
fn spacing_that_is_not_a_multiple_of_the_interval_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let text = "station,time,flow_vph,speed_kmh,occupancy\n\
                a,07:00,1200,100,0.05\na,07:05,1200,100,0.05\na,07:12,1200,100,0.05\n";
    let e = tidy::read(&write(dir.path(), "m.csv", text)).unwrap_err();
    assert!(matches!(e, FieldError::Value { line: 4, .. }), "{e:?}");
    assert_names(
        &e.to_string(),
        &["m.csv", "line 4", "07:12:00", "300 s", "07:05:00"],
    );
}

#[test]
fn rows_going_back_or_overlapping_are_non_monotonic() {
    let dir = tempfile::tempdir().unwrap();
    let head = "station,time,flow_vph,speed_kmh,occupancy,interval_s\n";
    for (rows, time) in [
        (
            "a,07:05,1,,,300\nb,07:00,1,,,300\na,07:00,1,,,300\n",
            "07:00:00",
        ),
        (
            "a,07:05,1,,,300\nb,07:00,1,,,300\na,07:05:00,1,,,300\n",
            "07:05:00",
        ),
        (
            "a,07:05,1,,,300\nb,07:00,1,,,300\na,07:09,1,,,300\n",
            "07:09:00",
        ),
    ] {
        let e = tidy::read(&write(dir.path(), "b.csv", &format!("{head}{rows}"))).unwrap_err();
        assert!(
            matches!(e, FieldError::NonMonotonic { line: 4, .. }),
            "{e:?}"
        );
        assert_names(
            &e.to_string(),
            &["b.csv", "line 4", "station a", time, "07:05:00 (line 2)"],
        );
    }
}

#[test]
fn an_unknown_header_is_unknown_format() {
    let dir = tempfile::tempdir().unwrap();
    for header in [
        "station,time,flow_vph,speed_mph,occupancy",
        "station,time,flow_vph,speed_kmh,occupancy,lane",
        "station,time,flow_vph,speed_kmh,occupancy,time",
    ] {
        let path = write(dir.path(), "h.csv", &format!("{header}\na,07:00,1,2,0.1\n"));
        let e = tidy::read(&path).unwrap_err();
        assert!(
            matches!(e, FieldError::UnknownFormat { line: 1, .. }),
            "{e:?}"
        );
        assert_names(
            &e.to_string(),
            &[
                "h.csv",
                "line 1",
                header,
                "station,time,flow_vph,speed_kmh,occupancy",
            ],
        );
    }
    let path = write(dir.path(), "h.csv", "id,when,flow\na,07:00,1\n");
    let e = load::load(&[path]).unwrap_err();
    assert!(
        matches!(e, FieldError::UnknownFormat { line: 1, .. }),
        "{e:?}"
    );
}

#[test]
fn bad_values_name_line_field_and_value() {
    let dir = tempfile::tempdir().unwrap();
    let head = "station,time,flow_vph,speed_kmh,occupancy,interval_s\n";
    for (row, variant, field, value) in [
        ("a,7h00,1,,,300", "Timestamp", "time", "7h00"),
        ("a,24:00,1,,,300", "Timestamp", "time", "24:00"),
        ("a,07:00,-1,,,300", "Number", "flow_vph", "-1"),
        ("a,07:00,1,nan,,300", "Number", "speed_kmh", "nan"),
        ("a,07:00,1,,1.2,300", "Number", "occupancy", "1.2"),
        ("a,07:00,1,,,0", "Number", "interval_s", "0"),
        (",07:00,1,,,300", "Value", "station", "\"\""),
        ("a,07:00,1,,", "Columns", "", "a,07:00,1,,"),
    ] {
        let path = write(
            dir.path(),
            "v.csv",
            &format!("{head}a,06:00,1,,,300\n{row}\n"),
        );
        let e = tidy::read(&path).unwrap_err();
        assert!(format!("{e:?}").starts_with(variant), "{row}: {e:?}");
        assert_names(&e.to_string(), &["v.csv", "line 3", field, value]);
    }
}

#[test]
fn implausible_flows_and_speeds_are_refused_naming_line_and_field() {
    // Issue 48 D5: a flow of 1e308 was accepted and made the calibration's objective NaN.
    let dir = tempfile::tempdir().unwrap();
    let head = "station,time,flow_vph,speed_kmh,occupancy,interval_s\n";
    for (row, field, value) in [
        ("a,07:00,1e308,,,300", "flow_vph", "1e308"),
        ("a,07:00,30001,,,300", "flow_vph", "30001"),
        ("a,07:00,100,200.5,,300", "speed_kmh", "200.5"),
        ("a,07:00,100,1e300,,300", "speed_kmh", "1e300"),
    ] {
        let path = write(
            dir.path(),
            "v.csv",
            &format!("{head}a,06:00,1,,,300\n{row}\n"),
        );
        let e = tidy::read(&path).unwrap_err().to_string();
        assert_names(&e, &["v.csv", "line 3", field, value, "in [0, "]);
    }
    // The limits themselves are plausible.
    let path = write(
        dir.path(),
        "ok.csv",
        &format!("{head}a,07:00,30000,200,,300\n"),
    );
    assert_eq!(tidy::read(&path).unwrap()[0].flow_vph, 30_000.0);
}

#[test]
fn a_load_holds_at_most_max_stations() {
    // Issue 48 D9: 2 million one-row stations in a 5 MB .gz took 1.57 GB.
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::from("station,time,flow_vph,speed_kmh,occupancy,interval_s\n");
    for k in 0..=platoonsim_field::MAX_STATIONS {
        text.push_str(&format!("s{k},07:00,100,,,300\n"));
    }
    let path = write(dir.path(), "many.csv", &text);
    let e = tidy::read(&path).unwrap_err();
    assert!(matches!(e, FieldError::TooMany { .. }), "{e:?}");
    assert_eq!(
        e.to_string(),
        format!(
            "{}: line 20002: more than 20000 stations in one load; split the data (by day or \
             corridor) or keep only the stations of the corridor",
            path.display()
        )
    );
    // One station fewer loads.
    let fewer: String = text
        .lines()
        .take(20_001)
        .map(|l| format!("{l}\n"))
        .collect();
    let path = write(dir.path(), "fewer.csv", &fewer);
    assert_eq!(load::load(&[path]).unwrap().len(), 20_000);
}

#[test]
fn a_byte_order_mark_is_read_past() {
    // Issue 48 D16: a file saved by a spreadsheet with a UTF-8 BOM was refused.
    let dir = tempfile::tempdir().unwrap();
    let text = "\u{feff}station,time,flow_vph,speed_kmh,occupancy\na,07:00,100,90,0.1\na,07:05,100,90,0.1\n";
    let path = write(dir.path(), "bom.csv", text);
    let rows = load::load(&[path]).unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0].station, "a");
}
