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
//! Only stations present on both sides are compared, in two groups: the **mainline**
//! stations, on which the criteria are judged, and the **ramp counters** (on- and off-ramp
//! stations, freeway connectors), whose flows are the demand's inputs: their fit is measured
//! and shown apart ([`Evaluation::ramp_fit`], [`Evaluation::ramp_criteria`]) but never
//! counted in the verdict, since a model fed the ramp counts fits them by construction.
//! Bottlenecks are identified on the
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
    /// The mainline stations' fit (HOV stations folded into their mainline station by the
    /// field reader); the criteria judge it.
    pub fit: Fit,
    /// The ramp counters' fit: inputs of the demand, shown, not judged.
    pub ramp_fit: Fit,
    pub sim_bottlenecks: Vec<Bottleneck>,
    pub field_bottlenecks: Vec<Bottleneck>,
    /// Field bottlenecks paired with simulated ones.
    pub bottlenecks: Vec<Pair>,
    /// The criteria, judged on the mainline stations: the verdict.
    pub criteria: Vec<Criterion>,
    /// The flow criteria measured on the ramp counters, for information only.
    pub ramp_criteria: Vec<Criterion>,
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

/// Is `kind` a ramp counter's (on-ramp, off-ramp, freeway connector)?
fn is_ramp(kind: &StationKind) -> bool {
    matches!(
        kind,
        StationKind::OnRamp | StationKind::OffRamp | StationKind::FreewayConnector
    )
}

/// The stations that count a ramp, by the simulated detector's kind or the field
/// placement's: their observations are the demand's inputs, not a test of the model.
pub fn ramp_stations(sim_places: &[Placed], field_places: &[Placed]) -> BTreeSet<String> {
    sim_places
        .iter()
        .chain(field_places)
        .filter(|p| is_ramp(&p.kind))
        .map(|p| p.station.clone())
        .collect()
}

/// `obs` split into (mainline, ramps) by [`ramp_stations`].
fn split(obs: &[Obs], ramps: &BTreeSet<String>) -> (Vec<Obs>, Vec<Obs>) {
    obs.iter()
        .cloned()
        .partition(|o| !ramps.contains(&o.station))
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
    let ramps = ramp_stations(sim_places, field_places);
    let (sim, sim_ramps) = split(&fit::within(sim, window.0, window.1), &ramps);
    let (field, field_ramps) = split(&fit::within(field, window.0, window.1), &ramps);
    let fit = fit::fit(&sim, &field);
    let ramp_fit = fit::fit(&sim_ramps, &field_ramps);
    let (sim_line, field_line) = bottleneck_lines(&fit.stations_compared, sim_places, field_places);
    let sim_bottlenecks = bottleneck::identify(&sim, &sim_line, &opts.bottleneck);
    let field_bottlenecks = bottleneck::identify(&field, &field_line, &opts.bottleneck);
    let bottlenecks = bottleneck::compare(&sim_bottlenecks, &field_bottlenecks, &opts.matching);
    let criteria = criteria::judge(&fit, &bottlenecks, &opts.matching);
    let ramp_criteria = criteria::judge_flows(&ramp_fit);
    Evaluation {
        window,
        fit,
        ramp_fit,
        sim_bottlenecks,
        field_bottlenecks,
        bottlenecks,
        criteria,
        ramp_criteria,
    }
}

#[cfg(test)]
mod tests;
