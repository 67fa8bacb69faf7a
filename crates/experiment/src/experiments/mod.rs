//! The experiments: `capacity` (paper Fig. 4), `sensitivity` (paper Table 3),
//! `flow-aware` (issue 3's acceptance test of the Flow-Aware strategy),
//! `calibrate-flow-aware` (a grid search for the Flow-Aware thresholds), `sr99` (the SR-99
//! corridor: paper Table 4 and Figs. 6-8), `sr99-demand` (the search for the SR-99 demand
//! scale at which the recurrent bottlenecks show) and, beyond the paper, `behaviour` (Table 3
//! under the published and the safe gap rule and with cooperative lane changes) and `energy`
//! (fuel with and without organization, docs/energy.md).
//!
//! [`run_experiment`] runs one into `<out>/<name>/`: the run files in `runs/`, then
//! `runs.csv`, `summary.csv`, `summary.md`, `run.json` and the figures (`capacity.png`/`.svg`,
//! `sensitivity.png`/`.svg`, …), all written atomically.

mod behaviour;
pub mod calibrate;
mod capacity;
pub mod energy;
mod figures;
mod flow_aware;
mod grid;
mod mechanism;
mod rules;
mod sensitivity;
pub mod sr99;
pub mod sr99_demand;
mod sr99_figures;

use crate::table::{self, SummaryRow};
use platoonsim_runs::atomic::write_atomic;
use platoonsim_runs::design::{self, Cell, Labels, Point};
use platoonsim_runs::runner::{self, Executor, Outcome, Runner};
use platoonsim_runs::safety;
pub(crate) use platoonsim_runs::table::metric_label;
pub use platoonsim_runs::Figure;
use platoonsim_runs::{Error, VERSION};
use platoonsim_scenario::{Preset, StrategyKind};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

pub use capacity::FILL_S as CAPACITY_FILL_S;
pub use capacity::PENETRATIONS as CAPACITY_PENETRATIONS;
pub use sensitivity::DEMANDS as SENSITIVITY_DEMANDS;

/// Which part of `reproduce` runs an experiment, in this order (and in the table's order
/// within a part); `None`: not part of the reproduction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// The homogeneous road, the paper's experiments.
    Road,
    /// The SR-99 corridor, with its own seeds (`--quick`: fewer penetrations, no search).
    Network,
    /// The engine's rules as sensitivities over the paper's model (after the paper's
    /// experiments under it).
    Rules,
    /// Beyond the paper, last.
    Beyond,
    None,
}

/// What an experiment's report sees: its settings, output directory, cells, runs (with
/// the derived metrics), statistics and what its procedure kept besides.
pub struct Results<'a> {
    pub settings: &'a Settings,
    pub dir: &'a Path,
    pub cells: &'a [Cell],
    pub outcomes: &'a [Outcome],
    pub rows: &'a [SummaryRow],
    pub(crate) extra: &'a Extra,
}

/// What a report function makes: the body of `summary.md` (tables, comparison with the
/// paper), the checks against the paper, the figures it drew and further files to write.
#[derive(Default)]
pub struct Report {
    pub body: String,
    pub checks: Vec<Check>,
    pub figures: Vec<Figure>,
    pub files: Vec<(PathBuf, Vec<u8>)>,
}

