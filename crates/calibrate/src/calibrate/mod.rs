//! Calibration of a scenario to field data (`platoonsim calibrate`; docs/calibrate.md): fit
//! chosen scenario keys so that the mean of a candidate's replications matches the field's
//! flows and speeds at the stations.
//!
//! * [`demand`]: the optional demand step (`[demand]`): entrance demands and exit fractions
//!   estimated from the field counts, set as fixed keys before the behaviour fit;
//! * [`params`]: the parameters file (fitted keys and bounds, budget, weights, `[set]`);
//! * [`space`]: normalized coordinates, bounds checked through the `--set` machinery;
//! * [`optimizer`]: CMA-ES as a replayed ask/tell;
//! * [`evaluate`]: a generation's runs (parallel, resumable, sharded like a sweep) and their
//!   objective values; [`objective`]: the terms and their weights;
//! * [`output`]: `trace.csv`, `calibrated.toml`, the convergence figure, the fit summaries,
//!   `run.json`.
//!
//! The start point is evaluated first (generation 0, so the result is never worse than the
//! start and `fit-before.md` has its values); then whole generations of `population`
//! candidates while the budget allows and CMA-ES has not stopped. Every value comes from run
//! files, the optimizer is seeded and replayed, and the runs are numbered in a fixed order:
//! the same parameters file and field data give the same trace and result at any `--jobs`
//! and any sharding.

pub mod demand;
pub mod evaluate;
pub mod objective;
pub mod optimizer;
pub mod output;
pub mod params;
pub mod space;

use crate::runner::{self, Executor, Runner};
use crate::sweep::shard::Shard;
use crate::Error;
use evaluate::{Batch, Target};
use objective::Terms;
use optimizer::{Ask, Setup};
use params::Params;
use platoonsim_field::{Obs, Placed};
use space::Space;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The field data: the observations, the stations' placement and the files they came from.
#[derive(Clone, Debug, Default)]
pub struct Field {
    pub obs: Vec<Obs>,
    /// The stations placed on the corridor (`--origin-pm` or `--stations`; may be empty:
    /// stations are then placed at the scenario's detector of the same name).
    pub places: Vec<Placed>,
    /// (path, FNV-1a 64 of the file's bytes, 16 hex digits).
    pub files: Vec<(String, String)>,
    /// Notes on the data (stations combined, intervals left out), for the fit reports.
    pub notes: Vec<String>,
}

/// How to run a calibration.
#[derive(Clone, Debug)]
pub struct Options {
    /// A built-in scenario name or a scenario file.
    pub scenario: String,
    /// The output directory (run files in `runs/`).
    pub out: PathBuf,
    pub jobs: Option<usize>,
    /// Compute only this share of each generation's runs, awaiting the others'; no outputs.
    pub shard: Option<Shard>,
    /// Recompute runs whose files exist.
    pub fresh: bool,
    pub bar: bool,
    pub lines: bool,
    /// A shard computes the runs it awaits after this long without one appearing.
    pub stale: Duration,
    /// The command line, for the provenance.
    pub arguments: Vec<String>,
}

/// One evaluated candidate: a row of `trace.csv`.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// 0 for the start point.
    pub generation: usize,
    pub candidate: usize,
    /// The fitted keys' values.
    pub values: Vec<f64>,
    pub terms: Terms,
    pub objective: f64,
}

/// What a calibration did.
#[derive(Clone, Debug)]
pub struct Done {
    pub dir: PathBuf,
    /// Every evaluated candidate (the start first).
    pub trace: Vec<Row>,
    /// Index into `trace` of the best (lowest objective; the first of equals).
    pub best: usize,
    /// Why CMA-ES stopped before the budget, if it did.
    pub stopped: Option<String>,
    /// Runs this invocation handled (its shard's and those it took over from a stale shard, or
    /// all), computed and reused.
    pub handled: usize,
    pub computed: usize,
    pub reused: usize,
    /// False for a shard: no output files.
    pub outputs: bool,
    pub wall_seconds: f64,
}

/// Calibrate with the engine.
pub fn run(p: &Params, field: &Field, opts: &Options) -> Result<Done, Error> {
    run_with(p, field, opts, &runner::simulate)
}

