use super::*;

fn placed(station: &str, x_m: f64, kind: StationKind) -> Placed {
    Placed {
        station: station.into(),
        x_m,
        kind,
        lanes: 3,
        name: station.into(),
    }
}

/// 06:00-09:00 at 5 min: stations A (0 m), B (1 km), C (2 km); B congested 07:00-08:00.
pub(super) fn corridor(flow_scale: f64) -> Vec<Obs> {
    let mut out = Vec::new();
    for (s, jam) in [("A", false), ("B", true), ("C", false)] {
        for k in 0..36u32 {
            let slow = jam && (12..24).contains(&k);
            out.push(Obs {
                station: s.into(),
                start_s: 6 * 3600 + 300 * k,
                interval_s: 300,
                flow_vph: flow_scale * (3000.0 + 50.0 * f64::from(k % 7)),
                speed_kmh: Some(if slow { 30.0 } else { 95.0 + f64::from(k % 5) }),
                occupancy: Some(0.1),
            });
        }
    }
    out
}

pub(super) fn line() -> Vec<Placed> {
    vec![
        placed("A", 0.0, StationKind::Mainline),
        placed("B", 1000.0, StationKind::Mainline),
        placed("R", 1500.0, StationKind::OnRamp),
        placed("C", 2000.0, StationKind::Mainline),
    ]
}

#[test]
fn the_same_data_passes_every_criterion() {
    let sim = corridor(1.0);
    let e = evaluate(&sim, &sim, &line(), &[], &Options::default());
    assert_eq!(e.window, (6 * 3600, 9 * 3600));
    assert_eq!(e.fit.stations_compared, ["A", "B", "C"]);
    assert_eq!(e.sim_bottlenecks.len(), 1);
    assert_eq!(e.sim_bottlenecks, e.field_bottlenecks);
    assert_eq!(e.sim_bottlenecks[0].onset_s, 7 * 3600);
    assert_eq!(e.sim_bottlenecks[0].clearance_s, 8 * 3600);
    assert!(e.passes(), "{:#?}", e.criteria);
    assert_eq!(e.objective(), Some(0.0));
}

/// A ramp counter `R` (placed as an on-ramp) with `flow` veh/h, 06:00-09:00.
fn ramp(flow: f64) -> Vec<Obs> {
    (0..36u32)
        .map(|k| Obs {
            station: "R".into(),
            start_s: 6 * 3600 + 300 * k,
            interval_s: 300,
            flow_vph: flow,
            speed_kmh: Some(60.0),
            occupancy: Some(0.05),
        })
        .collect()
}

#[test]
fn ramp_counters_are_measured_apart_and_left_out_of_the_verdict() {
    let sim = [corridor(1.0), ramp(500.0)].concat();
    let field = [corridor(1.0), ramp(1500.0)].concat();
    let e = evaluate(&sim, &field, &line(), &[], &Options::default());
    assert_eq!(e.fit.stations_compared, ["A", "B", "C"]);
    assert_eq!(e.ramp_fit.stations_compared, ["R"]);
    // The mainline fits perfectly: the verdict holds although the ramp is a third of its
    // count (GEH 31.6 in every hour).
    assert!(e.passes(), "{:#?}", e.criteria);
    assert_eq!(e.objective(), Some(0.0));
    assert_eq!(e.ramp_criteria.len(), 4);
    assert!(e.ramp_criteria.iter().all(|c| !c.pass));
    assert_eq!(
        e.ramp_fit.geh_max.map(|g| (g * 10.0).round() / 10.0),
        Some(31.6)
    );
    // A station placed as a ramp on the field side only is a ramp too.
    let field_places = vec![placed("R", 1500.0, StationKind::OffRamp)];
    let mut sim_line = line();
    sim_line.retain(|p| p.station != "R");
    let e = evaluate(&sim, &field, &sim_line, &field_places, &Options::default());
    assert_eq!(e.ramp_fit.stations_compared, ["R"]);
    assert!(e.passes());
}

#[test]
fn field_flows_half_again_fail_the_flow_criteria() {
    let sim = corridor(1.0);
    let field = corridor(1.5);
    let e = evaluate(&sim, &field, &line(), &[], &Options::default());
    assert!(!e.passes());
    assert!(!e.criteria[0].pass && e.criteria[4].pass && e.criteria[5].pass);
    assert_eq!(e.fit.geh_pass_share, Some(0.0));
}

