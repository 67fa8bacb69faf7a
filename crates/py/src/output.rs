//! The run files the command line writes, from the binding: `scenario.json`,
//! `scenario.toml`, `detectors.csv`, then `summary.json` last (a directory with a summary holds
//! a finished run), each atomically through the experiment crate's helper.

use platoonsim_experiment::atomic::write_atomic;
use platoonsim_experiment::detectors::{to_csv, Scope};
use platoonsim_sim::{Config, Output};
use std::path::{Path, PathBuf};

/// Pretty JSON with a final newline, as the command line writes it.
fn json<T: serde::Serialize>(value: &T) -> Result<Vec<u8>, String> {
    let mut bytes =
        serde_json::to_vec_pretty(value).map_err(|e| format!("cannot encode JSON: {e}"))?;
    bytes.push(b'\n');
    Ok(bytes)
}

/// Write the files of a finished run into `dir` (created if missing); the paths written.
pub fn write_run(dir: &Path, config: &Config, out: &Output) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir)
        .map_err(|e| format!("cannot create the output directory {}: {e}", dir.display()))?;
    let (detectors, _) =
        to_csv(&out.detectors, Scope::All, config.clock_start_s).map_err(|e| e.to_string())?;
    let files: [(&str, Vec<u8>); 4] = [
        ("scenario.json", json(config)?),
        (
            "scenario.toml",
            platoonsim_scenario::to_toml(config).into_bytes(),
        ),
        ("detectors.csv", detectors),
        ("summary.json", json(&out.summary)?),
    ];
    let mut written = Vec::with_capacity(files.len());
    for (name, bytes) in files {
        let path = dir.join(name);
        write_atomic(&path, &bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        written.push(path);
    }
    Ok(written)
}
