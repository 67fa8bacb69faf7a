//! `Core`: one simulation behind a mutex (the class must be `Sync`; a second thread that
//! finds it busy gets an error rather than a deadlock on the GIL).

use crate::convert::{columns_dict, event_dict, parse_side, set_args};
use crate::hooks::{lock, AdviceTable, EventBuffer, GatedOrganizer, TableOrganizer};
use crate::{CommandError, ScenarioError, SimulationError};
use numpy::{PyArray1, PyReadonlyArray1};
use platoonsim_scenario::Overrides;
use platoonsim_sim::command::MAX_COMMAND_ACCEL_MPS2;
use platoonsim_sim::snapshot::VehicleColumns;
use platoonsim_sim::{Command, Config, Event, Output, Simulation, StrategyKind};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, TryLockError};
use std::time::Instant;

/// One simulation and what the bindings keep beside it; `Core` holds one, `BatchCore`
/// (batch.rs) many.
pub(crate) struct Inner {
    /// `None` once finished.
    sim: Option<Simulation>,
    pub(crate) config: Config,
    output: Option<Output>,
    advice: Option<Arc<Mutex<AdviceTable>>>,
    events: Option<Arc<Mutex<Vec<Event>>>>,
    pub(crate) columns: VehicleColumns,
    /// Seconds spent stepping (the summary's `wall_seconds`).
    wall_s: f64,
    /// The switch of a gated PD organizer (`use_gate`).
    gate: Option<Arc<AtomicBool>>,
    /// The per-vehicle control task's state (control.rs).
    pub(crate) control: crate::control::State,
    /// The FlowMerge task's state (flow_merge.rs).
    pub(crate) flow_merge: crate::flow_merge::State,
    /// The scenario and overrides the config came from (to validate its PD rule for
    /// `use_gate` when the scenario's own strategy is another).
    source: (String, Overrides),
}

impl Inner {
    pub(crate) fn sim(&mut self) -> PyResult<&mut Simulation> {
        self.sim.as_mut().ok_or_else(|| {
            SimulationError::new_err(
                "the simulation is finished (finish() was called); its summary() is still \
                 available",
            )
        })
    }

    pub(crate) fn sim_ref(&self) -> Option<&Simulation> {
        self.sim.as_ref()
    }

    pub(crate) fn sim_mut(&mut self) -> Option<&mut Simulation> {
        self.sim.as_mut()
    }

    /// Whether the gated PD organizer is in use (`use_gate`).
    pub(crate) fn gated(&self) -> bool {
        self.gate.is_some()
    }

    pub(crate) fn steps_to(&self, t_s: f64) -> u64 {
        let dt = self.config.dt_s;
        (t_s / dt).round().max(0.0) as u64
    }
}

/// The extension's simulation; `platoonsim.Simulation` wraps it (docs/python.md).
#[pyclass(module = "platoonsim._platoonsim")]
pub struct Core {
    inner: Mutex<Inner>,
}

impl Core {
    fn with<T>(&self, f: impl FnOnce(&mut Inner) -> PyResult<T>) -> PyResult<T> {
        match self.inner.try_lock() {
            Ok(mut g) => f(&mut g),
            Err(TryLockError::Poisoned(p)) => f(&mut p.into_inner()),
            Err(TryLockError::WouldBlock) => Err(SimulationError::new_err(
                "the simulation is busy in another thread (use one Simulation per thread)",
            )),
        }
    }
}

fn scenario_err(e: impl std::fmt::Display) -> PyErr {
    ScenarioError::new_err(e.to_string())
}

/// Is the scenario argument scenario text rather than a name or a path?
fn is_toml_text(s: &str) -> bool {
    s.contains('\n') || (s.contains('=') && !std::path::Path::new(s).exists())
}

/// Step `n` times (fewer at the end of the run), timing the steps; the steps done. Called
/// without the GIL.
pub(crate) fn step_world(inner: &mut Inner, n: u64) -> Result<u64, String> {
    let sim = inner.sim.as_mut().ok_or_else(|| {
        "the simulation is finished (finish() was called); its summary() is still available"
            .to_string()
    })?;
    let start = Instant::now();
    let mut done = 0;
    let result = (|| {
        while done < n && !sim.finished() {
            sim.step()?;
            done += 1;
        }
        Ok::<u64, platoonsim_sim::SimError>(done)
    })();
    inner.wall_s += start.elapsed().as_secs_f64();
    result.map_err(|e| format!("the engine stopped: {e}"))
}