/// One experiment: a row of [`EXPERIMENTS`]. Its procedure makes the cells and runs them
/// through the runner (a fixed grid, or adaptive stages whose cells depend on earlier
/// results); its report turns the results into tables, checks and figures.
pub struct Experiment {
    /// The name on the command line and of the output directory.
    pub name: &'static str,
    /// A title for reports.
    pub title: &'static str,
    /// One paragraph for `--help`.
    pub help: &'static str,
    pub part: Part,
    /// Seeds per cell unless asked otherwise.
    pub default_seeds: u32,
    /// Simulates a scenario's own period: refuses `--duration` and `--warmup`.
    pub own_period: bool,
    /// The labels that make the cells of one point (differing only in strategy) adjacent in
    /// the safety table; `None`: no safety table (a grid of hundreds of cells) and no
    /// braking figure.
    pub safety_group: Option<&'static [&'static str]>,
    /// Other experiments whose run files are reused (they share runs).
    pub reuse_from: &'static [&'static str],
    /// How many runs it makes with these settings (at most, for a search).
    pub total_runs: fn(&Settings) -> usize,
    /// The procedure: the cells, their runs and the derived metrics.
    pub(crate) run: fn(&Settings, &Runner<'_>, &[u64]) -> Result<Done, Error>,
    pub report: fn(&Results<'_>) -> Result<Report, Error>,
    /// `reproduce --quick`'s changes to the settings (beyond its seeds).
    pub quick: fn(&mut Settings),
}

impl Experiment {
    /// The experiment of this name.
    pub fn named(name: &str) -> Option<ExperimentName> {
        EXPERIMENTS.iter().copied().find(|e| e.name == name)
    }

    pub fn as_str(&self) -> &'static str {
        self.name
    }

    pub fn title(&self) -> &'static str {
        self.title
    }

    pub fn total_runs(&self, s: &Settings) -> usize {
        (self.total_runs)(s)
    }
}

impl PartialEq for Experiment {
    fn eq(&self, other: &Experiment) -> bool {
        self.name == other.name
    }
}

