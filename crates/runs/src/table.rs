//! Result tables: `runs.csv` (one row per run), `summary.csv` (one row per cell and metric)
//! and the number formatting shared by the Markdown tables.
//!
//! `runs.csv` columns: the cell labels (e.g. `stage`, `penetration`, `demand_vphpl`,
//! `strategy`), `seed`, `key` (the run file name), then every metric: the numeric fields of
//! the engine's summary in its order (less the configuration echoes and `wall_seconds`, see
//! [`crate::record::NOT_METRICS`]), then the experiment's derived metrics (e.g.
//! `discharge_change_pct`, empty where they do not apply).
//!
//! `summary.csv` columns: the cell labels, `metric`, `mean`, `sd`, `n`, `ci_low`, `ci_high`,
//! `paper`, `difference` (mean − paper), `relative_difference_pct` (100 (mean − paper) /
//! |paper|, percent), `paper_source`, `runs_with_collisions` (the cell's runs that had a
//! collision: a failed run, see [`crate::safety`]; 0 in a valid cell). Cells without a value
//! (no paper value, n < 2 for sd and the interval, a metric that does not apply to a run) are
//! empty; `n` counts the runs that have a value.
//!
//! Number format: a count ([`crate::record::is_count`], and `n`, `seed`) is an integer; every
//! other number has a decimal point (`2040.0`, not `2040`), so that a column has one type
//! whatever its values, as in `summary.json`.

use crate::design::{Cell, Labels};
use crate::metric::Metric;
use crate::runner::Outcome;
use platoonsim_scenario::StrategyKind;
use std::borrow::Cow;

/// A column of the run table: a summary [`Metric`], or a derived column by name (an
/// experiment's `discharge_change_pct`, a sweep's `<metric>_diff`).
pub trait Column {
    fn column(&self) -> Cow<'_, str>;
}

impl Column for Metric {
    fn column(&self) -> Cow<'_, str> {
        self.name()
    }
}

/// A column named in report code: a summary [`Metric`], or a column an experiment derives
/// (by the name it gives it, e.g. `discharge_change_pct` of [`add_paired`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Col {
    Metric(Metric),
    Derived(&'static str),
}

impl Col {
    pub fn name(self) -> Cow<'static, str> {
        match self {
            Col::Metric(m) => m.name(),
            Col::Derived(n) => Cow::Borrowed(n),
        }
    }
}

impl From<Metric> for Col {
    fn from(m: Metric) -> Col {
        Col::Metric(m)
    }
}

impl Column for Col {
    fn column(&self) -> Cow<'_, str> {
        self.name()
    }
}

impl Column for str {
    fn column(&self) -> Cow<'_, str> {
        Cow::Borrowed(self)
    }
}

impl Column for String {
    fn column(&self) -> Cow<'_, str> {
        Cow::Borrowed(self)
    }
}
use crate::stats::Stats;
use crate::Error;

/// One cell and metric of `summary.csv`.
#[derive(Clone, Debug, PartialEq)]
pub struct SummaryRow {
    pub cell: usize,
    pub labels: Labels,
    pub metric: String,
    pub stats: Stats,
    pub paper: Option<PaperValue>,
    /// Runs of the cell with a collision (the same on every metric's row of the cell).
    pub collided: usize,
}

impl SummaryRow {
    /// mean − paper (NaN without a paper value).
    pub fn difference(&self) -> f64 {
        self.paper.map_or(f64::NAN, |p| self.stats.mean - p.value)
    }

    /// 100 (mean − paper) / |paper|, in percent (NaN without a paper value or if it is 0).
    pub fn relative_difference_pct(&self) -> f64 {
        match self.paper {
            Some(p) if p.value != 0.0 => 100.0 * (self.stats.mean - p.value) / p.value.abs(),
            _ => f64::NAN,
        }
    }
}

