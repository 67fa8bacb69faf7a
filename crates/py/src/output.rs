//! The run files the command line writes, from the binding: the same writer
//! (`platoonsim_runs::run_dir`), so a Python run directory has the same files and columns as
//! `platoonsim run`'s (`collisions.csv` if the run had any, the trip and trajectory tables if
//! they were recorded, an earlier run's leftovers removed, `summary.json` last).

use platoonsim_runs::columnar::Format;
use platoonsim_runs::run_dir;
use platoonsim_sim::{Config, Output};
use std::path::{Path, PathBuf};

/// Write the files of a finished run into `dir` (created if missing); the paths written.
pub fn write_run(dir: &Path, config: &Config, out: &Output) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir)
        .map_err(|e| format!("cannot create the output directory {}: {e}", dir.display()))?;
    run_dir::check_run_dir(dir)
        .map_err(|e| format!("cannot write the run into {}: {e}", dir.display()))?;
    run_dir::remove_stale_tmp(dir).map_err(|e| e.to_string())?;
    run_dir::write_run(dir, config, out, Format::Csv).map_err(|e| e.to_string())
}
