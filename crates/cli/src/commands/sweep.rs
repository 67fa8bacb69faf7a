//! `platoonsim sweep SPEC.toml`: a sweep of any scenario (see
//! `platoonsim_runs::sweep` and docs/sweeps.md).

use crate::{progress, EXIT_COLLISIONS};
use anyhow::{bail, Context, Result};
use clap::Args;
use platoonsim_runs::sweep::{self, shard::Shard, spec::Spec};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Debug, Args)]
pub struct SweepArgs {
    /// The sweep file (format in docs/sweeps.md).
    #[arg(value_name = "SPEC.toml")]
    pub spec: PathBuf,

    /// Output directory. Default: out/sweeps/NAME (NAME: the file's `name`, else its stem).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// Parallel runs (worker threads; each run is single-threaded). Default: one per core.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub jobs: Option<u32>,

    /// Run only share I of N of the runs (1-based), writing run files but no tables (collect
    /// them afterwards with --collect). Without it, a scheduler's array index is used when set:
    /// SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX (Kubernetes) or HQ_TASK_ID (HyperQueue).
    #[arg(long, value_name = "I/N", conflicts_with = "collect")]
    pub shard: Option<String>,

    /// The number of shards, for the array indices that do not carry it (JOB_COMPLETION_INDEX,
    /// HQ_TASK_ID; Slurm's SLURM_ARRAY_TASK_COUNT otherwise gives it).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub shards: Option<u32>,

    /// Compute nothing: write the tables and figures from the run files of all shards; fails
    /// naming the missing runs if any is missing.
    #[arg(long)]
    pub collect: bool,

    /// Ignore a scheduler's array index in the environment (run the whole sweep).
    #[arg(long, conflicts_with_all = ["shard", "collect"])]
    pub no_shard: bool,

    /// Recompute every run instead of reusing existing run files.
    #[arg(long, conflicts_with = "collect")]
    pub fresh: bool,

    /// Format of the tables runs and summary: csv, or parquet (typed columns, compressed).
    #[arg(long, value_enum, default_value = "csv")]
    pub format: crate::tables::FormatArg,
}

/// How a sweep or a calibration shares its directory: shards with each other.
pub fn share(sharded: bool) -> crate::out_lock::Share {
    if sharded {
        crate::out_lock::Share::Shard
    } else {
        crate::out_lock::Share::Alone
    }
}

/// Which shard this process runs: the flag, else the environment (unless --collect or
/// --no-shard).
fn shard(args: &SweepArgs) -> Result<Option<Shard>> {
    resolve_shard(
        args.shard.as_deref(),
        args.shards,
        args.collect || args.no_shard,
    )
}

/// The shard of a sweep or a calibration: `--shard I/N` (checked against `--shards N`), else,
/// unless `ignore_env`, a scheduler's array index (SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX,
/// HQ_TASK_ID) with `--shards N` for the count where the scheduler does not give it.
pub fn resolve_shard(
    flag: Option<&str>,
    shards: Option<u32>,
    ignore_env: bool,
) -> Result<Option<Shard>> {
    if let Some(text) = flag {
        let s = Shard::parse(text)?;
        if let Some(n) = shards {
            if n as usize != s.count {
                bail!("--shards {n} contradicts --shard {text}");
            }
        }
        return Ok(Some(s));
    }
    if ignore_env {
        return Ok(None);
    }
    let env = |k: &str| std::env::var(k).ok();
    let s = Shard::from_env(&env, shards.map(|n| n as usize))?;
    if s.is_none() && shards.is_some() {
        bail!(
            "--shards is given but no shard index: pass --shard I/N, or run under a scheduler \
             that sets SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX or HQ_TASK_ID"
        );
    }
    Ok(s)
}

pub fn sweep(args: &SweepArgs, quiet: bool) -> Result<ExitCode> {
    let spec = Spec::from_file(&args.spec)?;
    let shard = shard(args)?;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("out/sweeps").join(&spec.name));
    let _lock = crate::out_lock::lock(&out, share(shard.is_some()))?;
    let opts = sweep::Options {
        out,
        jobs: args.jobs.map(|n| n as usize),
        shard,
        collect: args.collect,
        fresh: args.fresh,
        bar: progress::wanted(quiet),
        lines: progress::lines_wanted(quiet),
        format: args.format.table(),
        arguments: std::env::args().collect(),
    };
    let ext = args.format.ext();
    let done = sweep::run(&spec, &opts).with_context(|| format!("sweep {} failed", spec.name))?;
    match shard {
        Some(s) => outln!(
            "sweep {} shard {s}: {} of {} runs ({} computed, {} reused) in {:.1} s; run files \
             in {}. When every shard is done: platoonsim sweep {} --out {} --collect",
            spec.name,
            done.handled,
            done.total,
            done.computed,
            done.reused,
            done.wall_seconds,
            done.dir.join("runs").display(),
            args.spec.display(),
            done.dir.display()
        )?,
        None => outln!(
            "sweep {}: {} runs ({} computed, {} reused) in {:.1} s. Files in {}: summary.md, \
             summary.{ext}, runs.{ext}, run.json, {} figures, runs/.",
            spec.name,
            done.total,
            done.computed,
            done.reused,
            done.wall_seconds,
            done.dir.display(),
            done.figures.len()
        )?,
    }
    if done.collided > 0 {
        errln!(
            "warning: {} of {} runs had collisions (failed runs; see summary.md and the \
             collisions column of runs.csv)",
            done.collided,
            done.total
        );
        return Ok(ExitCode::from(EXIT_COLLISIONS));
    }
    Ok(ExitCode::SUCCESS)
}
