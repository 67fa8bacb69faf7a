//! # platoonsim-experiment: the paper's experiments
//!
//! * [`experiments`]: the table of experiments ([`EXPERIMENTS`]): `capacity` (Fig. 4),
//!   `sensitivity` (Table 3), `flow-aware`, `calibrate-flow-aware`, `sr99` (Table 4,
//!   Figs. 6-8), `sr99-demand` (the demand-scale search), `behaviour` and `energy` (beyond
//!   the paper); each a procedure that makes cells and a report; [`corridor`] reads contours,
//!   lane series and bottlenecks from detector records.
//! * [`paper`]: the paper's values, each with its source; [`table`] summarizes with them.
//! * [`report`]: `REPORT.md` and a self-contained `report.html` over several experiments.
//!
//! The runs go through `platoonsim-runs` (cells, the resumable runner, run files,
//! statistics, tables, sweeps), whose modules are re-exported here under their names.

pub mod corridor;
pub mod experiments;
pub mod paper;
pub mod report;
pub mod table;

// The runner and its files, re-exported under their former paths.
pub use platoonsim_runs::{
    atomic, columnar, design, detectors, hash, metric, progress, record, runner, safety, stats,
    sweep, Error, Metric, VERSION,
};

pub use design::{Cell, Labels, RunSpec};
pub use experiments::{
    run_experiment, Check, Experiment, ExperimentName, ExperimentOutput, Part, Settings,
    CAPACITY_FILL_S, EXPERIMENTS,
};
pub use runner::{Outcome, Runner};
pub use stats::Stats;
