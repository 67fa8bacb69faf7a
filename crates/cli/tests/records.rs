//! `platoonsim run --trips / --trajectories` and `platoonsim time-space` end to end: the
//! per-vehicle records against the summary and the detectors, and the diagram drawn from them.

mod common;

use common::{num, platoonsim, read_csv, s, scratch, stderr, stdout, summary_without_wall_time};
use platoonsim_scenario::clock::clock_at;
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------- trips and trajectories

/// Ten minutes of SR-99 with both records, from 300 to 360 s every 0.5 s over the first 8 km.
const SR99_RECORDS: &[&str] = &[
    "run",
    "sr99",
    "--penetration",
    "0.4",
    "--seed",
    "1",
    "--duration",
    "600",
    "--warmup",
    "120",
    "-q",
    "--trips",
    "--trajectories",
    "0.5",
    "--trajectory-window",
    "300,360",
    "--trajectory-x=0,8000",
];

fn sr99_with_records(test: &str) -> PathBuf {
    let out = scratch(test).join("out");
    let mut args = SR99_RECORDS.to_vec();
    args.extend_from_slice(&["--out", s(&out)]);
    let o = platoonsim(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("Also written: trips.csv ("),
        "{}",
        stdout(&o)
    );
    out
}

#[test]
fn sr99_trips_agree_with_the_summary_and_the_off_ramp_detectors() {
    let out = sr99_with_records("sr99-records");
    let summary = summary_without_wall_time(&out);
    let n = |k: &str| summary[k].as_u64().unwrap();
    let trips = read_csv(&out.join("trips.csv"));
    let header = std::fs::read_to_string(out.join("trips.csv")).unwrap();
    assert!(header.starts_with(
        "id,kind,origin,destination,status,entered_s,depart_delay_s,left_s,travel_time_s,entry_x_m,last_x_m,\
         lane_changes,max_platoon,max_platoon_tg2,measured,entrance_arrival_s,entered_clock,left_clock\n"
    ));
    let status = |st: &str| trips.iter().filter(|t| t["status"] == st).count() as u64;
    assert_eq!(status("queued"), n("vehicles_waiting"));
    assert_eq!(trips.len() as u64 - status("queued"), n("vehicles_entered"));
    assert_eq!(status("in_network"), n("vehicles_in_network"));
    assert_eq!(
        status("exited") + status("missed_exit_then_end"),
        n("vehicles_exited")
    );
    assert!(status("missed_exit_then_end") <= n("missed_exits"));

    // The lane-change statistic, exactly, as integers.
    let measured: Vec<_> = trips.iter().filter(|t| t["measured"] == "true").collect();
    assert_eq!(measured.len() as u64, n("vehicles_counted"));
    let lane_changes: u64 = measured
        .iter()
        .map(|t| t["lane_changes"].parse::<u64>().unwrap())
        .sum();
    let per_vehicle = summary["lane_changes_per_vehicle"].as_f64().unwrap();
    assert_eq!(
        lane_changes,
        (per_vehicle * n("vehicles_counted") as f64).round() as u64
    );
    assert!(lane_changes > 0);

    // Per off-ramp: the trips that left by it = its detector's count over the run.
    let mut off_counts: std::collections::HashMap<String, u64> = Default::default();
    for r in read_csv(&out.join("detectors.csv")) {
        if r["kind"] == "off-ramp" && r["lane"] == "all" {
            *off_counts.entry(r["detector"].clone()).or_default() +=
                r["count"].parse::<u64>().unwrap();
        }
    }
    assert_eq!(off_counts.len(), 11, "{off_counts:?}");
    let mut total = 0;
    for (detector, count) in &off_counts {
        let ramp = detector.strip_suffix("-off").unwrap();
        let left_by_it = trips
            .iter()
            .filter(|t| t["destination"] == ramp && t["status"] == "exited")
            .count() as u64;
        assert_eq!(left_by_it, *count, "{detector}");
        total += count;
    }
    assert!(total > 100, "only {total} vehicles took an off-ramp");

    let mut origins = std::collections::BTreeSet::new();
    for t in trips.iter().filter(|t| t["status"] != "queued") {
        origins.insert(t["origin"].clone());
        assert!(["human", "cav"].contains(&t["kind"].as_str()), "{t:?}");
        let entered = num(t, "entered_s");
        // sr99 starts at 05:00: the clock columns follow the simulated times.
        assert_eq!(t["entered_clock"], clock_at(18_000, entered), "{t:?}");
        assert!(
            (num(t, "entrance_arrival_s") - (entered - num(t, "depart_delay_s"))).abs() < 1e-9,
            "{t:?}"
        );
        assert!(entered > 0.0 && entered <= 600.0, "{t:?}");
        assert!(num(t, "last_x_m") >= num(t, "entry_x_m"), "{t:?}");
        if t["status"] == "in_network" {
            assert!(
                t["destination"].is_empty() && t["left_s"].is_empty(),
                "{t:?}"
            );
            assert!(t["travel_time_s"].is_empty(), "{t:?}");
            assert!(t["left_clock"].is_empty(), "{t:?}");
        } else {
            let (left, tt) = (num(t, "left_s"), num(t, "travel_time_s"));
            assert_eq!(t["left_clock"], clock_at(18_000, left), "{t:?}");
            assert!(tt > 0.0, "{t:?}");
            assert!((tt - (left - entered)).abs() < 1e-6, "{t:?}");
            assert!(!t["destination"].is_empty(), "{t:?}");
        }
        if t["origin"] == "mainline" {
            assert_eq!(num(t, "entry_x_m"), -500.0, "{t:?}");
        }
    }
    // The mainline and the 16 on-ramps.
    assert_eq!(origins.len(), 17, "{origins:?}");
    assert!(origins.contains("mainline") && origins.contains("OR16"));
}