/// Label names over all cells, in first-appearance order.
pub fn label_columns(cells: &[Cell]) -> Vec<String> {
    let mut cols: Vec<String> = Vec::new();
    for c in cells {
        for (k, _) in &c.labels.0 {
            if !cols.contains(k) {
                cols.push(k.clone());
            }
        }
    }
    cols
}

/// Metric names over all runs, in first-appearance order.
pub fn metric_columns(outcomes: &[Outcome]) -> Vec<String> {
    let mut cols: Vec<String> = Vec::new();
    for o in outcomes {
        for k in o.fields.names() {
            if !cols.iter().any(|c| c == k) {
                cols.push(k.to_string());
            }
        }
    }
    cols
}

/// A number for a CSV cell: shortest round-trip text, with a decimal point also when the
/// value is integral (`2040.0`); empty for NaN or infinite.
pub fn csv_num(v: f64) -> String {
    if !v.is_finite() {
        String::new()
    } else if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{v:.1}")
    } else {
        format!("{v}")
    }
}

/// A metric's value in `runs.csv`: counts as integers, everything else as [`csv_num`].
fn metric_num(name: &str, v: f64) -> String {
    if crate::record::is_count(name) && v.is_finite() {
        format!("{v}")
    } else {
        csv_num(v)
    }
}

fn csv_error(e: impl std::fmt::Display) -> Error {
    Error::Other(format!("cannot encode CSV: {e}"))
}

/// A cell label as a column header of the Markdown tables, with its unit.
pub fn label_header(label: &str) -> String {
    match label {
        "penetration" => "CAV penetration (fraction)".into(),
        "demand_vphpl" => "Demand (veh/h/lane)".into(),
        "demand_scale" => "Demand scale (×)".into(),
        "strategy" => "Strategy".into(),
        "stage" => "Stage".into(),
        other => other.to_string(),
    }
}

/// `runs.csv`; see the module documentation.
pub fn runs_csv(cells: &[Cell], outcomes: &[Outcome]) -> Result<Vec<u8>, Error> {
    let labels = label_columns(cells);
    let metrics = metric_columns(outcomes);
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    let mut header: Vec<String> = labels.clone();
    header.push("seed".into());
    header.push("key".into());
    header.extend(metrics.iter().cloned());
    w.write_record(&header).map_err(csv_error)?;
    for o in outcomes {
        let cell = &cells[o.cell];
        let mut row: Vec<String> = labels
            .iter()
            .map(|k| cell.labels.get(k).unwrap_or("").to_string())
            .collect();
        row.push(o.seed.to_string());
        row.push(o.key.clone());
        row.extend(metrics.iter().map(|m| {
            o.fields
                .get(m)
                .map(|v| metric_num(m, v))
                .unwrap_or_default()
        }));
        w.write_record(&row).map_err(csv_error)?;
    }
    w.into_inner().map_err(csv_error)
}

/// A metric's values over the runs of one cell (runs lacking it are left out).
pub fn values<C: Column + ?Sized>(outcomes: &[Outcome], cell: usize, metric: &C) -> Vec<f64> {
    let metric = metric.column();
    outcomes
        .iter()
        .filter(|o| o.cell == cell)
        .filter_map(|o| o.fields.get(&metric))
        .collect()
}

/// Statistics of one cell's metric.
pub fn stats<C: Column + ?Sized>(outcomes: &[Outcome], cell: usize, metric: &C) -> Stats {
    Stats::of(&values(outcomes, cell, metric))
}

/// One row per cell and metric (cells in order; metrics in [`metric_columns`] order, each
/// only for the cells that have it), with the paper's value where it gives one.
pub fn summarize(
    cells: &[Cell],
    outcomes: &[Outcome],
    paper: impl Fn(&Labels, &str) -> Option<PaperValue>,
) -> Vec<SummaryRow> {
    let metrics = metric_columns(outcomes);
    let mut rows = Vec::new();
    for (i, cell) in cells.iter().enumerate() {
        for m in &metrics {
            let v = values(outcomes, i, m);
            if v.is_empty() {
                continue;
            }
            rows.push(SummaryRow {
                cell: i,
                labels: cell.labels.clone(),
                metric: m.clone(),
                stats: Stats::of(&v),
                paper: paper(&cell.labels, m),
                collided: crate::safety::collided_runs(outcomes, i),
            });
        }
    }
    rows
}