/// Step `sim` `n` times (fewer at the end of the run) without the GIL; the steps done.
fn step_n(py: Python<'_>, inner: &mut Inner, n: u64) -> PyResult<u64> {
    inner.sim()?;
    py.detach(|| step_world(inner, n))
        .map_err(SimulationError::new_err)
}

/// A simulation from a scenario name, path or text, with overrides (`--set` strings), a
/// seed and a strategy.
pub(crate) fn new_inner(
    scenario: &str,
    seed: Option<u64>,
    set: Vec<String>,
    strategy: Option<&str>,
    events: bool,
) -> PyResult<Inner> {
    let mut ov = Overrides {
        seed,
        ..Overrides::default()
    };
    ov.set = set;
    if let Some(name) = strategy {
        let kind = name
            .parse::<StrategyKind>()
            .map_err(|e| ScenarioError::new_err(format!("strategy: {e}")))?;
        ov.strategy = Some(kind);
    }
    let config = load(scenario, &ov)?;
    let mut sim = Simulation::new(config.clone()).map_err(scenario_err)?;
    let events = if events {
        let b = EventBuffer::default();
        let shared = b.events.clone();
        sim.observe(Box::new(b)).map_err(scenario_err)?;
        Some(shared)
    } else {
        None
    };
    Ok(Inner {
        sim: Some(sim),
        config,
        output: None,
        advice: None,
        events,
        columns: VehicleColumns::default(),
        wall_s: 0.0,
        gate: None,
        control: Default::default(),
        flow_merge: Default::default(),
        source: (scenario.to_string(), ov),
    })
}

fn load(scenario: &str, ov: &Overrides) -> PyResult<Config> {
    if is_toml_text(scenario) {
        platoonsim_scenario::from_toml(scenario, "scenario text", "scenario", ov)
    } else {
        platoonsim_scenario::load_with(scenario, ov)
    }
    .map_err(scenario_err)
}

/// Organize with the PD rule of the scenario's zone and window, switched on and off from
/// Python (`set_gate`); off at first. Before the first step.
pub(crate) fn use_gate(inner: &mut Inner) -> PyResult<()> {
    // The scenario validated with strategy.kind = "pd": its zone, window and lane.
    let (scenario, ov) = &inner.source;
    let mut ov = ov.clone();
    ov.strategy = Some(StrategyKind::PD);
    let mut cfg = inner.config.clone();
    cfg.strategy = load(scenario, &ov)?.strategy;
    let on = Arc::new(AtomicBool::new(false));
    let org = GatedOrganizer {
        inner: platoonsim_sim::organize::build(&cfg),
        on: on.clone(),
    };
    inner
        .sim()?
        .set_organizer(Box::new(org))
        .map_err(|e| SimulationError::new_err(e.to_string()))?;
    inner.gate = Some(on);
    Ok(())
}

pub(crate) fn set_gate(inner: &mut Inner, on: bool) -> PyResult<()> {
    let gate = inner
        .gate
        .as_ref()
        .ok_or_else(|| SimulationError::new_err("set_gate needs use_gate() first"))?;
    gate.store(on, Ordering::Relaxed);
    Ok(())
}

