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
use crate::gate;
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
    /// The gate task (`gate_setup`).
    gate: Mutex<Option<GateState>>,
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

/// The gate task of a batch: its spec, and every world's measure at the warm-up's end
/// (`start`) and at the last decision (`last`, totals since the warm-up).
struct GateState {
    spec: gate::Spec,
    start: Vec<gate::Measure>,
    last: Vec<gate::Measure>,
}

fn value_err<T>(m: String) -> PyResult<T> {
    Err(pyo3::exceptions::PyValueError::new_err(m))
}

/// The gate task's arrays over the N pairs: `obs` (N, 8), `flow_vphpl` and `speed_kmh`
/// (N, 3), `leftmost_share`, `mean_string_size`, `t_s`, `done` of the policy worlds; the
/// totals since the warm-up of CAVs that left, their strings and the discharge count, and the
/// collisions, and the mean speed on the road now, of both as (N, 2) [policy, twin];
/// after a step `reward`, `l_gain` and `discharge_change` of the interval.
fn gate_dict<'py>(
    py: Python<'py>,
    spec: &gate::Spec,
    m: &[gate::Measure],
    before: Option<&[gate::Measure]>,
) -> PyResult<Bound<'py, PyDict>> {
    let n = spec.n;
    let (p, t) = m.split_at(n);
    let d = PyDict::new(py);
    let obs: Vec<f32> = p.iter().flat_map(|x| x.obs()).collect();
    d.set_item(
        "obs",
        PyArray1::from_vec(py, obs).reshape([n, gate::FEATURES])?,
    )?;
    let per3 = |f: &dyn Fn(&gate::Measure) -> [f64; gate::DETECTORS]| {
        PyArray1::from_vec(py, p.iter().flat_map(f).collect::<Vec<f64>>())
            .reshape([n, gate::DETECTORS])
    };
    d.set_item("flow_vphpl", per3(&|x| x.flow_vphpl)?)?;
    d.set_item("speed_kmh", per3(&|x| x.speed_kmh)?)?;
    let col = |f: &dyn Fn(&gate::Measure) -> f64| PyArray1::from_vec(py, p.iter().map(f).collect());
    d.set_item("leftmost_share", col(&|x| x.leftmost_share))?;
    d.set_item("mean_string_size", col(&|x| x.string_size))?;
    d.set_item("t_s", col(&|x| x.t_s))?;
    d.set_item(
        "done",
        PyArray1::from_vec(py, p.iter().map(|x| x.done).collect()),
    )?;
    let pair = |f: &dyn Fn(&gate::Measure) -> u64| {
        PyArray1::from_vec(
            py,
            (0..n)
                .flat_map(|i| [f(&p[i]), f(&t[i])])
                .collect::<Vec<u64>>(),
        )
        .reshape([n, 2])
    };
    d.set_item("cav_exits", pair(&|x| x.exits.cavs)?)?;
    d.set_item("platoon_sum", pair(&|x| x.exits.platoon_sum)?)?;
    d.set_item("discharge_count", pair(&|x| x.discharge_total)?)?;
    d.set_item("collisions", pair(&|x| x.collisions)?)?;
    let pair_f = PyArray1::from_vec(
        py,
        (0..n)
            .flat_map(|i| [p[i].mean_speed_mps, t[i].mean_speed_mps])
            .collect::<Vec<f64>>(),
    )
    .reshape([n, 2])?;
    d.set_item("mean_speed_mps", pair_f)?;
    if let Some(b) = before {
        let (bp, bt) = b.split_at(n);
        let iv: Vec<gate::Interval> = (0..n)
            .map(|i| gate::interval(&bp[i], &p[i], &bt[i], &t[i], spec.penalty))
            .collect();
        let col =
            |f: &dyn Fn(&gate::Interval) -> f64| PyArray1::from_vec(py, iv.iter().map(f).collect());
        d.set_item("reward", col(&|x| x.reward))?;
        d.set_item("l_gain", col(&|x| x.l_gain))?;
        d.set_item("discharge_change", col(&|x| x.discharge_change))?;
    }
    Ok(d)
}

impl BatchCore {
    fn gate_spec(&self) -> PyResult<gate::Spec> {
        self.gate
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .as_ref()
            .map(|g| g.spec)
            .ok_or_else(|| SimulationError::new_err("gate_setup() first"))
    }

    /// Every world's measures at the warm-up's end and at the last decision.
    #[allow(clippy::type_complexity)]
    fn gate_last(&self) -> PyResult<(Vec<gate::Measure>, Vec<gate::Measure>)> {
        let g = self.gate.lock().unwrap_or_else(|e| e.into_inner());
        match g.as_ref() {
            Some(s) if !s.last.is_empty() => Ok((s.start.clone(), s.last.clone())),
            _ => Err(SimulationError::new_err("gate_reset() first")),
        }
    }

