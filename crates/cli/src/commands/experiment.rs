//! `platoonsim experiment NAME`: one of the paper's experiments, resumable, with its tables.

use crate::args::{ExperimentArgs, GridArgs, NetworkArgs};
use crate::progress;
use anyhow::{bail, Context, Result};
use platoonsim_experiment::experiments::{QUICK_NETWORK_SEEDS, QUICK_SEEDS};
use platoonsim_experiment::{run_experiment, ExperimentName, ExperimentOutput, Part, Settings};
use platoonsim_scenario::{demand_scales, thresholds};
use std::path::{Path, PathBuf};

/// The settings shared by `experiment` and `reproduce`.
pub fn settings(grid: &GridArgs, seeds: u32, quiet: bool) -> Settings {
    Settings {
        out: grid.out.clone(),
        seeds,
        jobs: grid.jobs.map(|n| n as usize),
        progress: progress::wanted(quiet),
        progress_lines: progress::lines_wanted(quiet),
        reuse: !grid.fresh,
        arguments: std::env::args().collect(),
        ..Settings::default()
    }
}

pub fn experiment(args: &ExperimentArgs, quiet: bool) -> Result<()> {
    let name = args.name;
    let (duration, warmup) =
        crate::messages::check_experiment_duration(name, args.duration, args.warmup)
            .map_err(anyhow::Error::msg)?;
    let default_seeds = match (args.quick, name.part) {
        (false, _) => name.default_seeds,
        (true, Part::Network) => QUICK_NETWORK_SEEDS,
        (true, _) => QUICK_SEEDS,
    };
    let mut s = settings(&args.grid, args.seeds.unwrap_or(default_seeds), quiet);
    s.duration_s = duration;
    s.warmup_s = warmup;
    s.flow_thresholds = args.flow_thresholds.clone();
    s.speed_thresholds = args.speed_thresholds.clone();
    s.tolerance_pct = args.tolerance;
    s.format = args.format.table();
    s.preset = args.preset.preset();
    network(&mut s, &args.network, name)?;
    if args.quick {
        (name.quick)(&mut s);
    }
    let _lock = crate::out_lock::lock(&s.dir(name.as_str()), crate::out_lock::Share::Alone)?;
    let out = run_experiment(name, &s).with_context(|| format!("experiment {name} failed"))?;
    crate::stdout::print(&describe(&out))?;
    if let Some(p) = &s.write_table {
        let what = if name.name == "calibrate-flow-aware" {
            "the chosen Flow-Aware thresholds"
        } else {
            "the demand scales found"
        };
        outln!(
            "Wrote {what} to {}; rebuild platoonsim to make them the default.",
            p.display()
        )?;
    }
    Ok(())
}

/// The SR-99 flags into the settings.
pub fn network(s: &mut Settings, n: &NetworkArgs, name: ExperimentName) -> Result<()> {
    if n.penetrations.is_empty() || n.penetrations.iter().any(|p| !(0.0..=1.0).contains(p)) {
        bail!("--penetrations: every value must lie in [0, 1]");
    }
    let positive = |v: f64| v.is_finite() && v > 0.0;
    if !positive(n.bottleneck_speed) || !positive(n.bottleneck_minutes) {
        bail!("--bottleneck-speed and --bottleneck-minutes must be positive");
    }
    if let Some(d) = n.network_duration {
        if !positive(d) {
            bail!("--network-duration must be positive");
        }
    }
    s.network_penetrations = n.penetrations.clone();
    s.demand_scale = n.demand_scale;
    s.demand_scale_table = n.demand_scale_table.clone();
    s.scale_grid = if n.no_search {
        Vec::new()
    } else {
        n.scales.clone()
    };
    s.bottleneck_speed_kmh = n.bottleneck_speed;
    s.bottleneck_minutes = n.bottleneck_minutes;
    s.network_duration_s = n.network_duration;
    if let Some(w) = &n.write_table {
        let embedded = match name.name {
            "sr99-demand" if !n.no_search => demand_scales::TABLE_PATH,
            "calibrate-flow-aware" => thresholds::TABLE_PATH,
            _ => bail!(
                "--write-table applies to calibrate-flow-aware and to sr99-demand with a search \
                 (not with --no-search)"
            ),
        };
        s.write_table = Some(table_path(w.as_deref(), embedded)?);
    }
    Ok(())
}

/// Where `--write-table` writes: FILE if given, else the embedded table's source in the
/// repository, `embedded` (from the current directory, or where this binary was built from).
fn table_path(given: Option<&Path>, embedded: &str) -> Result<PathBuf> {
    if let Some(p) = given {
        // Checked now rather than after hours of runs.
        if p.is_dir() {
            bail!("--write-table {}: is a directory; give a file", p.display());
        }
        let parent = p.parent().filter(|d| !d.as_os_str().is_empty());
        if parent.is_some_and(|d| !d.is_dir()) {
            bail!(
                "--write-table {}: the directory {} does not exist",
                p.display(),
                parent.map_or(String::new(), |d| d.display().to_string())
            );
        }
        return Ok(p.to_path_buf());
    }
    let here = PathBuf::from(embedded);
    if here.is_file() {
        return Ok(here);
    }
    let built = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(embedded);
    if built.is_file() {
        return Ok(built);
    }
    bail!("cannot find {embedded} (run from the repository root, or give --write-table FILE)")
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