impl std::fmt::Debug for Experiment {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

impl std::fmt::Display for Experiment {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

/// An experiment, as the table's row.
pub type ExperimentName = &'static Experiment;

/// Every experiment, in the order of `reproduce` (within its parts) and of `--help`.
pub const EXPERIMENTS: [&Experiment; 9] = [
    &capacity::EXPERIMENT,
    &sensitivity::EXPERIMENT,
    &flow_aware::EXPERIMENT,
    &rules::EXPERIMENT,
    &calibrate::EXPERIMENT,
    &sr99::EXPERIMENT,
    &sr99_demand::EXPERIMENT,
    &behaviour::EXPERIMENT,
    &energy::EXPERIMENT,
];

/// The experiment of this name; panics on a name not in [`EXPERIMENTS`] (for fixed names in
/// code and tests; input goes through [`Experiment::named`]).
pub fn get(name: &str) -> ExperimentName {
    Experiment::named(name).unwrap_or_else(|| panic!("no experiment {name}"))
}

/// Keeps nothing to change for `--quick`.
pub(crate) fn unchanged(_: &mut Settings) {}

/// Seeds per cell of `reproduce` on the homogeneous road with `--quick`.
pub const QUICK_SEEDS: u32 = 3;
/// Seeds per cell of `reproduce` on SR-99 with `--quick`.
pub const QUICK_NETWORK_SEEDS: u32 = 1;

/// The experiments of `reproduce` with their settings: `base` (its seeds, duration, output,
/// …) for the homogeneous road; on SR-99 `network_seeds` (or 10; 1 with `quick`) and
/// `network_duration_s`, which the parts after it share for their SR-99 cells; then each
/// row's quick changes. The paper's model comes first (issue 43): the homogeneous road's
/// experiments and `sr99` under `model.preset = "paper"`, then the engine's rules as
/// sensitivities over it; then every part under the platform's defaults.
pub fn reproduction(
    base: &Settings,
    quick: bool,
    network_seeds: Option<u32>,
    network_duration_s: Option<f64>,
) -> Vec<(ExperimentName, Settings)> {
    let network_seeds = network_seeds.unwrap_or(if quick { QUICK_NETWORK_SEEDS } else { 10 });
    let settings = |e: ExperimentName, preset: Preset| {
        let mut s = base.clone();
        s.preset = preset;
        if e.part == Part::Network || e.part == Part::Beyond {
            s.network_seeds = Some(network_seeds);
            s.network_duration_s = network_duration_s;
        }
        if e.part == Part::Network {
            s.seeds = network_seeds;
            s.network_seeds = None;
        }
        if quick {
            (e.quick)(&mut s);
        }
        (e, s)
    };
    let of = |part: Part| EXPERIMENTS.iter().copied().filter(move |e| e.part == part);
    let mut out = Vec::new();
    for e in of(Part::Road).chain(of(Part::Network).filter(|e| e.name == sr99::NAME)) {
        out.push(settings(e, Preset::Paper));
    }
    for e in of(Part::Rules) {
        out.push(settings(e, Preset::Platform));
    }
    for part in [Part::Road, Part::Network, Part::Beyond] {
        for e in of(part) {
            out.push(settings(e, Preset::Platform));
        }
    }
    out
}

/// How to run an experiment.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Settings {
    /// Output root; the experiment writes to `<out>/<name>/`.
    pub out: PathBuf,
    /// Seeds 1..=seeds per cell.
    pub seeds: u32,
    /// Worker threads (`None`: one per core).
    pub jobs: Option<usize>,
    /// Draw a progress bar (the caller decides: not with --quiet, only on a terminal).
    pub progress: bool,
    /// Without a bar, print progress lines on stderr (the caller decides: not with --quiet,
    /// only without a terminal, e.g. in a scheduler's log).
    pub progress_lines: bool,
    /// Reuse existing run files (false: recompute every run and overwrite its file).
    pub reuse: bool,
    /// Simulated time of every run (paper: 3600 s).
    pub duration_s: f64,
    /// Warm-up of the runs that have one (paper: 1200 s); PD acts from then to the end.
    pub warmup_s: f64,
    /// Demand of the capacity experiment's first stage, well above capacity (veh/h/lane).
    pub capacity_demand_vphpl: f64,
    /// `calibrate-flow-aware`: the grid of ρ_q (veh/h/lane) …
    pub flow_thresholds: Vec<f64>,
    /// … and of ρ_v (km/h).
    pub speed_thresholds: Vec<f64>,
    /// `calibrate-flow-aware`: the largest discharge loss accepted at any demand (%).
    pub tolerance_pct: f64,
    /// `sr99`, `sr99-demand`: the CAV penetrations (at 0 and 1 `sr99` runs the baseline only).
    pub network_penetrations: Vec<f64>,
    /// `sr99`: one demand scale for every cell, instead of the table.
    pub demand_scale: Option<f64>,
    /// `sr99`, and `sr99-demand` without a grid: a demand-scale table file (the format of
    /// `crates/scenario/scenarios/sr99_demand_scales.toml`) instead of the embedded one.
    pub demand_scale_table: Option<PathBuf>,
    /// Simulated time of the SR-99 runs (`None`: the scenario's 14,400 s, 05:00-09:00).
    pub network_duration_s: Option<f64>,
    /// `sr99-demand`: the demand scales to try, in increasing order; empty: no search, the
    /// criterion is only evaluated at the table's scale of each penetration.
    pub scale_grid: Vec<f64>,
    /// `sr99-demand`: a detector is congested in a 5-min interval slower than this (km/h) …
    pub bottleneck_speed_kmh: f64,
    /// … and a bottleneck is active if it stays congested this long (min).
    pub bottleneck_minutes: f64,
    /// `sr99-demand`: also write the scales found into this table file (e.g. the embedded
    /// table's source, to rebuild with them); `calibrate-flow-aware`: the chosen thresholds.
    pub write_table: Option<PathBuf>,
    /// `energy`: the homogeneous road's demands (veh/h/lane; default: the paper's Table 3).
    pub energy_demands: Vec<f64>,
    /// Seeds per cell on SR-99 in `energy` (`None`: `seeds`).
    pub network_seeds: Option<u32>,
    /// The model the runs' behaviour keys default to (`model.preset`; docs/model-choices.md):
    /// under `paper` every cell gets `model.preset = "paper"` and the experiment writes to
    /// `<out>/paper/<name>/`.
    pub preset: Preset,
    /// `runs` and `summary` as CSV or Parquet.
    pub format: platoonsim_runs::columnar::Format,
    /// The command line, for the provenance.
    pub arguments: Vec<String>,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            out: PathBuf::from("out"),
            seeds: 10,
            jobs: None,
            progress: false,
            progress_lines: false,
            reuse: true,
            duration_s: 3600.0,
            warmup_s: 1200.0,
            capacity_demand_vphpl: 4500.0,
            flow_thresholds: calibrate::FLOW_THRESHOLDS.to_vec(),
            speed_thresholds: calibrate::SPEED_THRESHOLDS.to_vec(),
            tolerance_pct: calibrate::TOLERANCE_PCT,
            network_penetrations: sr99::PENETRATIONS.to_vec(),
            demand_scale: None,
            demand_scale_table: None,
            network_duration_s: None,
            scale_grid: sr99_demand::SCALE_GRID.to_vec(),
            bottleneck_speed_kmh: sr99_demand::BOTTLENECK_SPEED_KMH,
            bottleneck_minutes: sr99_demand::BOTTLENECK_MINUTES,
            write_table: None,
            energy_demands: sensitivity::DEMANDS.to_vec(),
            network_seeds: None,
            preset: Preset::Platform,
            format: platoonsim_runs::columnar::Format::Csv,
            arguments: Vec::new(),
        }
    }
}

