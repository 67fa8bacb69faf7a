//! # platoonsim-experiment: the paper's experiments, as data
//!
//! * [`design`]: cells (labels + resolved configuration) and runs (cell × seed, seeds 1..=N).
//! * [`runner`]: runs in parallel (rayon; each run single-threaded), with a progress bar,
//!   resumable through atomic run files `<out>/<experiment>/runs/<key>.json`, where the key
//!   is the stable hash of the run's configuration ([`hash`]).
//!   Selected runs also keep detector records beside their run file ([`detectors`]).
//! * [`stats`]: mean, sample sd, n, Student-t 95 % confidence interval.
//! * [`table`]: `runs.csv`, `summary.csv` and `run.json`.
//! * [`paper`]: the paper's values, each with its source.
//! * [`experiments`]: `capacity` (Fig. 4), `sensitivity` (Table 3), `flow-aware`,
//!   `calibrate-flow-aware`, `sr99` (Table 4, Figs. 6-8) and `sr99-demand` (the demand-scale
//!   search); [`corridor`] reads contours, lane series and bottlenecks from detector records.
//! * [`compare`]: simulated detector data against field data (GEH, speeds, bottlenecks,
//!   the FHWA Toolbox III criteria; `platoonsim compare`).
//! * [`safety`]: runs with collisions (a failed run) and the safety measures per cell.
//! * [`report`]: `REPORT.md` and a self-contained `report.html` over several experiments.
//! * [`atomic`]: the one atomic file writer (also used by the CLI).

pub mod atomic;
pub mod calibrate;
pub mod columnar;
pub mod compare;
pub mod corridor;
pub mod design;
pub mod detectors;
pub mod experiments;
pub mod field_obs;
pub mod hash;
pub mod paper;
pub mod progress;
pub mod record;
pub mod report;
pub mod runner;
pub mod safety;
pub mod stats;
pub mod sweep;
pub mod table;

pub use design::{Cell, Labels, RunSpec};
pub use experiments::{
    run_experiment, Check, Experiment, ExperimentName, ExperimentOutput, Part, Settings,
    CAPACITY_FILL_S, EXPERIMENTS,
};
pub use runner::{Outcome, Runner};
pub use stats::Stats;

use std::path::Path;

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