/// `summary.csv`; see the module documentation.
pub fn summary_csv(cells: &[Cell], rows: &[SummaryRow]) -> Result<Vec<u8>, Error> {
    let labels = label_columns(cells);
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    let mut header = labels.clone();
    for h in [
        "metric",
        "mean",
        "sd",
        "n",
        "ci_low",
        "ci_high",
        "paper",
        "difference",
        "relative_difference_pct",
        "paper_source",
        "runs_with_collisions",
    ] {
        header.push(h.into());
    }
    w.write_record(&header).map_err(csv_error)?;
    for r in rows {
        let mut row: Vec<String> = labels
            .iter()
            .map(|k| r.labels.get(k).unwrap_or("").to_string())
            .collect();
        row.push(r.metric.clone());
        row.push(csv_num(r.stats.mean));
        row.push(csv_num(r.stats.sd));
        row.push(r.stats.n.to_string());
        row.push(csv_num(r.stats.ci_low));
        row.push(csv_num(r.stats.ci_high));
        row.push(r.paper.map(|p| csv_num(p.value)).unwrap_or_default());
        row.push(csv_num(r.difference()));
        row.push(csv_num(r.relative_difference_pct()));
        row.push(r.paper.map(|p| p.source.to_string()).unwrap_or_default());
        row.push(r.collided.to_string());
        w.write_record(&row).map_err(csv_error)?;
    }
    w.into_inner().map_err(csv_error)
}

/// Add a paired metric to the runs of `cell`: for each of its runs, the run of `base` with
/// the same seed gives the reference, and `name` = 100 (x − b) / b (percent change) if
/// `percent`, otherwise x − b. Runs without a partner (or with b = 0 for a percentage) get
/// NaN.
pub fn add_paired(
    outcomes: &mut [Outcome],
    base: usize,
    cell: usize,
    metric: Metric,
    name: &str,
    percent: bool,
) {
    pair_with_base(outcomes, base, cell, metric, name, |x, b| {
        if !percent {
            x - b
        } else if b != 0.0 {
            100.0 * (x - b) / b
        } else {
            f64::NAN
        }
    });
}

/// Add a paired ratio to the runs of `cell`: for each of its runs, the run of `base` with the
/// same seed gives b, and `name` = x / b (e.g. the L̄ gain L̄_PO / L̄_B). Runs without a
/// partner, or with b = 0 or a missing value, get NaN.
pub fn add_ratio(outcomes: &mut [Outcome], base: usize, cell: usize, metric: Metric, name: &str) {
    pair_with_base(outcomes, base, cell, metric, name, |x, b| {
        if b != 0.0 {
            x / b
        } else {
            f64::NAN
        }
    });
}

/// For each run of `cell`, `name` = `f(x, b)` with x its `metric` and b the `metric` of the
/// run of `base` with the same seed; NaN without a partner or a value.
fn pair_with_base(
    outcomes: &mut [Outcome],
    base: usize,
    cell: usize,
    metric: Metric,
    name: &str,
    f: impl Fn(f64, f64) -> f64,
) {
    let reference: Vec<(u64, f64)> = outcomes
        .iter()
        .filter(|o| o.cell == base)
        .filter_map(|o| o.fields.metric(metric).map(|v| (o.seed, v)))
        .collect();
    for o in outcomes.iter_mut().filter(|o| o.cell == cell) {
        let b = reference
            .iter()
            .find(|(s, _)| *s == o.seed)
            .map(|(_, v)| *v);
        let d = match (o.fields.metric(metric), b) {
            (Some(x), Some(b)) => f(x, b),
            _ => f64::NAN,
        };
        o.fields.set(name, d);
    }
}

// ---- Markdown number formatting -------------------------------------------------------

