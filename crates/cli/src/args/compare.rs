//! Arguments of `platoonsim compare`.

use anyhow::{bail, Result};
use clap::Args;
use platoonsim_scenario::clock::parse_clock;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct CompareArgs {
    /// Run directories written by `platoonsim run` (detectors.csv and scenario.toml, whose
    /// run.clock_start says when the run starts). Several are replications of one scenario
    /// and are averaged per station and interval.
    #[arg(value_name = "RUN_DIR", required = true)]
    pub runs: Vec<PathBuf>,

    /// Field data: PeMS station_5min files (plain or .gz) or tidy CSV files
    /// (station,time,flow_vph,speed_kmh,occupancy), read together. Takes every following
    /// value up to the next flag.
    #[arg(long, value_name = "FILE", required = true, num_args = 1..)]
    pub field: Vec<PathBuf>,

    /// PeMS station metadata: adds each HOV station to the mainline station at its postmile
    /// (the simulated corridor runs the HOV lane as an ordinary lane) and, with --origin-pm,
    /// places the stations by postmile.
    #[arg(long, value_name = "META.txt")]
    pub meta: Option<PathBuf>,

    /// With --meta: the absolute postmile of the corridor's x = 0, so that a station sits at
    /// x = (Abs_PM - PM) x 1609.344 m (SR-99: 287.230).
    #[arg(
        long = "origin-pm",
        value_name = "PM",
        requires = "meta",
        allow_negative_numbers = true
    )]
    pub origin_pm: Option<f64>,

    /// Instead of --origin-pm: a CSV station,x_m,kind[,lanes,name] placing the field
    /// stations (kind ML, OR, FR, HV or FF).
    #[arg(long, value_name = "TABLE.csv", conflicts_with = "origin_pm")]
    pub stations: Option<PathBuf>,

    /// Output directory (default: RUN_DIR/compare of the first run directory).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// Start of the period compared, clock time HH:MM or HH:MM:SS (default: the run's
    /// clock start).
    #[arg(long, value_name = "HH:MM")]
    pub from: Option<String>,

    /// End of the period compared, clock time HH:MM or HH:MM:SS (default: the end of the
    /// run).
    #[arg(long, value_name = "HH:MM")]
    pub to: Option<String>,
}

impl CompareArgs {
    /// The output directory.
    pub fn out_dir(&self) -> PathBuf {
        self.out
            .clone()
            .unwrap_or_else(|| self.runs[0].join("compare"))
    }

    /// The period compared: --from and --to (seconds after midnight), each defaulting to the
    /// simulated period's end `span`. Errors name the flag and the value.
    pub fn window(&self, span: (u32, u32)) -> Result<(u32, u32)> {
        let parse = |flag: &str, v: &Option<String>, default: u32| -> Result<u32> {
            match v {
                None => Ok(default),
                Some(text) => parse_clock(text).ok_or_else(|| {
                    anyhow::anyhow!(
                        "invalid --{flag} {text}: expected a clock time HH:MM or HH:MM:SS \
                         (00:00 to 23:59:59)"
                    )
                }),
            }
        };
        let from = parse("from", &self.from, span.0)?;
        let to = parse("to", &self.to, span.1)?;
        if from >= to {
            bail!(
                "invalid period --from {} --to {}: the start must be before the end",
                self.from.as_deref().unwrap_or("(run start)"),
                self.to.as_deref().unwrap_or("(run end)")
            );
        }
        Ok((from, to))
    }
}