/// Give command `kind` to every vehicle of `ids` (docs/python.md); `values[i]` is the
/// acceleration or the desired speed of `ids[i]`, `side` the lane change's side.
pub(crate) fn command_world(
    inner: &mut Inner,
    kind: &str,
    ids: &[i64],
    values: Option<&[f64]>,
    steps: u64,
    side: Option<&str>,
) -> PyResult<()> {
    let value = |i: usize, what: &str| -> PyResult<f64> {
        match values {
            Some(v) if v.len() == ids.len() => Ok(v[i]),
            Some(v) => Err(CommandError::new_err(format!(
                "{kind}: {} values for {} vehicle ids (one per id, or one for all)",
                v.len(),
                ids.len()
            ))),
            None => Err(CommandError::new_err(format!(
                "{kind}: needs {what} (the value argument)"
            ))),
        }
    };
    let mut commands = Vec::with_capacity(ids.len());
    for (i, &id) in ids.iter().enumerate() {
        let c = match kind {
            "accelerate" => Command::Accelerate {
                accel_mps2: value(i, "an acceleration in m/s²")?,
                steps,
            },
            "accelerate_capped" => Command::AccelerateCapped {
                accel_mps2: value(i, "an acceleration in m/s²")?,
                steps,
            },
            "accelerate_safe" => Command::AccelerateSafe {
                accel_mps2: value(i, "an acceleration in m/s²")?,
                steps,
            },
            "desired_speed" => Command::DesiredSpeed {
                speed_mps: value(i, "a desired speed in m/s")?,
            },
            "change_lane" => {
                let s = side.ok_or_else(|| {
                    CommandError::new_err("change_lane: needs side=\"left\" or \"right\"")
                })?;
                Command::ChangeLane {
                    side: parse_side(s).ok_or_else(|| {
                        CommandError::new_err(format!(
                            "change_lane: side = {s:?}: must be \"left\" or \"right\""
                        ))
                    })?,
                }
            }
            "release" => Command::Release,
            other => {
                return Err(CommandError::new_err(format!(
                    "command kind {other:?}: must be one of \"accelerate\", \
                     \"accelerate_capped\", \"accelerate_safe\", \"desired_speed\", \
                     \"change_lane\", \"release\""
                )))
            }
        };
        commands.push((id, c));
    }
    {
        let sim = inner.sim()?;
        // Check every id and value before applying any, so that a rejected batch
        // changes nothing (a lane change that is impossible there is only known to the
        // engine: it can still stop a batch half-way, and says so).
        let mut on_road = VehicleColumns::default();
        sim.vehicle_columns(&mut on_road);
        let mut known = on_road.id.clone();
        known.sort_unstable();
        for (i, &(id, c)) in commands.iter().enumerate() {
            if id < 0 || known.binary_search(&(id as u64)).is_err() {
                return Err(CommandError::new_err(format!(
                    "{kind}: ids[{i}] = {id}: vehicle {id} is not on the road"
                )));
            }
            let bad = match c {
                Command::Accelerate { accel_mps2, steps }
                | Command::AccelerateCapped { accel_mps2, steps }
                | Command::AccelerateSafe { accel_mps2, steps } => {
                    !(accel_mps2.is_finite() && accel_mps2.abs() <= MAX_COMMAND_ACCEL_MPS2)
                        || steps == 0
                }
                Command::DesiredSpeed { speed_mps } => {
                    !(speed_mps.is_finite() && (0.0..=100.0).contains(&speed_mps))
                }
                _ => false,
            };
            if bad {
                // The engine's message names the value and the allowed range.
                let err = sim.command(id as u64, c).err().map(|e| e.to_string());
                return Err(CommandError::new_err(format!(
                    "{kind}: ids[{i}] = {id}: {}",
                    err.unwrap_or_else(|| "invalid value".into())
                )));
            }
        }
        for (i, &(id, c)) in commands.iter().enumerate() {
            sim.command(id as u64, c).map_err(|e| {
                CommandError::new_err(format!(
                    "{kind}: ids[{i}] = {id}: {e} (the commands before it in this batch \
                     are in force)"
                ))
            })?;
        }
        Ok(())
    }
}

/// The latest closed interval of every detector, as columns.
pub(crate) fn detectors_dict<'py>(
    py: Python<'py>,
    inner: &mut Inner,
) -> PyResult<Bound<'py, PyDict>> {
    let recs = inner.sim()?.latest_detector_records();
    let d = PyDict::new(py);
    let col_s = |f: &dyn Fn(&platoonsim_sim::DetectorRecord) -> String| {
        recs.iter().map(f).collect::<Vec<_>>()
    };
    d.set_item("detector", col_s(&|r| r.detector.clone()))?;
    d.set_item("kind", col_s(&|r| r.kind.clone()))?;
    d.set_item("lane", col_s(&|r| r.lane.clone()))?;
    let col_f = |f: &dyn Fn(&platoonsim_sim::DetectorRecord) -> f64| {
        PyArray1::from_vec(py, recs.iter().map(f).collect())
    };
    d.set_item("position_m", col_f(&|r| r.position_m))?;
    d.set_item("interval_start_s", col_f(&|r| r.interval_start_s))?;
    d.set_item("interval_s", col_f(&|r| r.interval_s))?;
    let col_i = |f: &dyn Fn(&platoonsim_sim::DetectorRecord) -> i64| {
        PyArray1::from_vec(py, recs.iter().map(f).collect())
    };
    d.set_item("count", col_i(&|r| r.count as i64))?;
    d.set_item("cav_count", col_i(&|r| r.cav_count as i64))?;
    d.set_item("flow_vph", col_f(&|r| r.flow_vph))?;
    d.set_item("speed_kmh", col_f(&|r| r.speed_kmh.unwrap_or(f64::NAN)))?;
    d.set_item("occupancy", col_f(&|r| r.occupancy))?;
    Ok(d)
}

