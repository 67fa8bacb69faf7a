//! A run's output files and its one-paragraph summary. Files are written with
//! [`crate::atomic::write_atomic`].
//!
//! | file | content |
//! |---|---|
//! | `summary.json` | [`Summary`], pretty JSON |
//! | `detectors.csv` | one row per detector, lane (1 = rightmost, `all`) and interval |
//! | `*.parquet` | with `--format parquet`: the tables detectors, trips and trajectories as Parquet instead of CSV ([`crate::tables`]) |
//! | `scenario.json` | the resolved [`Config`] |
//! | `scenario.toml` | the same as a complete scenario file (`platoonsim run DIR/scenario.toml` reruns it) |
//! | `trips.csv` | with `--trips`: one row per vehicle that entered the road, then one per vehicle still in an entrance queue at the end ([`trips_csv`]) |
//! | `trajectories.csv` | with `--trajectories`: one row per vehicle and sample ([`write_trajectories`]) |
//! | `collisions.csv` | only if the run had collisions: one row per [`CollisionEvent`] ([`collisions_csv`]) |

use crate::atomic::{write_atomic, write_atomic_with};
use crate::tables::{self, FormatArg};
use anyhow::{Context, Result};
use platoonsim_experiment::detectors::Scope;
use platoonsim_sim::{CollisionEvent, Config, DetectorRecord, Output, TrajectoryPoint};
use std::io::Write;
use std::path::{Path, PathBuf};

mod paragraph;
mod trips;

pub use paragraph::{paragraph, si};
pub use trips::trips_csv;

/// The file of a run's collisions; like the record files, a stale one is removed by a run
/// without collisions, so that its absence means "no collision".
pub const COLLISIONS_FILE: &str = "collisions.csv";

/// Write every output file of a run into `dir` (which must exist) with CSV tables; returns
/// the paths written. See [`write_run_as`].
#[cfg(test)]
pub fn write_run(dir: &Path, config: &Config, output: &Output) -> Result<Vec<PathBuf>> {
    write_run_as(dir, config, output, FormatArg::Csv)
}

/// Write every output file of a run into `dir`, the tables (`detectors`, `trips`,
/// `trajectories`) in `format`; returns the paths written, `summary.json` last. See
/// [`write_run_files`] and [`write_summary`].
#[cfg(test)]
pub fn write_run_as(
    dir: &Path,
    config: &Config,
    output: &Output,
    format: FormatArg,
) -> Result<Vec<PathBuf>> {
    let mut written = write_run_files(dir, config, output, format)?;
    written.push(write_summary(dir, output)?);
    Ok(written)
}

/// The file whose presence says a run finished; see [`write_summary`].
pub const SUMMARY_FILE: &str = "summary.json";

/// Write `summary.json`, after every other file of the run: a run killed while writing leaves
/// no summary, so that a directory with one always holds a finished run.
pub fn write_summary(dir: &Path, output: &Output) -> Result<PathBuf> {
    let path = dir.join(SUMMARY_FILE);
    write_atomic(&path, &json(&output.summary)?)
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok(path)
}

/// Every file a run may write into its directory (the tables in both formats).
pub const RUN_FILES: [&str; 11] = [
    SUMMARY_FILE,
    "scenario.json",
    "scenario.toml",
    "detectors.csv",
    "detectors.parquet",
    "trips.csv",
    "trips.parquet",
    "trajectories.csv",
    "trajectories.parquet",
    COLLISIONS_FILE,
    "view.html",
];

/// Before a run into `dir`: remove the `.tmp` files an interrupted earlier run left of its own
/// outputs. Other files of the directory are left alone.
pub fn remove_stale_tmp(dir: &Path) -> Result<()> {
    // An atomic write's temporary file is `NAME.PID-N.tmp` (older builds: `NAME.tmp`).
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    for e in entries.flatten() {
        let file = e.file_name().to_string_lossy().into_owned();
        let ours = RUN_FILES.iter().any(|name| {
            file.strip_prefix(name)
                .and_then(|rest| rest.strip_suffix(".tmp"))
                .is_some_and(|mid| mid.is_empty() || mid.starts_with('.'))
        });
        if ours {
            remove_stale(&e.path())?;
        }
    }
    Ok(())
}

