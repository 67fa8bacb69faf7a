//! PeMS station_5min and metadata files written to a temporary directory: layouts accepted
//! and the error of each broken rule (its message names file, line, field and value).

use std::io::Write;
use std::path::{Path, PathBuf};

use platoonsim_field::{load, pems, FieldError, StationKind};

const ROWS: &str = "\
09/18/2014 07:00:00,400001,3,99,N,ML,,,,100,0.05,60.0
09/18/2014 07:00:00,400002,3,99,N,OR,,,,30,nan,
09/18/2014 07:05:00,400001,3,99,N,ML,,,,90,0.06,55.5
";

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn gzip(text: &str) -> Vec<u8> {
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    enc.write_all(text.as_bytes()).unwrap();
    enc.finish().unwrap()
}

fn message(e: FieldError) -> String {
    e.to_string()
}

fn assert_names(msg: &str, parts: &[&str]) {
    for p in parts {
        assert!(msg.contains(p), "{p:?} not in {msg:?}");
    }
}

#[test]
fn plain_and_gzip_give_the_same_rows_whatever_the_name() {
    let dir = tempfile::tempdir().unwrap();
    let plain = write(dir.path(), "day.txt", ROWS.as_bytes());
    // Named .txt although gzip: detected by the magic bytes.
    let gz = write(dir.path(), "day_gz.txt", &gzip(ROWS));
    let a = pems::read_station_5min(&plain).unwrap();
    assert_eq!(a, pems::read_station_5min(&gz).unwrap());
    assert_eq!(a.len(), 3);
    assert_eq!(a[0].flow_vph, 1200.0);
    assert_eq!(a[0].speed_kmh, Some(60.0 * 1.609344));
    assert_eq!(a[1].occupancy, None);
    assert_eq!(a[1].speed_kmh, None);
    assert_eq!((a[2].start_s, a[2].interval_s), (7 * 3600 + 300, 300));
}

#[test]
fn per_lane_fields_are_accepted_and_ignored() {
    let dir = tempfile::tempdir().unwrap();
    let row = "09/18/2014 07:00:00,400001,3,99,N,ML,0.5,20,100,100,0.05,60.0,\
               10,50,0.04,61.0,1,10,50,0.06,59.0,1\n";
    let path = write(dir.path(), "lanes.txt", row.as_bytes());
    let obs = pems::read_station_5min(&path).unwrap();
    assert_eq!(obs.len(), 1);
    assert_eq!(obs[0].flow_vph, 1200.0);
    assert_eq!(obs[0].occupancy, Some(0.05));
}

#[test]
fn a_row_without_total_flow_is_left_out() {
    let dir = tempfile::tempdir().unwrap();
    let text = "09/18/2014 07:00:00,400001,3,99,N,ML,,,,,,\n";
    let path = write(dir.path(), "noflow.txt", text.as_bytes());
    assert!(pems::read_station_5min(&path).unwrap().is_empty());
}

#[test]
fn truncated_gzip_is_a_gzip_error() {
    let dir = tempfile::tempdir().unwrap();
    let bytes = gzip(&ROWS.repeat(50));
    let path = write(dir.path(), "cut.gz", &bytes[..bytes.len() / 2]);
    let e = pems::read_station_5min(&path).unwrap_err();
    assert!(matches!(e, FieldError::Gzip { .. }), "{e:?}");
    assert_names(
        &message(e),
        &["cut.gz", "file ended inside the gzip stream"],
    );
    let e = load::load(&[path]).unwrap_err();
    assert!(matches!(e, FieldError::Gzip { .. }), "{e:?}");
}

#[test]
fn too_few_fields_is_a_columns_error_naming_the_line() {
    let dir = tempfile::tempdir().unwrap();
    let text = format!("{ROWS}09/18/2014 07:10:00,400001,3,99,N\n");
    let path = write(dir.path(), "short.txt", text.as_bytes());
    let e = pems::read_station_5min(&path).unwrap_err();
    assert!(
        matches!(
            e,
            FieldError::Columns {
                line: 4,
                found: 5,
                ..
            }
        ),
        "{e:?}"
    );
    assert_names(
        &message(e),
        &[
            "short.txt",
            "line 4",
            "5 field(s)",
            "400001",
            "at least 12 comma-separated",
        ],
    );
}

