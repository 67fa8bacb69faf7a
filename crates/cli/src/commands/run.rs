//! `platoonsim run`: one scenario, one seed, files in the output directory.

use crate::args::RunArgs;
use crate::{output, progress};
use anyhow::{Context, Result};

pub fn run(args: &RunArgs, quiet: bool) -> Result<()> {
    let config = args.scenario.load()?;
    let recording = args.recording(&config)?;
    // Create the directory before simulating, so that an unwritable one fails at once.
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create the output directory {}", args.out.display()))?;

    let bar = progress::sim_bar(config.duration_s, progress::wanted(quiet), &config.name);
    let out = progress::run_recording_with_bar(&config, &recording, &bar)
        .map_err(anyhow::Error::msg)
        .with_context(|| format!("simulation of scenario '{}' failed", config.name))?;

    output::write_run(&args.out, &config, &out)?;
    println!("{}", output::paragraph(&config, &out.summary, &args.out));
    let mut extra = Vec::new();
    if let Some(trips) = &out.trips {
        extra.push(format!("trips.csv ({} rows)", trips.len()));
    }
    if let Some(rows) = &out.trajectories {
        extra.push(format!("trajectories.csv ({} rows)", rows.len()));
    }
    if !extra.is_empty() {
        println!("Also written: {}.", extra.join(", "));
    }
    if out.summary.collisions > 0 {
        eprintln!(
            "warning: {} collisions (vehicle pairs overlapping in a step); see summary.json",
            out.summary.collisions
        );
    }
    Ok(())
}
