//! `platoonsim reproduce`: every experiment, then `REPORT.md` and `report.html`.

use crate::args::ReproduceArgs;
use crate::commands::experiment::{describe, settings};
use anyhow::{Context, Result};
use platoonsim_experiment::report::{self, ReportInput};
use platoonsim_experiment::{run_experiment, ExperimentName};
use std::time::Instant;

/// The report's "Notes on differences", written by hand in the repository.
const NOTES: &str = include_str!("../../../../docs/reproduction-notes.md");

/// Seeds per cell with --quick.
pub const QUICK_SEEDS: u32 = 3;

pub fn reproduce(args: &ReproduceArgs, quiet: bool) -> Result<()> {
    let start = Instant::now();
    let seeds = args
        .seeds
        .unwrap_or(if args.quick { QUICK_SEEDS } else { 10 });
    let mut s = settings(&args.grid, seeds, quiet);
    s.duration_s = args.duration;
    s.warmup_s = args.warmup;
    let mut outputs = Vec::new();
    for name in ExperimentName::ALL {
        let out = run_experiment(name, &s).with_context(|| format!("experiment {name} failed"))?;
        print!("{}", describe(&out));
        outputs.push(out);
    }
    let mut command = String::from("platoonsim reproduce");
    if args.quick {
        command.push_str(" --quick");
    }
    if let Some(n) = args.seeds {
        command.push_str(&format!(" --seeds {n}"));
    }
    if args.duration != 3600.0 || args.warmup != 1200.0 {
        command.push_str(&format!(
            " --duration {} --warmup {}",
            args.duration, args.warmup
        ));
    }
    let wall = start.elapsed().as_secs_f64();
    let input = ReportInput {
        outputs: &outputs,
        notes: NOTES,
        command: &command,
        seeds,
        jobs: s.jobs,
        wall_seconds: wall,
    };
    let (md, html) = report::write(&args.grid.out, &input).context("cannot write the report")?;
    println!(
        "Report: {} and {}. Total wall time {:.1} s ({:.1} min).",
        md.display(),
        html.display(),
        wall,
        wall / 60.0
    );
    Ok(())
}
