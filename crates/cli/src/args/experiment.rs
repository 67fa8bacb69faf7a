//! Command-line arguments of the experiment commands (`experiment`, `reproduce`). The doc
//! comments are the `--help` text.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::Args;
use platoonsim_experiment::{experiments, ExperimentName, EXPERIMENTS};
use std::path::PathBuf;

/// The experiments' names (with their help) from the experiment table.
fn experiment_names() -> impl TypedValueParser<Value = ExperimentName> {
    PossibleValuesParser::new(
        EXPERIMENTS
            .iter()
            .map(|e| PossibleValue::new(e.name).help(e.help)),
    )
    .map(|name| experiments::get(&name))
}

/// Flags shared by `experiment` and `reproduce`.
#[derive(Debug, Args)]
pub struct GridArgs {
    /// Output root directory; each experiment writes to DIR/<experiment>/.
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,

    /// Parallel runs (worker threads; each run is single-threaded). Default: one per core.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub jobs: Option<u32>,

    /// Recompute every run instead of reusing the run files of an earlier invocation (run
    /// files are otherwise reused when the configuration, seed and platoonsim build match).
    #[arg(long)]
    pub fresh: bool,
}

#[derive(Debug, Args)]
pub struct ExperimentArgs {
    /// Which experiment.
    #[arg(value_name = "NAME", value_parser = experiment_names())]
    pub name: ExperimentName,

    /// Seeds per cell (seeds 1..=N); the mean and a 95 % confidence interval are reported.
    /// Default: 10, or 3 for calibrate-flow-aware and sr99-demand.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub seeds: Option<u32>,

    /// Settings of `reproduce --quick` for this experiment: 3 seeds per cell (1 on SR-99)
    /// unless --seeds, and its quick changes (sr99, sr99-demand: 0 and 40 % CAV, no search;
    /// energy: 1500 and 2500 veh/h/lane, no SR-99 part).
    #[arg(long)]
    pub quick: bool,

    #[command(flatten)]
    pub grid: GridArgs,

    /// Simulated time of every run, for a quicker look (the paper's: 3600 s).
    /// [default: 3600; refused by sr99 and sr99-demand, which simulate the paper's 4-hour
    /// morning]
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub duration: Option<f64>,

    /// Warm-up of the runs that have one; PD acts after it (the paper's: 1200 s) [default:
    /// 1200; refused by sr99 and sr99-demand]
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub warmup: Option<f64>,

    /// calibrate-flow-aware: the rho_q values to try (veh/h/lane), comma-separated.
    #[arg(long, value_name = "LIST", value_delimiter = ',', default_values_t = platoonsim_experiment::experiments::calibrate::FLOW_THRESHOLDS)]
    pub flow_thresholds: Vec<f64>,

    /// calibrate-flow-aware: the rho_v values to try (km/h), comma-separated.
    #[arg(long, value_name = "LIST", value_delimiter = ',', default_values_t = platoonsim_experiment::experiments::calibrate::SPEED_THRESHOLDS)]
    pub speed_thresholds: Vec<f64>,

    /// calibrate-flow-aware: the largest discharge loss accepted at any demand (%).
    #[arg(long, value_name = "PCT", default_value_t = platoonsim_experiment::experiments::calibrate::TOLERANCE_PCT, value_parser = crate::messages::parse_tolerance)]
    pub tolerance: f64,

    #[command(flatten)]
    pub network: NetworkArgs,

    /// The model the behaviour keys default to (`model.preset`, docs/model-choices.md):
    /// paper (the paper's rules as published; writes to OUT/paper/NAME/) or platform (the
    /// engine's defaults).
    #[arg(long, value_enum, default_value = "platform")]
    pub preset: PresetArg,

    /// Format of the tables runs and summary: csv, or parquet (typed columns, compressed).
    #[arg(long, value_enum, default_value = "csv")]
    pub format: crate::tables::FormatArg,
}

