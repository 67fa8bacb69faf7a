//! `BatchCore`: N independent simulations stepped together across a thread pool (rayon), the
//! GIL released. Each world is exactly the `Core` of the same scenario, seed and overrides:
//! the worlds share nothing, so a world's outputs do not depend on the others or on the
//! number of threads. `platoonsim.BatchSimulation` wraps it (docs/python.md).
//!
//! Python organizers are not offered here (they would run under the GIL inside the parallel
//! step); the scenario's own strategy and the gated PD organizer (`use_gate`) are.

use crate::control::{self, Spec, FEATURES};
use crate::convert::set_args;
use crate::core::{
    command_world, detectors_dict, finish_world, new_inner, set_gate, step_world, use_gate,
    vehicles_dict, Inner,
};
use crate::flow_merge;
use crate::{CommandError, SimulationError};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rayon::prelude::*;
use std::path::PathBuf;
use std::sync::Mutex;

/// The most worlds in one batch.
pub const MAX_WORLDS: usize = 4096;

#[pyclass(module = "platoonsim._platoonsim")]
pub struct BatchCore {
    /// One lock per world, taken only by the caller that holds the batch (try_lock: a second
    /// thread gets an error, not a deadlock).
    worlds: Vec<Mutex<Inner>>,
    pool: rayon::ThreadPool,
    busy: Mutex<()>,
    /// The per-vehicle control task (`control_setup`).
    spec: Mutex<Option<Spec>>,
    /// The FlowMerge task (`flow_setup`).
    flow_spec: Mutex<Option<flow_merge::Spec>>,
}

/// What `flow_reset` and `flow_step` return: observations (N, k, 5) float32, the vehicle id
/// in each slot (N, k; −1 empty), rewards (N), mean speeds (N), vehicles on the road (N),
/// outflow (N), new collisions (N), done (N).
type FlowTuple<'py> = (
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<u64>>,
    Bound<'py, PyArray1<u64>>,
    Bound<'py, PyArray1<u64>>,
    Bound<'py, PyArray1<bool>>,
);

fn flow_tuple<'py>(
    py: Python<'py>,
    outs: Vec<flow_merge::Out>,
    k: usize,
) -> PyResult<FlowTuple<'py>> {
    let n = outs.len();
    let mut obs = Vec::with_capacity(n * k * flow_merge::FEATURES);
    let mut ids = Vec::with_capacity(n * k);
    for o in &outs {
        obs.extend_from_slice(&o.obs);
        ids.extend_from_slice(&o.ids);
    }
    Ok((
        PyArray1::from_vec(py, obs)
            .reshape([n, k, flow_merge::FEATURES])?
            .into_any(),
        PyArray1::from_vec(py, ids).reshape([n, k])?.into_any(),
        PyArray1::from_vec(py, outs.iter().map(|o| o.reward).collect()),
        PyArray1::from_vec(py, outs.iter().map(|o| o.mean_v).collect()),
        PyArray1::from_vec(py, outs.iter().map(|o| o.vehicles).collect()),
        PyArray1::from_vec(py, outs.iter().map(|o| o.outflow).collect()),
        PyArray1::from_vec(py, outs.iter().map(|o| o.collisions).collect()),
        PyArray1::from_vec(py, outs.iter().map(|o| o.done).collect()),
    ))
}

/// What `control_reset` and `control_step` return: observations (N, k, 6) float32, the
/// occupied slots (N, k), rewards (N), outflow (N), new collisions (N), done (N).
type ControlTuple<'py> = (
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<u64>>,
    Bound<'py, PyArray1<u64>>,
    Bound<'py, PyArray1<bool>>,
);

fn control_tuple<'py>(
    py: Python<'py>,
    outs: Vec<control::Out>,
    k: usize,
) -> PyResult<ControlTuple<'py>> {
    let n = outs.len();
    let mut obs = Vec::with_capacity(n * k * FEATURES);
    let mut mask = Vec::with_capacity(n * k);
    for o in &outs {
        obs.extend_from_slice(&o.obs);
        mask.extend_from_slice(&o.mask);
    }
    Ok((
        PyArray1::from_vec(py, obs)
            .reshape([n, k, FEATURES])?
            .into_any(),
        PyArray1::from_vec(py, mask).reshape([n, k])?.into_any(),
        PyArray1::from_vec(py, outs.iter().map(|o| o.reward).collect()),
        PyArray1::from_vec(py, outs.iter().map(|o| o.outflow).collect()),
        PyArray1::from_vec(py, outs.iter().map(|o| o.collisions).collect()),
        PyArray1::from_vec(py, outs.iter().map(|o| o.done).collect()),
    ))
}

