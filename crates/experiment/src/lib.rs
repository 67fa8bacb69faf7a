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
//! statistics, tables, sweeps); import its items from there.

pub mod corridor;
pub mod experiments;
pub mod paper;
pub mod report;
pub mod table;

pub use experiments::{
    run_experiment, Check, Experiment, ExperimentName, ExperimentOutput, Part, Settings,
    CAPACITY_FILL_S, EXPERIMENTS,
};
