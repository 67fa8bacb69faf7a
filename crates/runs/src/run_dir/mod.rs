//! The one writer of a run directory (`platoonsim run --out DIR` and the Python binding's
//! `Run.write(DIR)` both call it); the names and columns are `platoonsim-rundir`'s. Files are
//! written atomically through [`crate::atomic`], `summary.json` last.
//!
//! | file | content |
//! |---|---|
//! | `summary.json` | the engine's `Summary`, pretty JSON |
//! | `detectors.csv` | one row per detector, lane (1 = rightmost, `all`) and interval |
//! | `*.parquet` | with [`Format::Parquet`]: the tables detectors, trips and trajectories as Parquet instead of CSV ([`parquet`]) |
//! | `scenario.json` | the resolved [`Config`] |
//! | `scenario.toml` | the same as a complete scenario file (`platoonsim run DIR/scenario.toml` reruns it) |
//! | `road.json` | the road as the engine built it, for the viewer ([`road_sketch`]) |
//! | `trips.csv` | with the trip records: one row per vehicle that entered the road, then one per vehicle still in an entrance queue at the end ([`trips_csv`]) |
//! | `trajectories.csv` | with the trajectory records: one row per vehicle and sample ([`write_trajectories`]) |
//! | `collisions.csv` | only if the run had collisions: one row per [`CollisionEvent`] ([`collisions_csv`]) |

use crate::atomic::{
    check_output, check_writable_dir, remove_output, write_atomic, write_atomic_with,
};
use crate::columnar::Format;
use crate::detectors::Scope;
use crate::Error;
use platoonsim_rundir::{
    COLLISIONS, COLLISION_COLUMNS, DETECTORS, ROAD_JSON, RUN_FILES, SCENARIO_JSON, SCENARIO_TOML,
    SUMMARY, TABLES, TRAJECTORIES, TRAJECTORY_HEADER, TRIPS,
};
use platoonsim_sim::{CollisionEvent, Config, DetectorRecord, Output, TrajectoryPoint};
use std::io::Write;
use std::path::{Path, PathBuf};

pub mod parquet;
mod road;
mod trips;

pub use road::road_sketch;
pub use trips::{entrance_name, off_ramp_name, trips_csv};

fn cannot_write(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::Other(format!("cannot write {}: {e}", path.display()))
}

/// Write every output file of a run into `dir` (created if missing), the tables
/// (`detectors`, `trips`, `trajectories`) in `format`; returns the paths written,
/// `summary.json` last. See [`write_run_files`] and [`write_summary`].
pub fn write_run(
    dir: &Path,
    config: &Config,
    output: &Output,
    format: Format,
) -> Result<Vec<PathBuf>, Error> {
    std::fs::create_dir_all(dir).map_err(|e| {
        Error::Other(format!(
            "cannot create the output directory {}: {e}",
            dir.display()
        ))
    })?;
    let mut written = write_run_files(dir, config, output, format)?;
    written.push(write_summary(dir, output)?);
    Ok(written)
}

/// Write `summary.json`, after every other file of the run: a run killed while writing leaves
/// no summary, so that a directory with one always holds a finished run.
pub fn write_summary(dir: &Path, output: &Output) -> Result<PathBuf, Error> {
    let path = dir.join(SUMMARY);
    write_atomic(&path, &json(&output.summary)?).map_err(|e| cannot_write(&path, e))?;
    Ok(path)
}