impl BatchCore {
    fn world<T>(&self, i: usize, f: impl FnOnce(&mut Inner) -> PyResult<T>) -> PyResult<T> {
        let w = self.worlds.get(i).ok_or_else(|| {
            pyo3::exceptions::PyIndexError::new_err(format!(
                "world {i}: the batch has worlds 0 to {}",
                self.worlds.len() - 1
            ))
        })?;
        let mut g = w.try_lock().map_err(|_| {
            SimulationError::new_err("the batch is busy in another thread (one thread per batch)")
        })?;
        f(&mut g)
    }

    /// Every world, in parallel, without the GIL; the first error by world order.
    fn par<T: Send>(
        &self,
        py: Python<'_>,
        f: impl Fn(&mut Inner) -> Result<T, String> + Sync,
    ) -> PyResult<Vec<T>> {
        self.par_indexed(py, |_, w| f(w))
    }

    /// [`BatchCore::par`] for work that needs the world's index.
    fn par_indexed<T: Send>(
        &self,
        py: Python<'_>,
        f: impl Fn(usize, &mut Inner) -> Result<T, String> + Sync,
    ) -> PyResult<Vec<T>> {
        let _busy = self.busy.try_lock().map_err(|_| {
            SimulationError::new_err("the batch is busy in another thread (one thread per batch)")
        })?;
        let results: Vec<Result<T, String>> = py.detach(|| {
            self.pool.install(|| {
                self.worlds
                    .par_iter()
                    .enumerate()
                    .map(|(i, w)| {
                        let mut g = w.lock().unwrap_or_else(|e| e.into_inner());
                        f(i, &mut g)
                    })
                    .collect()
            })
        });
        results
            .into_iter()
            .enumerate()
            .map(|(i, r)| r.map_err(|e| SimulationError::new_err(format!("world {i}: {e}"))))
            .collect()
    }
}

impl BatchCore {
    fn flow_spec(&self) -> PyResult<flow_merge::Spec> {
        self.flow_spec
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .ok_or_else(|| SimulationError::new_err("flow_setup() first"))
    }

    /// The actions (worlds, k) as one row per world, checked: the shape, finite values.
    fn action_rows(
        &self,
        actions: &PyReadonlyArray2<'_, f64>,
        k: usize,
    ) -> PyResult<Vec<Vec<f64>>> {
        let a = actions.as_array();
        let shape = a.shape();
        if shape != [self.worlds.len(), k] {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "actions: shape {shape:?}, expected ({}, {k}) (worlds, slots)",
                self.worlds.len(),
            )));
        }
        if let Some(bad) = a.iter().find(|v| !v.is_finite()) {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "actions: {bad} is not a finite acceleration"
            )));
        }
        Ok(a.outer_iter().map(|r| r.to_vec()).collect())
    }

    fn control_spec(&self) -> PyResult<Spec> {
        self.spec
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .ok_or_else(|| SimulationError::new_err("control_setup() first"))
    }
}

