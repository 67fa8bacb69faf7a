//! `capacity` (paper Fig. 4). Stage 1, the baseline capacity: for each penetration, a demand
//! well above capacity (a queue forms at the entrance), no organization, no warm-up;
//! capacity = the highest 5-min discharge at the measurement detector over the run. Stage 2,
//! the PD bottleneck capacity (25-100 %; PD does not apply without CAVs): demand = the
//! stage-1 mean capacity of that penetration (rounded to 1 veh/h/lane), warm-up, then PD in
//! the control section to the end; capacity = the highest 5-min discharge after the warm-up.
//!
//! Stage 3 (ours, not in the paper): the dedicated lane (docs/organizers.md) as stage 2, at
//! the same input demand.
//!
//! All stages also report the mean queue discharge (`discharge_flow_vphpl`): stage 1 over
//! the run less its first interval, in which the empty road fills ([`FILL_S`]; that interval
//! is never the highest, so the capacity is the same as over the whole run), stage 2 after
//! the warm-up. The highest of several 5-min flows lies further above the mean the more the
//! flow fluctuates, and a PD queue discharges much less evenly than the entrance queue of
//! stage 1, so the two measures can order a PD cell and a baseline differently.

use super::{
    checks_md, find, grid, run_cells, Check, Done, Experiment, Part, Report, Results, Settings,
};
use crate::table::{self, fixed, md_table, paper_comparison, pm, signed, SummaryRow};
use platoonsim_runs::design::num;
use platoonsim_runs::runner::{Outcome, Runner};
use platoonsim_runs::sweep::spec::{Axis, Spec};
use platoonsim_runs::Metric;
use platoonsim_runs::{Cell, Error};
use platoonsim_scenario::StrategyKind;
use toml::Value;

pub const PENETRATIONS: [f64; 5] = [0.0, 0.25, 0.5, 0.75, 1.0];
const CAPACITY: Metric = Metric::MAX_SUSTAINED_FLOW;
const DISCHARGE: Metric = Metric::DISCHARGE_FLOW;
/// Stage 1 measures from the end of the first aggregation interval: the road is empty at the
/// start, and the first vehicles reach the discharge detector (6.1 km) after about 220 s.
pub const FILL_S: f64 = 300.0;

pub(super) const EXPERIMENT: Experiment = Experiment {
    name: "capacity",
    title: "Capacity with and without the PD lane (paper Fig. 4)",
    help: "Fig. 4: baseline capacity (demand above capacity) and PD bottleneck capacity at 0-100 % CAV.",
    part: Part::Road,
    default_seeds: 10,
    own_period: false,
    safety_group: Some(&["penetration"]),
    reuse_from: &[],
    // Stage 1, and stage 2's two strategies at every penetration but 0.
    total_runs: |s| {
        let n = grid::cell_count(EXPERIMENT.name, SWEEP);
        s.seeds as usize * (3 * n).saturating_sub(2)
    },
    run,
    report,
    quick: super::unchanged,
};

fn report(r: &Results<'_>) -> Result<Report, Error> {
    let (body, checks) = markdown(r.settings, r.cells, r.outcomes, r.rows);
    let figures = super::figures::capacity(r.dir, r.cells, r.rows, r.settings.preset)?;
    Ok(Report {
        body,
        checks,
        figures,
        ..Report::default()
    })
}

/// Stage 1: `sweeps/capacity.toml` at the settings' demand and duration, measured from
/// [`FILL_S`].
pub const SWEEP: &str = include_str!("../../../../sweeps/capacity.toml");

pub(super) fn stage1(s: &Settings) -> Result<Spec, Error> {
    let mut spec = grid::spec(EXPERIMENT.name, SWEEP, s)?;
    grid::fix(
        &mut spec,
        "demand.vph_per_lane",
        grid::float(s.capacity_demand_vphpl),
    );
    grid::fix(
        &mut spec,
        "run.warmup_s",
        grid::float(FILL_S.min(s.duration_s)),
    );
    Ok(spec)
}

/// Stage 2 from stage 1's spec: the PD lane and the dedicated lane (outer) at each
/// penetration with CAVs and its capacity (a bundle), with the settings' warm-up.
fn stage2(s: &Settings, points: Vec<(f64, f64)>) -> Result<Spec, Error> {
    let mut spec = grid::spec(EXPERIMENT.name, SWEEP, s)?;
    spec.set
        .retain(|(k, _)| k != "demand.vph_per_lane" && k != "strategy.kind");
    let kinds = [StrategyKind::PD, StrategyKind::DEDICATED];
    spec.axes = vec![
        Axis::plain(
            "strategy.kind",
            kinds.iter().map(|k| Value::from(k.as_str())).collect(),
        ),
        Axis::bundle(
            "point",
            points
                .into_iter()
                .map(|(p, demand)| {
                    vec![
                        ("run.penetration", grid::float(p)),
                        ("demand.vph_per_lane", grid::float(demand)),
                    ]
                })
                .collect(),
        ),
    ];
    Ok(spec)
}

