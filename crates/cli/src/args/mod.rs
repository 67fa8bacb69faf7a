//! Command-line arguments (clap derive). The doc comments are the `--help` text.

use anyhow::{bail, Result};
use clap::{Args, Parser, Subcommand, ValueEnum};
use platoonsim_scenario::{demand_scale_set, Overrides, ScenarioError, StrategyKind};
use platoonsim_sim::record::period_steps;
use platoonsim_sim::{Config, Recording, TrajectorySpec};
use std::path::PathBuf;

mod compare;
#[cfg(test)]
mod doc_flags;
mod experiment;
mod field;
pub use compare::CompareArgs;
pub use experiment::*;
pub use field::FieldFlags;

/// Microscopic freeway simulator for CACC platoons in mixed human/CAV traffic (Woo &
/// Skabardonis, "Flow-aware platoon formation of CAVs in mixed traffic").
#[derive(Debug, Parser)]
#[command(name = "platoonsim", version, propagate_version = true)]
#[command(
    after_help = "Run `platoonsim <COMMAND> --help` for a command's flags.\n\nExit codes: 0 \
                  success; 1 error; 2 invalid arguments; 3 `run` had collisions (unless \
                  --allow-collisions) or a `sweep` had runs with collisions; 141 standard \
                  output was closed (e.g. `| head`)."
)]
pub struct Cli {
    /// Hide progress bars (they are also hidden when stderr is not a terminal).
    #[arg(short, long, global = true, display_order = 1000)]
    pub quiet: bool,

    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Simulate one scenario; write summary.json, detectors.csv, scenario.json, scenario.toml
    /// and road.json (and on request trips.csv, trajectories.csv; collisions.csv if vehicles
    /// collided) to the output directory and print a short summary. Exits with 3 if the run
    /// had collisions (unless --allow-collisions).
    Run(RunArgs),
    /// Measure the engine's speed (vehicle updates per second) on the built-in homogeneous road
    /// at 50 % CAV and 2,500 veh/h/lane.
    Bench(BenchArgs),
    /// List the built-in scenarios.
    Scenarios,
    /// Print a scenario with every key resolved (defaults and overrides applied).
    Show(ShowArgs),
    /// Run one of the paper's experiments (a grid of cells x seeds, in parallel); write
    /// runs.csv, summary.csv, summary.md and run.json to OUT/NAME/. Resumable: finished runs
    /// are kept in OUT/NAME/runs/ and reused by a rerun with the same arguments.
    Experiment(ExperimentArgs),
    /// Run every experiment (the homogeneous road, then the SR-99 corridor) and write
    /// OUT/REPORT.md and OUT/report.html (our results beside the paper's, with the
    /// differences). --quick uses 3 seeds per cell on the homogeneous road and a reduced SR-99
    /// part.
    Reproduce(ReproduceArgs),
    /// Draw a time-space diagram of one lane from a trajectories.csv (written by `run
    /// --trajectories`): time on the x axis, position on the y axis, one line per vehicle while
    /// it is in the lane, coloured by speed (0-120 km/h), CAVs thick and humans thin. Writes
    /// STEM.png and STEM.svg.
    TimeSpace(TimeSpaceArgs),
    /// Write a self-contained HTML replay of a run made with --trajectories (default
    /// RUN_DIR/view.html): the road to scale, every vehicle coloured by kind, speed, platoon or
    /// driving mode, play/pause/step, zoom and pan, a minimap, detectors and a speed contour.
    /// Opens offline in any current browser; loads nothing from the network.
    View(ViewArgs),
    /// Run a sweep described by a TOML file (a scenario, seeds, fixed --set keys, axes whose
    /// product makes the cells, a reference level for paired differences); write runs.csv,
    /// summary.csv, summary.md, run.json and figures to OUT. Resumable, and shardable over a
    /// scheduler's job array (--shard I/N, or SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX,
    /// HQ_TASK_ID); see docs/sweeps.md.
    Sweep(crate::commands::sweep::SweepArgs),
    /// Compare runs with field detector data (PeMS station_5min or tidy CSV): GEH of hourly
    /// flows, 15-min speed RMSE, RMSNE and correlation, active bottlenecks on both sides,
    /// judged by the FHWA Traffic Analysis Toolbox Vol. III criteria and the project's
    /// targets; writes compare.md, compare.html, fit.json and speed contours to OUT
    /// (default RUN_DIR/compare). Detectors are matched to field stations by name; see
    /// docs/compare.md.
    Compare(CompareArgs),
    /// Fit chosen scenario keys to field data (PeMS station_5min or tidy CSV of flows and
    /// speeds at stations named like the scenario's detectors) with CMA-ES: each candidate is the mean of R replications;
    /// write calibrated.toml, trace.csv, convergence.png, fit-before.md, fit-after.md and
    /// run.json to OUT/NAME. Resumable, and shardable like a sweep (--shard I/N or a
    /// scheduler's array index); see docs/calibrate.md.
    Calibrate(crate::commands::calibrate::CalibrateArgs),
    /// Import a network of another tool as a scenario file: `import sumo NET.net.xml
    /// [--routes F] [--additional F] --out SCENARIO.toml` (SUMO networks, also built from
    /// OpenStreetMap by netconvert); see docs/import.md.
    Import(crate::commands::import::ImportArgs),
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
    #[arg(long, value_name = "P", allow_negative_numbers = true)]
    pub penetration: Option<f64>,

