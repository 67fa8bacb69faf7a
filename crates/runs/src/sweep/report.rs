//! `summary.md` and the figures of a sweep: for each shown metric, the mean against the
//! first axis with its 95 % band, one line per level of the other axes (a line chart when
//! the first axis is numeric, grouped bars with the interval as error bars otherwise).

use super::collect::{reference_text, Row};
use super::spec::{label, number, Spec, SpecError};
use crate::design::Cell;
use crate::metric::{Field, Metric, Part};
use crate::runner::Outcome;
use crate::table::metric_label;
use crate::table::{decimals, md_table, pm};
use crate::Error;
use crate::Figure;
use platoonsim_plot::{bar_chart, line_chart, Bars, Chart, Series, Style};
use platoonsim_sim::Counted;
use std::path::Path;

/// The metrics shown when the spec names none (those the runs have).
pub const DEFAULT_METRICS: [Metric; 9] = [
    Metric::DISCHARGE_FLOW,
    Metric::MAX_SUSTAINED_FLOW,
    Metric::Field(Field::NetworkDischarge),
    Metric::Field(Field::LaneChangesPerVehicle),
    Metric::Field(Field::AvgPlatoonLength),
    Metric::Field(Field::PlatooningProbability),
    Metric::Counted(Counted::SevereBrakings, Part::Rate),
    Metric::Counted(Counted::RearEndConflicts, Part::Rate),
    Metric::Counted(Counted::LaneChangeConflicts, Part::Rate),
];

/// The spec's `metrics`, each parsed into a [`Metric`] (checked before any run): an error
/// names the key, the value and the allowed names.
pub fn requested(spec: &Spec) -> Result<Vec<Metric>, SpecError> {
    spec.metrics
        .iter()
        .map(|m| {
            Metric::parse(m).ok_or_else(|| SpecError {
                origin: spec.origin.clone(),
                key: "metrics".into(),
                message: format!(
                    "'{m}' is not a metric of the run summary; the metrics are {}",
                    Metric::allowed_names()
                ),
            })
        })
        .collect()
}

/// The metrics to show: the spec's (each must be a metric the runs have), or the defaults.
pub fn shown(spec: &Spec, metrics: &[String]) -> Result<Vec<Metric>, Error> {
    let has = |m: &Metric| metrics.iter().any(|x| *x == m.name());
    if spec.metrics.is_empty() {
        return Ok(DEFAULT_METRICS.into_iter().filter(has).collect());
    }
    let wanted = requested(spec).map_err(|e| Error::Other(e.to_string()))?;
    for m in &wanted {
        if !has(m) {
            return Err(Error::Other(format!(
                "{}: metrics: '{m}' is not a metric of the runs; they are {}",
                spec.origin,
                metrics.join(", ")
            )));
        }
    }
    Ok(wanted)
}

fn row<'a>(rows: &'a [Row], cell: usize, metric: &str) -> Option<&'a Row> {
    rows.iter().find(|r| r.cell == cell && r.metric == metric)
}

/// The body of `summary.md`.
pub fn markdown(
    spec: &Spec,
    cells: &[Cell],
    outcomes: &[Outcome],
    rows: &[Row],
    shown: &[Metric],
) -> String {
    let mut md = format!("# Sweep {}\n\n", spec.name);
    if let Some(d) = &spec.description {
        md.push_str(&format!("{d}\n\n"));
    }
    md.push_str(&format!(
        "Scenario `{}`; {} cells x {} seeds = {} runs. Axes: {}. Mean ± half-width of the 95 % \
         confidence interval (Student t) over the seeds.",
        spec.scenario,
        cells.len(),
        spec.seeds.len(),
        outcomes.len(),
        if spec.axes.is_empty() {
            "none".to_string()
        } else {
            spec.axes
                .iter()
                .map(|a| {
                    format!(
                        "`{}` = {}",
                        a.key,
                        a.levels.iter().map(label).collect::<Vec<_>>().join(", ")
                    )
                })
                .collect::<Vec<_>>()
                .join("; ")
        }
    ));
    if let Some(r) = reference_text(spec) {
        md.push_str(&format!(
            " Δ = the paired difference with the run of the same seed at `{r}` (mean ± 95 % \
             half-width)."
        ));
    }
    md.push_str("\n\n");
    md.push_str(&crate::safety::warning_md(cells, outcomes));
    for m in shown {
        let m = &*m.name();
        md.push_str(&format!("## {}\n\n", metric_label(m)));
        let mut header: Vec<String> = spec.axes.iter().map(|a| a.key.clone()).collect();
        header.extend(["n".to_string(), m.to_string()]);
        if spec.compare.is_some() {
            header.extend(["Δ".to_string(), "Δ (%)".to_string()]);
        }
        let dec = decimals(m);
        let mut trs = Vec::new();
        for (c, cell) in cells.iter().enumerate() {
            let mut tr: Vec<String> = cell.labels.0.iter().map(|(_, v)| v.clone()).collect();
            let r = row(rows, c, m);
            tr.push(r.map_or("0".into(), |r| r.stats.n.to_string()));
            tr.push(r.map_or("–".into(), |r| pm(&r.stats, dec)));
            if spec.compare.is_some() {
                tr.push(
                    r.and_then(|r| r.diff.as_ref())
                        .map_or("–".into(), |d| pm(d, dec)),
                );
                tr.push(
                    r.and_then(|r| r.pct.as_ref())
                        .map_or("–".into(), |d| pm(d, 2)),
                );
            }
            trs.push(tr);
        }
        md.push_str(&md_table(&header, &trs));
        md.push('\n');
    }
    md
}

