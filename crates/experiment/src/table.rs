//! The runner's tables ([`platoonsim_runs::table`]), summarized with the paper's values.

pub use platoonsim_runs::table::*;

use platoonsim_runs::{Cell, Outcome};

/// One row per cell and metric (see [`platoonsim_runs::table::summarize`]), with the paper's
/// value of `experiment` where it gives one.
pub fn summarize(experiment: &str, cells: &[Cell], outcomes: &[Outcome]) -> Vec<SummaryRow> {
    platoonsim_runs::table::summarize(cells, outcomes, |labels, metric| {
        crate::paper::lookup(experiment, labels, metric)
    })
}
