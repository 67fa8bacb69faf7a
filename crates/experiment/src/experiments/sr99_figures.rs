//! The figures of `sr99` (PNG and SVG, through `platoonsim-plot`):
//!
//! * `sr99_contours`: speed contours, time × mainline detector index (1 = most upstream), of
//!   the baseline, PD and Flow-Aware PD at 40 % CAV (first seed), one colour scale (paper
//!   Fig. 6);
//! * `sr99_lanes`: at the detector upstream of the second Florin Rd on-ramp (`OR11-up`), per
//!   lane, the CAV flow ratio (top) and the speed (bottom) over time, baseline / PD /
//!   Flow-Aware PD (paper Fig. 7);
//! * `sr99_bars`: lane changes per vehicle, L̄ and network discharge vs penetration, bars for
//!   the three strategies with 95 % whiskers; a second row with the paper's Table 4 values
//!   (paper Fig. 8).

use super::figures::model_suffix;
use super::sr99::{self, Data, FIGURE_PENETRATION};
use super::{find, Extra, Figure};
use crate::corridor::{self, FLORIN_DETECTOR};
use crate::paper;
use crate::table::SummaryRow;
use platoonsim_plot::{
    bar_panels, heatmap_panels, panels, Bars, Chart, Heatmap, PlotError, Series, Style,
};
use platoonsim_runs::design::num;
use platoonsim_runs::Metric;
use platoonsim_runs::{Cell, Error, Labels};
use platoonsim_scenario::Preset;
use std::path::Path;

fn plot_error(e: PlotError) -> Error {
    Error::Other(e.to_string())
}

/// Colour range of the contours (km/h).
pub const SPEED_RANGE: (f64, f64) = (0.0, 120.0);

fn strategy_name(cells: &[Cell], c: usize) -> &'static str {
    sr99::strategy_of(&cells[c]).map_or("?", sr99::strategy_name)
}

pub(super) fn all(
    dir: &Path,
    cells: &[Cell],
    rows: &[SummaryRow],
    extra: &Extra,
    preset: Preset,
) -> Result<Vec<Figure>, Error> {
    let model = model_suffix(preset);
    let mut out = Vec::new();
    if let Extra::Sr99(d) = extra {
        if !d.figure_runs.is_empty() {
            out.push(contours(dir, cells, d, model)?);
            out.push(lanes(dir, cells, d, model)?);
        }
    }
    out.push(bars(dir, cells, rows, model)?);
    Ok(out)
}

/// The contour panels' data: one heat map per figure run.
pub fn contour_maps(cells: &[Cell], d: &Data) -> Vec<Heatmap> {
    d.figure_runs
        .iter()
        .map(|(c, recs)| {
            let k = corridor::contour(recs);
            Heatmap {
                title: strategy_name(cells, *c).into(),
                x_label: "Time from 05:00 (min)".into(),
                y_label: "Mainline detector (1 = most upstream)".into(),
                x: k.times_min.clone(),
                y: (1..=k.detectors.len()).map(|j| j as f64).collect(),
                z: k.speed_kmh,
                z_label: "Speed (km/h)".into(),
                z_range: SPEED_RANGE,
            }
        })
        .collect()
}

fn contours(dir: &Path, cells: &[Cell], d: &Data, model: &str) -> Result<Figure, Error> {
    let maps = contour_maps(cells, d);
    let title = format!(
        "SR-99 speed contours, {} % CAV (seed {}){model}",
        num(100.0 * FIGURE_PENETRATION),
        d.figure_seed
    );
    heatmap_panels(&maps, 3, &title, &dir.join("sr99_contours")).map_err(plot_error)?;
    let index = d.figure_runs.first().and_then(|(_, recs)| {
        corridor::mainline_detectors(recs)
            .iter()
            .position(|(n, _)| n == FLORIN_DETECTOR)
            .map(|i| i + 1)
    });
    Ok(Figure {
        title: format!(
            "Speed contours at {} % CAV, seed {} (paper Fig. 6): baseline, PD lane, Flow-Aware \
             PD lane; 5-min cross-section mean speed at each mainline detector, index 1 = most \
             upstream (Elk Grove Blvd); `{FLORIN_DETECTOR}` (upstream of the second Florin Rd \
             on-ramp) is index {}; grey: no vehicle crossed",
            num(100.0 * FIGURE_PENETRATION),
            d.figure_seed,
            index.map_or("?".into(), |i| i.to_string())
        ),
        stem: "sr99_contours".into(),
    })
}