/// [`run`] with another executor (tests count executions with it).
pub fn run_with(
    p: &Params,
    field: &Field,
    opts: &Options,
    exec: Executor<'_>,
) -> Result<Done, Error> {
    let start = Instant::now();
    let mut p = p.clone();
    let demand = match p.demand.is_empty() {
        true => None,
        false => {
            let d = estimate_demand(&p, field, &opts.scenario)?;
            // The estimate's keys win over [set] entries of the same key.
            p.set.retain(|(k, _)| !d.set.iter().any(|(dk, _)| dk == k));
            p.set.extend(d.set.clone());
            Some(d)
        }
    };
    let p = &p;
    let space = Space::new(&opts.scenario, p).map_err(|e| Error::Other(e.to_string()))?;
    let clock_start_s = space.base.clock_start_s.ok_or_else(|| {
        Error::Other(format!(
            "{}: the scenario has no run.clock_start; set it (e.g. --set in [set]: \
             \"run.clock_start\" = \"07:00\") so that simulated intervals meet the field's \
             clock times",
            opts.scenario
        ))
    })?;
    let start_values = space.values(&space.start);
    let prior_sd: Vec<Option<f64>> = p.params.iter().map(|q| q.prior_sd).collect();
    // The ramp counters are the demand's inputs: the objective fits the mainline alone, as
    // `compare` judges it (docs/compare.md).
    let judged = mainline_obs(&space.base, field);
    let target = Target {
        field: &judged,
        weights: p.weights,
        clock_start_s,
        warmup_s: space.base.warmup_s,
    };
    let seeds = p.seeds();
    let r = seeds.len();
    let gens = p.generations();
    let total = r + gens * p.population * r;
    let label = match opts.shard {
        Some(s) => format!("calibrate {} shard {s}", p.name),
        None => format!("calibrate {}", p.name),
    };
    let mine = evaluate::owned(opts.shard, 0, total);
    let bar = runner::bar(mine, opts.bar, &label);
    std::fs::create_dir_all(&opts.out).map_err(|e| Error::io(&opts.out, e))?;
    let runs_dir = opts.out.join("runs");
    let mut work = Runner::new(runs_dir.clone(), opts.jobs, bar.clone(), exec);
    work.reuse = !opts.fresh;
    if opts.lines && !opts.bar {
        work.log = Some(Arc::new(crate::progress::Lines::stderr(&label, mine)));
    }
    let never =
        |_: &platoonsim_sim::Config| -> Result<platoonsim_sim::Output, platoonsim_sim::SimError> {
            Err(platoonsim_sim::SimError::Config(
                "the reader computes nothing".into(),
            ))
        };
    let reader = Runner::new(runs_dir, Some(1), runner::bar(0, false, ""), &never);
    let batch = Batch {
        runner: &work,
        reader: &reader,
        shard: opts.shard,
        stale: opts.stale,
        poll: Duration::from_millis(200),
        taken_over: Default::default(),
    };
    let say = |line: String| {
        if opts.bar {
            bar.println(line);
        } else if opts.lines {
            eprintln!("{line}");
        }
    };

    // Generation 0: the start point.
    let evaluate =
        |generation: usize, points: &[Vec<f64>], first: usize| -> Result<Vec<Row>, Error> {
            let values: Vec<Vec<f64>> = points.iter().map(|x| space.values(x)).collect();
            let configs = values
                .iter()
                .map(|v| {
                    space.config(v).map_err(|e| {
                        Error::Other(format!(
                        "generation {generation}: the candidate {} is not a valid scenario: {e}",
                        space.set_args(v)[space.fixed.len()..].join(" ")
                    ))
                    })
                })
                .collect::<Result<Vec<_>, _>>()?;
            let specs = evaluate::specs(&configs, &seeds);
            let outcomes = evaluate::run(&batch, &specs, first)?;
            let mut terms = evaluate::objectives(&reader, &outcomes, configs.len(), &target)?;
            for (t, v) in terms.iter_mut().zip(&values) {
                t.values[4] = Some(objective::prior(v, &start_values, &prior_sd));
            }
            Ok(values
                .into_iter()
                .zip(terms)
                .enumerate()
                .map(|(c, (values, terms))| Row {
                    generation,
                    candidate: c,
                    values,
                    objective: terms.objective(&p.weights),
                    terms,
                })
                .collect())
        };
    let mut trace = evaluate(0, std::slice::from_ref(&space.start), 0)?;
    say(format!(
        "{label}: start, objective {}",
        output::short(trace[0].objective)
    ));
    let setup = Setup {
        start: space.start.clone(),
        sigma: p.sigma,
        population: p.population,
        seed: p.seed,
    };
    let mut told: Vec<Vec<f64>> = Vec::new();
    let mut stopped = None;
    for g in 1..=gens {
        let points = match optimizer::ask(&setup, &told).map_err(Error::Other)? {
            Ask::Points(points) => points,
            Ask::Stopped(why) => {
                stopped = Some(why);
                break;
            }
        };
        let first = r + (g - 1) * p.population * r;
        let rows = evaluate(g, &points, first)?;
        told.push(rows.iter().map(|row| row.objective).collect());
        trace.extend(rows);
        let best = &trace[best_index(&trace)];
        say(format!(
            "{label}: generation {g}/{gens}, best objective {} at {}",
            output::short(best.objective),
            output::point(&space, &best.values)
        ));
    }
    bar.finish_and_clear();
    let best = best_index(&trace);
    let handled = batch.taken_over.get()
        + if stopped.is_some() {
            evaluate::owned(opts.shard, 0, trace.len() * r)
        } else {
            mine
        };
    let mut done = Done {
        dir: opts.out.clone(),
        best,
        stopped,
        handled,
        computed: work.computed(),
        reused: handled.saturating_sub(work.computed()),
        outputs: false,
        trace,
        wall_seconds: 0.0,
    };
    if opts.shard.is_none() {
        done.wall_seconds = start.elapsed().as_secs_f64();
        output::write_all(
            p,
            field,
            opts,
            &space,
            &reader,
            &target,
            &done,
            demand.as_ref(),
        )?;
        done.outputs = true;
    }
    done.wall_seconds = start.elapsed().as_secs_f64();
    Ok(done)
}