/// Write every output file of a run into `dir` except `summary.json`, the tables
/// (`detectors`, `trips`, `trajectories`) in `format`; returns the paths written. `trips` and
/// `trajectories` are written if the output has the records, `collisions.csv` if the run had
/// collisions. A table of an earlier run that this one does not write (in either format) is
/// removed.
pub fn write_run_files(
    dir: &Path,
    config: &Config,
    output: &Output,
    format: FormatArg,
) -> Result<Vec<PathBuf>> {
    // An earlier run's summary would mark the files replaced below as finished until ours.
    remove_stale(&dir.join(SUMMARY_FILE))?;
    let files: [(&str, Vec<u8>); 2] = [
        ("scenario.json", json(config)?),
        (
            "scenario.toml",
            platoonsim_scenario::to_toml(config).into_bytes(),
        ),
    ];
    let mut written = Vec::with_capacity(files.len() + 3);
    let mut put = |path: PathBuf, bytes: &[u8]| -> Result<()> {
        write_atomic(&path, bytes).with_context(|| format!("cannot write {}", path.display()))?;
        written.push(path);
        Ok(())
    };
    for (name, bytes) in files {
        put(dir.join(name), &bytes)?;
    }
    let ext = format.ext();
    let table = |stem: &str| dir.join(format!("{stem}.{ext}"));
    let detectors = detectors_csv(&output.detectors, config.clock_start_s)?;
    match format {
        FormatArg::Csv => put(table("detectors"), &detectors)?,
        FormatArg::Parquet => put(
            table("detectors"),
            &tables::csv_to_parquet(&detectors, &tables::detector_kind)?,
        )?,
    }
    if let Some(trips) = &output.trips {
        let queued = output.queued.as_deref().unwrap_or_default();
        let csv = trips_csv(config, trips, queued)?;
        match format {
            FormatArg::Csv => put(table("trips"), &csv)?,
            FormatArg::Parquet => put(
                table("trips"),
                &tables::csv_to_parquet(&csv, &tables::trip_kind)?,
            )?,
        }
    }
    if let Some(rows) = &output.trajectories {
        let path = table("trajectories");
        match format {
            FormatArg::Csv => write_atomic_with(&path, |w| write_trajectories(w, rows))
                .with_context(|| format!("cannot write {}", path.display()))?,
            FormatArg::Parquet => tables::write_trajectories_parquet(&path, rows)?,
        }
        written.push(path);
    }
    // Tables this run did not write, in either format, are an earlier run's.
    for stem in ["detectors", "trips", "trajectories"] {
        for other in [FormatArg::Csv, FormatArg::Parquet] {
            let path = dir.join(format!("{stem}.{}", other.ext()));
            if !written.contains(&path) {
                remove_stale(&path)?;
            }
        }
    }
    let collisions_file = dir.join(COLLISIONS_FILE);
    if output.collision_events.is_empty() {
        remove_stale(&collisions_file)?;
    } else {
        let bytes = collisions_csv(&output.collision_events)?;
        write_atomic(&collisions_file, &bytes)
            .with_context(|| format!("cannot write {}", collisions_file.display()))?;
        written.push(collisions_file);
    }
    Ok(written)
}

/// Remove a file of an earlier run (nothing if there is none) through the one checked path
/// (`remove_output`: a regular file, or a link's regular target; anything else is refused,
/// never unlinked).
fn remove_stale(path: &Path) -> Result<()> {
    crate::atomic::remove_output(path)
        .with_context(|| format!("cannot remove {} of an earlier run", path.display()))
}

/// Before any work: refuse a run directory where one of the run's file names is something no
/// output may replace or remove (a device, FIFO, directory, socket, or a link to one), and a
/// directory that cannot take a new file.
pub fn check_run_dir(dir: &Path) -> Result<()> {
    crate::atomic::check_writable_dir(dir)?;
    for name in RUN_FILES {
        crate::atomic::check_output(&dir.join(name))?;
    }
    Ok(())
}

