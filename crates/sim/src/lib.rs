//! # platoonsim-sim: the engine
//!
//! Principal types: [`Config`] (validated input), [`Simulation`] (the state and
//! [`Simulation::step`]), [`Output`]/[`Summary`]/[`DetectorRecord`] (what a run produces), and
//! [`run`] (config → output, single-threaded and deterministic).

pub mod config;
pub mod summary;

pub use config::{Config, Demand, DetectorSpec, FlowAwareConfig, PdConfig, Road, Strategy};
pub use summary::{DetectorRecord, Output, Summary};

/// Progress callback: called with (simulated seconds so far, total seconds) every simulated minute.
pub type Progress<'a> = &'a mut dyn FnMut(f64, f64);

/// Run a whole simulation: validate, step to the end, and collect the outputs.
pub fn run(config: &Config, progress: Option<Progress<'_>>) -> Result<Output, String> {
    let _ = (config, progress);
    todo!("engine")
}