/// Before a run into `dir`: remove the `.tmp` files an interrupted earlier run left of its own
/// outputs. Other files of the directory are left alone.
pub fn remove_stale_tmp(dir: &Path) -> Result<(), Error> {
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
/// (`detectors`, `trips`, `trajectories`) in `format`; returns the paths written. `road.json`
/// is written for every run (the viewer draws the road from it). `trips` and
/// `trajectories` are written if the output has the records, `collisions.csv` if the run had
/// collisions. A table of an earlier run that this one does not write (in either format) is
/// removed, and so is an earlier run's summary, first.
pub fn write_run_files(
    dir: &Path,
    config: &Config,
    output: &Output,
    format: Format,
) -> Result<Vec<PathBuf>, Error> {
    // An earlier run's summary would mark the files replaced below as finished until ours.
    remove_stale(&dir.join(SUMMARY))?;
    let files: [(&str, Vec<u8>); 3] = [
        (SCENARIO_JSON, json(config)?),
        (
            SCENARIO_TOML,
            platoonsim_scenario::to_toml(config).into_bytes(),
        ),
        (ROAD_JSON, json(&road_sketch(config)?)?),
    ];
    let mut written = Vec::with_capacity(files.len() + 3);
    let mut put = |path: PathBuf, bytes: &[u8]| -> Result<(), Error> {
        write_atomic(&path, bytes).map_err(|e| cannot_write(&path, e))?;
        written.push(path);
        Ok(())
    };
    for (name, bytes) in files {
        put(dir.join(name), &bytes)?;
    }
    let ext = format.ext();
    let detectors = detectors_csv(&output.detectors, config.clock_start_s)?;
    match format {
        Format::Csv => put(dir.join(DETECTORS.csv), &detectors)?,
        Format::Parquet => put(
            dir.join(DETECTORS.parquet),
            &parquet::csv_to_parquet(&detectors, &parquet::detector_kind)?,
        )?,
    }
    if let Some(trips) = &output.trips {
        let queued = output.queued.as_deref().unwrap_or_default();
        let csv = trips_csv(config, trips, queued)?;
        match format {
            Format::Csv => put(dir.join(TRIPS.csv), &csv)?,
            Format::Parquet => put(
                dir.join(TRIPS.parquet),
                &parquet::csv_to_parquet(&csv, &parquet::trip_kind)?,
            )?,
        }
    }
    if let Some(rows) = &output.trajectories {
        let path = dir.join(TRAJECTORIES.file(ext));
        match format {
            Format::Csv => write_atomic_with(&path, |w| write_trajectories(w, rows))
                .map_err(|e| cannot_write(&path, e))?,
            Format::Parquet => parquet::write_trajectories_parquet(&path, rows)?,
        }
        written.push(path);
    }
    // Tables this run did not write, in either format, are an earlier run's.
    for table in TABLES {
        for name in [table.csv, table.parquet] {
            let path = dir.join(name);
            if !written.contains(&path) {
                remove_stale(&path)?;
            }
        }
    }
    let collisions_file = dir.join(COLLISIONS);
    if output.collision_events.is_empty() {
        remove_stale(&collisions_file)?;
    } else {
        let bytes = collisions_csv(&output.collision_events)?;
        write_atomic(&collisions_file, &bytes).map_err(|e| cannot_write(&collisions_file, e))?;
        written.push(collisions_file);
    }
    Ok(written)
}

/// Remove a file of an earlier run (nothing if there is none) through the one checked path
/// (`remove_output`: a regular file, or a link's regular target; anything else is refused,
/// never unlinked).
fn remove_stale(path: &Path) -> Result<(), Error> {
    remove_output(path).map_err(|e| {
        Error::Other(format!(
            "cannot remove {} of an earlier run: {e}",
            path.display()
        ))
    })
}

/// Before any work: refuse a run directory where one of the run's file names is something no
/// output may replace or remove (a device, FIFO, directory, socket, or a link to one), and a
/// directory that cannot take a new file.
pub fn check_run_dir(dir: &Path) -> std::io::Result<()> {
    check_writable_dir(dir)?;
    for name in RUN_FILES {
        check_output(&dir.join(name))?;
    }
    Ok(())
}

/// `collisions.csv`: the header, then one row per event in time order. `kind` is `rear-end`
/// or `lane-end`; `lane` counts from the right (1 = rightmost); the `other*` cells are empty
/// for a lane end (no other vehicle).
pub fn collisions_csv(events: &[CollisionEvent]) -> Result<Vec<u8>, Error> {
    let enc = |e: csv::Error| Error::Other(format!("cannot encode {COLLISIONS}: {e}"));
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    w.write_record(COLLISION_COLUMNS).map_err(enc)?;
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
        ])
        .map_err(enc)?;
    }
    w.into_inner()
        .map_err(|e| Error::Other(format!("cannot encode {COLLISIONS}: {e}")))
}

/// `trajectories.csv`, written row by row (it can be large): the header, then one row per
/// sample. `lane` counts lateral positions from the right starting at 1 (one more than the
/// engine's index: on the homogeneous road the lane numbers of detectors.csv; on a network
/// position 1 is that of the acceleration lanes); `mode` is
/// [`platoonsim_sim::vehicle::ModeLabel::as_str`]; `platoon_pos` the position in the CACC
/// string (1: leads one or drives alone); `regime` an automated CAV's control regime
/// ([`platoonsim_model::cav::CavMode::as_str`]), empty otherwise. Every field is a number or a
/// fixed word, so no quoting is needed.
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
pub fn json<T: serde::Serialize + ?Sized>(value: &T) -> Result<Vec<u8>, Error> {
    let mut bytes = serde_json::to_vec_pretty(value)
        .map_err(|e| Error::Other(format!("cannot encode JSON: {e}")))?;
    bytes.push(b'\n');
    Ok(bytes)
}

/// `detectors.csv`: the header, then one row per record; an interval without vehicles has an
/// empty `speed_kmh` cell. With `clock_start_s` (`run.clock_start`) a `clock` column
/// ("HH:MM:SS", the interval's start) follows `interval_start_s`.
pub fn detectors_csv(
    records: &[DetectorRecord],
    clock_start_s: Option<u32>,
) -> Result<Vec<u8>, Error> {
    // One writer for the run files and the experiment runner's kept detector files.
    let (bytes, _) = crate::detectors::to_csv(records, Scope::All, clock_start_s)
        .map_err(|e| Error::Other(e.to_string()))?;
    Ok(bytes)
}

#[cfg(test)]
mod tests;
