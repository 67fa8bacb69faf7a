//! One module per command.

pub mod bench;
pub mod calibrate;
pub mod compare;
pub mod experiment;
pub mod import;
pub mod reproduce;
pub mod run;
pub mod scenarios;
pub mod show;
pub mod sweep;
pub mod time_space;
pub mod view;

use crate::args::{Cli, Command};
use anyhow::Result;
use std::process::ExitCode;

/// Run the chosen command; the exit code of a command that succeeded (`run` has its own for
/// collisions).
pub fn dispatch(cli: Cli) -> Result<ExitCode> {
    let done = match cli.command {
        Command::Run(args) => return run::run(&args, cli.quiet),
        Command::Bench(args) => bench::bench(&args, cli.quiet),
        Command::Scenarios => scenarios::scenarios(),
        Command::Show(args) => show::show(&args),
        Command::Experiment(args) => experiment::experiment(&args, cli.quiet),
        Command::Reproduce(args) => reproduce::reproduce(&args, cli.quiet),
        Command::TimeSpace(args) => time_space::time_space(&args),
        Command::View(args) => view::view(&args),
        Command::Sweep(args) => return sweep::sweep(&args, cli.quiet),
        Command::Compare(args) => compare::compare(&args),
        Command::Calibrate(args) => calibrate::calibrate(&args, cli.quiet),
        Command::Import(args) => import::import(&args),
    };
    done.map(|()| ExitCode::SUCCESS)
}
