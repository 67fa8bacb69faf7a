//! # platoonsim-calibrate: runs against field data
//!
//! * [`compare`]: simulated detector data against field data (GEH, speeds, bottlenecks,
//!   the FHWA Toolbox III criteria; `platoonsim compare`).
//! * [`calibrate`]: a scenario's parameters fitted to field data by CMA-ES, replayed
//!   generation by generation from run files (`platoonsim calibrate`; docs/calibrate.md).
//! * [`field_obs`]: a run's detector records as field data (`field::Obs` rows), so simulated
//!   and field data go through one set of measures.
//!
//! The runs go through `platoonsim-runs` (cells, the resumable runner, sweeps), whose
//! modules are used here under their own names.

pub mod calibrate;
pub mod compare;
pub mod field_obs;

use platoonsim_runs::{atomic, design, detectors, progress, record, runner, sweep, Error, VERSION};