/// Every vehicle on the road, as numpy columns.
pub(crate) fn vehicles_dict<'py>(
    py: Python<'py>,
    inner: &mut Inner,
) -> PyResult<Bound<'py, PyDict>> {
    let Inner { sim, columns, .. } = inner;
    let sim = sim.as_ref().ok_or_else(|| {
        SimulationError::new_err("the simulation is finished: no vehicles to read")
    })?;
    sim.vehicle_columns(columns);
    columns_dict(py, columns)
}

/// End the run now, write the run files into `out_dir` if given; the summary as JSON.
pub(crate) fn finish_world(inner: &mut Inner, out_dir: Option<PathBuf>) -> PyResult<String> {
    if let Some(sim) = inner.sim.take() {
        inner.output = Some(sim.finish(inner.wall_s));
    }
    let out = inner.output.as_ref().expect("set above");
    if let Some(dir) = out_dir {
        crate::output::write_run(&dir, &inner.config, out)
            .map_err(pyo3::exceptions::PyOSError::new_err)?;
    }
    serde_json::to_string(&out.summary)
        .map_err(|e| SimulationError::new_err(format!("cannot encode the summary: {e}")))
}

#[pymethods]
impl Core {
    #[new]
    #[pyo3(signature = (scenario, seed=None, overrides=None, strategy=None, events=true))]
    fn new(
        scenario: &str,
        seed: Option<u64>,
        overrides: Option<&Bound<'_, PyDict>>,
        strategy: Option<&str>,
        events: bool,
    ) -> PyResult<Self> {
        let set = match overrides {
            Some(d) => set_args(d)?,
            None => Vec::new(),
        };
        Ok(Core {
            inner: Mutex::new(new_inner(scenario, seed, set, strategy, events)?),
        })
    }

    /// Advance `n` steps (fewer if the run ends first); the steps done.
    fn step(&self, py: Python<'_>, n: u64) -> PyResult<u64> {
        self.with(|inner| step_n(py, inner, n))
    }

    /// Step until the simulated time reaches `t_s` (or the run ends); the steps done.
    fn run_until(&self, py: Python<'_>, t_s: f64) -> PyResult<u64> {
        if !t_s.is_finite() {
            return Err(pyo3::exceptions::PyValueError::new_err(format!(
                "run_until: t_s = {t_s} must be finite"
            )));
        }
        self.with(|inner| {
            let target = inner.steps_to(t_s);
            let now = inner.sim()?.steps_done();
            step_n(py, inner, target.saturating_sub(now))
        })
    }

    /// Steps done so far.
    #[getter]
    fn steps(&self) -> PyResult<u64> {
        self.with(|i| {
            Ok(match &i.sim {
                Some(s) => s.steps_done(),
                None => i.output.as_ref().map_or(0, |o| o.summary.steps),
            })
        })
    }

    /// Steps of the whole run.
    #[getter]
    fn total_steps(&self) -> PyResult<u64> {
        self.with(|i| Ok(i.steps_to(i.config.duration_s)))
    }

    #[getter]
    fn dt_s(&self) -> PyResult<f64> {
        self.with(|i| Ok(i.config.dt_s))
    }

    #[getter]
    fn time_s(&self) -> PyResult<f64> {
        self.with(|i| {
            Ok(match &i.sim {
                Some(s) => s.time_s(),
                None => i.config.duration_s.min(
                    i.output
                        .as_ref()
                        .map_or(0.0, |o| o.summary.steps as f64 * i.config.dt_s),
                ),
            })
        })
    }

    #[getter]
    fn done(&self) -> PyResult<bool> {
        self.with(|i| Ok(i.sim.as_ref().is_none_or(Simulation::finished)))
    }

    #[getter]
    fn finished(&self) -> PyResult<bool> {
        self.with(|i| Ok(i.sim.is_none()))
    }

    /// The validated config as JSON (`scenario.json`).
    fn config_json(&self) -> PyResult<String> {
        self.with(|i| {
            serde_json::to_string(&i.config)
                .map_err(|e| SimulationError::new_err(format!("cannot encode the config: {e}")))
        })
    }

