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

    #[command(flatten)]
    pub source: super::FieldFlags,

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