impl Settings {
    /// Where the experiment `name` writes: `<out>/<name>/`, under the paper preset
    /// `<out>/paper/<name>/`.
    pub fn dir(&self, name: &str) -> PathBuf {
        match self.preset {
            Preset::Platform => self.out.join(name),
            Preset::Paper => self.out.join(Preset::Paper.as_str()).join(name),
        }
    }

    /// The `--set` that gives a cell this preset (none for the default, `platform`, so that
    /// the cells and their keys stay as they were).
    pub fn preset_set(&self) -> Option<String> {
        (self.preset != Preset::Platform).then(|| {
            format!(
                "{}={}",
                platoonsim_scenario::preset::KEY,
                self.preset.as_str()
            )
        })
    }
}

/// A statement about the results, e.g. one of issue 3's targets, and whether it holds.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Check {
    pub statement: String,
    pub passed: bool,
}

/// Everything an experiment produced.
#[derive(Clone, Debug)]
pub struct ExperimentOutput {
    pub name: ExperimentName,
    pub dir: PathBuf,
    pub settings: Settings,
    pub cells: Vec<Cell>,
    pub outcomes: Vec<Outcome>,
    pub rows: Vec<SummaryRow>,
    /// The body of `summary.md` (tables, comparison with the paper, checks), without its
    /// title and figures.
    pub body: String,
    pub checks: Vec<Check>,
    pub figures: Vec<Figure>,
    pub computed: usize,
    pub reused: usize,
    pub wall_seconds: f64,
}

impl ExperimentOutput {
    /// Markdown image links of the figures, with `prefix` before each file name.
    pub fn figures_md(&self, prefix: &str) -> String {
        let mut s = String::new();
        for f in &self.figures {
            s.push_str(&format!(
                "![{}]({prefix}{}.png)\n\n*{}* ([SVG]({prefix}{}.svg))\n\n",
                f.title, f.stem, f.title, f.stem
            ));
        }
        s
    }

    /// The whole `summary.md`.
    pub fn summary_md(&self) -> String {
        let mut s = format!("# {}\n\n{}", self.name.title(), self.body);
        if !self.figures.is_empty() {
            s.push_str("\n## Figures\n\n");
            s.push_str(&self.figures_md(""));
        }
        s
    }
}

/// Run an experiment with the engine; see the module documentation.
pub fn run_experiment(
    name: ExperimentName,
    settings: &Settings,
) -> Result<ExperimentOutput, Error> {
    run_experiment_with(name, settings, &runner::simulate)
}

/// The cells and runs an experiment produced, with its derived metrics added, and what an
/// experiment keeps for its tables and figures beyond them.
pub(crate) struct Done {
    pub cells: Vec<Cell>,
    pub outcomes: Vec<Outcome>,
    pub extra: Extra,
}

impl Done {
    pub fn new(cells: Vec<Cell>, outcomes: Vec<Outcome>) -> Done {
        Done {
            cells,
            outcomes,
            extra: Extra::None,
        }
    }
}