#[test]
fn trajectory_rows_lie_in_the_windows_and_move_forward() {
    let out = sr99_with_records("sr99-trajectories");
    let text = std::fs::read_to_string(out.join("trajectories.csv")).unwrap();
    assert!(text.starts_with("t_s,id,kind,lane,x_m,v_mps,a_mps2,mode,platoon_pos,regime\n"));
    let rows = read_csv(&out.join("trajectories.csv"));
    assert!(rows.len() > 1000, "{} rows", rows.len());
    let lanes = {
        let c: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("scenario.json")).unwrap()).unwrap();
        c["road"]["lanes"].as_u64().unwrap()
    };
    let mut times = std::collections::BTreeSet::new();
    let mut last: std::collections::HashMap<String, (f64, f64)> = Default::default();
    for r in &rows {
        let (t, x, v, lane) = (
            num(r, "t_s"),
            num(r, "x_m"),
            num(r, "v_mps"),
            num(r, "lane"),
        );
        assert!((300.0..=360.0).contains(&t), "{r:?}");
        assert_eq!((t * 2.0).fract(), 0.0, "not a multiple of 0.5 s: {r:?}");
        assert!((0.0..=8000.0).contains(&x), "{r:?}");
        assert!(v >= 0.0, "{r:?}");
        assert!(
            lane >= 1.0 && lane <= lanes as f64 && lane.fract() == 0.0,
            "{r:?}"
        );
        assert!(
            ["cf", "blc", "ycf", "cf-auto", "blc-auto", "ycf-auto"].contains(&r["mode"].as_str()),
            "{r:?}"
        );
        if let Some(&(t0, x0)) = last.get(&r["id"]) {
            assert!(t > t0 && x >= x0, "{r:?} after t = {t0}, x = {x0}");
        }
        last.insert(r["id"].clone(), (t, x));
        times.insert((t * 2.0) as u64);
    }
    // Every sample time of the window has rows.
    assert_eq!(times.len(), 121);
}

