//! The experiments' figures, drawn by `platoonsim-plot` (PNG and SVG, written atomically):
//! capacity vs penetration with 95 % bands (baseline and PD, the paper's values as markers),
//! and the Table 3 quantities vs demand (four panels, baseline and PD with 95 % bands, the
//! paper's values as markers).

use super::{capacity, find, sensitivity, Figure};
use crate::table::{Col, SummaryRow};
use platoonsim_plot::{line_chart, panels, Chart, Series, Style};
use platoonsim_runs::design::num;
use platoonsim_runs::Metric;
use platoonsim_runs::{Cell, Error};
use platoonsim_scenario::{Preset, StrategyKind};
use std::path::Path;

/// A series' mean, low and high over the given cells (NaN where a cell is missing).
pub(super) fn curve(
    rows: &[SummaryRow],
    cells: &[Option<usize>],
    metric: impl Into<Col>,
) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let metric = metric.into().name();
    let mut m = Vec::new();
    let mut lo = Vec::new();
    let mut hi = Vec::new();
    for c in cells {
        let r = c.and_then(|c| rows.iter().find(|r| r.cell == c && r.metric == *metric));
        m.push(r.map_or(f64::NAN, |r| r.stats.mean));
        lo.push(r.map_or(f64::NAN, |r| r.stats.ci_low));
        hi.push(r.map_or(f64::NAN, |r| r.stats.ci_high));
    }
    (m, lo, hi)
}

/// The paper's values of a metric over the given cells (NaN where it gives none).
fn paper(rows: &[SummaryRow], cells: &[Option<usize>], metric: Metric) -> Vec<f64> {
    let metric = metric.name();
    cells
        .iter()
        .map(|c| {
            c.and_then(|c| rows.iter().find(|r| r.cell == c && r.metric == *metric))
                .and_then(|r| r.paper)
                .map_or(f64::NAN, |p| p.value)
        })
        .collect()
}

pub(super) fn series(
    name: &str,
    x: &[f64],
    (y, lo, hi): (Vec<f64>, Vec<f64>, Vec<f64>),
    style: Style,
) -> Series {
    Series {
        name: name.into(),
        x: x.to_vec(),
        y,
        band: Some((lo, hi)),
        style,
    }
}

fn markers(name: &str, x: &[f64], y: Vec<f64>) -> Option<Series> {
    if y.iter().all(|v| !v.is_finite()) {
        return None;
    }
    Some(Series {
        name: name.into(),
        x: x.to_vec(),
        y,
        band: None,
        style: Style::Markers,
    })
}

/// The model a figure ran under, for its drawn title: a chart seen on its own (a PNG passed
/// around) must say whether it shows the paper's model or the platform's defaults.
pub(super) fn model_suffix(preset: Preset) -> &'static str {
    match preset {
        Preset::Paper => " — the paper's model",
        Preset::Platform => " — platform defaults",
    }
}

pub(super) fn plot_error(e: platoonsim_plot::PlotError) -> Error {
    Error::Other(e.to_string())
}

/// `capacity.png` / `.svg`.
pub(super) fn capacity(
    dir: &Path,
    cells: &[Cell],
    rows: &[SummaryRow],
    preset: Preset,
) -> Result<Vec<Figure>, Error> {
    let x: Vec<f64> = capacity::PENETRATIONS.iter().map(|p| 100.0 * p).collect();
    let pick = |k: StrategyKind| -> Vec<Option<usize>> {
        capacity::PENETRATIONS
            .iter()
            .map(|&p| capacity::at(cells, k, &num(p)))
            .collect()
    };
    let (base, pd, dl) = (
        pick(StrategyKind::NONE),
        pick(StrategyKind::PD),
        pick(StrategyKind::DEDICATED),
    );
    let m = Metric::MAX_SUSTAINED_FLOW;
    let mut s = vec![
        series(
            "baseline (no organization), 95 % CI",
            &x,
            curve(rows, &base, m),
            Style::Line,
        ),
        series("PD lane, 95 % CI", &x, curve(rows, &pd, m), Style::Dashed),
        series(
            "dedicated lane (ours), 95 % CI",
            &x,
            curve(rows, &dl, m),
            Style::Line,
        ),
    ];
    s.extend(markers("paper, baseline (text)", &x, paper(rows, &base, m)));
    s.extend(markers("paper, PD lane (text)", &x, paper(rows, &pd, m)));
    let chart = Chart {
        title: format!(
            "Capacity vs CAV penetration (paper Fig. 4){}",
            model_suffix(preset)
        ),
        x_label: "CAV penetration (%)".into(),
        y_label: "Capacity: highest 5-min discharge (veh/h/lane)".into(),
        series: s,
        y_range: None,
    };
    line_chart(&chart, &dir.join("capacity")).map_err(plot_error)?;
    Ok(vec![Figure {
        title: "Capacity vs CAV penetration: baseline, PD lane and dedicated lane (ours), mean and 95 % confidence band; markers: the paper's values stated in its text".into(),
        stem: "capacity".into(),
    }])
}

/// `sensitivity.png` / `.svg`: four panels.
pub(super) fn sensitivity(
    dir: &Path,
    cells: &[Cell],
    rows: &[SummaryRow],
    preset: Preset,
) -> Result<Vec<Figure>, Error> {
    let x: Vec<f64> = sensitivity::DEMANDS.to_vec();
    let pick = |k: StrategyKind| -> Vec<Option<usize>> {
        sensitivity::DEMANDS
            .iter()
            .map(|&d| {
                find(
                    cells,
                    &[("demand_vphpl", &num(d)), ("strategy", k.as_str())],
                )
            })
            .collect()
    };
    let (b, po, dl) = (
        pick(StrategyKind::NONE),
        pick(StrategyKind::PD),
        pick(StrategyKind::DEDICATED),
    );
    let panel = |metric: Metric, title: &str, y_label: &str| {
        let mut s = vec![
            series(
                "baseline (B), 95 % CI",
                &x,
                curve(rows, &b, metric),
                Style::Line,
            ),
            series(
                "PD lane (PO), 95 % CI",
                &x,
                curve(rows, &po, metric),
                Style::Dashed,
            ),
            series(
                "dedicated lane (DL, ours), 95 % CI",
                &x,
                curve(rows, &dl, metric),
                Style::Line,
            ),
        ];
        s.extend(markers("paper B", &x, paper(rows, &b, metric)));
        s.extend(markers("paper PO", &x, paper(rows, &po, metric)));
        Chart {
            title: title.into(),
            x_label: "Demand (veh/h/lane)".into(),
            y_label: y_label.into(),
            series: s,
            y_range: None,
        }
    };
    let charts = [
        panel(
            Metric::LANE_CHANGES_PER_VEHICLE,
            "Lane changes per vehicle",
            "Lane changes / vehicle",
        ),
        panel(Metric::AVG_PLATOON_LENGTH, "Average platoon length", "CAVs"),
        panel(
            Metric::PLATOONING_PROBABILITY,
            "Platooning probability P_P",
            "Probability",
        ),
        panel(Metric::DISCHARGE_FLOW, "Discharge flow", "veh/h/lane"),
    ];
    panels(
        &charts,
        2,
        &format!(
            "Platoon organization at 50 % CAV vs demand (paper Table 3){}",
            model_suffix(preset)
        ),
        &dir.join("sensitivity"),
    )
    .map_err(plot_error)?;
    Ok(vec![Figure {
        title: "Table 3 quantities vs demand: baseline (B) and PD lane (PO), mean and 95 % confidence band; markers: the paper's Table 3".into(),
        stem: "sensitivity".into(),
    }])
}