/// `v` with `dec` decimals; "–" for NaN.
pub fn fixed(v: f64, dec: usize) -> String {
    if v.is_finite() {
        format!("{v:.dec$}")
    } else {
        "–".into()
    }
}

/// `v` with a sign and `dec` decimals (`+0.03`, `-1.20`); "–" for NaN.
pub fn signed(v: f64, dec: usize) -> String {
    if v.is_finite() {
        format!("{v:+.dec$}")
    } else {
        "–".into()
    }
}

/// `mean ± half-width` of the 95 % interval (only the mean if there is no interval).
pub fn pm(s: &Stats, dec: usize) -> String {
    let hw = s.half_width();
    if hw.is_finite() {
        format!("{} ± {}", fixed(s.mean, dec), fixed(hw, dec))
    } else {
        fixed(s.mean, dec)
    }
}

/// `[low, high]` of the 95 % interval; "–" if there is none.
pub fn interval(s: &Stats, dec: usize) -> String {
    if s.ci_low.is_finite() && s.ci_high.is_finite() {
        format!("[{}, {}]", fixed(s.ci_low, dec), fixed(s.ci_high, dec))
    } else {
        "–".into()
    }
}

/// A Markdown table from a header and rows.
pub fn md_table(header: &[String], rows: &[Vec<String>]) -> String {
    let mut s = String::new();
    s.push_str(&format!("| {} |\n", header.join(" | ")));
    s.push_str(&format!(
        "|{}\n",
        header.iter().map(|_| "---|").collect::<String>()
    ));
    for r in rows {
        s.push_str(&format!("| {} |\n", r.join(" | ")));
    }
    s
}

/// Decimals used to show a metric.
pub fn decimals(metric: &str) -> usize {
    match metric {
        m if m.starts_with("lane_changes") => 3,
        "avg_platoon_length" | "platoon_length_gain" | "platoon_length_ratio" => 2,
        m if m.ends_with("_per_100vkm") => 3,
        "platooning_probability" => 3,
        m if m.ends_with("_pct") => 2,
        m if m.ends_with("_vphpl") => 1,
        _ => 2,
    }
}