/// The cells of a stage, labelled by it first (`baseline`, or the strategy).
fn staged(spec: &Spec, stage: Option<&str>) -> Result<Vec<Cell>, Error> {
    let mut cells = grid::cells_of(spec)?;
    for c in &mut cells {
        let name = stage.or(c.labels.get("strategy")).unwrap_or("").to_string();
        c.labels.0.insert(0, ("stage".into(), name));
    }
    Ok(cells)
}

pub(super) fn run(s: &Settings, runner: &Runner<'_>, seeds: &[u64]) -> Result<Done, Error> {
    let stage1 = staged(&stage1(s)?, Some("baseline"))?;
    let mut outcomes = run_cells(runner, &stage1, seeds, 0)?;

    // PD does not apply without CAVs.
    let mut points = Vec::new();
    for (i, c) in stage1.iter().enumerate() {
        let p = c.config.penetration;
        if p <= 0.0 {
            continue;
        }
        let cap = table::stats(&outcomes, i, &CAPACITY).mean;
        if !(cap.is_finite() && cap > 0.0) {
            return Err(Error::Other(format!(
                "capacity: no baseline capacity at penetration {p} (stage 1 gave {cap})"
            )));
        }
        points.push((p, cap.round()));
    }
    let stage2 = staged(&stage2(s, points)?, None)?;
    outcomes.extend(run_cells(runner, &stage2, seeds, stage1.len())?);
    let mut cells = stage1;
    cells.extend(stage2);
    Ok(Done::new(cells, outcomes))
}

/// The cell of a strategy (stage 1: none) at a penetration (as its label).
pub(super) fn at(cells: &[Cell], k: StrategyKind, penetration: &str) -> Option<usize> {
    find(
        cells,
        &[("strategy", k.as_str()), ("penetration", penetration)],
    )
}

