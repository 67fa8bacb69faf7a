//! # platoonsim-runs: grids of runs, resumable, and their tables
//!
//! * [`design`]: cells (labels + resolved configuration) and runs (cell × seed, seeds 1..=N).
//! * [`runner`]: runs in parallel (rayon; each run single-threaded), with a progress bar,
//!   resumable through atomic run files `<dir>/runs/<key>.json`, where the key is the
//!   stable hash of the run's configuration ([`hash`]); [`record`] is the run file's
//!   format. Selected runs also keep detector records beside their run file ([`detectors`]).
//! * [`metric`]: the per-run metrics, a typed [`Metric`] per numeric field of the engine's
//!   summary (the tables' columns, the sweep files' `metrics`).
//! * [`stats`]: mean, sample sd, n, Student-t 95 % confidence interval.
//! * [`table`]: `runs.csv`, `summary.csv` (or Parquet, [`columnar`]) and Markdown tables.
//! * [`safety`]: runs with collisions (a failed run) and the safety measures per cell.
//! * [`sweep`]: sweeps of any scenario described as data (`sweeps/*.toml`).
//! * [`run_dir`]: the one writer of a run directory (`platoonsim run --out`, the Python
//!   binding), with the names and columns of `platoonsim-rundir`.
//! * [`atomic`]: the one atomic file writer (also used by the CLI); [`page`]: Markdown as a
//!   self-contained HTML page.
//!
//! The paper's experiments (`platoonsim-experiment`) and the calibration to field data
//! (`platoonsim-calibrate`) run through this crate.

pub mod atomic;
pub mod columnar;
pub mod design;
pub mod detectors;
pub mod hash;
pub mod metric;
pub mod page;
pub mod progress;
pub mod record;
pub mod run_dir;
pub mod runner;
pub mod safety;
pub mod stats;
pub mod sweep;
pub mod table;

pub use design::{Cell, Labels, RunSpec};
pub use metric::Metric;
pub use runner::{Outcome, Runner};
pub use stats::Stats;

use serde::Serialize;
use std::path::Path;

/// A figure of an experiment: `<dir>/<stem>.png` and `.svg`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Figure {
    pub title: String,
    pub stem: String,
}

/// The crate version, written into run files and provenance.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Why an experiment could not be run or written.
#[derive(Clone, Debug, thiserror::Error)]
pub enum Error {
    #[error("cannot write or read {path}: {message}")]
    Io { path: String, message: String },
    #[error(transparent)]
    Scenario(#[from] std::sync::Arc<platoonsim_scenario::ScenarioError>),
    #[error("run {key} (seed {seed}) failed: {message}")]
    Run {
        key: String,
        seed: u64,
        message: String,
    },
    #[error("cannot start the worker threads: {0}")]
    Threads(String),
    #[error("{0}")]
    Other(String),
}

impl Error {
    pub fn io(path: &Path, e: std::io::Error) -> Error {
        Error::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        }
    }
}

impl From<platoonsim_scenario::ScenarioError> for Error {
    fn from(e: platoonsim_scenario::ScenarioError) -> Error {
        Error::Scenario(std::sync::Arc::new(e))
    }
}
