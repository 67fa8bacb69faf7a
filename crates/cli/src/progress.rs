//! Progress bars on stderr, fed by the engine's [`platoonsim_sim::Progress`] callback.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;

/// Whether to draw progress: not with `--quiet`, and only when stderr is a terminal.
pub fn wanted(quiet: bool) -> bool {
    !quiet && std::io::stderr().is_terminal()
}

/// Whether to print progress lines instead of a bar: not with `--quiet`, and only when
/// stderr is not a terminal (a log file, a scheduler's output).
pub fn lines_wanted(quiet: bool) -> bool {
    !quiet && !std::io::stderr().is_terminal()
}

/// A bar counting simulated seconds; hidden (drawing nothing) unless `show`.
pub fn sim_bar(total_s: f64, show: bool, label: &str) -> ProgressBar {
    if !show {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(total_s.max(0.0).ceil() as u64);
    let style = ProgressStyle::with_template(
        "{prefix} [{elapsed_precise}] {bar:40.cyan/blue} {pos}/{len} s simulated (eta {eta})",
    )
    .unwrap_or_else(|_| ProgressStyle::default_bar())
    .progress_chars("=> ");
    bar.set_style(style);
    bar.set_prefix(label.to_string());
    bar
}

/// Run a simulation, drawing `bar` from the engine's progress callback.
pub fn run_with_bar(
    config: &platoonsim_sim::Config,
    bar: &ProgressBar,
) -> Result<platoonsim_sim::Output, platoonsim_sim::SimError> {
    run_recording_with_bar(config, &platoonsim_sim::Recording::default(), bar)
}

/// [`run_with_bar`] that also records what `recording` asks for.
pub fn run_recording_with_bar(
    config: &platoonsim_sim::Config,
    recording: &platoonsim_sim::Recording,
    bar: &ProgressBar,
) -> Result<platoonsim_sim::Output, platoonsim_sim::SimError> {
    if bar.is_hidden() {
        return platoonsim_sim::run_recording(config, recording, None);
    }
    let mut update = |done_s: f64, _total_s: f64| bar.set_position(done_s.max(0.0) as u64);
    let result = platoonsim_sim::run_recording(config, recording, Some(&mut update));
    bar.finish_and_clear();
    result
}
