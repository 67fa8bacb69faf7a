//! `platoonsim view`: the HTML replay of a run directory (the page is built by
//! `platoonsim_view`; this module writes it atomically and reports what went in).

use crate::args::ViewArgs;
use anyhow::{Context, Result};
use platoonsim_runs::atomic::write_atomic;
use std::path::Path;

/// The page's name inside the run directory when no --out is given.
pub const DEFAULT_FILE: &str = platoonsim_rundir::VIEW;

pub fn view(args: &ViewArgs) -> Result<()> {
    let file = args
        .out
        .clone()
        .unwrap_or_else(|| args.dir.join(DEFAULT_FILE));
    write(&args.dir, &file)?;
    outln!("{}", file.display())?;
    Ok(())
}

/// Build the page for the run in `dir` and write it to `file`; prints one line about its
/// content and size to stderr.
pub fn write(dir: &Path, file: &Path) -> Result<()> {
    // The page must not replace one of the run's files it is built from (`--out
    // RUN/trajectories.csv` did), nor anything that is not a regular file.
    let inputs: Vec<std::path::PathBuf> = platoonsim_rundir::RUN_FILES
        .iter()
        .filter(|name| **name != DEFAULT_FILE)
        .map(|name| dir.join(name))
        .collect();
    let inputs: Vec<&Path> = inputs.iter().map(|p| p.as_path()).collect();
    platoonsim_runs::atomic::refuse_input(file, &inputs)?;
    platoonsim_runs::atomic::check_output(file)?;
    let v = platoonsim_view::build(dir)?;
    write_atomic(file, v.html.as_bytes())
        .with_context(|| format!("cannot write {}", file.display()))?;
    errln!(
        "view: {} samples of {} vehicles in {} frames, {:.1} MB{}",
        v.rows,
        v.vehicles,
        v.frames,
        v.html.len() as f64 / 1e6,
        if v.platoon_column {
            ""
        } else {
            " (platoons inferred: no platoon_pos column)"
        }
    );
    Ok(())
}