/// The columns of `collisions.csv`, in the order of [`CollisionEvent`]'s fields.
pub const COLLISION_COLUMNS: [&str; 11] = [
    "t_s",
    "kind",
    "lane",
    "x_m",
    "vehicle",
    "vehicle_kind",
    "v_mps",
    "other",
    "other_kind",
    "other_v_mps",
    "overlap_m",
];

/// `collisions.csv`: the header, then one row per event in time order. `kind` is `rear-end`
/// or `lane-end`; `lane` counts from the right (1 = rightmost); the `other*` cells are empty
/// for a lane end (no other vehicle).
pub fn collisions_csv(events: &[CollisionEvent]) -> Result<Vec<u8>> {
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    w.write_record(COLLISION_COLUMNS)?;
    for e in events {
        w.write_record([
            format!("{}", e.t_s),
            e.kind.as_str().to_string(),
            e.lane.to_string(),
            format!("{}", e.x_m),
            e.vehicle.to_string(),
            e.vehicle_kind.to_string(),
            format!("{}", e.v_mps),
            e.other.map(|o| o.to_string()).unwrap_or_default(),
            e.other_kind.unwrap_or_default().to_string(),
            e.other_v_mps.map(|v| format!("{v}")).unwrap_or_default(),
            format!("{}", e.overlap_m),
        ])?;
    }
    w.into_inner().context("cannot encode collisions.csv")
}

/// One line about the first collision, for the warning on stderr: time, kind, lane, place and
/// the vehicles involved.
pub fn describe_collision(e: &CollisionEvent) -> String {
    let who = match (e.other, e.other_kind) {
        (Some(o), Some(k)) => format!(
            "{} {} ({:.1} m/s) ran into {k} {o} ({:.1} m/s)",
            e.vehicle_kind,
            e.vehicle,
            e.v_mps,
            e.other_v_mps.unwrap_or(f64::NAN)
        ),
        _ => format!(
            "{} {} ({:.1} m/s) reached the end of its lane",
            e.vehicle_kind, e.vehicle, e.v_mps
        ),
    };
    format!(
        "t = {} s, {} in lane {} at x = {:.1} m: {who}, overlap {:.2} m",
        e.t_s,
        e.kind.as_str(),
        e.lane,
        e.x_m,
        e.overlap_m
    )
}

/// The header of `trajectories.csv`.
pub const TRAJECTORY_HEADER: &str = "t_s,id,kind,lane,x_m,v_mps,a_mps2,mode,platoon_pos,regime";

/// `trajectories.csv`, written row by row (it can be large): the header, then one row per
/// sample. `lane` counts lateral positions from the right starting at 1 (one more than the
/// engine's index: on the homogeneous road the lane numbers of detectors.csv; on a network
/// position 1 is that of the acceleration lanes); `mode` is
/// [`platoonsim_sim::vehicle::ModeLabel::as_str`]; `platoon_pos` the position in the CACC
/// string (1: leads one or drives alone); `regime` an automated CAV's control regime
/// ([`platoonsim_model::cav::CavMode::as_str`]), empty otherwise. Every field is a number or a fixed word,
/// so no quoting is needed.
pub fn write_trajectories(w: &mut dyn Write, rows: &[TrajectoryPoint]) -> std::io::Result<()> {
    writeln!(w, "{TRAJECTORY_HEADER}")?;
    for r in rows {
        writeln!(
            w,
            "{},{},{},{},{},{},{},{},{},{}",
            r.t_s,
            r.id,
            r.kind.as_str(),
            r.lane + 1,
            r.x_m,
            r.v_mps,
            r.a_mps2,
            r.mode.as_str(),
            r.platoon_pos,
            r.regime.map_or("", |m| m.as_str())
        )?;
    }
    Ok(())
}

/// Pretty JSON with a final newline.
pub fn json<T: serde::Serialize + ?Sized>(value: &T) -> Result<Vec<u8>> {
    let mut bytes = serde_json::to_vec_pretty(value).context("cannot encode JSON")?;
    bytes.push(b'\n');
    Ok(bytes)
}

