//! One module per command.

pub mod bench;
pub mod experiment;
pub mod reproduce;
pub mod run;
pub mod scenarios;
pub mod show;
pub mod time_space;

use crate::args::{Cli, Command};
use anyhow::Result;

/// Run the chosen command.
pub fn dispatch(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Run(args) => run::run(&args, cli.quiet),
        Command::Bench(args) => bench::bench(&args, cli.quiet),
        Command::Scenarios => scenarios::scenarios(),
        Command::Show(args) => show::show(&args),
        Command::Experiment(args) => experiment::experiment(&args, cli.quiet),
        Command::Reproduce(args) => reproduce::reproduce(&args, cli.quiet),
        Command::TimeSpace(args) => time_space::time_space(&args),
    }
}
