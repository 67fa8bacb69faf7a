//! One module per command. To come (issue 3): `experiment` (a grid of runs in parallel, with
//! resumable atomic result files) and `reproduce` (every experiment, with a report).

pub mod bench;
pub mod run;
pub mod scenarios;
pub mod show;

use crate::args::{Cli, Command};
use anyhow::Result;

/// Run the chosen command.
pub fn dispatch(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Run(args) => run::run(&args, cli.quiet),
        Command::Bench(args) => bench::bench(&args, cli.quiet),
        Command::Scenarios => scenarios::scenarios(),
        Command::Show(args) => show::show(&args),
    }
}
