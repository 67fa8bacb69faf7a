//! `platoonsim calibrate SCENARIO --field FILE... --params PARAMS.toml`: fit chosen scenario
//! keys to field data (see `platoonsim_calibrate::calibrate` and docs/calibrate.md).

use super::compare::field_data;
use crate::progress;
use anyhow::{Context, Result};
use clap::Args;
use platoonsim_calibrate::calibrate::{self, params::Params, Field};
use std::path::PathBuf;
use std::time::Duration;

#[derive(Debug, Args)]
pub struct CalibrateArgs {
    /// The scenario to calibrate: a built-in name or a scenario file. It must set
    /// run.clock_start (directly or under the parameters file's [set]).
    #[arg(value_name = "SCENARIO-NAME-OR-FILE")]
    pub scenario: String,

    #[command(flatten)]
    pub source: crate::args::FieldFlags,

    /// The parameters file: fitted keys and bounds, budget, replications, objective weights,
    /// fixed [set] keys (format in docs/calibrate.md).
    #[arg(long, value_name = "PARAMS.toml")]
    pub params: PathBuf,

    /// Output directory; the files go to DIR/NAME (NAME: the parameters file's `name`, else
    /// its stem).
    #[arg(long, value_name = "DIR", default_value = "out/calibrate")]
    pub out: PathBuf,

    /// Parallel runs (worker threads; each run is single-threaded). Default: one per core.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub jobs: Option<u32>,

    /// Compute only share I of N of every generation's runs (1-based), awaiting the other
    /// shards' run files; writes no outputs (run once more without a shard to write them,
    /// reusing every run). Without it, a scheduler's array index is used when set:
    /// SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX (Kubernetes) or HQ_TASK_ID (HyperQueue).
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,

    /// The number of shards, for the array indices that do not carry it (JOB_COMPLETION_INDEX,
    /// HQ_TASK_ID).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub shards: Option<u32>,

    /// Ignore a scheduler's array index in the environment (compute every run, write the
    /// outputs).
    #[arg(long, conflicts_with = "shard")]
    pub no_shard: bool,

    /// A shard computes the runs it awaits from other shards itself when none of them has
    /// appeared for this long (seconds).
    #[arg(long, value_name = "S", default_value_t = 600.0)]
    pub stale_after: f64,

    /// Recompute every run instead of reusing existing run files.
    #[arg(long)]
    pub fresh: bool,
}

pub fn calibrate(args: &CalibrateArgs, quiet: bool) -> Result<()> {
    let params = Params::from_file(&args.params)?;
    let shard = super::sweep::resolve_shard(args.shard.as_deref(), args.shards, args.no_shard)?;
    if !(args.stale_after.is_finite() && args.stale_after >= 0.0) {
        anyhow::bail!(
            "invalid --stale-after {}: expected seconds >= 0",
            args.stale_after
        );
    }
    let (obs, places, notes) = field_data(&args.source, (0, 86_400))?;
    let mut field = Field {
        obs,
        places,
        notes,
        files: Vec::new(),
    };
    for f in &args.source.field {
        let bytes =
            // A regular file, bounded like the field readers (16 GiB).
            platoonsim_scenario::bounded::read(f, 16 << 30)
                .with_context(|| format!("cannot read --field {}", f.display()))?;
        field.files.push((
            f.display().to_string(),
            format!("{:016x}", platoonsim_runs::hash::fnv1a64(&bytes)),
        ));
    }
    let out = args.out.join(&params.name);
    let _lock = crate::out_lock::lock(&out, super::sweep::share(shard.is_some()))?;
    let opts = calibrate::Options {
        scenario: args.scenario.clone(),
        out,
        jobs: args.jobs.map(|n| n as usize),
        shard,
        fresh: args.fresh,
        bar: progress::wanted(quiet),
        lines: progress::lines_wanted(quiet),
        stale: Duration::from_secs_f64(args.stale_after),
        arguments: std::env::args().collect(),
    };
    let done = calibrate::run(&params, &field, &opts)
        .with_context(|| format!("calibrate {} failed", params.name))?;
    let best = &done.trace[done.best];
    let point: Vec<String> = params
        .params
        .iter()
        .zip(&best.values)
        .map(|(q, v)| format!("{} = {v}", q.key))
        .collect();
    let stopped = done
        .stopped
        .as_ref()
        .map(|w| format!(" (CMA-ES stopped early: {w})"))
        .unwrap_or_default();
    match shard {
        Some(s) => outln!(
            "calibrate {} shard {s}: {} candidates, {} runs ({} computed, {} reused) in {:.1} s{stopped}; \
             best objective {} at {}. Run files in {}; write the outputs with an unsharded run.",
            params.name,
            done.trace.len(),
            done.handled,
            done.computed,
            done.reused,
            done.wall_seconds,
            best.objective,
            point.join(", "),
            done.dir.join("runs").display()
        )?,
        None => outln!(
            "calibrate {}: {} candidates, {} runs ({} computed, {} reused) in {:.1} s{stopped}; \
             best objective {} (start {}) at {}. Files in {}: calibrated.toml, trace.csv, \
             convergence.png, fit-before.md, fit-after.md, run.json, runs/.",
            params.name,
            done.trace.len(),
            done.handled,
            done.computed,
            done.reused,
            done.wall_seconds,
            best.objective,
            done.trace[0].objective,
            point.join(", "),
            done.dir.display()
        )?,
    }
    Ok(())
}