    /// Every vehicle on the road, as numpy columns.
    fn vehicles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.with(|inner| vehicles_dict(py, inner))
    }

    /// The latest closed interval of every detector, as columns.
    fn detectors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.with(|inner| detectors_dict(py, inner))
    }

    /// The events since the last call, oldest first.
    fn events<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        self.with(|inner| {
            let Some(buffer) = &inner.events else {
                return Err(SimulationError::new_err(
                    "events are not recorded: create the Simulation with events=True",
                ));
            };
            let drained = std::mem::take(&mut *lock(buffer));
            let list = PyList::empty(py);
            for e in &drained {
                list.append(event_dict(py, e)?)?;
            }
            Ok(list)
        })
    }

    /// Give command `kind` to every vehicle of `ids` (docs/python.md); `values[i]` is the
    /// acceleration or the desired speed of `ids[i]`, `side` the lane change's side.
    #[pyo3(signature = (kind, ids, values=None, steps=1, side=None))]
    fn command(
        &self,
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
        self.with(|inner| command_world(inner, kind, ids, values, steps, side))
    }

    /// The ids of the vehicles under command, in the order the commands were given.
    fn commanded(&self) -> PyResult<Vec<u64>> {
        self.with(|inner| Ok(inner.sim()?.commanded().collect()))
    }

    /// Organize with a table set from Python (`set_advice`) instead of the config's
    /// strategy. Before the first step.
    fn use_organizer(
        &self,
        name: String,
        advises_humans: bool,
        advises_cavs: bool,
    ) -> PyResult<()> {
        self.with(|inner| {
            let table = Arc::new(Mutex::new(AdviceTable::default()));
            let org = TableOrganizer {
                name,
                humans: advises_humans,
                cavs: advises_cavs,
                table: table.clone(),
            };
            inner
                .sim()?
                .set_organizer(Box::new(org))
                .map_err(|e| SimulationError::new_err(e.to_string()))?;
            inner.advice = Some(table);
            Ok(())
        })
    }

    /// The advice for the next steps: vehicle `ids[i]` joins lane `lanes[i]` (engine index,
    /// 0 = rightmost; -1: no advice, and the Python layer refuses lanes below -1) with desire
    /// `strengths[i]`.
    fn set_advice(
        &self,
        ids: PyReadonlyArray1<'_, i64>,
        lanes: PyReadonlyArray1<'_, i64>,
        strengths: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<()> {
        let (ids, lanes, strengths) = (ids.as_slice()?, lanes.as_slice()?, strengths.as_slice()?);
        if lanes.len() != ids.len() || strengths.len() != ids.len() {
            return Err(CommandError::new_err(format!(
                "advice: {} lanes and {} strengths for {} vehicles (one each)",
                lanes.len(),
                strengths.len(),
                ids.len()
            )));
        }
        self.with(|inner| {
            let n_lanes = i64::from(inner.config.road.lanes);
            for i in 0..ids.len() {
                if ids[i] < 0 {
                    return Err(CommandError::new_err(format!(
                        "advice: id {} is not a vehicle id",
                        ids[i]
                    )));
                }
                if lanes[i] >= n_lanes {
                    return Err(CommandError::new_err(format!(
                        "advice for vehicle {}: lane {} does not exist (lanes 0 to {}, or -1 \
                         for none)",
                        ids[i],
                        lanes[i],
                        n_lanes - 1
                    )));
                }
                if lanes[i] >= 0
                    && !(strengths[i].is_finite() && (0.0..=1.0).contains(&strengths[i]))
                {
                    return Err(CommandError::new_err(format!(
                        "advice for vehicle {}: strength {} must be in [0, 1]",
                        ids[i], strengths[i]
                    )));
                }
            }
            let table = inner.advice.as_ref().ok_or_else(|| {
                SimulationError::new_err("set_advice needs an organizer (use_organizer)")
            })?;
            let ids: Vec<u64> = ids.iter().map(|&i| i as u64).collect();
            lock(table).set(&ids, lanes, strengths);
            Ok(())
        })
    }

    /// The leftmost through lane (the PD lane) at each position of `x_m`; −1 where none.
    fn leftmost_through<'py>(
        &self,
        py: Python<'py>,
        x_m: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Bound<'py, PyArray1<i64>>> {
        let x = x_m.as_slice()?;
        self.with(|inner| {
            let sim = inner.sim()?;
            let lanes = x
                .iter()
                .map(|&x| sim.leftmost_through_at(x).map_or(-1, i64::from))
                .collect();
            Ok(PyArray1::from_vec(py, lanes))
        })
    }

    /// End the run now (the vehicles on the road count with what they did so far), write the
    /// run files into `out_dir` if given, and return the summary as JSON.
    #[pyo3(signature = (out_dir=None))]
    fn finish(&self, out_dir: Option<PathBuf>) -> PyResult<String> {
        self.with(|inner| finish_world(inner, out_dir))
    }

    /// Organize with the scenario's PD rule behind a switch (`set_gate`, off at first).
    /// Before the first step.
    fn use_gate(&self) -> PyResult<()> {
        self.with(use_gate)
    }

    /// Switch the gated PD organizer on or off for the next steps.
    fn set_gate(&self, on: bool) -> PyResult<()> {
        self.with(|inner| set_gate(inner, on))
    }
}