/// A table comparing each of the paper's values with ours, for the rows that have one:
/// quantity (from `describe`), ours with its 95 % interval, the paper's value and source,
/// the difference and relative difference, and whether the paper's value lies in our
/// interval.
pub fn paper_comparison(rows: &[SummaryRow], describe: impl Fn(&SummaryRow) -> String) -> String {
    let header: Vec<String> = [
        "Quantity (unit)",
        "Ours (the row's unit)",
        "95 % CI (the row's unit)",
        "Paper (the row's unit)",
        "Difference (the row's unit)",
        "Relative (%)",
        "Paper value in our CI",
        "Source",
    ]
    .iter()
    .map(|h| h.to_string())
    .collect();
    let mut out = Vec::new();
    for r in rows {
        let Some(p) = r.paper else { continue };
        let dec = decimals(&r.metric);
        let inside = if !r.stats.ci_low.is_finite() {
            "– (n < 2)"
        } else if r.stats.covers(p.value) {
            "yes"
        } else {
            "no"
        };
        let rel = r.relative_difference_pct() / 100.0;
        out.push(vec![
            describe(r),
            fixed(r.stats.mean, dec),
            interval(&r.stats, dec),
            fixed(p.value, dec),
            signed(r.difference(), dec),
            if rel.is_finite() {
                format!("{} %", signed(100.0 * rel, 1))
            } else {
                "–".into()
            },
            inside.into(),
            p.source.into(),
        ]);
    }
    if out.is_empty() {
        return "The paper gives no value for these cells.\n".into();
    }
    md_table(&header, &out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::Fields;
    use platoonsim_sim::Config;

    fn cells() -> Vec<Cell> {
        let c = Config::homogeneous(0.5, 1000.0, 300.0, 60.0, 1);
        vec![
            Cell {
                labels: Labels::new()
                    .with("demand_vphpl", "1000")
                    .with("strategy", "none"),
                config: c.clone(),
            },
            Cell {
                labels: Labels::new()
                    .with("demand_vphpl", "1000")
                    .with("strategy", "pd"),
                config: c,
            },
        ]
    }

    fn outcome(cell: usize, seed: u64, q: f64, lbar: f64) -> Outcome {
        Outcome {
            cell,
            seed,
            key: format!("k{cell}{seed}"),
            fields: Fields(vec![
                ("discharge_flow_vphpl".into(), q),
                ("avg_platoon_length".into(), lbar),
            ]),
            computed: true,
        }
    }

    #[test]
    fn the_ratio_pairs_runs_by_seed() {
        let mut outs = vec![
            outcome(0, 1, 1000.0, 2.5),
            outcome(0, 2, 1010.0, 0.0),
            outcome(1, 2, 1010.0, 5.2),
            outcome(1, 1, 990.0, 5.0),
            outcome(1, 3, 990.0, 4.0),
        ];
        add_ratio(
            &mut outs,
            0,
            1,
            Metric::Field(crate::metric::Field::AvgPlatoonLength),
            "platoon_length_ratio",
        );
        let r = |i: usize| outs[i].fields.get("platoon_length_ratio");
        assert_eq!(r(3), Some(2.0), "seed 1: 5.0 / 2.5");
        assert!(r(2).unwrap().is_nan(), "seed 2: the baseline is 0");
        assert!(r(4).unwrap().is_nan(), "seed 3: no baseline run");
        assert_eq!(r(0), None, "the baseline gets no ratio");
    }

    #[test]
    fn csv_shapes() {
        let cells = cells();
        let mut outs = vec![
            outcome(0, 1, 1000.0, 2.5),
            outcome(0, 2, 1010.0, f64::NAN),
            outcome(1, 1, 990.0, 5.0),
            outcome(1, 2, 1010.0, 5.2),
        ];
        add_paired(
            &mut outs,
            0,
            1,
            Metric::DISCHARGE_FLOW,
            "discharge_change_pct",
            true,
        );
        let runs = String::from_utf8(runs_csv(&cells, &outs).unwrap()).unwrap();
        let lines: Vec<&str> = runs.lines().collect();
        assert_eq!(
            lines[0],
            "demand_vphpl,strategy,seed,key,discharge_flow_vphpl,avg_platoon_length,discharge_change_pct"
        );
        assert_eq!(lines.len(), 1 + 4);
        // Not counts: always a decimal point, so each column has one type.
        assert_eq!(lines[2], "1000,none,2,k02,1010.0,,");
        assert_eq!(lines[3], "1000,pd,1,k11,990.0,5.0,-1.0");
        assert_eq!(lines[4], "1000,pd,2,k12,1010.0,5.2,0.0");
        for l in &lines {
            assert_eq!(l.split(',').count(), 7, "{l}");
        }

        // Reference values as the paper's Table 3 gives them at 1000 veh/h/lane.
        let paper = [
            ("none", Col::Metric(Metric::DISCHARGE_FLOW), 1006.3),
            ("none", Col::Metric(Metric::AVG_PLATOON_LENGTH), 2.6),
            ("pd", Col::Derived("discharge_change_pct"), 0.04),
        ]
        .map(|(strategy, metric, value)| PaperValue {
            experiment: "sensitivity",
            cell: match strategy {
                "none" => CellSel::of(StrategyKind::NONE, &[]),
                _ => CellSel::of(StrategyKind::PD, &[]),
            },
            metric,
            value,
            source: "Table 3",
        });
        let rows = summarize(&cells, &outs, |labels, metric| {
            paper
                .iter()
                .find(|p| p.metric.name() == metric && p.cell.matches(labels))
                .copied()
        });
        // Cell 0: two metrics; cell 1: three.
        assert_eq!(rows.len(), 5);
        let q_b = &rows[0];
        assert_eq!(
            (q_b.metric.as_str(), q_b.stats.n, q_b.stats.mean),
            ("discharge_flow_vphpl", 2, 1005.0)
        );
        assert_eq!(q_b.paper.unwrap().value, 1006.3);
        assert!((q_b.difference() - (1005.0 - 1006.3)).abs() < 1e-9);
        let lbar_b = &rows[1];
        assert_eq!(lbar_b.stats.n, 1); // the NaN is left out
        let dq = rows
            .iter()
            .find(|r| r.metric == "discharge_change_pct")
            .unwrap();
        assert_eq!(dq.stats.mean, -0.5);
        assert_eq!(dq.paper.unwrap().value, 0.04);

        let summary = String::from_utf8(summary_csv(&cells, &rows).unwrap()).unwrap();
        let lines: Vec<&str> = summary.lines().collect();
        assert_eq!(
            lines[0],
            "demand_vphpl,strategy,metric,mean,sd,n,ci_low,ci_high,paper,difference,relative_difference_pct,paper_source,runs_with_collisions"
        );
        assert_eq!(lines.len(), 1 + 5);
        let mut r = csv::Reader::from_reader(summary.as_bytes());
        for rec in r.records() {
            assert_eq!(rec.unwrap().len(), 13);
        }
        assert!(lines[2].starts_with("1000,none,avg_platoon_length,2.5,,1,,,2.6,"));
        // (2.5 − 2.6) / 2.6 in percent.
        assert!(lines[2].contains(",-3.84615384615384"), "{}", lines[2]);
    }

    #[test]
    fn markdown_helpers() {
        let s = Stats::of(&[1.0, 2.0, 3.0]);
        assert_eq!(pm(&s, 2), "2.00 ± 2.48");
        assert_eq!(signed(0.5, 1), "+0.5");
        assert_eq!(fixed(f64::NAN, 1), "–");
        let t = md_table(&["a".into(), "b".into()], &[vec!["1".into(), "2".into()]]);
        assert_eq!(t, "| a | b |\n|---|---|\n| 1 | 2 |\n");
    }
}

/// A reference value of a study (e.g. a published table's), with where it comes from: of an
/// experiment, a cell (a subset of the cell's labels) and a column (a metric of the runs or
/// one the experiment derives).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PaperValue {
    pub experiment: &'static str,
    /// Labels the cell must have.
    pub cell: CellSel,
    pub metric: Col,
    pub value: f64,
    pub source: &'static str,
}