#[pymethods]
impl BatchCore {
    #[new]
    #[pyo3(signature = (scenario, seeds, overrides=None, strategy=None, threads=None))]
    fn new(
        scenario: &str,
        seeds: Vec<u64>,
        overrides: Option<&Bound<'_, PyList>>,
        strategy: Option<&str>,
        threads: Option<usize>,
    ) -> PyResult<Self> {
        if seeds.is_empty() || seeds.len() > MAX_WORLDS {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "seeds: {} given; a batch has 1 to {MAX_WORLDS} worlds (one seed each)",
                seeds.len()
            )));
        }
        // Overrides: one dict for every world, or a list of one dict per world.
        let sets: Vec<Vec<String>> = match overrides {
            None => vec![Vec::new(); seeds.len()],
            Some(list) => {
                if list.len() != 1 && list.len() != seeds.len() {
                    return Err(pyo3::exceptions::PyValueError::new_err(format!(
                        "overrides: {} dicts for {} worlds (one for all, or one per world)",
                        list.len(),
                        seeds.len()
                    )));
                }
                let mut sets = Vec::with_capacity(seeds.len());
                for i in 0..seeds.len() {
                    let item = list.get_item(if list.len() == 1 { 0 } else { i })?;
                    let d = item.cast::<PyDict>().map_err(|_| {
                        pyo3::exceptions::PyTypeError::new_err(format!(
                            "overrides[{i}]: a dict of scenario keys to values"
                        ))
                    })?;
                    sets.push(set_args(d)?);
                }
                sets
            }
        };
        let threads = match threads {
            Some(0) => {
                return Err(pyo3::exceptions::PyValueError::new_err(
                    "threads = 0: give at least 1 (or None for every core)",
                ))
            }
            Some(n) => n.min(1024),
            None => std::thread::available_parallelism().map_or(1, |n| n.get()),
        };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| {
                SimulationError::new_err(format!("cannot start {threads} threads: {e}"))
            })?;
        let mut worlds = Vec::with_capacity(seeds.len());
        for (i, (seed, set)) in seeds.iter().zip(sets).enumerate() {
            let w = new_inner(scenario, Some(*seed), set, strategy, false).map_err(|e| {
                Python::attach(|py| {
                    let msg = e.value(py).to_string();
                    PyErr::from_type(e.get_type(py), format!("world {i}: {msg}"))
                })
            })?;
            worlds.push(Mutex::new(w));
        }
        Ok(BatchCore {
            worlds,
            pool,
            busy: Mutex::new(()),
            spec: Mutex::new(None),
            flow_spec: Mutex::new(None),
        })
    }

    #[getter]
    fn num_worlds(&self) -> usize {
        self.worlds.len()
    }

    #[getter]
    fn threads(&self) -> usize {
        self.pool.current_num_threads()
    }

    /// Advance every world `n` steps (fewer at the end of a run); the steps each did.
    fn step(&self, py: Python<'_>, n: u64) -> PyResult<Vec<u64>> {
        self.par(py, |w| step_world(w, n))
    }

    /// Step every world until its simulated time reaches `t_s`; the steps each did.
    fn run_until(&self, py: Python<'_>, t_s: f64) -> PyResult<Vec<u64>> {
        if !t_s.is_finite() {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "run_until: t_s = {t_s} must be finite"
            )));
        }
        self.par(py, |w| {
            let target = w.steps_to(t_s);
            let now = w
                .sim()
                .map_err(|_| "the simulation is finished".to_string())?
                .steps_done();
            step_world(w, target.saturating_sub(now))
        })
    }

    /// Simulated time of each world.
    fn time_s(&self) -> PyResult<Vec<f64>> {
        (0..self.worlds.len())
            .map(|i| self.world(i, |w| Ok(w.sim()?.time_s())))
            .collect()
    }

    /// Whether each world's run has reached its end.
    fn done(&self) -> PyResult<Vec<bool>> {
        (0..self.worlds.len())
            .map(|i| self.world(i, |w| Ok(w.sim().map_or(true, |s| s.finished()))))
            .collect()
    }

    #[getter]
    fn dt_s(&self) -> PyResult<f64> {
        self.world(0, |w| Ok(w.config.dt_s))
    }

    /// World `i`'s validated config as JSON.
    fn config_json(&self, i: usize) -> PyResult<String> {
        self.world(i, |w| {
            serde_json::to_string(&w.config)
                .map_err(|e| SimulationError::new_err(format!("cannot encode the config: {e}")))
        })
    }

    /// World `i`'s vehicles as numpy columns.
    fn vehicles<'py>(&self, py: Python<'py>, i: usize) -> PyResult<Bound<'py, PyDict>> {
        self.world(i, |w| vehicles_dict(py, w))
    }

    /// World `i`'s latest detector interval as columns.
    fn detectors<'py>(&self, py: Python<'py>, i: usize) -> PyResult<Bound<'py, PyDict>> {
        self.world(i, |w| detectors_dict(py, w))
    }

    /// A command to vehicles of world `i` (as `Simulation.command`).
    #[pyo3(signature = (i, kind, ids, values=None, steps=1, side=None))]
    fn command(
        &self,
        i: usize,
        kind: &str,
        ids: PyReadonlyArray1<'_, i64>,
        values: Option<PyReadonlyArray1<'_, f64>>,
        steps: u64,
        side: Option<&str>,
    ) -> PyResult<()> {
        let ids = ids.as_slice()?;
        let values = match &values {
            Some(v) => Some(v.as_slice()?),
            None => None,
        };
        self.world(i, |w| {
            command_world(w, kind, ids, values, steps, side).map_err(|e| {
                Python::attach(|py| CommandError::new_err(format!("world {i}: {}", e.value(py))))
            })
        })
    }

    /// Every world organizes with the scenario's PD rule behind a switch, off at first.
    /// Before the first step.
    fn use_gate(&self) -> PyResult<()> {
        (0..self.worlds.len()).try_for_each(|i| self.world(i, use_gate))
    }

    /// Switch each world's gate: `on[i]` for world i.
    fn set_gates(&self, on: Vec<bool>) -> PyResult<()> {
        if on.len() != self.worlds.len() {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "set_gates: {} values for {} worlds (one each)",
                on.len(),
                self.worlds.len()
            )));
        }
        on.iter()
            .enumerate()
            .try_for_each(|(i, &g)| self.world(i, |w| set_gate(w, g)))
    }

    /// Set up the per-vehicle control task (control.rs): `k` slots, `steps` engine steps per
    /// action, the scales, the penalty and the action bounds.
    #[allow(clippy::too_many_arguments)]
    fn control_setup(
        &self,
        k: usize,
        steps: u64,
        v_ref: f64,
        gap_ref: f64,
        accel_penalty: f64,
        a_low: f64,
        a_high: f64,
    ) -> PyResult<()> {
        let ok = (1..=1024).contains(&k)
            && steps >= 1
            && [v_ref, gap_ref, a_high]
                .iter()
                .all(|v| v.is_finite() && *v > 0.0)
            && accel_penalty.is_finite()
            && accel_penalty >= 0.0
            && a_low.is_finite()
            && a_low < 0.0;
        if !ok {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "control_setup: k = {k} (1-1024), steps = {steps} (>= 1), v_ref = {v_ref}, \
                 gap_ref = {gap_ref}, a_high = {a_high} (> 0), accel_penalty = {accel_penalty} \
                 (>= 0), a_low = {a_low} (< 0)"
            )));
        }
        *self.spec.lock().unwrap_or_else(|e| e.into_inner()) = Some(Spec {
            k,
            steps,
            v_ref,
            gap_ref,
            accel_penalty,
            a_low,
            a_high,
        });
        Ok(())
    }

    fn control_reset<'py>(&self, py: Python<'py>) -> PyResult<ControlTuple<'py>> {
        let spec = self.control_spec()?;
        let outs = self.par(py, |w| control::start(w, &spec))?;
        control_tuple(py, outs, spec.k)
    }

    /// One step of the control task in every world: `actions` (N, k) accelerations (m/s²).
    fn control_step<'py>(
        &self,
        py: Python<'py>,
        actions: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<ControlTuple<'py>> {
        let spec = self.control_spec()?;
        let rows = self.action_rows(&actions, spec.k)?;
        let outs = self.par_indexed(py, |i, w| control::step(w, &spec, &rows[i]))?;
        control_tuple(py, outs, spec.k)
    }

    /// Set up the FlowMerge task (flow_merge.rs): `k` = num_rl slots, `steps` engine steps per
    /// action, the observation scales, the reward's target speed, t_min and weights, the action
    /// bounds, and whether the listed vehicles are commanded.
    #[allow(clippy::too_many_arguments)]
    fn flow_setup(
        &self,
        k: usize,
        steps: u64,
        max_speed: f64,
        max_length: f64,
        target_v: f64,
        t_min: f64,
        eta1: f64,
        eta2: f64,
        a_low: f64,
        a_high: f64,
        control: bool,
    ) -> PyResult<()> {
        let spec = flow_merge::Spec {
            k,
            steps,
            max_speed,
            max_length,
            target_v,
            t_min,
            eta1,
            eta2,
            a_low,
            a_high,
            control,
        };
        spec.check()
            .map_err(pyo3::exceptions::PyValueError::new_err)?;
        *self.flow_spec.lock().unwrap_or_else(|e| e.into_inner()) = Some(spec);
        Ok(())
    }

    fn flow_reset<'py>(&self, py: Python<'py>) -> PyResult<FlowTuple<'py>> {
        let spec = self.flow_spec()?;
        let outs = self.par(py, |w| flow_merge::start(w, &spec))?;
        flow_tuple(py, outs, spec.k)
    }

    /// One action of the FlowMerge task in every world: `actions` (N, k) accelerations (m/s²),
    /// finite (the Python side clips them to the bounds).
    fn flow_step<'py>(
        &self,
        py: Python<'py>,
        actions: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<FlowTuple<'py>> {
        let spec = self.flow_spec()?;
        let rows = self.action_rows(&actions, spec.k)?;
        let outs = self.par_indexed(py, |i, w| flow_merge::step(w, &spec, &rows[i]))?;
        flow_tuple(py, outs, spec.k)
    }

    /// End world `i`'s run (writing its files into `out_dir` if given); its summary as JSON.
    #[pyo3(signature = (i, out_dir=None))]
    fn finish(&self, i: usize, out_dir: Option<PathBuf>) -> PyResult<String> {
        self.world(i, |w| finish_world(w, out_dir))
    }
}
