//! Safety per cell (issues 18, 29, docs/safety.md): which runs had collisions, and the
//! surrogate safety measures of the engine's summary (hard, severe and at-limit brakings and
//! rear-end and lane-change conflicts per 100 veh-km, TET, TIT, the smallest TTC, the
//! largest deceleration) as Markdown tables, and the braking histogram as a figure.
//!
//! A run with a collision is a failed run: vehicles overlapped or ran past the end of a lane,
//! so its discharge, lane changes and platoons are not those of physical traffic. Every
//! experiment's `summary.md` (and the report) therefore opens with [`warning_md`] when any run
//! collided, and `summary.csv` counts the failed runs of each cell.

use crate::design::{Cell, Labels};
use crate::metric::{Field, Kind, Metric, Part};
use crate::runner::Outcome;
use crate::stats::Stats;
use crate::table::{self, md_table, pm};
use crate::Error;
use crate::Figure;
use platoonsim_model::safety::PEAK_BIN_EDGES_MPS2;
use platoonsim_sim::Counted;
use std::path::Path;

/// The safety columns: (metric of the summary, column title, decimals).
pub const METRICS: [(Metric, &str, usize); 10] = [
    (Metric::Field(Field::VehicleKm), "Vehicle-km (veh·km)", 0),
    (
        Metric::Counted(Counted::HardBrakings, Part::Rate),
        "Hard brakings > 4 m/s² (per 100 veh-km)",
        3,
    ),
    (
        Metric::Counted(Counted::SevereBrakings, Part::Rate),
        "Severe brakings ≥ 6 m/s² (per 100 veh-km)",
        3,
    ),
    (
        Metric::Counted(Counted::BrakingsAtLimit, Part::Rate),
        "Brakings at the limit b_e (per 100 veh-km)",
        3,
    ),
    (
        Metric::Counted(Counted::RearEndConflicts, Part::Rate),
        "Rear-end conflicts (per 100 veh-km)",
        2,
    ),
    (
        Metric::Counted(Counted::LaneChangeConflicts, Part::Rate),
        "Lane-change conflicts (per 100 veh-km)",
        2,
    ),
    (Metric::Field(Field::TetS), "TET (s)", 1),
    (Metric::Field(Field::TitS2), "TIT (s²)", 1),
    (Metric::Field(Field::MinTtc), "Min TTC (s)", 2),
    (
        Metric::Field(Field::MaxDeceleration),
        "Max deceleration (m/s²)",
        2,
    ),
];

/// The by-kind columns: the braking classes and the lane-change conflicts per 100 veh-km of
/// human-driven vehicles and of CAVs.
pub const BY_KIND: [(Counted, &str, usize); 3] = [
    (Counted::HardBrakings, "Hard brakings", 3),
    (Counted::SevereBrakings, "Severe brakings", 3),
    (Counted::LaneChangeConflicts, "Lane-change conflicts", 2),
];

/// Whether a run collided. A run file without the field (an older engine) counts as no
/// collision known; such files are not reused by a new build anyway.
pub fn collided(o: &Outcome) -> bool {
    o.fields.metric(Metric::COLLISIONS).is_some_and(|c| c > 0.0)
}

/// The runs of `cell` that collided.
pub fn collided_runs(outcomes: &[Outcome], cell: usize) -> usize {
    outcomes
        .iter()
        .filter(|o| o.cell == cell && collided(o))
        .count()
}

/// A cell that had collisions: its index, the seeds of the runs that collided, its run count.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Failed {
    pub cell: usize,
    pub seeds: Vec<u64>,
    pub runs: usize,
}

/// Every cell with at least one collided run, in cell order.
pub fn failed_cells(cells: &[Cell], outcomes: &[Outcome]) -> Vec<Failed> {
    (0..cells.len())
        .filter_map(|c| {
            let seeds: Vec<u64> = outcomes
                .iter()
                .filter(|o| o.cell == c && collided(o))
                .map(|o| o.seed)
                .collect();
            let runs = outcomes.iter().filter(|o| o.cell == c).count();
            (!seeds.is_empty()).then_some(Failed {
                cell: c,
                seeds,
                runs,
            })
        })
        .collect()
}

