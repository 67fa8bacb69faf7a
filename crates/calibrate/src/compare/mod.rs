//! Simulated detector data against field data (`platoonsim compare`; docs/compare.md).
//!
//! * [`runs`]: a run directory's cross-section detector rows as [`Obs`] at clock time, its
//!   detectors as [`Placed`] stations; replications averaged ([`crate::field_obs`]).
//! * [`evaluate`]: the pure part, also the calibration's objective ingredient: the window,
//!   the [`Fit`] (GEH, speed RMSE/RMSNE/correlation), the bottlenecks on both sides and their
//!   pairing, the criteria. No files, no figures.
//! * [`contours`]: simulated | field | difference speed contours (PNG + SVG).
//! * [`files`]: `compare.md`, `compare.html`, `fit.json` and the figure, atomically.
//!
//! Only stations present on both sides are compared. Bottlenecks are identified on the
//! compared mainline stations only, so that both sides see the same station spacing: the
//! simulated side at its detectors' positions, the field side at the stations' placement
//! (postmile or table), or at the detector of the same name where the placement has none.

pub mod contours;
pub mod files;
pub mod runs;

use platoonsim_field::bottleneck::{self, Bottleneck, MatchParams, Pair};
use platoonsim_field::criteria::{self, Criterion};
use platoonsim_field::fit::{self, Fit};
use platoonsim_field::{Obs, Placed, StationKind};
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;

/// What a comparison may be told besides its data.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Options {
    /// The period compared `[from, to)`, s after midnight; `None`: the simulated period.
    pub window: Option<(u32, u32)>,
    pub bottleneck: bottleneck::Params,
    pub matching: MatchParams,
}

/// Everything measured by one comparison.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// The period compared, s after midnight.
    pub window: (u32, u32),
    pub fit: Fit,
    pub sim_bottlenecks: Vec<Bottleneck>,
    pub field_bottlenecks: Vec<Bottleneck>,
    /// Field bottlenecks paired with simulated ones.
    pub bottlenecks: Vec<Pair>,
    pub criteria: Vec<Criterion>,
}

impl Evaluation {
    /// The fit's scalar to minimize ([`Fit::objective`]); `None` without matched data.
    pub fn objective(&self) -> Option<f64> {
        self.fit.objective()
    }

    /// Whether every criterion holds.
    pub fn passes(&self) -> bool {
        criteria::all_pass(&self.criteria)
    }
}

/// The simulated period: the earliest start to the latest end of `sim` (`None` if empty).
pub fn sim_span(sim: &[Obs]) -> Option<(u32, u32)> {
    let from = sim.iter().map(|o| o.start_s).min()?;
    let to = sim.iter().map(|o| o.start_s + o.interval_s).max()?;
    Some((from, to))
}

/// The mainline stations both sides compare, placed on each side: (simulated, field).
pub fn bottleneck_lines(
    compared: &[String],
    sim_places: &[Placed],
    field_places: &[Placed],
) -> (Vec<Placed>, Vec<Placed>) {
    let names: BTreeSet<&str> = compared.iter().map(String::as_str).collect();
    let (mut sim, mut field) = (Vec::new(), Vec::new());
    for s in sim_places
        .iter()
        .filter(|s| names.contains(s.station.as_str()))
    {
        let f = field_places.iter().find(|f| f.station == s.station);
        let mainline =
            s.kind == StationKind::Mainline && f.is_none_or(|f| f.kind == StationKind::Mainline);
        if mainline {
            sim.push(s.clone());
            field.push(f.cloned().unwrap_or_else(|| s.clone()));
        }
    }
    (sim, field)
}

/// Compare `sim` with `field` observations (module doc). `sim_places`: the simulated
/// detectors (position, kind); `field_places`: the field stations' placement (may be empty).
pub fn evaluate(
    sim: &[Obs],
    field: &[Obs],
    sim_places: &[Placed],
    field_places: &[Placed],
    opts: &Options,
) -> Evaluation {
    let window = opts.window.or_else(|| sim_span(sim)).unwrap_or((0, 0));
    let sim = fit::within(sim, window.0, window.1);
    let field = fit::within(field, window.0, window.1);
    let fit = fit::fit(&sim, &field);
    let (sim_line, field_line) = bottleneck_lines(&fit.stations_compared, sim_places, field_places);
    let sim_bottlenecks = bottleneck::identify(&sim, &sim_line, &opts.bottleneck);
    let field_bottlenecks = bottleneck::identify(&field, &field_line, &opts.bottleneck);
    let bottlenecks = bottleneck::compare(&sim_bottlenecks, &field_bottlenecks, &opts.matching);
    let criteria = criteria::judge(&fit, &bottlenecks, &opts.matching);
    Evaluation {
        window,
        fit,
        sim_bottlenecks,
        field_bottlenecks,
        bottlenecks,
        criteria,
    }
}

#[cfg(test)]
mod tests;