/// The field observations of the mainline stations: without the stations the scenario counts
/// at a ramp (a `station` on a ramp) or the placement lists as a ramp.
fn mainline_obs(base: &platoonsim_sim::Config, field: &Field) -> Vec<platoonsim_field::Obs> {
    use platoonsim_sim::config::DetectorKind;
    let sim_ramps = base
        .detectors
        .iter()
        .filter(|d| !matches!(d.kind, DetectorKind::Mainline))
        .map(|d| platoonsim_field::Placed {
            station: d.name.clone(),
            x_m: d.position_m,
            kind: platoonsim_field::StationKind::OnRamp,
            lanes: 0,
            name: d.name.clone(),
        })
        .collect::<Vec<_>>();
    let ramps = crate::compare::ramp_stations(&sim_ramps, &field.places);
    field
        .obs
        .iter()
        .filter(|o| !ramps.contains(&o.station))
        .cloned()
        .collect()
}

/// The lowest objective's index (the first of equals).
pub fn best_index(trace: &[Row]) -> usize {
    let mut best = 0;
    for (i, r) in trace.iter().enumerate() {
        if r.objective < trace[best].objective {
            best = i;
        }
    }
    best
}

/// The demand step: the scenario with the fixed keys and no demand offset, then the estimate.
fn estimate_demand(p: &Params, field: &Field, scenario: &str) -> Result<demand::Demand, Error> {
    let mut set: Vec<String> = p
        .set
        .iter()
        .map(|(k, v)| crate::sweep::spec::set_arg(k, v))
        .collect();
    set.push("network.demand_offset_s=0".into());
    let overrides = platoonsim_scenario::Overrides {
        set,
        ..Default::default()
    };
    let config = platoonsim_scenario::load_with(scenario, &overrides)
        .map_err(|e| Error::Other(format!("{}: [demand]: {e}", p.origin)))?;
    demand::demand(&config, field, &p.demand)
        .map_err(|e| Error::Other(format!("{}: {e}", p.origin)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use platoonsim_field::StationKind;
    use platoonsim_sim::config::{DetectorKind, DetectorSpec};

    fn obs(station: &str) -> Obs {
        Obs {
            station: station.into(),
            start_s: 0,
            interval_s: 300,
            flow_vph: 100.0,
            speed_kmh: Some(90.0),
            occupancy: None,
        }
    }

    #[test]
    fn the_objective_fits_the_mainline_stations_not_the_ramp_counters() {
        // "R1" counts an off-ramp in the scenario; "R2" is an on-ramp by the field's placement.
        let mut base = platoonsim_sim::Config::homogeneous(0.0, 1000.0, 600.0, 0.0, 1);
        base.detectors.push(DetectorSpec {
            name: "R1".into(),
            position_m: 100.0,
            kind: DetectorKind::OffRamp { ramp: 0 },
            exit: true,
        });
        let field = Field {
            obs: vec![obs("discharge"), obs("R1"), obs("R2"), obs("upstream")],
            places: vec![Placed {
                station: "R2".into(),
                x_m: 50.0,
                kind: StationKind::OnRamp,
                lanes: 1,
                name: "R2".into(),
            }],
            files: Vec::new(),
            notes: Vec::new(),
        };
        let kept: Vec<String> = mainline_obs(&base, &field)
            .into_iter()
            .map(|o| o.station)
            .collect();
        assert_eq!(kept, ["discharge", "upstream"]);
    }
}