/// The SR-99 experiments' flags.
#[derive(Debug, Args)]
pub struct NetworkArgs {
    /// sr99, sr99-demand: the CAV penetrations (0 to 1), comma-separated.
    #[arg(long, value_name = "LIST", value_delimiter = ',', default_values_t = platoonsim_experiment::experiments::sr99::PENETRATIONS)]
    pub penetrations: Vec<f64>,

    /// sr99: one demand scale for every penetration instead of the table.
    #[arg(long, value_name = "F", conflicts_with = "demand_scale_table")]
    pub demand_scale: Option<f64>,

    /// sr99 (and sr99-demand --no-search): the demand scales by penetration from this file
    /// (the format of crates/scenario/scenarios/sr99_demand_scales.toml, e.g. the
    /// demand_scales.toml that sr99-demand writes) instead of the embedded table.
    #[arg(long, value_name = "FILE")]
    pub demand_scale_table: Option<PathBuf>,

    /// sr99-demand: the demand scales to try at each penetration, comma-separated (in
    /// increasing order; the search stops at the first with both bottlenecks).
    #[arg(long, value_name = "LIST", value_delimiter = ',', default_values_t = platoonsim_experiment::experiments::sr99_demand::SCALE_GRID)]
    pub scales: Vec<f64>,

    /// sr99-demand: no search; only evaluate the bottleneck criterion at the table's scales.
    #[arg(long)]
    pub no_search: bool,

    /// sr99-demand: a detector is congested in a 5-min interval slower than this (km/h).
    #[arg(long, value_name = "KMH", default_value_t = platoonsim_experiment::experiments::sr99_demand::BOTTLENECK_SPEED_KMH)]
    pub bottleneck_speed: f64,

    /// sr99-demand: a bottleneck is active once a watched detector stays congested this long
    /// (min).
    #[arg(long, value_name = "MIN", default_value_t = platoonsim_experiment::experiments::sr99_demand::BOTTLENECK_MINUTES)]
    pub bottleneck_minutes: f64,

    /// sr99-demand: also write the scales found into the embedded table file (default:
    /// crates/scenario/scenarios/sr99_demand_scales.toml of this repository) or into FILE;
    /// calibrate-flow-aware: the chosen thresholds (default:
    /// crates/scenario/scenarios/flow_aware_thresholds.toml). Rebuild to use them.
    #[arg(long, value_name = "FILE", num_args = 0..=1, require_equals = false)]
    pub write_table: Option<Option<PathBuf>>,

    /// Simulated time of the SR-99 runs (tests only; the paper's: 14400 s).
    #[arg(long, value_name = "S", hide = true)]
    pub network_duration: Option<f64>,
}

#[derive(Debug, Args)]
pub struct ReproduceArgs {
    /// Fewer seeds (3 per cell) so that it finishes within minutes.
    #[arg(long)]
    pub quick: bool,

    /// Seeds per cell (default 10, or 3 with --quick).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    pub seeds: Option<u32>,

    #[command(flatten)]
    pub grid: GridArgs,

    /// Simulated time of every run (tests only: the report is the paper's with 3600 s).
    #[arg(long, value_name = "S", default_value_t = 3600.0, hide = true)]
    pub duration: f64,

    /// Warm-up of the runs that have one (tests only; the paper's: 1200 s).
    #[arg(long, value_name = "S", default_value_t = 1200.0, hide = true)]
    pub warmup: f64,

    /// Simulated time of the SR-99 runs (tests only; the paper's: 14400 s).
    #[arg(long, value_name = "S", hide = true)]
    pub network_duration: Option<f64>,
}

/// `--preset`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum PresetArg {
    /// The paper's rules as published.
    Paper,
    /// The engine's defaults.
    #[default]
    Platform,
}

impl PresetArg {
    pub fn preset(self) -> platoonsim_scenario::Preset {
        match self {
            PresetArg::Paper => platoonsim_scenario::Preset::Paper,
            PresetArg::Platform => platoonsim_scenario::Preset::Platform,
        }
    }
}
