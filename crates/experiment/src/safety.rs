//! Safety per cell (issue 18, docs/safety.md): which runs had collisions, and the surrogate
//! safety measures of the engine's summary (emergency brakings, conflicts, TET, TIT, the
//! smallest TTC, the largest deceleration) as a Markdown table.
//!
//! A run with a collision is a failed run: vehicles overlapped or ran past the end of a lane,
//! so its discharge, lane changes and platoons are not those of physical traffic. Every
//! experiment's `summary.md` (and the report) therefore opens with [`warning_md`] when any run
//! collided, and `summary.csv` counts the failed runs of each cell.

use crate::design::{Cell, Labels};
use crate::runner::Outcome;
use crate::stats::Stats;
use crate::table::{self, md_table, pm};

/// The safety columns: (metric of the summary, column title, decimals).
pub const METRICS: [(&str, &str, usize); 6] = [
    ("emergency_brakings", "Emergency brakings (episodes)", 1),
    ("conflicts", "Conflicts, TTC < TTC* (episodes)", 1),
    ("tet_s", "TET (s)", 1),
    ("tit_s2", "TIT (s²)", 1),
    ("min_ttc_s", "Min TTC (s)", 2),
    ("max_deceleration_mps2", "Max deceleration (m/s²)", 2),
];

/// Whether a run collided. A run file without the field (an older engine) counts as no
/// collision known; such files are not reused by a new build anyway.
pub fn collided(o: &Outcome) -> bool {
    o.fields.get("collisions").is_some_and(|c| c > 0.0)
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

/// The `## Safety` section: one row per cell (cells sharing the `group` labels adjacent, so
/// that a point's baseline and PD rows are side by side), its labels, the runs with
/// collisions, and the mean ± 95 % half-width of each of [`METRICS`]. The minimum TTC is
/// averaged over the runs in which a follower closed in (`n` given when some did not).
pub fn section_md(cells: &[Cell], outcomes: &[Outcome], group: &[&str]) -> String {
    let labels = table::label_columns(cells);
    let mut header: Vec<String> = labels.iter().map(|l| table::label_header(l)).collect();
    header.push("Runs with collisions (runs)".into());
    header.extend(METRICS.iter().map(|m| m.1.to_string()));
    let mut rows = Vec::new();
    for c in grouped(cells, group) {
        let runs = outcomes.iter().filter(|o| o.cell == c).count();
        if runs == 0 {
            continue;
        }
        let mut row: Vec<String> = labels
            .iter()
            .map(|k| cells[c].labels.get(k).unwrap_or("").to_string())
            .collect();
        let bad = collided_runs(outcomes, c);
        row.push(if bad > 0 {
            format!("**{bad} of {runs}** (invalid)")
        } else {
            format!("0 of {runs}")
        });
        for (metric, _, dec) in METRICS {
            let v = table::values(outcomes, c, metric);
            let s = Stats::of(&v);
            let mut text = pm(&s, dec);
            if !v.is_empty() && s.n < runs {
                text.push_str(&format!(" (n = {})", s.n));
            }
            row.push(text);
        }
        rows.push(row);
    }
    format!(
        "## Safety\n\nSurrogate safety measures per cell (definitions in docs/safety.md): mean ± \
         half-width of the 95 % confidence interval over the seeds. Emergency brakings \
         (episodes of braking harder than the normal limit), conflicts (follower-leader \
         episodes with a time to collision below TTC*), time-exposed (TET) and time-integrated \
         (TIT) TTC, and the smallest TTC are measured after the warm-up; the largest \
         deceleration over the whole run. A cell with collisions is invalid.\n\n{}",
        md_table(&header, &rows)
    )
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
}