#[test]
fn the_window_defaults_to_the_simulated_period() {
    let sim: Vec<Obs> = corridor(1.0)
        .into_iter()
        .filter(|o| o.start_s < 8 * 3600)
        .collect();
    // The field day is longer: its hours outside the simulation are not "missing".
    let e = evaluate(&sim, &corridor(1.0), &line(), &[], &Options::default());
    assert_eq!(e.window, (6 * 3600, 8 * 3600));
    assert_eq!(e.fit.hour_coverage.missing_in_sim, 0);
    assert_eq!(e.fit.hour_coverage.matched, 6);
    // An explicit window narrows both sides.
    let opts = Options {
        window: Some((7 * 3600, 8 * 3600)),
        ..Options::default()
    };
    let e = evaluate(&sim, &corridor(1.0), &line(), &[], &opts);
    assert_eq!(e.fit.hour_coverage.matched, 3);
}

#[test]
fn bottleneck_lines_take_compared_mainline_stations_placed_on_each_side() {
    let compared: Vec<String> = ["A", "B", "C", "R"].map(String::from).to_vec();
    let field = [
        placed("B", 1100.0, StationKind::Mainline),
        placed("C", 2000.0, StationKind::Hov),
    ];
    let (s, f) = bottleneck_lines(&compared, &line(), &field);
    let names = |v: &[Placed]| v.iter().map(|p| p.station.clone()).collect::<Vec<_>>();
    // R is a ramp; C is an HOV station in the field.
    assert_eq!(names(&s), ["A", "B"]);
    assert_eq!(names(&f), ["A", "B"]);
    // A has no field placement: it takes the simulated position.
    assert_eq!((f[0].x_m, f[1].x_m), (0.0, 1100.0));
}

#[test]
fn contours_have_three_panels_and_an_exact_difference() {
    let sim = corridor(1.0);
    let mut field = corridor(1.0);
    for o in field.iter_mut() {
        o.speed_kmh = o.speed_kmh.map(|v| v - 7.0);
    }
    field.retain(|o| !(o.station == "C" && o.start_s == 6 * 3600));
    let l = line();
    let maps = contours::panels(&sim, &field, &l[..2], &l[..2], (6 * 3600, 9 * 3600));
    assert_eq!(maps.len(), 3);
    assert_eq!(maps[0].x.len(), 36);
    assert_eq!(maps[0].y, [0.0, 1.0]);
    assert_eq!(maps[0].x[0], (6.0 * 3600.0 + 150.0) / 3600.0);
    assert!(maps[2].z.iter().flatten().all(|&d| d == 7.0));
    assert_eq!(maps[2].z_range, (-10.0, 10.0));
    // Station C is not in the line given: no column.
    assert!(maps[1].z.iter().all(|r| r.len() == 2));
}

#[test]
fn files_report_page_json_and_figure() {
    let dir = std::env::temp_dir().join(format!("platoonsim-compare-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let sim = corridor(1.0);
    let mut field = corridor(1.5);
    field.retain(|o| !(o.station == "A" && o.start_s == 6 * 3600));
    let opts = Options::default();
    let e = evaluate(&sim, &field, &line(), &[], &opts);
    let inputs = files::Inputs {
        runs: vec!["out/run".into()],
        field_files: vec!["field.csv".into()],
        notes: vec![],
    };
    let written = files::write(&dir, &inputs, &e, &opts, &sim, &field, &line(), &[]).unwrap();
    let names: Vec<String> = written
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "compare.md",
            "compare.html",
            "fit.json",
            "contours.png",
            "contours.svg"
        ]
    );
    let md = std::fs::read_to_string(dir.join("compare.md")).unwrap();
    assert!(md.contains("✗ **does not hold**") && md.contains("![speed contours](contours.png)"));
    let html = std::fs::read_to_string(dir.join("compare.html")).unwrap();
    assert!(html.contains("data:image/png;base64,") && html.contains("class=\"fail\""));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("fit.json")).unwrap()).unwrap();
    assert_eq!(json["pass"], false);
    assert_eq!(json["from"], "06:00");
    assert_eq!(json["fit"]["hour_coverage"]["missing_in_field"], 1);
    assert_eq!(json["criteria"].as_array().unwrap().len(), 7);
    assert_eq!(json["ramp_criteria"].as_array().unwrap().len(), 4);
    assert_eq!(json["sim_bottlenecks"][0]["onset_s"], 7 * 3600);
    if std::env::var_os("PLATOONSIM_COMPARE_KEEP").is_none() {
        let _ = std::fs::remove_dir_all(&dir);
    }
}
