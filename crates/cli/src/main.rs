//! `platoonsim`: the command line. Commands live in [`commands`], one module each; typed
//! errors from the libraries become `anyhow` errors here and are printed once, with their
//! causes, by `main`.
//!
//! Exit codes: 0 success; 1 an error (printed as `error: …`); 2 a usage error (from clap);
//! [`EXIT_COLLISIONS`] a `run` whose simulation had collisions (unless `--allow-collisions`)
//! or a `sweep` with a run that had;
//! [`EXIT_BROKEN_PIPE`] standard output was closed by its reader (`| head`), quietly.
// The doc comments of the clap structs are the command-line help, written for the terminal:
// `<N>`, `[[0.6,1.0]]` and the like are meant literally there, not as HTML or links.
#![allow(rustdoc::invalid_html_tags, rustdoc::broken_intra_doc_links)]

// First, so that its `outln!` is in scope in the modules below.
#[macro_use]
mod stdout;
mod args;
mod commands;
mod messages;
mod out_lock;
mod output;
mod progress;
mod tables;

use clap::Parser;
use std::io::IsTerminal;
use std::process::ExitCode;

/// `run`: the simulation had at least one collision (the files are written all the same).
pub const EXIT_COLLISIONS: u8 = 3;
/// Standard output was closed before everything was written: 128 + SIGPIPE, what a shell
/// reports for a program killed by the signal, so `set -o pipefail` scripts see a failure.
pub const EXIT_BROKEN_PIPE: u8 = 141;

fn main() -> ExitCode {
    let cli = match args::Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage(e),
    };
    match commands::dispatch(cli) {
        Ok(code) => code,
        Err(e) => match stdout::find(&e) {
            Some(w) if w.is_broken_pipe() => ExitCode::from(EXIT_BROKEN_PIPE),
            _ => {
                errln!("error: {e:#}");
                ExitCode::FAILURE
            }
        },
    }
}

/// A parse that ends early: help and version go to standard output like every command's
/// output, so a closed pipe (`--help | true`) exits with [`EXIT_BROKEN_PIPE`] as they do; a
/// usage error is clap's (exit 2). On a terminal clap prints them itself, in colour.
fn usage(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    let to_stdout = matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion);
    if !to_stdout || std::io::stdout().is_terminal() {
        e.exit();
    }
    match stdout::print(&e.render().to_string()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(w) if w.is_broken_pipe() => ExitCode::from(EXIT_BROKEN_PIPE),
        Err(w) => {
            errln!("error: {w}");
            ExitCode::FAILURE
        }
    }
}