    /// Arrival rate at the entrance in vehicles per hour per lane (sets demand.vph_per_lane).
    #[arg(long, value_name = "VEH_PER_H_PER_LANE", allow_negative_numbers = true)]
    pub demand: Option<f64>,

    /// Simulated time in seconds (sets run.duration_s).
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub duration: Option<f64>,

    /// Warm-up in seconds; lane-change, platoon and discharge statistics are measured from
    /// then to the end (sets run.warmup_s).
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub warmup: Option<f64>,

    /// Random seed; the same seed gives identical results (sets run.seed).
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = crate::messages::parse_seed)]
    pub seed: Option<u64>,

    /// Platoon organization strategy (sets strategy.kind).
    #[arg(long, value_enum, value_name = "STRATEGY")]
    pub strategy: Option<StrategyArg>,

    /// Network scenarios (e.g. sr99): multiplier on every entrance demand, on top of the
    /// corridor's base multiplier (sets network.demand_scale; default: the scale at the run's
    /// penetration in the table the scenario names in network.demand_scale_table, as sr99
    /// does, else 1).
    #[arg(long, value_name = "F")]
    pub demand_scale: Option<f64>,

    /// Set any scenario key, e.g. --set human.buffer_s=0.2 --set run.seed=3
    /// --set cav.time_gap_shares=[[0.6,1.0]] --set detectors[0].position_m=4800. The value is
    /// read as TOML (number, array, inline table, quoted string), otherwise as a plain string.
    /// Repeatable; a later --set of the same key wins.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
}

impl ScenarioArgs {
    /// The overrides; `--demand-scale` travels as the last `--set` (of network.demand_scale),
    /// so that it wins over a --set of the same key like the other typed flags.
    pub fn overrides(&self) -> Overrides {
        let mut set = self.set.clone();
        set.extend(self.demand_scale.map(demand_scale_set));
        Overrides {
            penetration: self.penetration,
            demand_vphpl: self.demand,
            duration_s: self.duration,
            warmup_s: self.warmup,
            seed: self.seed,
            strategy: self.strategy.map(StrategyKind::from),
            set,
        }
    }