    fn gate_store(&self, start: Option<Vec<gate::Measure>>, last: Vec<gate::Measure>) {
        if let Some(g) = self.gate.lock().unwrap_or_else(|e| e.into_inner()).as_mut() {
            if let Some(s) = start {
                g.start = s;
            }
            g.last = last;
        }
    }

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
            gate: Mutex::new(None),
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

    /// Set up the gate task (gate.rs) before the first step: worlds 0..N are the policy's
    /// (`gated[i]`: the scenario's PD rule behind the policy's switch; else the world's own
    /// strategy, a baseline), worlds N..2N their twins (the switch always off).
    fn gate_setup(
        &self,
        decision_s: f64,
        warmup_s: f64,
        decisions: u64,
        penalty: f64,
        gated: Vec<bool>,
    ) -> PyResult<()> {
        let n = gated.len();
        if n == 0 || 2 * n != self.worlds.len() {
            return value_err(format!(
                "gate_setup: {} worlds and {n} gated flags: the batch must have 2N worlds \
                 (N policy worlds, then their twins) and N flags",
                self.worlds.len()
            ));
        }
        if !(penalty.is_finite() && penalty >= 0.0) {
            return value_err(format!(
                "discharge_penalty = {penalty}: must be a finite number >= 0"
            ));
        }
        if decisions == 0 {
            return value_err("decisions = 0: must be at least 1".into());
        }
        let spec = self.world(0, |w| {
            let c = &w.config;
            let whole = |x: f64| x.is_finite() && x >= 0.0 && (x - x.round()).abs() < 1e-9;
            if c.road.network.is_some() {
                return value_err(
                    "the gate task needs a plain road (a scenario without [network])".into(),
                );
            }
            if c.detectors.len() < gate::DETECTORS {
                return value_err(format!(
                    "the gate task needs at least {} detectors (upstream, control section, \
                     discharge); the scenario has {}",
                    gate::DETECTORS,
                    c.detectors.len()
                ));
            }
            if !(decision_s > 0.0 && whole(decision_s / c.dt_s)) {
                return value_err(format!(
                    "decision_s = {decision_s}: must be a whole number of steps of {} s",
                    c.dt_s
                ));
            }
            if c.warmup_s != 0.0 {
                return value_err(format!(
                    "run.warmup_s = {}: the gate task counts every vehicle (L̄ from the paper's \
                     statistics), so it must be 0; the task's own warm-up is warmup_s",
                    c.warmup_s
                ));
            }
            if c.aggregation_s != decision_s {
                return value_err(format!(
                    "measurement.aggregation_s = {}: must equal decision_s = {decision_s}",
                    c.aggregation_s
                ));
            }
            if !whole(warmup_s / decision_s) {
                return value_err(format!(
                    "warmup_s = {warmup_s}: must be a whole number of decision intervals \
                     ({decision_s} s) >= 0"
                ));
            }
            Ok(gate::Spec {
                n,
                decision_steps: (decision_s / c.dt_s).round() as u64,
                warmup_steps: (warmup_s / c.dt_s).round() as u64,
                decisions,
                penalty,
                zone: (c.road.control_start_m, c.road.control_end_m),
                leftmost: c.road.lanes - 1,
            })
        })?;
        for i in 0..self.worlds.len() {
            let twin_or_gated = gated.get(i).copied().unwrap_or(true);
            self.world(i, |w| if twin_or_gated { use_gate(w) } else { Ok(()) })?;
        }
        *self.gate.lock().unwrap_or_else(|e| e.into_inner()) = Some(GateState {
            spec,
            start: Vec::new(),
            last: Vec::new(),
        });
        Ok(())
    }

    /// Run every world through the warm-up; the first observations and infos.
    fn gate_reset<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let spec = self.gate_spec()?;
        let m = self.par(py, |w| gate::warm_up(w, &spec))?;
        // Totals count from here.
        let zero: Vec<gate::Measure> = m
            .iter()
            .map(|x| gate::Measure {
                exits: gate::ExitMeter::default(),
                ..*x
            })
            .collect();
        let d = gate_dict(py, &spec, &zero, None)?;
        self.gate_store(Some(m), zero);
        Ok(d)
    }

    /// One decision in every pair: `on[i]` switches policy world i's organizer (ignored for
    /// a baseline world), then every world steps one decision interval.
    fn gate_step<'py>(&self, py: Python<'py>, on: Vec<bool>) -> PyResult<Bound<'py, PyDict>> {
        let spec = self.gate_spec()?;
        if on.len() != spec.n {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "gate_step: {} actions for {} worlds (one each)",
                on.len(),
                spec.n
            )));
        }
        let (start, before) = self.gate_last()?;
        for (i, &g) in on.iter().enumerate() {
            self.world(i, |w| if w.gated() { set_gate(w, g) } else { Ok(()) })?;
        }
        let m = self.par_indexed(py, |i, w| gate::advance(w, &spec, &start[i], &before[i]))?;
        let d = gate_dict(py, &spec, &m, Some(&before))?;
        self.gate_store(None, m);
        Ok(d)
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
