//! Sweeps of any scenario described as data (`platoonsim sweep SPEC.toml`): the cartesian
//! product of axes of scenario keys, times seeds, run by the experiments' runner (parallel,
//! resumable through atomic run files, provenance in `run.json`) and summarized like the
//! experiments: `runs.csv`, `summary.csv` (or `.parquet`), `summary.md` and a figure per
//! shown metric.
//!
//! * [`spec`]: the sweep file and its validation (errors name the spec key);
//! * [`plan`]: the cells, resolved through the scenario crate's `--set` machinery;
//! * [`shard`]: the deterministic share of runs of one process (`--shard I/N` or a
//!   scheduler's array index);
//! * [`collect`]: paired differences and the tables; [`report`]: `summary.md`, figures.
//!
//! A sharded invocation only computes (or reuses) its runs' files in `<out>/runs/`; the
//! tables are written by an invocation without a shard (which computes whatever is still
//! missing) or by `--collect` (which computes nothing and fails if runs are missing). The
//! tables depend only on the run files, so sharded and unsharded sweeps give the same bytes.

pub mod collect;
pub mod plan;
pub mod report;
pub mod shard;
// The sweep file format lives with the scenario format (the fuzz targets read it without
// this crate).
pub use platoonsim_scenario::sweep_spec as spec;

use crate::atomic::write_atomic;
use crate::design::{self, Cell, Labels};
use crate::runner::{self, Executor, Outcome, Runner};
use crate::Figure;
use crate::{Error, VERSION};
use platoonsim_sim::Config;
use serde::Serialize;
use shard::Shard;
use spec::Spec;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

/// How to run a sweep.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// The sweep's output directory (run files in `runs/`).
    pub out: PathBuf,
    /// Worker threads (`None`: one per core).
    pub jobs: Option<usize>,
    /// Only this share of the runs, and no tables.
    pub shard: Option<Shard>,
    /// Compute nothing: write the tables from the run files, all of which must be there.
    pub collect: bool,
    /// Recompute runs whose files exist.
    pub fresh: bool,
    /// A progress bar (on a terminal).
    pub bar: bool,
    /// Progress lines on stderr (no terminal).
    pub lines: bool,
    /// `runs` and `summary` as CSV or Parquet.
    pub format: crate::columnar::Format,
    /// The command line, for the provenance.
    pub arguments: Vec<String>,
}

/// What a sweep invocation did.
#[derive(Clone, Debug)]
pub struct Done {
    pub dir: PathBuf,
    /// Runs of the whole sweep.
    pub total: usize,
    /// Runs this invocation handled (its shard's, or all).
    pub handled: usize,
    pub computed: usize,
    pub reused: usize,
    /// Runs with a collision (0 unless the tables were written).
    pub collided: usize,
    /// False for a shard: the tables were not written.
    pub tables: bool,
    pub figures: Vec<Figure>,
    pub wall_seconds: f64,
}

/// Run (a share of) a sweep with the engine.
pub fn run(spec: &Spec, opts: &Options) -> Result<Done, Error> {
    run_with(spec, opts, &runner::simulate)
}