#[test]
fn trajectory_strings_and_regimes_follow_the_cacc_rules() {
    let out = sr99_with_records("sr99-strings");
    let rows = read_csv(&out.join("trajectories.csv"));
    // Per sample time and lane, the vehicles front first: a string member (position k > 1)
    // is a CAV directly behind the vehicle at position k - 1, also a CAV.
    let mut by_lane: std::collections::BTreeMap<(u64, u64), Vec<&_>> = Default::default();
    for r in &rows {
        let key = ((num(r, "t_s") * 2.0) as u64, num(r, "lane") as u64);
        by_lane.entry(key).or_default().push(r);
    }
    let (mut members, mut regimes, mut handovers) = (0, 0, 0);
    for lane in by_lane.values_mut() {
        lane.sort_by(|a, b| num(b, "x_m").total_cmp(&num(a, "x_m")));
        for (k, r) in lane.iter().enumerate() {
            let pos = num(r, "platoon_pos");
            let auto = r["mode"].ends_with("-auto");
            // The regime is that of the step just simulated; the mode label says whether the
            // automation drives from now on: they differ only in the step where a driver's
            // relaxation ends and the automation takes back over.
            assert!(
                auto || r["regime"].is_empty(),
                "regime only when automated: {r:?}"
            );
            if auto && r["regime"].is_empty() {
                handovers += 1;
            } else if auto {
                assert!(
                    ["speed", "gap", "gap-closing", "collision-avoidance"]
                        .contains(&r["regime"].as_str()),
                    "{r:?}"
                );
                regimes += 1;
            }
            if r["kind"] == "human" {
                assert_eq!(pos, 1.0, "{r:?}");
            }
            // The trajectory window is the first 8 km, so a leader may be outside it.
            if pos > 1.0 && k > 0 {
                let ahead = lane[k - 1];
                assert_eq!(r["kind"], "cav", "{r:?}");
                assert_eq!(ahead["kind"], "cav", "{ahead:?} ahead of {r:?}");
                assert_eq!(num(ahead, "platoon_pos"), pos - 1.0, "{ahead:?} / {r:?}");
                members += 1;
            }
        }
    }
    assert!(members > 100, "{members} string members");
    assert!(regimes > 1000, "{regimes} automated samples");
    assert!(
        handovers * 100 < regimes,
        "{handovers} hand-backs in {regimes} samples"
    );
}

#[test]
fn records_are_reproducible_and_do_not_change_the_other_outputs() {
    let a = sr99_with_records("records-a");
    let b = sr99_with_records("records-b");
    for file in ["trips.csv", "trajectories.csv"] {
        assert_eq!(
            std::fs::read(a.join(file)).unwrap(),
            std::fs::read(b.join(file)).unwrap(),
            "{file}"
        );
    }
    // The same run without the flags: the same four files, and none of the record files.
    let plain = scratch("records-plain").join("out");
    let mut args: Vec<&str> = SR99_RECORDS
        .iter()
        .copied()
        .take_while(|a| *a != "--trips")
        .collect();
    args.extend_from_slice(&["--out", s(&plain)]);
    let o = platoonsim(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stdout(&o).contains("Also written"), "{}", stdout(&o));
    for file in [
        "detectors.csv",
        "scenario.json",
        "scenario.toml",
        "road.json",
    ] {
        assert_eq!(
            std::fs::read(a.join(file)).unwrap(),
            std::fs::read(plain.join(file)).unwrap(),
            "{file}"
        );
    }
    assert_eq!(
        summary_without_wall_time(&a),
        summary_without_wall_time(&plain)
    );
    assert!(!plain.join("trips.csv").exists());
    assert!(!plain.join("trajectories.csv").exists());
}

// ---------------------------------------------------------------- time-space

