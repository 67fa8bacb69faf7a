//! Command-line arguments (clap derive). The doc comments are the `--help` text.

use anyhow::Result;
use clap::{Args, Parser, Subcommand, ValueEnum};
use platoonsim_scenario::{Overrides, StrategyKind};
use platoonsim_sim::Config;
use std::path::PathBuf;

/// Microscopic freeway simulator for CACC platoons in mixed human/CAV traffic (Woo &
/// Skabardonis, "Flow-aware platoon formation of CAVs in mixed traffic").
#[derive(Debug, Parser)]
#[command(name = "platoonsim", version, propagate_version = true)]
#[command(after_help = "Run `platoonsim <COMMAND> --help` for a command's flags.")]
pub struct Cli {
    /// Hide progress bars (they are also hidden when stderr is not a terminal).
    #[arg(short, long, global = true, display_order = 1000)]
    pub quiet: bool,

    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Simulate one scenario; write summary.json, detectors.csv, scenario.json and
    /// scenario.toml to the output directory and print a short summary.
    Run(RunArgs),
    /// Measure the engine's speed (vehicle updates per second) on the built-in homogeneous road
    /// at 50 % CAV and 2,500 veh/h/lane.
    Bench(BenchArgs),
    /// List the built-in scenarios.
    Scenarios,
    /// Print a scenario with every key resolved (defaults and overrides applied).
    Show(ShowArgs),
}

/// Which scenario, and what to change in it. Overrides act on the scenario file before it
/// is checked: the typed flags below are applied after all --set values.
#[derive(Debug, Args)]
pub struct ScenarioArgs {
    /// A built-in scenario name (see `platoonsim scenarios`) or the path of a scenario TOML
    /// file. An argument containing '/' or ending in .toml is always read as a file.
    #[arg(value_name = "SCENARIO-NAME-OR-FILE")]
    pub scenario: String,

    /// Share of CAVs among arriving vehicles, from 0 to 1 (sets run.penetration).
    #[arg(long, value_name = "P")]
    pub penetration: Option<f64>,

    /// Arrival rate at the entrance in vehicles per hour per lane (sets demand.vph_per_lane).
    #[arg(long, value_name = "VEH_PER_H_PER_LANE")]
    pub demand: Option<f64>,

    /// Simulated time in seconds (sets run.duration_s).
    #[arg(long, value_name = "S")]
    pub duration: Option<f64>,

    /// Warm-up in seconds; lane-change, platoon and discharge statistics are measured from
    /// then to the end (sets run.warmup_s).
    #[arg(long, value_name = "S")]
    pub warmup: Option<f64>,

    /// Random seed; the same seed gives identical results (sets run.seed).
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,

    /// Platoon organization strategy (sets strategy.kind).
    #[arg(long, value_enum, value_name = "STRATEGY")]
    pub strategy: Option<StrategyArg>,

    /// Set any scenario key, e.g. --set human.buffer_s=0.2 --set run.seed=3
    /// --set cav.time_gap_shares=[[0.6,1.0]] --set detectors[0].position_m=4800. The value is
    /// read as TOML (number, array, inline table, quoted string), otherwise as a plain string.
    /// Repeatable; a later --set of the same key wins.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
}

impl ScenarioArgs {
    pub fn overrides(&self) -> Overrides {
        Overrides {
            penetration: self.penetration,
            demand_vphpl: self.demand,
            duration_s: self.duration,
            warmup_s: self.warmup,
            seed: self.seed,
            strategy: self.strategy.map(StrategyKind::from),
            set: self.set.clone(),
        }
    }

    /// Load and validate the scenario with the overrides.
    pub fn load(&self) -> Result<Config> {
        Ok(platoonsim_scenario::load_with(
            &self.scenario,
            &self.overrides(),
        )?)
    }
}

/// Platoon organization strategy.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum StrategyArg {
    /// No organization (the baseline).
    None,
    /// Pseudo-dedicated lane: in its zone and time window, CAVs move toward the leftmost lane.
    Pd,
    /// PD lane only while nearby detectors report flow below and speed above the thresholds.
    FlowAware,
}

impl From<StrategyArg> for StrategyKind {
    fn from(s: StrategyArg) -> Self {
        match s {
            StrategyArg::None => StrategyKind::None,
            StrategyArg::Pd => StrategyKind::Pd,
            StrategyArg::FlowAware => StrategyKind::FlowAware,
        }
    }
}

#[derive(Debug, Args)]
pub struct RunArgs {
    #[command(flatten)]
    pub scenario: ScenarioArgs,

    /// Output directory (created if missing; existing files in it are replaced).
    #[arg(long, value_name = "DIR", default_value = "out/run")]
    pub out: PathBuf,
}

#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Simulated seconds per repetition (warm-up: a third of it, at most 1200 s).
    #[arg(long, value_name = "S", default_value_t = 3600.0)]
    pub duration: f64,

    /// Number of repetitions; the best and the median are reported.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub repeat: u32,

    /// Random seed.
    #[arg(long, value_name = "N", default_value_t = 1)]
    pub seed: u64,

    /// Print the result as JSON on stdout instead of text.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, Args)]
pub struct ShowArgs {
    #[command(flatten)]
    pub scenario: ScenarioArgs,

    /// Output format: toml is a complete scenario file that `platoonsim run` accepts; json is
    /// the engine's resolved configuration, as written to scenario.json.
    #[arg(long, value_enum, default_value = "toml")]
    pub format: ShowFormat,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ShowFormat {
    Toml,
    Json,
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn clap_definition_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn flags_map_to_overrides() {
        let cli = Cli::try_parse_from([
            "platoonsim",
            "run",
            "homogeneous",
            "--penetration",
            "0.25",
            "--demand",
            "2000",
            "--duration",
            "600",
            "--warmup",
            "120",
            "--seed",
            "7",
            "--strategy",
            "flow-aware",
            "--set",
            "human.buffer_s=0.2",
            "--set",
            "run.dt_s=0.05",
        ])
        .unwrap();
        let Command::Run(run) = cli.command else {
            panic!()
        };
        let o = run.scenario.overrides();
        assert_eq!(o.penetration, Some(0.25));
        assert_eq!(o.demand_vphpl, Some(2000.0));
        assert_eq!(o.duration_s, Some(600.0));
        assert_eq!(o.warmup_s, Some(120.0));
        assert_eq!(o.seed, Some(7));
        assert_eq!(o.strategy, Some(StrategyKind::FlowAware));
        assert_eq!(o.set, vec!["human.buffer_s=0.2", "run.dt_s=0.05"]);
        assert_eq!(run.out, PathBuf::from("out/run"));
    }
}
