//! A run directory as field-comparable data: its `detectors.csv` cross-section rows as
//! [`Obs`] at clock time (`run.clock_start` of its `scenario.toml`), its detectors as
//! [`Placed`] stations (position in the corridor coordinate of `position_m`, kind, lanes).
//! Several runs (replications) are averaged per station and interval
//! ([`crate::field_obs::mean_over_runs`]); they must have the same detectors and clock.

use crate::detectors::from_csv;
use crate::field_obs::{mean_over_runs, to_obs};
use crate::Error;
use platoonsim_field::{Obs, Placed, StationKind};
use platoonsim_rundir::{DetectorKind, Lane, DETECTORS, SCENARIO_TOML};
use platoonsim_scenario::bounded;
use platoonsim_scenario::clock::{format_clock, parse_clock};
use platoonsim_sim::DetectorRecord;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// One run directory, read.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    pub dir: PathBuf,
    /// Clock time of t = 0, s after midnight.
    pub clock_start_s: u32,
    pub obs: Vec<Obs>,
    pub places: Vec<Placed>,
}

/// Replications read and averaged.
#[derive(Clone, Debug, PartialEq)]
pub struct Runs {
    pub dirs: Vec<PathBuf>,
    pub obs: Vec<Obs>,
    pub places: Vec<Placed>,
}

fn other(msg: String) -> Error {
    Error::Other(msg)
}

/// `run.clock_start` of a run's `scenario.toml`, s after midnight.
pub fn clock_start(dir: &Path) -> Result<u32, Error> {
    let path = dir.join(SCENARIO_TOML);
    let text = bounded::read_text(&path, platoonsim_scenario::limits::MAX_FILE_BYTES as u64)
        .map_err(|e| Error::io(&path, e))?;
    let value: toml::Value = toml::from_str(&text)
        .map_err(|e| other(format!("{}: not a scenario file: {e}", path.display())))?;
    let clock = value.get("run").and_then(|r| r.get("clock_start"));
    match clock {
        Some(toml::Value::String(s)) => parse_clock(s).ok_or_else(|| {
            other(format!(
                "{}: run.clock_start = {s:?} is not a clock time \"HH:MM\" or \"HH:MM:SS\"",
                path.display()
            ))
        }),
        Some(v) => Err(other(format!(
            "{}: run.clock_start = {v} is not a clock time \"HH:MM\" or \"HH:MM:SS\"",
            path.display()
        ))),
        None => Err(other(format!(
            "{}: the scenario has no run.clock_start; field data is at clock time, so the run \
             must say when it starts: set run.clock_start (e.g. \"05:00\") and run it again",
            path.display()
        ))),
    }
}

/// The detectors of `records` as stations: position, kind (`mainline`, `on-ramp`,
/// `off-ramp`), lanes (the lane rows it has).
pub fn places(records: &[DetectorRecord]) -> Vec<Placed> {
    let mut by_name: BTreeMap<&str, (f64, &str, BTreeSet<&str>)> = BTreeMap::new();
    for r in records {
        let e = by_name
            .entry(&r.detector)
            .or_insert((r.position_m, &r.kind, BTreeSet::new()));
        if !Lane::is_all(&r.lane) {
            e.2.insert(&r.lane);
        }
    }
    let mut out: Vec<Placed> = by_name
        .into_iter()
        .map(|(name, (x_m, kind, lanes))| Placed {
            station: name.to_string(),
            x_m,
            kind: match kind.parse() {
                Ok(DetectorKind::Mainline) => StationKind::Mainline,
                Ok(DetectorKind::OnRamp) => StationKind::OnRamp,
                Ok(DetectorKind::OffRamp) => StationKind::OffRamp,
                Err(_) => StationKind::Other(kind.to_string()),
            },
            lanes: lanes.len() as u32,
            name: name.to_string(),
        })
        .collect();
    out.sort_by(|a, b| a.x_m.total_cmp(&b.x_m).then(a.station.cmp(&b.station)));
    out
}

/// Read one run directory.
pub fn read_run(dir: &Path) -> Result<Run, Error> {
    let clock_start_s = clock_start(dir)?;
    let path = DETECTORS.csv_in(dir);
    // Read whole: bounded like the viewer's tables (5 million detector records are ~500 MB).
    let bytes = match bounded::read(&path, 2 << 30) {
        Ok(b) => b,
        Err(e) if dir.join(DETECTORS.parquet).exists() => {
            return Err(other(format!(
                "{}: {e}; this run wrote {}, and compare reads {}: run it again with \
                 --format csv",
                path.display(),
                DETECTORS.parquet,
                DETECTORS.csv
            )))
        }
        Err(e) => return Err(Error::io(&path, e)),
    };
    let records = from_csv(&bytes).map_err(|e| other(format!("{}: {e}", path.display())))?;
    Ok(Run {
        dir: dir.to_path_buf(),
        clock_start_s,
        obs: to_obs(&records, clock_start_s),
        places: places(&records),
    })
}

/// Read runs (replications of one scenario) and average them.
pub fn read_runs(dirs: &[PathBuf]) -> Result<Runs, Error> {
    let runs = dirs
        .iter()
        .map(|d| read_run(d))
        .collect::<Result<Vec<_>, _>>()?;
    let Some(first) = runs.first() else {
        return Err(other("no run directory given".into()));
    };
    for r in &runs[1..] {
        if r.clock_start_s != first.clock_start_s {
            return Err(other(format!(
                "{} starts at {} but {} at {}: replications must share run.clock_start",
                r.dir.display(),
                format_clock(r.clock_start_s),
                first.dir.display(),
                format_clock(first.clock_start_s)
            )));
        }
        if r.places != first.places {
            return Err(other(format!(
                "{} and {} have different detectors (names, positions or kinds): \
                 replications must be runs of one scenario",
                r.dir.display(),
                first.dir.display()
            )));
        }
    }
    // One run is used as it is: its mean would equal it only up to rounding (s·w/w).
    let obs = if runs.len() == 1 {
        first.obs.clone()
    } else {
        mean_over_runs(&runs.iter().map(|r| r.obs.clone()).collect::<Vec<_>>())
    };
    Ok(Runs {
        dirs: dirs.to_vec(),
        obs,
        places: first.places.clone(),
    })
}