/// A lane's legend name: lane 1 is the rightmost, the last the leftmost (the PD lane).
fn lane_name(lane: &str, last: &str) -> String {
    if lane == last {
        format!("lane {lane} (leftmost, PD lane)")
    } else if lane == "1" {
        "lane 1 (rightmost)".into()
    } else {
        format!("lane {lane}")
    }
}

/// The lane figure's charts: CAV flow ratio per strategy, then speed per strategy.
pub fn lane_charts(cells: &[Cell], d: &Data) -> Vec<Chart> {
    let series: Vec<(String, Vec<corridor::LaneSeries>)> = d
        .figure_runs
        .iter()
        .map(|(c, recs)| {
            (
                strategy_name(cells, *c).to_string(),
                corridor::lane_series(recs, FLORIN_DETECTOR),
            )
        })
        .collect();
    let chart = |name: &str, lanes: &[corridor::LaneSeries], ratio: bool| {
        let last = lanes.last().map_or("", |l| l.lane.as_str());
        Chart {
            title: name.into(),
            x_label: "Time from 05:00 (min)".into(),
            y_label: if ratio {
                "CAV flow / total flow".into()
            } else {
                "Speed (km/h)".into()
            },
            series: lanes
                .iter()
                .map(|l| Series {
                    name: lane_name(&l.lane, last),
                    x: l.times_min.clone(),
                    y: if ratio {
                        l.cav_ratio.clone()
                    } else {
                        l.speed_kmh.clone()
                    },
                    band: None,
                    style: if l.lane == last {
                        Style::Dashed
                    } else {
                        Style::Line
                    },
                })
                .collect(),
            y_range: Some(if ratio { (0.0, 1.0) } else { SPEED_RANGE }),
        }
    };
    let mut charts: Vec<Chart> = series.iter().map(|(n, l)| chart(n, l, true)).collect();
    charts.extend(series.iter().map(|(n, l)| chart(n, l, false)));
    charts
}

fn lanes(dir: &Path, cells: &[Cell], d: &Data, model: &str) -> Result<Figure, Error> {
    let charts = lane_charts(cells, d);
    let cols = d.figure_runs.len().max(1);
    let title = format!(
        "SR-99 at {FLORIN_DETECTOR}, {} % CAV: CAV flow ratio and speed per lane{model}",
        num(100.0 * FIGURE_PENETRATION)
    );
    panels(&charts, cols, &title, &dir.join("sr99_lanes")).map_err(plot_error)?;
    Ok(Figure {
        title: format!(
            "Lane by lane at `{FLORIN_DETECTOR}` (50 m upstream of the second Florin Rd on-ramp), \
             {} % CAV, seed {} (paper Fig. 7): top, the CAV flow ratio (CAVs / all vehicles per \
             5-min interval); bottom, the speed; left to right baseline, PD lane, Flow-Aware PD \
             lane; lane 1 is the rightmost, the dashed line the leftmost (PD) lane",
            num(100.0 * FIGURE_PENETRATION),
            d.figure_seed
        ),
        stem: "sr99_lanes".into(),
    })
}