    /// Load and validate the scenario with the overrides.
    pub fn load(&self) -> Result<Config> {
        match platoonsim_scenario::load_with(&self.scenario, &self.overrides()) {
            Ok(config) => {
                // Legal geometry known to collide: said once, before anything runs.
                for w in platoonsim_scenario::validate::warnings(&config) {
                    errln!("warning: {w}");
                }
                Ok(config)
            }
            // Name the flag rather than the key it sets.
            Err(ScenarioError::Override { arg, reason })
                if self.demand_scale.map(demand_scale_set).as_ref() == Some(&arg) =>
            {
                bail!(
                    "invalid --demand-scale {}: {reason} (--demand-scale scales a network's \
                     demand; on a homogeneous road use --demand)",
                    self.demand_scale.unwrap_or_default()
                )
            }
            Err(e) => {
                match crate::messages::warmup_hint(self.duration, self.warmup, &e.to_string()) {
                    Some(hint) => bail!("{e}\n  {hint}"),
                    None => Err(e.into()),
                }
            }
        }
    }
}

/// The strategy names of the engine's table ([`platoonsim_sim::STRATEGIES`]), with their
/// descriptions for `--help`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StrategyArg(pub StrategyKind);

impl ValueEnum for StrategyArg {
    fn value_variants<'a>() -> &'a [Self] {
        static ALL: std::sync::OnceLock<Vec<StrategyArg>> = std::sync::OnceLock::new();
        ALL.get_or_init(|| StrategyKind::all().map(StrategyArg).collect())
    }

    fn to_possible_value(&self) -> Option<clap::builder::PossibleValue> {
        Some(clap::builder::PossibleValue::new(self.0.as_str()).help(self.0.entry().about))
    }
}

impl From<StrategyArg> for StrategyKind {
    fn from(s: StrategyArg) -> Self {
        s.0
    }
}

#[derive(Debug, Args)]
pub struct RunArgs {
    #[command(flatten)]
    pub scenario: ScenarioArgs,

    /// Output directory (created if missing; existing files in it are replaced, and a
    /// trips.csv, trajectories.csv or collisions.csv of an earlier run is removed unless this
    /// run writes one).
    #[arg(long, value_name = "DIR", default_value = "out/run")]
    pub out: PathBuf,

    /// Exit with 0 even if the simulation had collisions (the warning is printed all the
    /// same). Without it, a run with collisions exits with code 3 after writing its files,
    /// collisions.csv among them.
    #[arg(long)]
    pub allow_collisions: bool,

    /// Format of the tables detectors, trips and trajectories: csv, or parquet (typed columns,
    /// compressed; detectors.parquet, trips.parquet, trajectories.parquet).
    #[arg(long, value_enum, default_value = "csv")]
    pub format: crate::tables::FormatArg,

    /// Also write trips.csv: one row per vehicle that entered the road (entrance, exit, times,
    /// travel time, lane changes, largest platoon). Does not change the simulation.
    #[arg(long)]
    pub trips: bool,

    /// Also write OUT/view.html, the replay of `platoonsim view` (needs --trajectories; add
    /// --trips for the trips of clicked vehicles).
    #[arg(long, requires = "trajectories")]
    pub view: bool,

    /// Also write trajectories.csv: lane, position, speed, acceleration and driving mode of
    /// every vehicle on the road every PERIOD_S seconds of simulated time (a positive multiple
    /// of the time step run.dt_s, 0.1 s by default). Large: a 4-hour corridor run sampled every
    /// second gives tens of millions of rows; narrow it with --trajectory-window and
    /// --trajectory-x. Does not change the simulation.
    #[arg(long, value_name = "PERIOD_S", allow_negative_numbers = true)]
    pub trajectories: Option<f64>,

    /// With --trajectories: only the samples at simulated times T0 <= t <= T1 (seconds).
    #[arg(
        long,
        value_name = "T0,T1",
        value_delimiter = ',',
        allow_hyphen_values = true,
        requires = "trajectories"
    )]
    pub trajectory_window: Option<Vec<f64>>,

    /// With --trajectories: only the vehicles whose front is at X0 <= x <= X1 (metres, in the
    /// coordinate of detectors.csv's position_m).
    #[arg(
        long,
        value_name = "X0,X1",
        value_delimiter = ',',
        allow_hyphen_values = true,
        requires = "trajectories"
    )]
    pub trajectory_x: Option<Vec<f64>>,
}