/// What a cell must be: its strategy (its `strategy` label), if that matters, and further
/// labels, (name, value) pairs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellSel {
    pub strategy: Option<StrategyKind>,
    pub labels: &'static [(&'static str, &'static str)],
}

impl CellSel {
    /// A cell of this strategy with these labels.
    pub const fn of(
        strategy: StrategyKind,
        labels: &'static [(&'static str, &'static str)],
    ) -> CellSel {
        CellSel {
            strategy: Some(strategy),
            labels,
        }
    }

    /// Whether a cell's labels are selected.
    pub fn matches(&self, labels: &Labels) -> bool {
        labels.matches(self.labels)
            && self
                .strategy
                .is_none_or(|k| labels.get("strategy") == Some(k.as_str()))
    }
}

/// Human-readable metric names.
pub fn metric_label(metric: &str) -> &str {
    match metric {
        "lane_changes_per_vehicle" => "lane changes per vehicle",
        "lane_changes_per_cav" => "lane changes per CAV",
        "lane_changes_per_human" => "lane changes per human-driven vehicle",
        "avg_platoon_length" => "average platoon length L̄",
        "platooning_probability" => "platooning probability P_P",
        "discharge_flow_vphpl" => "discharge flow (veh/h/lane)",
        "max_sustained_flow_vphpl" => "capacity = highest 5-min discharge (veh/h/lane)",
        "discharge_change_pct" => "discharge change vs baseline (%)",
        "platoon_length_gain" => "L̄ gain vs baseline",
        "platoon_length_ratio" => "L̄ relative to the baseline (ratio)",
        other => other,
    }
}
