//! # platoonsim-py: the Python package's extension module
//!
//! `platoonsim._platoonsim.Core` holds one `platoonsim_sim::Simulation` and exchanges whole arrays with
//! Python: the vehicles as numpy columns, the lane advice of a Python organizer as one table
//! per call, commands vectorized over vehicle ids; the learning tasks per world
//! (`control.rs`: CavControl-v0, `flow_merge.rs`: FlowMerge-v0). The pure-Python package (`python/platoonsim`)
//! wraps it in the documented API (docs/python.md). Stepping releases the GIL.

mod batch;
mod control;
mod convert;
mod core;
mod flow_merge;
mod gate;
mod hooks;
mod output;

use pyo3::prelude::*;

pyo3::create_exception!(
    platoonsim,
    ScenarioError,
    pyo3::exceptions::PyValueError,
    "A scenario, an override or a strategy name is not valid; the message names the field, \
     the value and what is allowed (the command line's message)."
);
pyo3::create_exception!(
    platoonsim,
    CommandError,
    pyo3::exceptions::PyValueError,
    "A command or an advice table that cannot be applied (unknown vehicle id, value out of \
     range, lengths that differ)."
);
pyo3::create_exception!(
    platoonsim,
    SimulationError,
    pyo3::exceptions::PyRuntimeError,
    "The engine stopped (a non-finite state), or the simulation is used in a way its state \
     does not allow (after finish, from two threads at once)."
);

#[pymodule]
fn _platoonsim(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<core::Core>()?;
    m.add_class::<batch::BatchCore>()?;
    m.add("ScenarioError", m.py().get_type::<ScenarioError>())?;
    m.add("CommandError", m.py().get_type::<CommandError>())?;
    m.add("SimulationError", m.py().get_type::<SimulationError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("MAX_WORLDS", batch::MAX_WORLDS)?;
    m.add(
        "MODE_LABELS",
        platoonsim_sim::snapshot::MODE_LABELS.to_vec(),
    )?;
    m.add(
        "REGIME_LABELS",
        platoonsim_sim::snapshot::REGIME_LABELS.to_vec(),
    )?;
    m.add(
        "STRATEGIES",
        platoonsim_sim::STRATEGIES
            .iter()
            .map(|e| e.name)
            .collect::<Vec<_>>(),
    )?;
    m.add(
        "BUILTIN_SCENARIOS",
        platoonsim_scenario::BUILTINS
            .iter()
            .map(|b| b.name)
            .collect::<Vec<_>>(),
    )?;
    Ok(())
}
