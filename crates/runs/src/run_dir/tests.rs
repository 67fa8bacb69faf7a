//! The run directory's writer, on real runs and by hand-made records.

use super::*;
use platoonsim_sim::vehicle::{Kind, ModeLabel};
use platoonsim_sim::{Queued, Trip, TripStatus};

fn record(speed: Option<f64>) -> DetectorRecord {
    DetectorRecord {
        detector: "discharge".into(),
        kind: "mainline".into(),
        position_m: 6100.0,
        lane: "all".into(),
        interval_start_s: 1200.0,
        interval_s: 300.0,
        count: 180,
        cav_count: 90,
        flow_vph: 2160.0,
        speed_kmh: speed,
        occupancy: 0.125,
    }
}

#[test]
fn detectors_csv_has_the_columns_and_empty_speed_cells() {
    let bytes = detectors_csv(&[record(Some(97.25)), record(None)], None).unwrap();
    let text = String::from_utf8(bytes).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines,
        vec![
            "detector,kind,position_m,lane,interval_start_s,interval_s,count,cav_count,flow_vph,speed_kmh,occupancy",
            "discharge,mainline,6100,all,1200,300,180,90,2160,97.25,0.125",
            "discharge,mainline,6100,all,1200,300,180,90,2160,,0.125",
        ]
    );
}

/// A real five-minute run of the homogeneous road.
fn short_run() -> (Config, Output) {
    let o = platoonsim_scenario::Overrides {
        duration_s: Some(300.0),
        warmup_s: Some(60.0),
        ..Default::default()
    };
    let config = platoonsim_scenario::load_with("homogeneous", &o).unwrap();
    let out = platoonsim_sim::run(&config, None).unwrap();
    (config, out)
}

#[test]
fn write_run_writes_every_file_atomically() {
    let dir = std::env::temp_dir().join(format!("platoonsim-output-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let (config, out) = short_run();
    let written = write_run(&dir, &config, &out, Format::Csv).unwrap();
    assert_eq!(written.len(), 5);
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "detectors.csv",
            "road.json",
            "scenario.json",
            "scenario.toml",
            "summary.json"
        ]
    );
    // road.json reads back into the contract's type, as the builder made it.
    let road: platoonsim_rundir::road::RoadSketch =
        serde_json::from_slice(&std::fs::read(dir.join("road.json")).unwrap()).unwrap();
    assert_eq!(road, road_sketch(&config).unwrap());
    assert_eq!((road.lanes, road.end_m), (3, 6500.0));
    let s: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(s["vehicle_updates"], out.summary.vehicle_updates);
    let csv = std::fs::read(dir.join("detectors.csv")).unwrap();
    assert_eq!(csv, detectors_csv(&out.detectors, None).unwrap());
    let c: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("scenario.json")).unwrap()).unwrap();
    assert_eq!(c["road"]["length_m"], 6500.0);
    let back = platoonsim_scenario::load(dir.join("scenario.toml").to_str().unwrap()).unwrap();
    assert_eq!(back, config);
}

#[test]
fn trips_and_trajectories_csv_text() {
    let o = platoonsim_scenario::Overrides {
        duration_s: Some(60.0),
        ..Default::default()
    };
    let sr99 = platoonsim_scenario::load_with("sr99", &o).unwrap();
    assert_eq!(entrance_name(&sr99, 0), "mainline");
    assert_eq!(entrance_name(&sr99, 7), "OR7");
    assert_eq!(off_ramp_name(&sr99, 2), "FR3");
    let trip = |status, left: Option<f64>| Trip {
        id: 42,
        kind: Kind::Cav,
        origin: 7,
        status,
        entered_s: 12.3,
        arrived_s: 12.05,
        depart_delay_s: 0.25,
        left_s: left,
        travel_time_s: left.map(|l| l - 12.3),
        entry_x_m: 5734.0,
        last_x_m: 9000.25,
        lane_changes: 2,
        max_platoon: 3,
        max_platoon_tg2: 1,
        energy: None,
        measured: false,
    };
    let trips = [
        trip(TripStatus::Exited { off_ramp: Some(2) }, Some(112.5)),
        trip(TripStatus::Exited { off_ramp: None }, Some(112.5)),
        trip(TripStatus::MissedExitThenEnd { missed: 2 }, Some(112.5)),
        trip(TripStatus::InNetwork, None),
    ];
    let queued = [Queued {
        id: 43,
        kind: Kind::Human,
        origin: 0,
        arrived_s: 55.5,
        depart_delay_s: 4.5,
    }];
    // sr99 names its clock start (05:00): the clock columns come last.
    let text = String::from_utf8(trips_csv(&sr99, &trips, &queued).unwrap()).unwrap();
    assert_eq!(
        text.lines().collect::<Vec<_>>(),
        [
            "id,kind,origin,destination,status,entered_s,depart_delay_s,left_s,travel_time_s,entry_x_m,last_x_m,lane_changes,max_platoon,max_platoon_tg2,measured,entrance_arrival_s,entered_clock,left_clock",
            "42,cav,OR7,FR3,exited,12.3,0.25,112.5,100.2,5734,9000.25,2,3,1,false,12.05,05:00:12.3,05:01:52.5",
            "42,cav,OR7,end,exited,12.3,0.25,112.5,100.2,5734,9000.25,2,3,1,false,12.05,05:00:12.3,05:01:52.5",
            "42,cav,OR7,end,missed_exit_then_end,12.3,0.25,112.5,100.2,5734,9000.25,2,3,1,false,12.05,05:00:12.3,05:01:52.5",
            "42,cav,OR7,,in_network,12.3,0.25,,,5734,9000.25,2,3,1,false,12.05,05:00:12.3,",
            "43,human,mainline,,queued,,4.5,,,,,0,0,0,false,55.5,,",
        ]
    );
    // Without a clock start, no clock columns.
    let mut plain = sr99.clone();
    plain.clock_start_s = None;
    let text = String::from_utf8(trips_csv(&plain, &trips[3..], &queued).unwrap()).unwrap();
    assert_eq!(
        text.lines().collect::<Vec<_>>(),
        [
            "id,kind,origin,destination,status,entered_s,depart_delay_s,left_s,travel_time_s,entry_x_m,last_x_m,lane_changes,max_platoon,max_platoon_tg2,measured,entrance_arrival_s",
            "42,cav,OR7,,in_network,12.3,0.25,,,5734,9000.25,2,3,1,false,12.05",
            "43,human,mainline,,queued,,4.5,,,,,0,0,0,false,55.5",
        ]
    );
    let homogeneous = Config::homogeneous(0.5, 2000.0, 60.0, 0.0, 1);
    assert_eq!(entrance_name(&homogeneous, 0), "mainline");

    let point = TrajectoryPoint {
        t_s: 30.5,
        id: 7,
        kind: Kind::Human,
        lane: 0,
        x_m: -120.5,
        v_mps: 0.0,
        a_mps2: -1.25,
        mode: ModeLabel::Blc,
        regime: None,
        platoon_pos: 1,
    };
    let mut bytes = Vec::new();
    write_trajectories(&mut bytes, &[point]).unwrap();
    assert_eq!(
        String::from_utf8(bytes).unwrap(),
        "t_s,id,kind,lane,x_m,v_mps,a_mps2,mode,platoon_pos,regime\n30.5,7,human,1,-120.5,0,-1.25,blc,1,\n"
    );
}