/// The paper Fig. 8 panels: ours (with 95 % whiskers), then the paper's Table 4 values.
pub fn bar_charts(cells: &[Cell], rows: &[SummaryRow]) -> Vec<Bars> {
    let mut pens: Vec<f64> = Vec::new();
    for c in cells {
        if let Some(p) = c.labels.get("penetration").and_then(|p| p.parse().ok()) {
            if !pens.contains(&p) {
                pens.push(p);
            }
        }
    }
    let groups: Vec<String> = pens
        .iter()
        .map(|p| format!("{} %", num(100.0 * p)))
        .collect();
    let metrics = [
        (
            Metric::LANE_CHANGES_PER_VEHICLE,
            "Lane changes per vehicle",
            "1/veh",
        ),
        (
            Metric::AVG_PLATOON_LENGTH,
            "Average platoon length L",
            "CAVs",
        ),
        (Metric::NETWORK_DISCHARGE, "Network discharge", "veh/h"),
    ];
    let mut ours = Vec::new();
    let mut theirs = Vec::new();
    for (metric, title, unit) in metrics {
        let name = metric.name();
        let mut s_ours = Vec::new();
        let mut s_paper = Vec::new();
        for k in sr99::STRATEGIES {
            let ks = k.as_str();
            let mut mean = Vec::new();
            let mut err = Vec::new();
            let mut pap = Vec::new();
            for &p in &pens {
                let ps = num(p);
                let r = find(cells, &[("penetration", &ps), ("strategy", ks)])
                    .and_then(|c| rows.iter().find(|r| r.cell == c && r.metric == *name));
                let skip = metric == Metric::AVG_PLATOON_LENGTH && p == 0.0;
                mean.push(r.filter(|_| !skip).map_or(f64::NAN, |r| r.stats.mean));
                err.push(r.map_or(f64::NAN, |r| r.stats.half_width()));
                let labels = Labels::new().with("penetration", ps).with("strategy", ks);
                pap.push(paper::lookup("sr99", &labels, &name).map_or(f64::NAN, |v| v.value));
            }
            let name = sr99::strategy_name(k).to_string();
            s_ours.push((name.clone(), mean, Some(err)));
            s_paper.push((name, pap, None));
        }
        // One y range for ours and the paper's panel of a quantity: both cover every bar of
        // both (ours with its whiskers).
        let mut shared: Vec<f64> = Vec::new();
        for (_, v, e) in &s_ours {
            for (g, x) in v.iter().enumerate() {
                let h = e.as_ref().and_then(|e| e.get(g)).copied().unwrap_or(0.0);
                let h = if h.is_finite() { h } else { 0.0 };
                shared.extend([x - h, x + h]);
            }
        }
        shared.extend(s_paper.iter().flat_map(|(_, v, _)| v.iter().copied()));
        shared.retain(|v| v.is_finite());
        ours.push(Bars {
            title: format!("{title}: ours"),
            y_label: unit.into(),
            groups: groups.clone(),
            series: s_ours,
            y_include: shared.clone(),
        });
        theirs.push(Bars {
            title: format!("{title}: paper"),
            y_label: unit.into(),
            groups: groups.clone(),
            series: s_paper,
            y_include: shared,
        });
    }
    ours.extend(theirs);
    ours
}