impl RunArgs {
    /// What to record besides the standard outputs (--trips, --trajectories and its windows),
    /// checked against the loaded scenario. Errors name the flag, the value and what is allowed.
    pub fn recording(&self, config: &Config) -> Result<Recording> {
        let mut rec = Recording {
            trips: self.trips,
            trajectories: None,
        };
        let Some(period_s) = self.trajectories else {
            return Ok(rec);
        };
        let dt = config.dt_s;
        if period_steps(period_s, dt).is_none() {
            bail!(
                "invalid --trajectories {}: the sampling period (s) must be a positive \
                 multiple of the time step run.dt_s = {dt} s",
                crate::messages::short_num(period_s)
            );
        }
        let window_s = match pair(&self.trajectory_window) {
            None => None,
            Some((text, Some((t0, t1)))) if t0 >= 0.0 && t0 < t1 => {
                if t0 >= config.duration_s {
                    bail!(
                        "invalid --trajectory-window {text}: T0 must be before the end of the \
                         run (run.duration_s = {} s)",
                        config.duration_s
                    );
                }
                Some((t0, t1))
            }
            Some((text, _)) => bail!(
                "invalid --trajectory-window {text}: expected T0,T1 with 0 <= T0 < T1 (seconds \
                 of simulated time)"
            ),
        };
        let x_m = match pair(&self.trajectory_x) {
            None => None,
            Some((text, Some((x0, x1)))) if x0 < x1 => {
                let origin = config.road.origin_m();
                let end = origin + config.road.length_m;
                if x1 < origin || x0 > end {
                    bail!(
                        "invalid --trajectory-x {text}: the range must overlap the road, which \
                         spans {origin} to {end} m in this coordinate"
                    );
                }
                Some((x0, x1))
            }
            Some((text, _)) => bail!(
                "invalid --trajectory-x {text}: expected X0,X1 with X0 < X1 (metres, in the \
                 coordinate of the detector records' position_m)"
            ),
        };
        rec.trajectories = Some(TrajectorySpec {
            period_s,
            window_s,
            x_m,
        });
        Ok(rec)
    }
}

/// A two-number flag value: its text as given (numbers joined by commas) and the pair if it is
/// two finite numbers.
fn pair(v: &Option<Vec<f64>>) -> Option<(String, Option<(f64, f64)>)> {
    let v = v.as_ref()?;
    let text = v.iter().map(f64::to_string).collect::<Vec<_>>().join(",");
    let p = match v[..] {
        [a, b] if a.is_finite() && b.is_finite() => Some((a, b)),
        _ => None,
    };
    Some((text, p))
}

#[derive(Debug, Args)]
pub struct ViewArgs {
    /// A run's output directory holding trajectories.csv and road.json (detectors.csv,
    /// trips.csv and collisions.csv are used when present).
    #[arg(value_name = "RUN_DIR")]
    pub dir: PathBuf,

    /// The HTML file to write (default: RUN_DIR/view.html).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
}

#[derive(Debug, Args)]
pub struct TimeSpaceArgs {
    /// The trajectories.csv to draw.
    #[arg(value_name = "TRAJECTORIES_CSV")]
    pub csv: PathBuf,

    /// The lane to draw, numbered from 1 (the rightmost position) as in trajectories.csv.
    /// A vehicle's line is broken while it is in another lane.
    #[arg(
        long,
        value_name = "N",
        default_value_t = 1,
        allow_negative_numbers = true
    )]
    pub lane: i64,

    /// Output file stem: writes STEM.png and STEM.svg (default: time_space_lane<N> next to
    /// the CSV).
    #[arg(long, value_name = "STEM")]
    pub out: Option<PathBuf>,
}

impl TimeSpaceArgs {
    /// The lane, checked (lanes are numbered from 1).
    pub fn lane(&self) -> Result<u32> {
        match u32::try_from(self.lane) {
            Ok(lane) if lane >= 1 => Ok(lane),
            _ => bail!(
                "invalid --lane {}: lanes are numbered from 1 (the rightmost position), as in \
                 the trajectory records' lane column",
                self.lane
            ),
        }
    }