#[test]
fn write_run_writes_the_records_asked_for_and_removes_stale_ones() {
    let dir = std::env::temp_dir().join(format!("platoonsim-output-rec-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let o = platoonsim_scenario::Overrides {
        duration_s: Some(120.0),
        warmup_s: Some(30.0),
        ..Default::default()
    };
    let config = platoonsim_scenario::load_with("homogeneous", &o).unwrap();
    let rec = platoonsim_sim::Recording {
        trips: true,
        trajectories: Some(platoonsim_sim::TrajectorySpec {
            period_s: 10.0,
            window_s: None,
            x_m: None,
        }),
    };
    let out = platoonsim_sim::run_recording(&config, &rec, None).unwrap();
    let written = write_run(&dir, &config, &out, Format::Csv).unwrap();
    assert_eq!(written.len(), 7);
    let trips = std::fs::read_to_string(dir.join("trips.csv")).unwrap();
    // One row per vehicle that entered, one per vehicle still queued at the end.
    assert_eq!(
        trips.lines().count() as u64,
        1 + out.summary.vehicles_entered + out.summary.vehicles_waiting
    );
    assert_eq!(
        trips.matches(",queued,").count() as u64,
        out.summary.vehicles_waiting
    );
    let traj = std::fs::read_to_string(dir.join("trajectories.csv")).unwrap();
    let rows = out.trajectories.as_ref().unwrap().len();
    assert!(rows > 0);
    assert_eq!(traj.lines().count(), 1 + rows);
    // A run without the records removes those of the earlier run.
    let plain = platoonsim_sim::run(&config, None).unwrap();
    assert_eq!(
        write_run(&dir, &config, &plain, Format::Csv).unwrap().len(),
        5
    );
    assert!(!dir.join("trips.csv").exists());
    assert!(!dir.join("trajectories.csv").exists());
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 5);
}

#[test]
fn collisions_csv_has_a_row_per_event() {
    use platoonsim_sim::CollisionKind;
    let rear = CollisionEvent {
        t_s: 61.3,
        kind: CollisionKind::RearEnd,
        lane: 2,
        x_m: 4020.5,
        vehicle: 17,
        vehicle_kind: "human",
        v_mps: 12.25,
        other: Some(15),
        other_kind: Some("cav"),
        other_v_mps: Some(3.5),
        overlap_m: 0.125,
    };
    let end = CollisionEvent {
        kind: CollisionKind::LaneEnd,
        other: None,
        other_kind: None,
        other_v_mps: None,
        ..rear.clone()
    };
    let text = String::from_utf8(collisions_csv(&[rear, end]).unwrap()).unwrap();
    assert_eq!(
        text.lines().collect::<Vec<_>>(),
        [
            "t_s,kind,lane,x_m,vehicle,vehicle_kind,v_mps,other,other_kind,other_v_mps,overlap_m",
            "61.3,rear-end,2,4020.5,17,human,12.25,15,cav,3.5,0.125",
            "61.3,lane-end,2,4020.5,17,human,12.25,,,,0.125",
        ]
    );
}
