//! The tables of a sweep: paired differences added to the runs, `runs.csv` (the experiments'
//! format: axes, seed, key, every metric, then the differences) and `summary.csv`.
//!
//! With `[compare] AXIS = LEVEL`, every run of a cell whose AXIS is not LEVEL is paired with
//! the run of the same seed in the cell that differs only in AXIS = LEVEL (its reference).
//! For every metric `m` it gets `m_diff` = x − x_ref and `m_pct` = 100 (x − x_ref) / x_ref
//! (empty where x_ref is 0 or either value is missing).
//!
//! `summary.csv`: one row per cell and metric: the axes, `metric`, `mean`, `sd`, `n`,
//! `ci_low`, `ci_high` (Student-t 95 % interval of the mean over the seeds),
//! `runs_with_collisions`, and with a comparison `reference` (e.g. `strategy.kind=none`),
//! `diff_mean`, `diff_sd`, `diff_n`, `diff_ci_low`, `diff_ci_high` (the paired difference and
//! its interval) and `pct_mean`, `pct_ci_low`, `pct_ci_high` (the same for the percent
//! change); these are empty on the reference cells.

use super::plan::combinations;
use super::spec::{label, Spec};
use crate::design::Cell;
use crate::runner::Outcome;
use crate::stats::Stats;
use crate::table::{csv_num, label_columns, metric_columns, values};
use crate::Error;

/// The reference cell of each cell (`None` for reference cells and without a comparison).
pub fn references(spec: &Spec) -> Vec<Option<usize>> {
    let combos = combinations(spec);
    let Some((axis, level)) = spec.compare else {
        return vec![None; combos.len()];
    };
    combos
        .iter()
        .map(|c| {
            if c[axis] == level {
                return None;
            }
            let mut r = c.clone();
            r[axis] = level;
            combos.iter().position(|x| *x == r)
        })
        .collect()
}

/// Add the paired differences of every metric to the compared runs; returns the metric
/// names (before the differences), in `runs.csv` order.
pub fn add_differences(spec: &Spec, outcomes: &mut [Outcome]) -> Vec<String> {
    let metrics = metric_columns(outcomes);
    let refs = references(spec);
    if spec.compare.is_none() {
        return metrics;
    }
    // (cell, seed) -> outcome index, for the references.
    let find = |outs: &[Outcome], cell: usize, seed: u64| {
        outs.iter().position(|o| o.cell == cell && o.seed == seed)
    };
    for i in 0..outcomes.len() {
        let Some(rc) = refs[outcomes[i].cell] else {
            continue;
        };
        let r = find(outcomes, rc, outcomes[i].seed);
        for m in &metrics {
            let x = outcomes[i].fields.get(m);
            let b = r.and_then(|r| outcomes[r].fields.get(m));
            let (d, p) = match (x, b) {
                (Some(x), Some(b)) => (
                    x - b,
                    if b != 0.0 {
                        100.0 * (x - b) / b
                    } else {
                        f64::NAN
                    },
                ),
                _ => (f64::NAN, f64::NAN),
            };
            outcomes[i].fields.set(&format!("{m}_diff"), d);
            outcomes[i].fields.set(&format!("{m}_pct"), p);
        }
    }
    metrics
}

/// One row of `summary.csv`.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub cell: usize,
    pub metric: String,
    pub stats: Stats,
    pub diff: Option<Stats>,
    pub pct: Option<Stats>,
    pub collided: usize,
}

/// Statistics per cell and metric (cells in order, metrics in `runs.csv` order).
pub fn summarize(
    spec: &Spec,
    cells: &[Cell],
    outcomes: &[Outcome],
    metrics: &[String],
) -> Vec<Row> {
    let refs = references(spec);
    let mut rows = Vec::new();
    for (c, reference) in refs.iter().enumerate().take(cells.len()) {
        for m in metrics {
            let v = values(outcomes, c, m);
            if v.is_empty() {
                continue;
            }
            let compared = reference.is_some();
            rows.push(Row {
                cell: c,
                metric: m.clone(),
                stats: Stats::of(&v),
                diff: compared.then(|| Stats::of(&values(outcomes, c, &format!("{m}_diff")))),
                pct: compared.then(|| Stats::of(&values(outcomes, c, &format!("{m}_pct")))),
                collided: crate::safety::collided_runs(outcomes, c),
            });
        }
    }
    rows
}

fn csv_error(e: impl std::fmt::Display) -> Error {
    Error::Other(format!("cannot encode CSV: {e}"))
}

/// The reference of the comparison as text (`strategy.kind=none`).
pub fn reference_text(spec: &Spec) -> Option<String> {
    spec.compare
        .map(|(a, l)| format!("{}={}", spec.axes[a].key, label(&spec.axes[a].levels[l])))
}

/// `summary.csv`; see the module documentation.
pub fn summary_csv(spec: &Spec, cells: &[Cell], rows: &[Row]) -> Result<Vec<u8>, Error> {
    let labels = label_columns(cells);
    let reference = reference_text(spec);
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    let mut header = labels.clone();
    header.extend(
        [
            "metric",
            "mean",
            "sd",
            "n",
            "ci_low",
            "ci_high",
            "runs_with_collisions",
        ]
        .map(String::from),
    );
    if reference.is_some() {
        header.extend(
            [
                "reference",
                "diff_mean",
                "diff_sd",
                "diff_n",
                "diff_ci_low",
                "diff_ci_high",
                "pct_mean",
                "pct_ci_low",
                "pct_ci_high",
            ]
            .map(String::from),
        );
    }
    w.write_record(&header).map_err(csv_error)?;
    for r in rows {
        let mut row: Vec<String> = labels
            .iter()
            .map(|k| cells[r.cell].labels.get(k).unwrap_or("").to_string())
            .collect();
        let s = &r.stats;
        row.push(r.metric.clone());
        row.extend([
            csv_num(s.mean),
            csv_num(s.sd),
            s.n.to_string(),
            csv_num(s.ci_low),
            csv_num(s.ci_high),
        ]);
        row.push(r.collided.to_string());
        if let Some(reference) = &reference {
            match (&r.diff, &r.pct) {
                (Some(d), Some(p)) => {
                    row.push(reference.clone());
                    row.extend([
                        csv_num(d.mean),
                        csv_num(d.sd),
                        d.n.to_string(),
                        csv_num(d.ci_low),
                        csv_num(d.ci_high),
                        csv_num(p.mean),
                        csv_num(p.ci_low),
                        csv_num(p.ci_high),
                    ]);
                }
                _ => row.extend(std::iter::repeat_n(String::new(), 9)),
            }
        }
        w.write_record(&row).map_err(csv_error)?;
    }
    w.into_inner().map_err(csv_error)
}