fn plot_error(e: platoonsim_plot::PlotError) -> Error {
    Error::Other(e.to_string())
}

/// One figure per shown metric (none without axes); returns them.
pub fn figures(
    dir: &Path,
    spec: &Spec,
    cells: &[Cell],
    rows: &[Row],
    shown: &[Metric],
) -> Result<Vec<Figure>, Error> {
    let Some(first) = spec.axes.first() else {
        return Ok(Vec::new());
    };
    let n_first = first.levels.len();
    // A group: the levels of the other axes; the cell of (first-axis level, group), if it was
    // not skipped.
    let combos = spec.combinations();
    let mut tails: Vec<&[usize]> = Vec::new();
    for c in &combos {
        if !tails.contains(&&c[1..]) {
            tails.push(&c[1..]);
        }
    }
    let groups = tails.len();
    let cell_at = |l: usize, g: usize| combos.iter().position(|c| c[0] == l && &c[1..] == tails[g]);
    let group_name = |g: usize| -> String {
        let Some(c) = (0..n_first).find_map(|l| cell_at(l, g)) else {
            return String::new();
        };
        cells[c].labels.0[1..]
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let xs: Option<Vec<f64>> = first.levels.iter().map(number).collect();
    let mut out = Vec::new();
    for m in shown {
        let m = &*m.name();
        let stem = format!("fig_{m}");
        let title = format!("{} against {}", metric_label(m), first.key);
        let get = |l: usize, g: usize| cell_at(l, g).and_then(|c| row(rows, c, m)).map(|r| r.stats);
        match &xs {
            Some(x) => {
                let series = (0..groups)
                    .map(|g| {
                        let st: Vec<_> = (0..n_first).map(|l| get(l, g)).collect();
                        let f = |pick: fn(&crate::Stats) -> f64| -> Vec<f64> {
                            st.iter()
                                .map(|s| s.as_ref().map_or(f64::NAN, pick))
                                .collect()
                        };
                        Series {
                            name: group_name(g),
                            x: x.clone(),
                            y: f(|s| s.mean),
                            band: Some((f(|s| s.ci_low), f(|s| s.ci_high))),
                            style: Style::Line,
                        }
                    })
                    .collect();
                let chart = Chart {
                    title: title.clone(),
                    x_label: first.key.clone(),
                    y_label: metric_label(m).to_string(),
                    series,
                    y_range: None,
                };
                line_chart(&chart, &dir.join(&stem)).map_err(plot_error)?;
            }
            None => {
                let bars = Bars {
                    y_include: Vec::new(),
                    title: title.clone(),
                    y_label: metric_label(m).to_string(),
                    groups: first.levels.iter().map(label).collect(),
                    series: (0..groups)
                        .map(|g| {
                            let st: Vec<_> = (0..n_first).map(|l| get(l, g)).collect();
                            (
                                group_name(g),
                                st.iter().map(|s| s.map_or(f64::NAN, |s| s.mean)).collect(),
                                Some(
                                    st.iter()
                                        .map(|s| s.map_or(f64::NAN, |s| s.half_width()))
                                        .collect(),
                                ),
                            )
                        })
                        .collect(),
                };
                bar_chart(&bars, &dir.join(&stem)).map_err(plot_error)?;
            }
        }
        out.push(Figure { title, stem });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec(metrics: &str) -> Spec {
        let text = format!("scenario = \"homogeneous\"\nseeds = 1\nmetrics = {metrics}\n");
        Spec::from_toml(&text, "s.toml", "s").unwrap()
    }

    #[test]
    fn the_spec_names_metrics_of_the_summary() {
        let s = spec(r#"["fuel_l", "braking_peaks_cav_2", "hard_brakings_per_100vkm_human"]"#);
        let got: Vec<String> = requested(&s)
            .unwrap()
            .iter()
            .map(|m| m.to_string())
            .collect();
        assert_eq!(
            got,
            [
                "fuel_l",
                "braking_peaks_cav_2",
                "hard_brakings_per_100vkm_human"
            ]
        );
        let e = requested(&spec(r#"["avg_platoon_length", "seed"]"#)).unwrap_err();
        assert_eq!((e.origin.as_str(), e.key.as_str()), ("s.toml", "metrics"));
        assert!(e.message.starts_with("'seed' is not a metric"), "{e}");
        assert!(e.message.contains("avg_platoon_length, "), "{e}");
        assert!(e.message.contains("braking_peaks_<cav|human>_<bin>"), "{e}");
    }

    #[test]
    fn the_defaults_are_those_the_runs_have() {
        let s = spec(r#"["vehicles_entered"]"#);
        let have = ["vehicles_entered".to_string(), "avg_platoon_length".into()];
        assert_eq!(
            shown(&s, &have).unwrap(),
            [Metric::Field(Field::VehiclesEntered)]
        );
        let none = Spec {
            metrics: Vec::new(),
            ..s.clone()
        };
        assert_eq!(shown(&none, &have).unwrap(), [Metric::AVG_PLATOON_LENGTH]);
        let e = shown(&s, &have[1..]).unwrap_err().to_string();
        assert!(
            e.contains("'vehicles_entered' is not a metric of the runs"),
            "{e}"
        );
    }
}