fn bars(dir: &Path, cells: &[Cell], rows: &[SummaryRow], model: &str) -> Result<Figure, Error> {
    let charts = bar_charts(cells, rows);
    bar_panels(
        &charts,
        3,
        &format!(
            "SR-99: lane changes, platoon length and network discharge vs CAV penetration{model}"
        ),
        &dir.join("sr99_bars"),
    )
    .map_err(plot_error)?;
    Ok(Figure {
        title: "Lane changes per vehicle, average platoon length L̄ and network discharge vs CAV \
                penetration (paper Fig. 8): top, ours (mean, whiskers: 95 % confidence \
                interval); bottom, the paper's Table 4"
            .into(),
        stem: "sr99_bars".into(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table;
    use platoonsim_runs::record::Fields;
    use platoonsim_runs::runner::Outcome;
    use platoonsim_sim::{Config, DetectorRecord};

    fn rec(det: &str, x: f64, lane: &str, t: f64, cavs: u64, speed: f64) -> DetectorRecord {
        DetectorRecord {
            detector: det.into(),
            kind: "mainline".into(),
            position_m: x,
            lane: lane.into(),
            interval_start_s: t,
            interval_s: 300.0,
            count: 10,
            cav_count: cavs,
            flow_vph: 120.0,
            speed_kmh: Some(speed),
            occupancy: 0.1,
        }
    }

    /// Three 40 % cells and a 0 % baseline; synthetic records at two detectors, two lanes.
    fn synthetic() -> (Vec<Cell>, Data, Vec<Outcome>) {
        let cfg = Config::homogeneous(0.4, 1000.0, 60.0, 0.0, 1);
        let mut cells = vec![Cell {
            labels: Labels::new()
                .with("penetration", "0")
                .with("strategy", "none"),
            config: cfg.clone(),
        }];
        let mut data = Data {
            figure_runs: Vec::new(),
            figure_seed: 1,
        };
        for (i, k) in ["none", "pd", "flow-aware"].iter().enumerate() {
            cells.push(Cell {
                labels: Labels::new()
                    .with("penetration", "0.4")
                    .with("strategy", *k),
                config: cfg.clone(),
            });
            let mut recs = Vec::new();
            for t in 0..6 {
                let t = 300.0 * t as f64;
                for (det, x) in [("OR11-up", 11197.0), ("OR1-up", -50.0)] {
                    recs.push(rec(det, x, "1", t, 2 + i as u64, 90.0));
                    recs.push(rec(det, x, "2", t, 8 - i as u64, 30.0));
                    recs.push(rec(det, x, "all", t, 5, 60.0 + t / 100.0));
                }
            }
            data.figure_runs.push((cells.len() - 1, recs));
        }
        let mut outcomes = Vec::new();
        for c in 0..cells.len() {
            for seed in 1..=2 {
                outcomes.push(Outcome {
                    cell: c,
                    seed,
                    key: String::new(),
                    fields: Fields(vec![
                        (
                            "network_discharge_vph".into(),
                            9000.0 + c as f64 + seed as f64,
                        ),
                        ("lane_changes_per_vehicle".into(), 2.0 + c as f64),
                        ("avg_platoon_length".into(), 3.0),
                    ]),
                    computed: true,
                });
            }
        }
        (cells, data, outcomes)
    }

    #[test]
    fn figure_data_from_synthetic_records() {
        let (cells, data, outcomes) = synthetic();
        let maps = contour_maps(&cells, &data);
        assert_eq!(maps.len(), 3);
        assert_eq!(maps[1].title, "PD");
        // Detectors sorted by position: OR1-up (index 1) before OR11-up (index 2).
        assert_eq!(maps[0].y, [1.0, 2.0]);
        assert_eq!(maps[0].x, [2.5, 7.5, 12.5, 17.5, 22.5, 27.5]);
        assert_eq!(maps[0].z[1], [63.0, 63.0]);

        let charts = lane_charts(&cells, &data);
        assert_eq!(charts.len(), 6);
        let names: Vec<&str> = charts[0].series.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["lane 1 (rightmost)", "lane 2 (leftmost, PD lane)"]);
        assert_eq!(charts[0].series[0].y[0], 0.2);
        assert_eq!(charts[1].series[1].y[0], 0.7);
        assert_eq!(charts[3].series[1].y[0], 30.0);
        assert_eq!(charts[3].series[1].style, Style::Dashed);
        assert_eq!(charts[2].y_range, Some((0.0, 1.0)));

        let rows = table::summarize("sr99", &cells, &outcomes);
        let bars = bar_charts(&cells, &rows);
        assert_eq!(bars.len(), 6);
        assert_eq!(bars[0].groups, ["0 %", "40 %"]);
        // Ours: the baseline's lane changes at 0 % and 40 %; PD only at 40 %.
        assert_eq!(bars[0].series[0].1, [2.0, 3.0]);
        assert!(bars[0].series[1].1[0].is_nan());
        // L̄ has no value at 0 %.
        assert!(bars[1].series[0].1[0].is_nan());
        // The paper's row: Table 4.
        assert_eq!(bars[5].series[0].1, [10675.8, 11739.8]);
        assert_eq!(bars[3].series[1].1[1], 4.90);
        assert!(bars[3].series[0].2.is_none());

        let dir = std::env::temp_dir().join(format!("platoonsim-sr99fig-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let figs = all(&dir, &cells, &rows, &Extra::Sr99(data), Preset::Paper).unwrap();
        let stems: Vec<&str> = figs.iter().map(|f| f.stem.as_str()).collect();
        assert_eq!(stems, ["sr99_contours", "sr99_lanes", "sr99_bars"]);
        assert!(figs[0].title.contains("is index 2"));
        for stem in stems {
            for ext in ["png", "svg"] {
                let f = dir.join(format!("{stem}.{ext}"));
                assert!(std::fs::metadata(&f).unwrap().len() > 1000, "{f:?}");
            }
            // Each drawn title names the model.
            let svg = std::fs::read_to_string(dir.join(format!("{stem}.svg"))).unwrap();
            assert!(
                svg.contains("the paper&apos;s model") || svg.contains("the paper's model"),
                "{stem}"
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
