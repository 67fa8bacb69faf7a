//! `platoonsim run`: one scenario, one seed, files in the output directory.

use crate::args::RunArgs;
use crate::{out_lock, output, progress, EXIT_COLLISIONS};
use anyhow::{Context, Result};
use platoonsim_rundir::{COLLISIONS, DETECTORS, TRAJECTORIES, TRIPS};
use platoonsim_runs::run_dir;
use std::process::ExitCode;

/// Simulate and write the files; the exit code is [`EXIT_COLLISIONS`] if the run had
/// collisions (a failed run: its results are not physical) unless `--allow-collisions`.
pub fn run(args: &RunArgs, quiet: bool) -> Result<ExitCode> {
    let config = args.scenario.load()?;
    let recording = args.recording(&config)?;
    // Create and lock the directory before simulating, so that an unwritable one, or one
    // another process is writing, fails at once.
    let _lock = out_lock::lock(&args.out, out_lock::Share::Alone)?;
    run_dir::check_run_dir(&args.out)?;
    run_dir::remove_stale_tmp(&args.out)?;

    let name = crate::messages::printable(&config.name);
    let bar = progress::sim_bar(config.duration_s, progress::wanted(quiet), &name);
    let out = progress::run_recording_with_bar(&config, &recording, &bar)
        .with_context(|| format!("simulation of scenario '{name}' failed"))?;

    let writing = std::time::Instant::now();
    let mut written = run_dir::write_run_files(&args.out, &config, &out, args.format.table())?;
    let view_file = args.out.join(super::view::DEFAULT_FILE);
    if args.view {
        super::view::write(&args.out, &view_file)?;
    }
    // Last, so that a directory with a summary.json holds a finished run.
    written.push(run_dir::write_summary(&args.out, &out)?);
    let write_s = writing.elapsed().as_secs_f64();
    // The warning goes first, so that it is on stderr even if stdout is closed below.
    if let Some(first) = out.collision_events.first() {
        errln!(
            "warning: {} collision{} (the run is invalid: vehicles overlapped or ran past the \
             end of a lane); the first: {}; every one in {}",
            out.summary.collisions,
            if out.summary.collisions == 1 { "" } else { "s" },
            output::describe_collision(first),
            args.out.join(COLLISIONS).display()
        );
    }
    let failed = out.summary.collisions > 0 && !args.allow_collisions;
    let printed = (|| -> Result<()> {
        let paragraph = output::paragraph(&config, &out.summary, &args.out);
        outln!(
            "{}",
            paragraph.replace(DETECTORS.csv, &DETECTORS.file(args.format.ext()))
        )?;
        let ext = args.format.ext();
        let mut extra = Vec::new();
        if let Some(trips) = &out.trips {
            let queued = out.queued.as_ref().map_or(0, Vec::len);
            extra.push(format!(
                "{} ({} rows)",
                TRIPS.file(ext),
                trips.len() + queued
            ));
        }
        if let Some(rows) = &out.trajectories {
            extra.push(format!("{} ({} rows)", TRAJECTORIES.file(ext), rows.len()));
        }
        if !extra.is_empty() {
            let bytes: u64 = written
                .iter()
                .filter_map(|p| std::fs::metadata(p).ok())
                .map(|m| m.len())
                .sum();
            outln!(
                "Also written: {}. Output files: {:.1} MB written in {write_s:.2} s.",
                extra.join(", "),
                bytes as f64 / 1e6
            )?;
        }
        if args.view {
            outln!("Replay: {}", view_file.display())?;
        }
        Ok(())
    })();
    match printed {
        // A failed run keeps its exit status when stdout is closed (`| true`): the collision
        // is the news, the closed pipe is not.
        Err(e) if failed && crate::stdout::find(&e).is_some_and(|w| w.is_broken_pipe()) => {
            return Ok(ExitCode::from(EXIT_COLLISIONS));
        }
        r => r?,
    }
    if failed {
        return Ok(ExitCode::from(EXIT_COLLISIONS));
    }
    Ok(ExitCode::SUCCESS)
}