pub(super) fn markdown(
    s: &Settings,
    cells: &[Cell],
    _outcomes: &[Outcome],
    rows: &[SummaryRow],
) -> (String, Vec<Check>) {
    let mut md = format!(
        "Homogeneous road (3 lanes, 5 km approach, 1 km control section). Stage 1 (baseline): \
         demand {} veh/h/lane, above capacity so that a queue forms at the entrance, no \
         platoon organization, {} s; capacity = highest 5-min flow at the discharge detector. \
         Stage 2 (PD): demand = the stage-1 mean capacity at that penetration, {} s warm-up, \
         then the PD lane in the control section to the end ({} s); capacity = highest 5-min \
         flow after the warm-up. Mean discharge = the mean flow at the same detector over the \
         same window (stage 1 without its first {} s, in which the empty road fills). {} seeds \
         per cell; ours = mean ± half-width of the 95 % \
         confidence interval (Student t). The paper gives Fig. 4 only as a figure; the values \
         below are those stated in its text (≈), the others are blank.\n\n",
        num(s.capacity_demand_vphpl),
        num(s.duration_s),
        num(s.warmup_s),
        num(s.duration_s),
        num(FILL_S),
        s.seeds
    );
    let header: Vec<String> = [
        "CAV penetration (%)",
        "Baseline capacity, ours (veh/h/lane)",
        "paper (veh/h/lane)",
        "difference (veh/h/lane)",
        "PD input demand (veh/h/lane)",
        "PD capacity, ours (veh/h/lane)",
        "paper (veh/h/lane)",
        "difference (veh/h/lane)",
        "PD vs baseline (%)",
        "Dedicated-lane capacity, ours (veh/h/lane)",
        "dedicated vs baseline (%)",
        "Baseline mean discharge (veh/h/lane)",
        "PD mean discharge (veh/h/lane)",
        "Dedicated mean discharge (veh/h/lane)",
    ]
    .iter()
    .map(|h| h.to_string())
    .collect();
    let mut table_rows = Vec::new();
    let mut checks = Vec::new();
    let mut below = Vec::new();
    let row_of = |cell: usize| {
        rows.iter()
            .find(|r| r.cell == cell && r.metric == CAPACITY.name())
    };
    let mean_of = |cell: usize| {
        rows.iter()
            .find(|r| r.cell == cell && r.metric == DISCHARGE.name())
    };
    let base0 = at(cells, StrategyKind::NONE, "0");
    let cap0 = base0.and_then(row_of).map(|r| r.stats);
    let mean0 = base0.and_then(mean_of).map(|r| r.stats);
    for &p in &PENETRATIONS {
        let pen = num(p);
        let b_cell = at(cells, StrategyKind::NONE, &pen);
        let b = b_cell.and_then(row_of);
        let pd_cell = at(cells, StrategyKind::PD, &pen);
        let pd = pd_cell.and_then(row_of);
        let mean = |c: Option<usize>| {
            c.and_then(mean_of)
                .map_or("–".to_string(), |r| pm(&r.stats, 0))
        };
        let paper = |r: Option<&SummaryRow>| {
            r.and_then(|r| r.paper)
                .map_or(String::new(), |v| format!("≈{}", fixed(v.value, 0)))
        };
        let diff = |r: Option<&SummaryRow>| {
            r.filter(|r| r.paper.is_some())
                .map_or(String::new(), |r| signed(r.difference(), 0))
        };
        let input = pd_cell.map_or("– (PD needs CAVs)".to_string(), |c| {
            format!("{:.0}", cells[c].config.demand.vph_per_lane)
        });
        let versus = match (b, pd) {
            (Some(b), Some(pd)) => {
                let rel = 100.0 * (pd.stats.mean - b.stats.mean) / b.stats.mean;
                below.push((p, pd.stats.mean < b.stats.mean, rel));
                format!("{} %", signed(rel, 1))
            }
            _ => String::new(),
        };
        let dl_cell = at(cells, StrategyKind::DEDICATED, &pen);
        let dl = dl_cell.and_then(row_of);
        let dl_versus = match (b, dl) {
            (Some(b), Some(dl)) => format!(
                "{} %",
                signed(100.0 * (dl.stats.mean - b.stats.mean) / b.stats.mean, 1)
            ),
            _ => String::new(),
        };
        table_rows.push(vec![
            format!("{} %", num(100.0 * p)),
            b.map_or("–".into(), |r| pm(&r.stats, 0)),
            paper(b),
            diff(b),
            input,
            pd.map_or("–".into(), |r| pm(&r.stats, 0)),
            paper(pd),
            diff(pd),
            versus,
            dl.map_or("–".into(), |r| pm(&r.stats, 0)),
            dl_versus,
            mean(b_cell),
            mean(pd_cell),
            mean(dl_cell),
        ]);
    }
    md.push_str("Capacity in veh/h/lane.\n\n");
    md.push_str(&md_table(&header, &table_rows));

    if !below.is_empty() {
        let all = below.iter().all(|(_, b, _)| *b);
        let list: Vec<String> = below
            .iter()
            .map(|(p, _, rel)| format!("{} % at {} % CAV", signed(*rel, 1), num(100.0 * p)))
            .collect();
        checks.push(Check {
            statement: format!(
                "the PD capacity is below the baseline capacity wherever PD applies ({})",
                list.join(", ")
            ),
            passed: all,
        });
    }
    let pd25 = at(cells, StrategyKind::PD, "0.25")
        .and_then(row_of)
        .map(|r| r.stats);
    if let (Some(pd25), Some(cap0)) = (pd25, cap0) {
        checks.push(Check {
            statement: format!(
                "the PD capacity at 25 % CAV ({:.0} veh/h/lane) is below the baseline capacity \
                 at 0 % ({:.0}); paper ≈1,800 vs ≈2,000",
                pd25.mean, cap0.mean
            ),
            passed: pd25.mean < cap0.mean,
        });
    }
    let pd25_mean = at(cells, StrategyKind::PD, "0.25")
        .and_then(mean_of)
        .map(|r| r.stats);
    if let (Some(pd), Some(b)) = (pd25_mean, mean0) {
        md.push_str(&format!(
            "\nWith the mean discharge instead of the highest 5-min flow, the PD lane at 25 % \
             CAV discharges {} veh/h/lane against {} at 0 % CAV ({} %). The highest 5-min flow \
             is further above the mean for the PD queue, whose discharge fluctuates, than for \
             the steady entrance queue of the baseline.\n",
            pm(&pd, 0),
            pm(&b, 0),
            signed(100.0 * (pd.mean - b.mean) / b.mean, 1)
        ));
    }
    md.push_str("\n## Against the paper\n\n");
    md.push_str(&paper_comparison(rows, |r| {
        let stage = match r.labels.get("strategy").and_then(|k| k.parse().ok()) {
            Some(StrategyKind::PD) => "PD capacity",
            Some(StrategyKind::DEDICATED) => "dedicated-lane capacity",
            _ => "baseline capacity",
        };
        format!(
            "{stage} at {} % CAV",
            num(100.0
                * r.labels
                    .get("penetration")
                    .and_then(|p| p.parse::<f64>().ok())
                    .unwrap_or(f64::NAN))
        )
    }));
    md.push_str("\n## Checks (the paper's findings)\n\n");
    md.push_str(&checks_md(&checks));
    (md, checks)
}