/// Experiment-specific results besides the runs' metrics.
#[derive(Default)]
pub(crate) enum Extra {
    #[default]
    None,
    /// `sr99`: the detector records of the figure runs.
    Sr99(sr99::Data),
    /// `sr99-demand`: the search.
    Demand(sr99_demand::Data),
}

/// [`run_experiment`] with another executor (tests count executions with it).
pub fn run_experiment_with(
    name: ExperimentName,
    settings: &Settings,
    exec: Executor<'_>,
) -> Result<ExperimentOutput, Error> {
    if settings.seeds == 0 {
        return Err(Error::Other("at least one seed is needed".into()));
    }
    let start = Instant::now();
    let dir = settings.dir(name.as_str());
    std::fs::create_dir_all(&dir).map_err(|e| Error::io(&dir, e))?;
    let seeds = design::seeds(settings.seeds);
    let bar = runner::bar(name.total_runs(settings), settings.progress, name.as_str());
    let mut runner = Runner::new(dir.join("runs"), settings.jobs, bar.clone(), exec);
    runner.reuse = settings.reuse;
    if settings.progress_lines && !settings.progress {
        runner.log = Some(std::sync::Arc::new(
            platoonsim_runs::progress::Lines::stderr(name.as_str(), name.total_runs(settings)),
        ));
    }
    runner.reuse_from = name
        .reuse_from
        .iter()
        .map(|other| settings.dir(other).join("runs"))
        .collect();
    let done = (name.run)(settings, &runner, &seeds);
    bar.finish_and_clear();
    let Done {
        cells,
        outcomes,
        extra,
    } = done?;
    let rows = table::summarize(name.as_str(), &cells, &outcomes);
    let report = (name.report)(&Results {
        settings,
        dir: &dir,
        cells: &cells,
        outcomes: &outcomes,
        rows: &rows,
        extra: &extra,
    })?;
    let (body, checks) = with_safety(name, &cells, &outcomes, report.body, report.checks);
    let mut figures = report.figures;
    if name.safety_group.is_some() {
        figures.extend(safety::braking_figure(&dir, &cells, &outcomes)?);
    }
    for (path, bytes) in &report.files {
        write_file(path, bytes)?;
    }

    let mut out = ExperimentOutput {
        name,
        dir: dir.clone(),
        settings: settings.clone(),
        cells,
        outcomes,
        rows,
        body,
        checks,
        figures,
        computed: runner.computed(),
        reused: runner.reused(),
        wall_seconds: 0.0,
    };
    out.body.push_str(&format!(
        "\n## Runs\n\n{} runs ({} seeds per cell): {} computed, {} reused from earlier run files; \
         {:.1} s wall time. Every run is in `runs.csv`; statistics per cell and metric in \
         `summary.csv`; provenance in `run.json`.\n",
        out.outcomes.len(),
        settings.seeds,
        out.computed,
        out.reused,
        start.elapsed().as_secs_f64()
    ));
    out.wall_seconds = start.elapsed().as_secs_f64();
    write_outputs(&out)?;
    Ok(out)
}

/// The experiment's body and checks with the safety parts added: a warning first if any run
/// collided, a `## Safety` table last (not for `calibrate-flow-aware`, whose grid of
/// thresholds would make it hundreds of rows; its warning still lists the failed cells), and
/// a check that no run collided.
pub(crate) fn with_safety(
    name: ExperimentName,
    cells: &[Cell],
    outcomes: &[Outcome],
    body: String,
    mut checks: Vec<Check>,
) -> (String, Vec<Check>) {
    // Cells of one point (differing only in strategy) on adjacent rows.
    let group = name.safety_group;
    let mut md = safety::warning_md(cells, outcomes);
    md.push_str(&body);
    if let Some(group) = group {
        md.push('\n');
        md.push_str(&safety::section_md(cells, outcomes, group));
    }
    let failed: usize = (0..cells.len())
        .map(|c| safety::collided_runs(outcomes, c))
        .sum();
    checks.push(Check {
        statement: if failed == 0 {
            format!("no run had a collision ({} runs)", outcomes.len())
        } else {
            format!(
                "no run had a collision: {failed} of {} runs had collisions, their cells are \
                 invalid (see the warning in summary.md)",
                outcomes.len()
            )
        },
        passed: failed == 0,
    });
    (md, checks)
}