#[test]
fn a_bad_timestamp_is_a_timestamp_error() {
    let dir = tempfile::tempdir().unwrap();
    let text = "13/45/2014 07:00:00,400001,3,99,N,ML,,,,100,0.05,60.0\n";
    let path = write(dir.path(), "date.txt", text.as_bytes());
    let e = pems::read_station_5min(&path).unwrap_err();
    assert!(matches!(e, FieldError::Timestamp { line: 1, .. }), "{e:?}");
    assert_names(
        &message(e),
        &[
            "date.txt",
            "line 1",
            "Timestamp",
            "13/45/2014 07:00:00",
            "MM/DD/YYYY HH:MM:SS",
        ],
    );
}

#[test]
fn out_of_range_numbers_are_number_errors() {
    let dir = tempfile::tempdir().unwrap();
    for (row, field, value) in [
        (
            "09/18/2014 07:00:00,4,3,99,N,ML,,,,-3,0.05,60.0",
            "Total Flow",
            "-3",
        ),
        (
            "09/18/2014 07:00:00,4,3,99,N,ML,,,,3,1.5,60.0",
            "Avg Occupancy",
            "1.5",
        ),
        (
            "09/18/2014 07:00:00,4,3,99,N,ML,,,,3,0.1,fast",
            "Avg Speed",
            "fast",
        ),
    ] {
        let path = write(dir.path(), "num.txt", format!("{row}\n").as_bytes());
        let e = pems::read_station_5min(&path).unwrap_err();
        assert!(matches!(e, FieldError::Number { line: 1, .. }), "{e:?}");
        assert_names(&message(e), &["num.txt", "line 1", field, value]);
    }
}

#[test]
fn time_going_back_or_repeating_is_non_monotonic() {
    let dir = tempfile::tempdir().unwrap();
    for (later, time) in [
        ("06:55:00", "06:55:00"),
        ("07:05:00", "07:05:00"),
        ("07:02:00", "07:02:00"),
    ] {
        let text = format!("{ROWS}09/18/2014 {later},400001,3,99,N,ML,,,,90,0.06,55.5\n");
        let path = write(dir.path(), "back.txt", text.as_bytes());
        let e = pems::read_station_5min(&path).unwrap_err();
        assert!(
            matches!(e, FieldError::NonMonotonic { line: 4, .. }),
            "{e:?}"
        );
        assert_names(
            &message(e),
            &["back.txt", "line 4", "400001", "07:05:00 (line 3)", time],
        );
    }
}

#[test]
fn two_dates_in_one_file_or_one_load_are_mixed_dates() {
    let dir = tempfile::tempdir().unwrap();
    let text = format!("{ROWS}09/19/2014 07:10:00,400001,3,99,N,ML,,,,90,0.06,55.5\n");
    let path = write(dir.path(), "two.txt", text.as_bytes());
    let e = pems::read_station_5min(&path).unwrap_err();
    assert!(matches!(e, FieldError::MixedDates { line: 4, .. }), "{e:?}");
    assert_names(
        &message(e),
        &["two.txt", "line 4", "2014-09-19", "2014-09-18", "line 1"],
    );

    let a = write(dir.path(), "a.txt", ROWS.as_bytes());
    let b = write(
        dir.path(),
        "b.txt",
        ROWS.replace("09/18", "09/19").as_bytes(),
    );
    let e = load::load(&[a, b]).unwrap_err();
    assert!(matches!(e, FieldError::MixedDates { .. }), "{e:?}");
    assert_names(&message(e), &["b.txt", "a.txt", "2014-09-19", "2014-09-18"]);
}

#[test]
fn load_concatenates_and_rejects_an_interval_in_two_files() {
    let dir = tempfile::tempdir().unwrap();
    let a = write(dir.path(), "a.txt", ROWS.as_bytes());
    let later = "09/18/2014 07:10:00,400001,3,99,N,ML,,,,80,0.05,58.0\n";
    let b = write(dir.path(), "b.txt.gz", &gzip(later));
    let obs = load::load(&[a.clone(), b]).unwrap();
    assert_eq!(obs.len(), 4);
    assert_eq!(obs[3].start_s, 7 * 3600 + 600);

    let again = write(
        dir.path(),
        "again.txt",
        &ROWS.as_bytes()[..ROWS.find('\n').unwrap() + 1],
    );
    let e = load::load(&[a, again]).unwrap_err();
    assert!(matches!(e, FieldError::Overlap { .. }), "{e:?}");
    assert_names(&message(e), &["again.txt", "a.txt", "400001", "07:00:00"]);
}