/// A cell's labels as text: `penetration 0.5, demand_vphpl 2500, strategy pd`.
pub fn cell_name(labels: &Labels) -> String {
    labels
        .0
        .iter()
        .map(|(k, v)| format!("{k} {v}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A figure panel's title: the labels that tell the cells apart (a label with one value in
/// every cell is left out), short names first: `variant published, demand 1000, strategy pd`.
pub fn panel_name(cells: &[Cell], c: usize) -> String {
    let varies = |k: &str| {
        let first = cells[0].labels.get(k);
        cells.iter().any(|x| x.labels.get(k) != first)
    };
    fn short(k: &str) -> &str {
        match k {
            "demand_vphpl" => "demand",
            "penetration" => "CAV",
            other => other,
        }
    }
    let parts: Vec<String> = cells[c]
        .labels
        .0
        .iter()
        .filter(|(k, _)| varies(k))
        .map(|(k, v)| format!("{} {v}", short(k)))
        .collect();
    if parts.is_empty() {
        cell_name(&cells[c].labels)
    } else {
        parts.join(", ")
    }
}

/// The list items of the failed cells (`- <experiment>: <cell>: 2 of 10 runs (seeds 3, 7)`),
/// `prefix` before each cell (e.g. the experiment's name).
pub fn failed_list(cells: &[Cell], failed: &[Failed], prefix: &str) -> String {
    let mut s = String::new();
    for f in failed {
        let seeds: Vec<String> = f.seeds.iter().map(u64::to_string).collect();
        s.push_str(&format!(
            "- {prefix}{}: {} of {} runs (seed{} {})\n",
            cell_name(&cells[f.cell].labels),
            f.seeds.len(),
            f.runs,
            if f.seeds.len() == 1 { "" } else { "s" },
            seeds.join(", ")
        ));
    }
    s
}

/// The warning that opens a `summary.md` whose experiment had collisions (empty if none).
pub fn warning_md(cells: &[Cell], outcomes: &[Outcome]) -> String {
    let failed = failed_cells(cells, outcomes);
    if failed.is_empty() {
        return String::new();
    }
    let n: usize = failed.iter().map(|f| f.seeds.len()).sum();
    format!(
        "> **Warning: {n} run{} with collisions — these results are invalid.** In the cells \
         below, vehicles overlapped or ran past the end of a lane (a correct run has none; \
         docs/safety.md); their statistics include these runs. `runs.csv` has each run's \
         `collisions`, `summary.csv` each cell's `runs_with_collisions`.\n\n{}\n",
        if n == 1 { "" } else { "s" },
        failed_list(cells, &failed, "")
            .lines()
            .map(|l| format!("> {l}\n"))
            .collect::<String>()
    )
}

/// Order cells so that those with the same values of `group` (e.g. the demand) are adjacent,
/// keeping the cell order inside a group (e.g. baseline before PD). Values compare as numbers
/// where both are numbers.
fn grouped(cells: &[Cell], group: &[&str]) -> Vec<usize> {
    let key = |c: usize| -> Vec<&str> {
        group
            .iter()
            .map(|g| cells[c].labels.get(g).unwrap_or(""))
            .collect()
    };
    let cmp = |a: &str, b: &str| match (a.parse::<f64>(), b.parse::<f64>()) {
        (Ok(x), Ok(y)) => x.total_cmp(&y),
        _ => a.cmp(b),
    };
    let mut order: Vec<usize> = (0..cells.len()).collect();
    order.sort_by(|&a, &b| {
        key(a)
            .iter()
            .zip(key(b).iter())
            .map(|(x, y)| cmp(x, y))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    order
}

/// One row per cell (in `order`): its labels, then `text(cell, runs)` for each column.
fn cell_table(
    cells: &[Cell],
    outcomes: &[Outcome],
    order: &[usize],
    columns: &[String],
    text: impl Fn(usize, usize, usize) -> String,
) -> String {
    let labels = table::label_columns(cells);
    let mut header: Vec<String> = labels.iter().map(|l| table::label_header(l)).collect();
    header.extend(columns.iter().cloned());
    let mut rows = Vec::new();
    for &c in order {
        let runs = outcomes.iter().filter(|o| o.cell == c).count();
        if runs == 0 {
            continue;
        }
        let mut row: Vec<String> = labels
            .iter()
            .map(|k| cells[c].labels.get(k).unwrap_or("").to_string())
            .collect();
        row.extend((0..columns.len()).map(|i| text(c, i, runs)));
        rows.push(row);
    }
    md_table(&header, &rows)
}

/// Mean ± 95 % half-width of a cell's metric over its runs (`n` given when some runs lack it).
fn mean_text(outcomes: &[Outcome], c: usize, metric: Metric, dec: usize, runs: usize) -> String {
    let v = table::values(outcomes, c, &metric);
    let s = Stats::of(&v);
    let mut text = pm(&s, dec);
    if !v.is_empty() && s.n < runs {
        text.push_str(&format!(" (n = {})", s.n));
    }
    text
}

/// The TTC* of the cells, as text: `1.5 s`, or every value if the cells differ.
pub fn ttc_thresholds(cells: &[Cell]) -> String {
    let mut v: Vec<f64> = cells
        .iter()
        .map(|c| c.config.safety.ttc_threshold_s)
        .collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    let v: Vec<String> = v
        .iter()
        .map(|t| format!("{} s", crate::design::num(*t)))
        .collect();
    v.join(", ")
}

/// The `## Safety` section: one row per cell (cells sharing the `group` labels adjacent, so
/// that a point's baseline and PD rows are side by side), its labels, the runs with
/// collisions, and the mean ± 95 % half-width of each of [`METRICS`]; then the braking
/// classes and lane-change conflicts by vehicle kind ([`BY_KIND`]). The minimum TTC is
/// averaged over the runs in which a follower closed in, a rate over the runs in which
/// vehicles of its kind drove (`n` given when some did not).
pub fn section_md(cells: &[Cell], outcomes: &[Outcome], group: &[&str]) -> String {
    let order = grouped(cells, group);
    let mut columns = vec!["Runs with collisions (runs)".to_string()];
    columns.extend(METRICS.iter().map(|m| m.1.to_string()));
    let main = cell_table(cells, outcomes, &order, &columns, |c, i, runs| {
        if i == 0 {
            let bad = collided_runs(outcomes, c);
            return if bad > 0 {
                format!("**{bad} of {runs}** (invalid)")
            } else {
                format!("0 of {runs}")
            };
        }
        let (metric, _, dec) = METRICS[i - 1];
        mean_text(outcomes, c, metric, dec, runs)
    });
    let kinds = [(Part::RateHuman, "human-driven"), (Part::RateCav, "CAV")];
    let columns: Vec<String> = BY_KIND
        .iter()
        .flat_map(|(_, title, _)| {
            kinds
                .iter()
                .map(move |(_, k)| format!("{title}, {k} (per 100 veh-km)"))
        })
        .collect();
    let by_kind = cell_table(cells, outcomes, &order, &columns, |c, i, runs| {
        let (measure, _, dec) = BY_KIND[i / kinds.len()];
        let part = kinds[i % kinds.len()].0;
        mean_text(outcomes, c, Metric::Counted(measure, part), dec, runs)
    });
    format!(
        "## Safety\n\nSurrogate safety measures per cell (definitions in docs/safety.md, spec \
         9.4): mean ± half-width of the 95 % confidence interval over the seeds, measured \
         after the warm-up except the largest deceleration (whole run). Braking episodes \
         (consecutive steps of one vehicle braking harder than 4 m/s²) are classed by their \
         peak: hard (> 4 m/s²), severe (≥ 6 m/s², about the 0.6 g near-crash trigger of the \
         100-Car naturalistic study) and at the vehicle's emergency limit b_e. A conflict is an \
         episode of a follower-leader pair with a time to collision below TTC* = {}; it is a \
         lane-change conflict when the pair was formed by a lane change in the step it starts \
         (SSAM's lane-change class), a rear-end conflict otherwise. Rates are per 100 \
         vehicle-km driven in the window. A cell with collisions is invalid.\n\n{}\nBy \
         vehicle kind (the braking vehicle's, the conflict's follower's), per 100 veh-km of \
         that kind:\n\n{}",
        ttc_thresholds(cells),
        main,
        by_kind
    )
}

/// The bins of the braking histogram as axis labels: `4–5`, …, `≥ 9` (m/s²).
fn bin_labels() -> Vec<String> {
    let e = PEAK_BIN_EDGES_MPS2;
    (0..e.len())
        .map(|i| match e.get(i + 1) {
            Some(hi) => format!("{}–{}", e[i], hi),
            None => format!("≥ {}", e[i]),
        })
        .collect()
}

/// A cell's episodes per 100 veh-km of `kind` in each peak bin: the bins' counts over its
/// runs divided by the vehicle-km of that kind over the same runs (NaN without any).
pub fn peak_rates(outcomes: &[Outcome], cell: usize, kind: Kind) -> Vec<f64> {
    let km = match kind {
        Kind::Cav => Field::VehicleKmCav,
        Kind::Human => Field::VehicleKmHuman,
    };
    let km: f64 = table::values(outcomes, cell, &Metric::Field(km))
        .iter()
        .sum();
    (0..PEAK_BIN_EDGES_MPS2.len())
        .map(|i| {
            let n: f64 = table::values(outcomes, cell, &Metric::BrakingPeaks(kind, i))
                .iter()
                .sum();
            if km > 0.0 {
                n * 100.0 / km
            } else {
                f64::NAN
            }
        })
        .collect()
}

/// `braking.png` / `.svg`: one panel per cell, the hard-braking episodes per 100 veh-km by
/// peak deceleration, human-driven vehicles and CAVs side by side. None when no run has the
/// histogram (older run files).
pub fn braking_figure(
    dir: &Path,
    cells: &[Cell],
    outcomes: &[Outcome],
) -> Result<Vec<Figure>, Error> {
    if !outcomes.iter().any(|o| {
        o.fields
            .metric(Metric::BrakingPeaks(Kind::Human, 0))
            .is_some()
    }) {
        return Ok(Vec::new());
    }
    let panels: Vec<(usize, Vec<f64>, Vec<f64>)> = (0..cells.len())
        .filter(|&c| outcomes.iter().any(|o| o.cell == c))
        .map(|c| {
            let (h, v) = (
                peak_rates(outcomes, c, Kind::Human),
                peak_rates(outcomes, c, Kind::Cav),
            );
            (c, h, v)
        })
        .collect();
    // One y scale for every panel, so that the cells compare at a glance.
    let top = panels
        .iter()
        .flat_map(|(_, h, v)| h.iter().chain(v))
        .copied()
        .filter(|x| x.is_finite())
        .fold(0.0, f64::max);
    let charts: Vec<platoonsim_plot::Bars> = panels
        .into_iter()
        .map(|(c, h, v)| platoonsim_plot::Bars {
            title: panel_name(cells, c),
            y_label: "episodes per 100 veh-km".into(),
            groups: bin_labels(),
            series: vec![("human-driven".into(), h, None), ("CAV".into(), v, None)],
            y_include: vec![0.0, top],
        })
        .collect();
    let title = "Hard-braking episodes by peak deceleration (m/s²), per 100 veh-km of each kind";
    platoonsim_plot::bar_panels(&charts, 3, title, &dir.join("braking"))
        .map_err(|e| Error::Other(e.to_string()))?;
    Ok(vec![Figure {
        title: format!(
            "{title}: episodes of braking beyond 4 m/s² binned by their peak, after the \
             warm-up, over all seeds of each cell (docs/safety.md)"
        ),
        stem: "braking".into(),
    }])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_sort_as_numbers() {
        let c = platoonsim_sim::Config::homogeneous(0.5, 1000.0, 60.0, 0.0, 1);
        let cell = |d: &str, k: &str| Cell {
            labels: Labels::new().with("demand_vphpl", d).with("strategy", k),
            config: c.clone(),
        };
        let cells = [
            cell("1000", "none"),
            cell("500", "none"),
            cell("1000", "pd"),
            cell("500", "pd"),
        ];
        assert_eq!(grouped(&cells, &["demand_vphpl"]), [1, 3, 0, 2]);
        assert_eq!(grouped(&cells, &[]), [0, 1, 2, 3]);
        assert_eq!(
            cell_name(&cells[2].labels),
            "demand_vphpl 1000, strategy pd"
        );
    }

    #[test]
    fn a_panel_names_only_the_labels_that_vary() {
        let c = platoonsim_sim::Config::homogeneous(0.5, 1000.0, 60.0, 0.0, 1);
        let cell = |d: &str, k: &str| Cell {
            labels: Labels::new()
                .with("penetration", "0.5")
                .with("demand_vphpl", d)
                .with("strategy", k),
            config: c.clone(),
        };
        let cells = [cell("1000", "none"), cell("2500", "pd")];
        assert_eq!(panel_name(&cells, 1), "demand 2500, strategy pd");
        // A single cell: every label, as in the tables.
        assert_eq!(
            panel_name(&cells[..1], 0),
            "penetration 0.5, demand_vphpl 1000, strategy none"
        );
    }
}
