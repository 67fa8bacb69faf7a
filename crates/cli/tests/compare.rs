//! `platoonsim compare` end to end: a small run compared with field data made from its own
//! detectors fits exactly; the same data with flows half again as large fails the flow
//! criteria, and the report shows it; bad input fails with a clear error.

mod common;

use common::{platoonsim, read_csv, s, scratch, stderr, stdout};
use std::path::{Path, PathBuf};

/// One hour on the homogeneous road from 06:00, its three detectors named like PeMS
/// stations. Returns the run directory.
fn small_run(dir: &Path) -> PathBuf {
    let run = dir.join("run");
    let o = platoonsim(&[
        "run",
        "homogeneous",
        "--duration",
        "3600",
        "--warmup",
        "600",
        "--demand",
        "1500",
        "--set",
        "run.clock_start=\"06:00\"",
        "--set",
        "detectors[0].name=\"400001\"",
        "--set",
        "detectors[1].name=\"400002\"",
        "--set",
        "detectors[2].name=\"400003\"",
        "--set",
        "measurement.detector=\"400003\"",
        "--quiet",
        "--out",
        s(&run),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    run
}

/// A tidy field file from the run's own cross-section rows, flows times `scale`.
fn tidy_from_run(run: &Path, file: &Path, scale: f64) {
    let mut text = String::from("station,time,flow_vph,speed_kmh,occupancy\n");
    for r in read_csv(&run.join("detectors.csv")) {
        if r["lane"] != "all" {
            continue;
        }
        let flow: f64 = r["flow_vph"].parse().unwrap();
        let flow = if scale == 1.0 {
            r["flow_vph"].clone()
        } else {
            format!("{}", flow * scale)
        };
        text.push_str(&format!(
            "{},{},{},{},{}\n",
            r["detector"], r["clock"], flow, r["speed_kmh"], r["occupancy"]
        ));
    }
    std::fs::write(file, text).unwrap();
}

fn fit_json(dir: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(dir.join("fit.json")).unwrap()).unwrap()
}

#[test]
fn a_run_against_its_own_detectors_fits_and_scaled_flows_do_not() {
    let dir = scratch("own");
    let run = small_run(&dir);
    let field = dir.join("field.csv");
    tidy_from_run(&run, &field, 1.0);

    let o = platoonsim(&["compare", s(&run), "--field", s(&field)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("Compared 3 station(s), 06:00–07:00: 3 station-hours, 12 15-min speeds."),
        "{out}"
    );
    assert!(out.contains("Every criterion holds."), "{out}");
    let compare = run.join("compare");
    let j = fit_json(&compare);
    assert_eq!(j["pass"], true);
    assert_eq!(j["fit"]["geh_pass_share"], 1.0);
    assert_eq!(j["fit"]["geh_mean"], 0.0);
    assert_eq!(j["fit"]["total_flow_diff"], 0.0);
    assert_eq!(j["fit"]["speed_rmse_kmh"], 0.0);
    assert_eq!(j["fit"]["speed_rmsne"], 0.0);
    let r = j["fit"]["speed_correlation"].as_f64().unwrap();
    assert!((r - 1.0).abs() < 1e-12, "{r}");
    assert_eq!(j["objective"], 0.0);
    assert_eq!(j["fit"]["hour_coverage"]["missing_in_field"], 0);
    assert_eq!(j["fit"]["hour_coverage"]["missing_in_sim"], 0);
    for f in ["compare.md", "compare.html", "contours.png", "contours.svg"] {
        assert!(compare.join(f).is_file(), "{f}");
    }
    let md = std::fs::read_to_string(compare.join("compare.md")).unwrap();
    assert!(md.contains("**Verdict:** all 7 criteria hold."));

    // Field flows 1.5 times the simulated ones: GEH fails, shown as ✗.
    let scaled = dir.join("scaled.csv");
    tidy_from_run(&run, &scaled, 1.5);
    let out_dir = dir.join("scaled");
    let o = platoonsim(&[
        "compare",
        s(&run),
        "--out",
        s(&out_dir),
        "--field",
        s(&scaled),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("✗ Hourly flows: GEH < 5: 0.0 % of 3 station-hours"),
        "{out}"
    );
    let j = fit_json(&out_dir);
    assert_eq!(j["pass"], false);
    assert_eq!(j["fit"]["geh_pass_share"], 0.0);
    let md = std::fs::read_to_string(out_dir.join("compare.md")).unwrap();
    assert!(md.contains("| Hourly flows: GEH < 5 | > 85.0 % of station-hours | 0.0 % of 3 station-hours | ✗ **does not hold** |"), "{md}");
    // Speeds are untouched: they still fit (the 15-min means weigh them by the scaled flows,
    // so only up to rounding).
    assert!(j["fit"]["speed_rmse_kmh"].as_f64().unwrap() < 1e-9);

    // A window: 06:15 to 06:45 holds no whole clock hour.
    let o = platoonsim(&[
        "compare",
        s(&run),
        "--out",
        s(&dir.join("w")),
        "--from",
        "06:15",
        "--to",
        "06:45",
        "--field",
        s(&field),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let j = fit_json(&dir.join("w"));
    assert_eq!(j["fit"]["hour_coverage"]["matched"], 0);
    assert_eq!(j["fit"]["speed_intervals"], 6);
}

#[test]
fn bad_input_is_named() {
    let dir = scratch("bad");
    let run = small_run(&dir);
    let field = dir.join("field.csv");
    tidy_from_run(&run, &field, 1.0);
    let err = |args: &[&str]| {
        let o = platoonsim(args);
        assert!(!o.status.success(), "{args:?} succeeded");
        stderr(&o)
    };
    let e = err(&["compare", s(&run), "--from", "6:00", "--field", s(&field)]);
    assert!(
        e.contains("invalid --from 6:00: expected a clock time HH:MM"),
        "{e}"
    );
    let e = err(&[
        "compare",
        s(&run),
        "--from",
        "07:00",
        "--to",
        "06:30",
        "--field",
        s(&field),
    ]);
    assert!(e.contains("invalid period --from 07:00 --to 06:30"), "{e}");
    // Field stations of other names: nothing to compare.
    let other = dir.join("other.csv");
    std::fs::write(
        &other,
        "station,time,interval_s,flow_vph,speed_kmh,occupancy\n9,06:00,300,1,1,0.1\n",
    )
    .unwrap();
    let e = err(&["compare", s(&run), "--field", s(&other)]);
    assert!(
        e.contains("no simulated detector has the name of a field station"),
        "{e}"
    );
    assert!(e.contains("400001, 400002, 400003"), "{e}");
    // A station table whose stations are none of the field's (issue 48: accepted, and the
    // GEH pass changed from 80.0 % to 64.9 %).
    let table = dir.join("stations.csv");
    std::fs::write(
        &table,
        "station,x_m,kind
777,100,ML
778,900,ML
",
    )
    .unwrap();
    let e = err(&[
        "compare",
        s(&run),
        "--field",
        s(&field),
        "--stations",
        s(&table),
    ]);
    assert!(
        e.contains(&format!(
            "--stations {}: none of its stations (777, 778) is in the field files (stations \
             400001, 400002, 400003)",
            table.display()
        )),
        "{e}"
    );
    // A run without run.clock_start.
    let plain = dir.join("plain");
    let o = platoonsim(&[
        "run",
        "homogeneous",
        "--duration",
        "300",
        "--warmup",
        "60",
        "--quiet",
        "--out",
        s(&plain),
    ]);
    assert!(o.status.success());
    let e = err(&["compare", s(&plain), "--field", s(&field)]);
    assert!(e.contains("has no run.clock_start"), "{e}");
    // --origin-pm needs --meta.
    let e = err(&[
        "compare",
        s(&run),
        "--origin-pm",
        "287.23",
        "--field",
        s(&field),
    ]);
    assert!(e.contains("--meta"), "{e}");
}