#[test]
fn load_rejects_a_file_of_neither_layout() {
    let dir = tempfile::tempdir().unwrap();
    let meta = write(dir.path(), "meta.txt", b"ID\tFwy\tDir\n1\t99\tN\n");
    let e = load::load(&[meta]).unwrap_err();
    assert!(
        matches!(e, FieldError::UnknownFormat { line: 1, .. }),
        "{e:?}"
    );
    assert_names(
        &message(e),
        &[
            "meta.txt",
            "line 1",
            "ID\\tFwy",
            "PeMS station_5min",
            "tidy",
        ],
    );
}

const META: &str = "Name\tID\tFwy\tDir\tDistrict\tCounty\tAbs_PM\tType\tLanes\tUser_ID_1\n\
                    Elk Grove Blvd\t313190\t99\tN\t3\t\t287.295\tML\t2\t\n\
                    \"A\" St\t319092\t99\tN\t3\t\t275.404\tCD\t\t\n";

#[test]
fn meta_columns_are_found_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "meta.txt", META.as_bytes());
    let meta = pems::read_meta(&path).unwrap();
    assert_eq!(meta.len(), 2);
    assert_eq!(meta[0].id, "313190");
    assert_eq!(meta[0].abs_pm, 287.295);
    assert_eq!(meta[0].lanes, 2);
    assert_eq!(meta[0].name, "Elk Grove Blvd");
    assert_eq!(meta[1].kind, StationKind::Other("CD".into()));
    assert_eq!(meta[1].lanes, 0);
    assert_eq!(meta[1].name, "\"A\" St");
}

#[test]
fn meta_errors_name_file_line_field_and_value() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(
        dir.path(),
        "m.txt",
        META.replace("\tLanes", "\tLn").as_bytes(),
    );
    let e = pems::read_meta(&path).unwrap_err();
    assert!(matches!(e, FieldError::Header { line: 1, .. }), "{e:?}");
    assert_names(&message(e), &["m.txt", "line 1", "no column Lanes"]);

    let path = write(
        dir.path(),
        "m.txt",
        META.replace("287.295", "287,3").as_bytes(),
    );
    let e = pems::read_meta(&path).unwrap_err();
    assert!(matches!(e, FieldError::Number { line: 2, .. }), "{e:?}");
    assert_names(
        &message(e),
        &["m.txt", "line 2", "Abs_PM", "287,3", "postmile"],
    );

    let path = write(
        dir.path(),
        "m.txt",
        META.replace("319092", "313190").as_bytes(),
    );
    let e = pems::read_meta(&path).unwrap_err();
    assert!(matches!(e, FieldError::Value { line: 3, .. }), "{e:?}");
    assert_names(&message(e), &["m.txt", "line 3", "ID", "313190", "once"]);
}

#[test]
fn implausible_pems_counts_and_speeds_are_refused() {
    // Issue 48 D5: the flow and speed columns had no upper bound.
    let dir = tempfile::tempdir().unwrap();
    let good = ROWS.lines().next().unwrap();
    let fields: Vec<&str> = good.split(',').collect();
    for (col, value, name) in [
        (9, "1e308", "Total Flow"),
        (9, "2501", "Total Flow"),
        (11, "130", "Avg Speed"),
    ] {
        let mut f: Vec<String> = fields.iter().map(|s| s.to_string()).collect();
        f[col] = value.into();
        let path = write(dir.path(), "d.txt", format!("{}\n", f.join(",")).as_bytes());
        let e = message(platoonsim_field::pems::read_station_5min(&path).unwrap_err());
        assert_names(&e, &["d.txt", "line 1", name, value]);
    }
}

#[test]
fn a_byte_order_mark_is_read_past_in_pems_files_too() {
    let dir = tempfile::tempdir().unwrap();
    let path = write(dir.path(), "bom.txt", format!("\u{feff}{ROWS}").as_bytes());
    let rows = platoonsim_field::load::load(&[path]).unwrap();
    assert_eq!(rows.len(), 3);
}
