//! `platoonsim experiment NAME`: one of the paper's experiments, resumable, with its tables.

use crate::args::{ExperimentArgs, GridArgs};
use crate::progress;
use anyhow::{Context, Result};
use platoonsim_experiment::{run_experiment, ExperimentName, ExperimentOutput, Settings};

/// The settings shared by `experiment` and `reproduce`.
pub fn settings(grid: &GridArgs, seeds: u32, quiet: bool) -> Settings {
    Settings {
        out: grid.out.clone(),
        seeds,
        jobs: grid.jobs.map(|n| n as usize),
        progress: progress::wanted(quiet),
        reuse: !grid.fresh,
        arguments: std::env::args().collect(),
        ..Settings::default()
    }
}

pub fn experiment(args: &ExperimentArgs, quiet: bool) -> Result<()> {
    let name = ExperimentName::from(args.name);
    let default_seeds = if name == ExperimentName::CalibrateFlowAware {
        3
    } else {
        10
    };
    let mut s = settings(&args.grid, args.seeds.unwrap_or(default_seeds), quiet);
    s.duration_s = args.duration;
    s.warmup_s = args.warmup;
    s.flow_thresholds = args.flow_thresholds.clone();
    s.speed_thresholds = args.speed_thresholds.clone();
    s.tolerance_pct = args.tolerance;
    let out = run_experiment(name, &s).with_context(|| format!("experiment {name} failed"))?;
    print!("{}", describe(&out));
    Ok(())
}

/// A few lines about a finished experiment: files, runs, checks.
pub fn describe(out: &ExperimentOutput) -> String {
    let mut s = format!(
        "{}: {} runs ({} computed, {} reused) in {:.1} s. Files in {}: summary.md, summary.csv, \
         runs.csv, run.json, runs/.\n",
        out.name,
        out.outcomes.len(),
        out.computed,
        out.reused,
        out.wall_seconds,
        out.dir.display()
    );
    for c in &out.checks {
        s.push_str(&format!(
            "  [{}] {}\n",
            if c.passed { "holds" } else { "does not hold" },
            c.statement
        ));
    }
    s
}