fn write_file(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    write_atomic(path, bytes).map_err(|e| Error::io(path, e))
}

#[derive(Serialize)]
struct Provenance<'a> {
    experiment: &'a str,
    version: &'a str,
    arguments: &'a [String],
    settings: &'a Settings,
    seeds: Vec<u64>,
    runs: usize,
    computed: usize,
    reused: usize,
    wall_seconds: f64,
    finished_unix_s: u64,
    cells: Vec<platoonsim_runs::sweep::CellProvenance<'a>>,
}

/// Write `runs.csv`, `summary.csv` (or `.parquet`, [`Settings::format`]), `summary.md` and
/// `run.json`.
pub fn write_outputs(out: &ExperimentOutput) -> Result<(), Error> {
    let dir = &out.dir;
    let labels = table::label_columns(&out.cells);
    let format = out.settings.format;
    let runs = table::runs_csv(&out.cells, &out.outcomes)?;
    platoonsim_runs::columnar::write_table(dir, "runs", &runs, &labels, format)?;
    let summary = table::summary_csv(&out.cells, &out.rows)?;
    platoonsim_runs::columnar::write_table(dir, "summary", &summary, &labels, format)?;
    write_file(&dir.join("summary.md"), out.summary_md().as_bytes())?;
    let prov = Provenance {
        experiment: out.name.as_str(),
        version: VERSION,
        arguments: &out.settings.arguments,
        settings: &out.settings,
        seeds: design::seeds(out.settings.seeds),
        runs: out.outcomes.len(),
        computed: out.computed,
        reused: out.reused,
        wall_seconds: out.wall_seconds,
        finished_unix_s: std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs()),
        cells: platoonsim_runs::sweep::cell_provenance(&out.cells, &out.outcomes),
    };
    let mut bytes = serde_json::to_vec_pretty(&prov)
        .map_err(|e| Error::Other(format!("cannot encode run.json: {e}")))?;
    bytes.push(b'\n');
    write_file(&dir.join("run.json"), &bytes)
}

// ---- helpers shared by the experiments ---------------------------------------------------

/// A homogeneous-road cell with the standard labels.
pub(crate) fn cell(extra: &[(&str, String)], p: Point) -> Result<Cell, Error> {
    let mut labels = Labels::new();
    for (k, v) in extra {
        labels = labels.with(k, v.clone());
    }
    labels = labels
        .with("penetration", design::num(p.penetration))
        .with("demand_vphpl", design::num(p.demand_vphpl))
        .with("strategy", p.strategy.as_str());
    let config = design::homogeneous(&p)?;
    Ok(Cell { labels, config })
}

/// A point with the settings' duration and warm-up.
pub(crate) fn point(s: &Settings, penetration: f64, demand: f64, strategy: StrategyKind) -> Point {
    Point {
        penetration,
        demand_vphpl: demand,
        strategy,
        duration_s: s.duration_s,
        warmup_s: s.warmup_s,
        set: s.preset_set().into_iter().collect(),
    }
}

/// Run cells (indices offset by `offset` in the outcomes).
pub(crate) fn run_cells(
    runner: &Runner<'_>,
    cells: &[Cell],
    seeds: &[u64],
    offset: usize,
) -> Result<Vec<Outcome>, Error> {
    let mut out = runner.run(&design::runs(cells, seeds))?;
    for o in &mut out {
        o.cell += offset;
    }
    Ok(out)
}

/// Index of the cell with these labels.
pub(crate) fn find(cells: &[Cell], wanted: &[(&str, &str)]) -> Option<usize> {
    cells.iter().position(|c| c.labels.matches(wanted))
}

/// A bullet list of checks.
pub(crate) fn checks_md(checks: &[Check]) -> String {
    let mut s = String::new();
    for c in checks {
        s.push_str(&format!(
            "- **{}**: {}\n",
            if c.passed { "holds" } else { "does not hold" },
            c.statement
        ));
    }
    s
}