    /// The output stem: --out, or time_space_lane<N> next to the CSV.
    pub fn stem(&self, lane: u32) -> PathBuf {
        self.out
            .clone()
            .unwrap_or_else(|| self.csv.with_file_name(format!("time_space_lane{lane}")))
    }
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
            "--demand-scale",
            "1.1",
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
        assert_eq!(o.strategy, Some(StrategyKind::FLOW_AWARE));
        assert_eq!(
            o.set,
            vec![
                "human.buffer_s=0.2",
                "run.dt_s=0.05",
                "network.demand_scale=1.1"
            ]
        );
        assert_eq!(run.out, PathBuf::from("out/run"));
    }

    fn run_args(extra: &[&str]) -> RunArgs {
        let mut argv = vec!["platoonsim", "run", "homogeneous"];
        argv.extend_from_slice(extra);
        let Command::Run(run) = Cli::try_parse_from(argv).unwrap().command else {
            panic!()
        };
        run
    }

    #[test]
    fn recording_flags() {
        let config = Config::homogeneous(0.5, 2000.0, 600.0, 120.0, 1);
        let rec = |extra: &[&str]| run_args(extra).recording(&config);
        assert_eq!(rec(&[]).unwrap(), Recording::default());
        assert!(rec(&["--trips"]).unwrap().trips);
        let r = rec(&[
            "--trajectories",
            "0.5",
            "--trajectory-window",
            "10,20",
            "--trajectory-x=-5,100",
        ])
        .unwrap();
        assert!(!r.trips);
        assert_eq!(
            r.trajectories,
            Some(TrajectorySpec {
                period_s: 0.5,
                window_s: Some((10.0, 20.0)),
                x_m: Some((-5.0, 100.0)),
            })
        );
        for (extra, expected) in [
            (&["--trajectories", "0"][..], "invalid --trajectories 0: the sampling period (s) must be a positive multiple of the time step run.dt_s = 0.1 s"),
            (&["--trajectories", "0.15"], "invalid --trajectories 0.15:"),
            (&["--trajectories", "-1"], "invalid --trajectories -1:"),
            (&["--trajectories", "NaN"], "invalid --trajectories NaN:"),
            (
                &["--trajectories", "1", "--trajectory-window", "5,1"],
                "invalid --trajectory-window 5,1: expected T0,T1 with 0 <= T0 < T1",
            ),
            (&["--trajectories", "1", "--trajectory-window", "5"], "invalid --trajectory-window 5:"),
            (&["--trajectories", "1", "--trajectory-window", "1,2,3"], "invalid --trajectory-window 1,2,3:"),
            (&["--trajectories", "1", "--trajectory-window", "-1,2"], "invalid --trajectory-window -1,2:"),
            (
                &["--trajectories", "1", "--trajectory-window", "600,700"],
                "invalid --trajectory-window 600,700: T0 must be before the end of the run (run.duration_s = 600 s)",
            ),
            (&["--trajectories", "1", "--trajectory-x", "9,9"], "invalid --trajectory-x 9,9: expected X0,X1 with X0 < X1"),
            (
                &["--trajectories", "1", "--trajectory-x", "7000,8000"],
                "invalid --trajectory-x 7000,8000: the range must overlap the road, which spans 0 to 6500 m",
            ),
        ] {
            let err = rec(extra).unwrap_err().to_string();
            assert!(err.starts_with(expected), "{extra:?}: {err}");
        }
        // The windows need --trajectories; the numbers must be numbers.
        for bad in [
            &["run", "homogeneous", "--trajectory-window", "1,2"][..],
            &["run", "homogeneous", "--trajectory-x", "1,2"],
            &[
                "run",
                "homogeneous",
                "--trajectories",
                "1",
                "--trajectory-window",
                "a,b",
            ],
            &["run", "homogeneous", "--trajectories", "fast"],
        ] {
            let mut argv = vec!["platoonsim"];
            argv.extend_from_slice(bad);
            assert!(Cli::try_parse_from(argv).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn experiment_and_reproduce_flags() {
        let cli = Cli::try_parse_from(["platoonsim", "experiment", "flow-aware"]).unwrap();
        let Command::Experiment(e) = cli.command else {
            panic!()
        };
        assert_eq!(
            e.name,
            platoonsim_experiment::experiments::get("flow-aware")
        );
        assert_eq!((e.seeds, e.grid.jobs, e.grid.fresh), (None, None, false));
        assert_eq!(e.flow_thresholds.len(), 5);
        assert_eq!(e.tolerance, 0.5);

        let cli = Cli::try_parse_from([
            "platoonsim",
            "experiment",
            "calibrate-flow-aware",
            "--flow-thresholds",
            "1500,2000",
            "--speed-thresholds",
            "0",
            "--tolerance",
            "1",
        ])
        .unwrap();
        let Command::Experiment(e) = cli.command else {
            panic!()
        };
        assert_eq!(
            e.name,
            platoonsim_experiment::experiments::get("calibrate-flow-aware")
        );
        assert_eq!(e.flow_thresholds, [1500.0, 2000.0]);
        assert_eq!(e.speed_thresholds, [0.0]);
        assert_eq!(e.tolerance, 1.0);
        assert_eq!(e.grid.out, PathBuf::from("out"));
        // Not given: the defaults (3600 s, 1200 s) are applied by check_experiment_duration.
        assert_eq!((e.duration, e.warmup), (None, None));
        assert_eq!(
            crate::messages::check_experiment_duration(e.name, e.duration, e.warmup),
            Ok((3600.0, 1200.0))
        );

        let cli = Cli::try_parse_from([
            "platoonsim",
            "-q",
            "reproduce",
            "--quick",
            "--out",
            "o",
            "--jobs",
            "1",
            "--seeds",
            "4",
        ])
        .unwrap();
        assert!(cli.quiet);
        let Command::Reproduce(r) = cli.command else {
            panic!()
        };
        assert!(r.quick);
        assert_eq!((r.seeds, r.grid.jobs), (Some(4), Some(1)));
        assert_eq!(r.grid.out, PathBuf::from("o"));

        let cli = Cli::try_parse_from([
            "platoonsim",
            "experiment",
            "sr99-demand",
            "--penetrations",
            "0,0.4",
            "--scales",
            "1,1.1",
            "--bottleneck-speed",
            "50",
            "--write-table",
        ])
        .unwrap();
        let Command::Experiment(e) = cli.command else {
            panic!()
        };
        assert_eq!(
            e.name,
            platoonsim_experiment::experiments::get("sr99-demand")
        );
        assert_eq!(e.network.penetrations, [0.0, 0.4]);
        assert_eq!(e.network.scales, [1.0, 1.1]);
        assert_eq!(e.network.bottleneck_speed, 50.0);
        assert_eq!(e.network.bottleneck_minutes, 30.0);
        assert_eq!(e.network.write_table, Some(None));
        let cli = Cli::try_parse_from(["platoonsim", "experiment", "sr99"]).unwrap();
        let Command::Experiment(e) = cli.command else {
            panic!()
        };
        assert_eq!(e.network.penetrations.len(), 6);
        assert_eq!(e.network.scales.len(), 11);
        assert_eq!(
            (e.network.write_table, e.network.demand_scale),
            (None, None)
        );
        assert!(Cli::try_parse_from([
            "platoonsim",
            "experiment",
            "sr99",
            "--demand-scale",
            "1.1",
            "--demand-scale-table",
            "t.toml"
        ])
        .is_err());
        assert!(Cli::try_parse_from(["platoonsim", "experiment", "table9"]).is_err());
        assert!(
            Cli::try_parse_from(["platoonsim", "experiment", "capacity", "--seeds", "0"]).is_err()
        );
        assert!(Cli::try_parse_from(["platoonsim", "reproduce", "--jobs", "0"]).is_err());
    }
}