/// [`run`] with another executor (tests count executions with it).
pub fn run_with(spec: &Spec, opts: &Options, exec: Executor<'_>) -> Result<Done, Error> {
    let start = Instant::now();
    if opts.collect && opts.shard.is_some() {
        return Err(Error::Other(
            "--collect writes the tables of the whole sweep; it takes no shard".into(),
        ));
    }
    // The metrics are checked before any run is computed.
    report::requested(spec).map_err(|e| Error::Other(e.to_string()))?;
    let cells = plan::cells(spec).map_err(|e| Error::Other(e.to_string()))?;
    let specs = design::runs(&cells, &spec.seeds);
    let total = specs.len();
    let mine: Vec<design::RunSpec> = match opts.shard {
        Some(s) => specs
            .iter()
            .enumerate()
            .filter(|(r, _)| s.owns(*r))
            .map(|(_, x)| x.clone())
            .collect(),
        None => specs.clone(),
    };
    std::fs::create_dir_all(&opts.out).map_err(|e| Error::io(&opts.out, e))?;
    if opts.shard.is_none() {
        // Before any run: every table and report name must be absent, a regular file or a
        // link to one (a FIFO at `runs.parquet` was unlinked after the whole sweep).
        for name in TABLE_FILES {
            let p = opts.out.join(name);
            crate::atomic::check_output(&p).map_err(|e| Error::io(&p, e))?;
        }
    }
    let label = match opts.shard {
        Some(s) => format!("sweep {} shard {s}", spec.name),
        None => format!("sweep {}", spec.name),
    };
    let bar = runner::bar(mine.len(), opts.bar, &label);
    let never = |_: &Config| -> Result<platoonsim_sim::Output, platoonsim_sim::SimError> {
        Err(platoonsim_sim::SimError::Config(
            "--collect computes nothing".into(),
        ))
    };
    let mut r = Runner::new(
        opts.out.join("runs"),
        opts.jobs,
        bar.clone(),
        if opts.collect { &never } else { exec },
    );
    r.reuse = !opts.fresh || opts.collect;
    if opts.lines && !opts.bar {
        r.log = Some(Arc::new(crate::progress::Lines::stderr(&label, mine.len())));
    }
    if opts.collect {
        let missing: Vec<&design::RunSpec> = mine.iter().filter(|s| !r.is_done(s)).collect();
        if !missing.is_empty() {
            let first: Vec<String> = missing
                .iter()
                .take(5)
                .map(|s| {
                    format!(
                        "{} ({}, seed {})",
                        s.key(),
                        crate::safety::cell_name(&cells[s.cell].labels),
                        s.seed
                    )
                })
                .collect();
            return Err(Error::Other(format!(
                "--collect: {} of {total} runs have no valid run file in {} (run the missing \
                 shards, or rerun without --collect to compute them); the first: {}",
                missing.len(),
                r.runs_dir.display(),
                first.join("; ")
            )));
        }
    }
    let outcomes = r.run(&mine);
    bar.finish_and_clear();
    let mut outcomes = outcomes?;
    let mut done = Done {
        dir: opts.out.clone(),
        total,
        handled: mine.len(),
        computed: r.computed(),
        reused: r.reused(),
        collided: 0,
        tables: false,
        figures: Vec::new(),
        wall_seconds: 0.0,
    };
    if opts.shard.is_none() {
        let metrics = collect::add_differences(spec, &mut outcomes);
        let rows = collect::summarize(spec, &cells, &outcomes, &metrics);
        let shown = report::shown(spec, &metrics)?;
        let write = |name: &str, bytes: &[u8]| {
            let p = opts.out.join(name);
            write_atomic(&p, bytes).map_err(|e| Error::io(&p, e))
        };
        let labels = crate::table::label_columns(&cells);
        let runs = crate::table::runs_csv(&cells, &outcomes)?;
        crate::columnar::write_table(&opts.out, "runs", &runs, &labels, opts.format)?;
        let summary = collect::summary_csv(spec, &cells, &rows)?;
        crate::columnar::write_table(&opts.out, "summary", &summary, &labels, opts.format)?;
        done.figures = report::figures(&opts.out, spec, &cells, &rows, &shown)?;
        let mut md = report::markdown(spec, &cells, &outcomes, &rows, &shown);
        if !done.figures.is_empty() {
            md.push_str("## Figures\n\n");
            for f in &done.figures {
                md.push_str(&format!(
                    "![{}]({}.png)\n\n*{}* ([SVG]({}.svg))\n\n",
                    f.title, f.stem, f.title, f.stem
                ));
            }
        }
        done.collided = outcomes
            .iter()
            .filter(|o| crate::safety::collided(o))
            .count();
        done.tables = true;
        done.wall_seconds = start.elapsed().as_secs_f64();
        md.push_str(&format!(
            "## Runs\n\n{} runs: {} computed, {} reused from run files, by this invocation \
             ({:.1} s wall time). Every run is in `runs.csv`; statistics per cell and metric \
             in `summary.csv`; provenance in `run.json`.\n",
            outcomes.len(),
            done.computed,
            done.reused,
            done.wall_seconds
        ));
        write("summary.md", md.as_bytes())?;
        write(
            "run.json",
            &provenance(spec, opts, &cells, &outcomes, &done)?,
        )?;
    }
    done.wall_seconds = start.elapsed().as_secs_f64();
    Ok(done)
}

/// The files an unsharded sweep writes into its directory (both formats of each table, which
/// replace each other), checked before any run; the figures are named by the spec.
pub const TABLE_FILES: [&str; 6] = [
    "runs.csv",
    "runs.parquet",
    "summary.csv",
    "summary.parquet",
    "summary.md",
    "run.json",
];

/// One cell of a `run.json` (a sweep's or an experiment's): its labels, its runs and the
/// scenario they share.
#[derive(Serialize)]
pub struct CellProvenance<'a> {
    labels: &'a Labels,
    /// Run keys (file names in runs/), one per seed.
    keys: Vec<&'a str>,
    /// The resolved scenario; `seed` is replaced by each run's.
    scenario: &'a Config,
}

/// The cells of a `run.json`, each with the keys of its runs in `outcomes`.
pub fn cell_provenance<'a>(cells: &'a [Cell], outcomes: &'a [Outcome]) -> Vec<CellProvenance<'a>> {
    cells
        .iter()
        .enumerate()
        .map(|(i, c)| CellProvenance {
            labels: &c.labels,
            keys: outcomes
                .iter()
                .filter(|o| o.cell == i)
                .map(|o| o.key.as_str())
                .collect(),
            scenario: &c.config,
        })
        .collect()
}

#[derive(Serialize)]
struct Provenance<'a> {
    sweep: &'a str,
    version: &'a str,
    engine: &'a str,
    arguments: &'a [String],
    spec_file: &'a str,
    spec: &'a str,
    seeds: &'a [u64],
    runs: usize,
    computed: usize,
    reused: usize,
    wall_seconds: f64,
    finished_unix_s: u64,
    cells: Vec<CellProvenance<'a>>,
}

fn provenance(
    spec: &Spec,
    opts: &Options,
    cells: &[Cell],
    outcomes: &[Outcome],
    done: &Done,
) -> Result<Vec<u8>, Error> {
    let p = Provenance {
        sweep: &spec.name,
        version: VERSION,
        engine: crate::record::engine_id(),
        arguments: &opts.arguments,
        spec_file: &spec.origin,
        spec: &spec.text,
        seeds: &spec.seeds,
        runs: outcomes.len(),
        computed: done.computed,
        reused: done.reused,
        wall_seconds: done.wall_seconds,
        finished_unix_s: std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs()),
        cells: cell_provenance(cells, outcomes),
    };
    let mut bytes = serde_json::to_vec_pretty(&p)
        .map_err(|e| Error::Other(format!("cannot encode run.json: {e}")))?;
    bytes.push(b'\n');
    Ok(bytes)
}