/// `detectors.csv`: the header, then one row per record; an interval without vehicles has an
/// empty `speed_kmh` cell. With `clock_start_s` (`run.clock_start`) a `clock` column
/// ("HH:MM:SS", the interval's start) follows `interval_start_s`.
pub fn detectors_csv(records: &[DetectorRecord], clock_start_s: Option<u32>) -> Result<Vec<u8>> {
    // One writer for the run files and the experiment runner's kept detector files.
    let (bytes, _) = platoonsim_experiment::detectors::to_csv(records, Scope::All, clock_start_s)?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::paragraph::wrap;
    use super::trips::{entrance_name, off_ramp_name};
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
        let written = write_run(&dir, &config, &out).unwrap();
        assert_eq!(written.len(), 4);
        let mut names: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names,
            [
                "detectors.csv",
                "scenario.json",
                "scenario.toml",
                "summary.json"
            ]
        );
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
        let dir =
            std::env::temp_dir().join(format!("platoonsim-output-rec-{}", std::process::id()));
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
        let written = write_run(&dir, &config, &out).unwrap();
        assert_eq!(written.len(), 6);
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
        assert_eq!(write_run(&dir, &config, &plain).unwrap().len(), 4);
        assert!(!dir.join("trips.csv").exists());
        assert!(!dir.join("trajectories.csv").exists());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 4);
    }

    #[test]
    fn paragraph_mentions_the_key_figures() {
        let (config, out) = short_run();
        let s = &out.summary;
        let p = paragraph(&config, s, Path::new("out/run"));
        let flat = p.replace('\n', " ");
        let discharge = format!("{:.1} veh/h/lane", s.discharge_flow_vphpl);
        let entered = format!("{} entered", s.vehicles_entered);
        for part in [
            "homogeneous:",
            "50 % CAV",
            "2500 veh/h/lane demand",
            "detector 'discharge'",
            &discharge,
            &entered,
            "out/run",
        ] {
            assert!(flat.contains(part), "{part} missing in:\n{p}");
        }
        assert!(p.lines().all(|l| l.len() <= 96), "{p}");
    }

    #[test]
    fn paragraph_of_a_network_run_gives_its_demand_scale_and_exits() {
        let o = platoonsim_scenario::Overrides {
            duration_s: Some(60.0),
            penetration: Some(0.4),
            ..Default::default()
        };
        let config = platoonsim_scenario::load_with("sr99", &o).unwrap();
        let out = platoonsim_sim::run(&config, None).unwrap();
        let p = paragraph(&config, &out.summary, Path::new("out/run")).replace('\n', " ");
        for part in [
            "sr99:",
            "40 % CAV, the network's demand x 1.210,",
            "Network discharge (off-ramps and the end):",
            "missed exits",
        ] {
            assert!(p.contains(part), "{part} missing in:\n{p}");
        }
        assert!(!p.contains("veh/h/lane demand"), "{p}");
    }

    #[test]
    fn collisions_csv_and_the_warning_line() {
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
        let text =
            String::from_utf8(collisions_csv(&[rear.clone(), end.clone()]).unwrap()).unwrap();
        assert_eq!(
            text.lines().collect::<Vec<_>>(),
            [
                "t_s,kind,lane,x_m,vehicle,vehicle_kind,v_mps,other,other_kind,other_v_mps,overlap_m",
                "61.3,rear-end,2,4020.5,17,human,12.25,15,cav,3.5,0.125",
                "61.3,lane-end,2,4020.5,17,human,12.25,,,,0.125",
            ]
        );
        assert_eq!(
            describe_collision(&rear),
            "t = 61.3 s, rear-end in lane 2 at x = 4020.5 m: human 17 (12.2 m/s) ran into cav 15 \
             (3.5 m/s), overlap 0.12 m"
        );
        assert_eq!(
            describe_collision(&end),
            "t = 61.3 s, lane-end in lane 2 at x = 4020.5 m: human 17 (12.2 m/s) reached the end \
             of its lane, overlap 0.12 m"
        );
    }

    #[test]
    fn wrap_keeps_words_and_width() {
        let w = wrap("aaa bbb ccc ddd", 7);
        assert_eq!(w, "aaa bbb\nccc ddd");
        assert_eq!(si(12_345_678.0), "12.35 M");
        assert_eq!(si(950.0), "950");
    }
}
