//! # platoonsim-sim: the engine
//!
//! Principal types: [`Config`] (validated input), [`Simulation`] (the state and
//! [`Simulation::step`], whose doc lists the phases), [`Output`]/[`Summary`]/[`DetectorRecord`]
//! (what a run produces), and [`run`] (config → output, single-threaded and deterministic).
//! Optional per-vehicle records: [`Recording`] → [`Trip`]s and [`TrajectoryPoint`]s
//! ([`run_recording`], module `record`). What a library user reads of the state: vehicles as
//! [`VehicleView`]s (module `view`), and after each step an [`Observer`]'s [`StepView`].
//!
//! Modules by phase: `sense` (neighbours, platoons), `decide` (lane-change decisions and
//! accelerations), `execute` (lane changes), `insert` (arrivals, insertion), `meter` (ramp meters), `detector`,
//! `metrics`, `organize` (platoon organization: the `Organizer` trait and the strategies), `rng` (named random streams).

mod automation;
pub mod behaviour;
pub mod command;
pub mod config;
mod decide;
mod desire;
mod detect;
pub mod detector;
pub mod energy;
mod error;
pub mod events;
mod execute;
mod exits;
mod here;
mod insert;
mod integrate;
mod invariants;
pub mod mechanism;
mod meter;
pub mod metrics;
pub mod network;
pub mod organize;
mod place;
pub mod record;
pub mod rng;
mod safety;
mod sense;
mod sim;
pub mod snapshot;
mod state;
mod steer;
pub mod summary;
#[cfg(test)]
mod tests_safe_gaps;
pub mod vehicle;
pub mod view;
mod yielding;

pub use command::Command;
pub use config::{
    Config, Demand, DetectorKind, DetectorSpec, FlowAwareConfig, LaneExtent, Meter, MeterLaw,
    Network, OffRamp, OnRamp, PdConfig, Road, Strategy,
};
pub use energy::{EnergyMeter, EnergySummary, TripEnergy};
pub use error::SimError;
pub use events::{Departure, Event, LaneChangeReason, Observer, StepView};
pub use organize::{Advice, LaneChoice, Organizer, StrategyKind, UnknownStrategy, STRATEGIES};
pub use platoonsim_model::lanechange::Side;
pub use record::{Queued, Recording, TrajectoryPoint, TrajectorySpec, Trip, TripStatus};
pub use safety::Counted;
pub use sim::Simulation;
pub use snapshot::VehicleColumns;
pub use summary::{
    BrakingPeaks, CollisionEvent, CollisionKind, CountedMeasure, CountedMeasures, DetectorRecord,
    MeterSummary, Output, Summary,
};
pub use vehicle::{Kind, Mode, ModeLabel};
pub use view::VehicleView;

/// Progress callback: called with (simulated seconds so far, total seconds) every simulated minute.
pub type Progress<'a> = &'a mut dyn FnMut(f64, f64);

/// Run a whole simulation: validate, step to the end, and collect the outputs.
/// Single-threaded and deterministic: the same config gives bit-identical outputs (except
/// `wall_seconds`).
pub fn run(config: &Config, progress: Option<Progress<'_>>) -> Result<Output, SimError> {
    run_recording(config, &Recording::default(), progress)
}

/// [`run`] that also records trips and trajectories as `recording` asks
/// ([`Output::trips`], [`Output::trajectories`]). The other outputs are those of [`run`]:
/// recording does not change the simulation.
pub fn run_recording(
    config: &Config,
    recording: &Recording,
    mut progress: Option<Progress<'_>>,
) -> Result<Output, SimError> {
    let start = std::time::Instant::now();
    let mut sim = Simulation::new(config.clone())?;
    sim.record(recording)?;
    let every = (60.0 / config.dt_s).round().max(1.0) as u64;
    let total = config.duration_s;
    while !sim.finished() {
        sim.step()?;
        if let Some(p) = progress.as_mut() {
            if sim.clock.step % every == 0 {
                p(sim.time_s(), total);
            }
        }
    }
    Ok(sim.finish(start.elapsed().as_secs_f64()))
}