/// `time-space` fails with exit code 1 and says `expected` on stderr, writing no figure.
fn assert_time_space_fails(dir: &Path, args: &[&str], expected: &str) {
    let mut all = vec!["time-space"];
    all.extend_from_slice(args);
    let o = platoonsim(&all);
    assert_eq!(o.status.code(), Some(1), "{all:?}: {}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains(expected),
        "{all:?}: expected {expected:?} in:\n{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    let figures = std::fs::read_dir(dir)
        .unwrap()
        .filter(|e| {
            let name = e.as_ref().unwrap().file_name();
            let name = name.to_string_lossy();
            name.ends_with(".png") || name.ends_with(".svg")
        })
        .count();
    assert_eq!(figures, 0, "a figure was written for {all:?}");
}

#[test]
fn time_space_refuses_bad_input() {
    let dir = scratch("tsd-refusals");
    let head = "t_s,id,kind,lane,x_m,v_mps,a_mps2,mode\n";
    let good = dir.join("trajectories.csv");
    std::fs::write(
        &good,
        format!("{head}0,1,cav,1,0,20,0,cf\n1,1,cav,1,20,20,0,cf\n"),
    )
    .unwrap();
    let missing = dir.join("nope.csv");
    assert_time_space_fails(&dir, &[s(&missing)], "cannot read");
    assert_time_space_fails(&dir, &[s(&missing)], "nope.csv");
    let wrong = dir.join("detectors.csv");
    std::fs::write(&wrong, "t_s,detector,flow\n1,2,3\n").unwrap();
    assert_time_space_fails(&dir, &[s(&wrong)], "is not a trajectories.csv");
    let bad = dir.join("bad.csv");
    std::fs::write(
        &bad,
        format!("{head}0,1,cav,1,0,20,0,cf\n1,1,cav,1,20,fast,0,cf\n"),
    )
    .unwrap();
    assert_time_space_fails(&dir, &[s(&bad)], "bad.csv line 3, column v_mps: 'fast'");
    assert_time_space_fails(
        &dir,
        &[s(&good), "--lane", "0"],
        "invalid --lane 0: lanes are numbered from 1",
    );
    assert_time_space_fails(&dir, &[s(&good), "--lane", "3"], "no sample in lane 3");
    assert_time_space_fails(
        &dir,
        &[s(&good), "--lane", "-1"],
        "invalid --lane -1: lanes are numbered from 1",
    );
    // The good file draws, next to the CSV by default.
    let o = platoonsim(&["time-space", s(&good)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.join("time_space_lane1.png").exists());
    assert!(dir.join("time_space_lane1.svg").exists());
}

#[test]
fn time_space_draws_what_run_writes() {
    let out = scratch("tsd-run").join("out");
    let o = platoonsim(&[
        "run",
        "homogeneous",
        "--duration",
        "300",
        "--warmup",
        "60",
        "--quiet",
        "--demand",
        "2000",
        "--trajectories",
        "1",
        "--out",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = out.join("trajectories.csv");
    let rows = read_csv(&csv);
    assert!(rows.len() > 1000, "{} rows", rows.len());
    // Stays in lane 2: per vehicle, the runs of consecutive samples in lane 2.
    let mut last: std::collections::HashMap<String, bool> = Default::default();
    let mut stays = 0;
    for r in &rows {
        let here = r["lane"] == "2";
        let before = last.insert(r["id"].clone(), here).unwrap_or(false);
        stays += usize::from(here && !before);
    }
    assert!(stays > 10, "{stays} stays in lane 2");
    let stem = out.join("fig/lane2");
    let o = platoonsim(&["time-space", s(&csv), "--lane", "2", "--out", s(&stem)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let png = out.join("fig/lane2.png");
    let svg = out.join("fig/lane2.svg");
    assert_eq!(
        stdout(&o),
        format!("{}\n{}\n", png.display(), svg.display())
    );
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("lane 2"));
    // Every stay is at least one polyline (more where the speed colour changes) or a dot.
    let drawn = text.matches("<polyline").count() + text.matches("<circle").count();
    assert!(drawn >= stays, "{drawn} elements for {stays} stays");
}
