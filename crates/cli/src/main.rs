//! `platoonsim`: the command line. Commands live in [`commands`], one module each; typed
//! errors from the libraries become `anyhow` errors here and are printed once, with their
//! causes, by `main`.

mod args;
mod atomic;
mod commands;
mod output;
mod progress;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = args::Cli::parse();
    match commands::dispatch(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
