//! `flow-aware` (issue 3's acceptance test): homogeneous road, 50 % CAV, 2,500 veh/h/lane,
//! baseline vs Flow-Aware (thresholds, radius: the scenario's defaults) vs PD, 60 min with
//! a 20-min warm-up. Per seed pair with the baseline: the discharge change
//! (`discharge_change_pct`) and the L̄ gain (`platoon_length_gain`).

use super::{checks_md, find, run_cells, Check, Done, Experiment, Part, Report, Results, Settings};
use crate::table::Col;
use crate::table::{self, md_table, pm, SummaryRow};
use platoonsim_runs::design::num;
use platoonsim_runs::runner::{Outcome, Runner};
use platoonsim_runs::Metric;
use platoonsim_runs::{Cell, Error};
use platoonsim_scenario::StrategyKind;

pub const PENETRATION: f64 = 0.5;
pub const DEMAND: f64 = 2500.0;
/// The largest discharge loss the Flow-Aware strategy may cause (%).
pub const TOLERANCE_PCT: f64 = 0.5;

const STRATEGIES: [StrategyKind; 3] = [
    StrategyKind::NONE,
    StrategyKind::FLOW_AWARE,
    StrategyKind::PD,
];

pub(super) const EXPERIMENT: Experiment = Experiment {
    name: "flow-aware",
    title: "Flow-Aware strategy on the homogeneous road",
    help: "Baseline vs Flow-Aware vs PD at 50 % CAV and 2500 veh/h/lane.",
    part: Part::Road,
    default_seeds: 10,
    own_period: false,
    safety_group: Some(&[]),
    reuse_from: &[],
    total_runs: |s| s.seeds as usize * super::grid::cell_count(EXPERIMENT.name, SWEEP),
    run,
    report,
    quick: super::unchanged,
};

fn report(r: &Results<'_>) -> Result<Report, Error> {
    let (body, checks) = markdown(r.settings, r.cells, r.outcomes, r.rows);
    Ok(Report {
        body,
        checks,
        ..Report::default()
    })
}

/// The grid: `sweeps/flow-aware.toml`.
pub const SWEEP: &str = include_str!("../../../../sweeps/flow-aware.toml");

pub(super) fn run(s: &Settings, runner: &Runner<'_>, seeds: &[u64]) -> Result<Done, Error> {
    let cells = super::grid::cells(EXPERIMENT.name, SWEEP, s)?;
    let mut outcomes = run_cells(runner, &cells, seeds, 0)?;
    for i in 1..cells.len() {
        table::add_paired(
            &mut outcomes,
            0,
            i,
            Metric::DISCHARGE_FLOW,
            "discharge_change_pct",
            true,
        );
        table::add_paired(
            &mut outcomes,
            0,
            i,
            Metric::AVG_PLATOON_LENGTH,
            "platoon_length_gain",
            false,
        );
    }
    Ok(Done::new(cells, outcomes))
}

pub(super) fn markdown(
    s: &Settings,
    cells: &[Cell],
    _outcomes: &[Outcome],
    rows: &[SummaryRow],
) -> (String, Vec<Check>) {
    let thresholds = cells
        .iter()
        .find_map(|c| c.config.strategy.thresholds.clone());
    let th = thresholds.map_or("?".to_string(), |t| {
        format!(
            "ρ_q = {} veh/h/lane, ρ_v = {} km/h, detectors within {} m",
            num(t.flow_threshold_vphpl),
            num(t.speed_threshold_kmh),
            num(t.radius_m)
        )
    });
    let mut md = format!(
        "Homogeneous road, {} % CAV, {} veh/h/lane, {} s with the first {} s as warm-up. \
         Baseline = no organization; PD = PD lane in the control section after the warm-up; \
         Flow-Aware = the same, only while the detectors nearby report flow below ρ_q and \
         speed above ρ_v ({th}; the scenario's defaults). Changes are per seed pair with the \
         baseline. {} seeds per cell; mean ± half-width of the 95 % confidence interval. The \
         paper has no such table for the homogeneous road.\n\n",
        num(100.0 * PENETRATION),
        num(DEMAND),
        num(s.duration_s),
        num(s.warmup_s),
        s.seeds
    );
    let get = |k: StrategyKind, m: Col| {
        find(cells, &[("strategy", k.as_str())])
            .and_then(|c| rows.iter().find(|r| r.cell == c && r.metric == m.name()))
    };
    let header: Vec<String> = [
        "Strategy",
        "Discharge (veh/h/lane)",
        "Change vs baseline (%)",
        "L̄ (veh)",
        "L̄ gain (veh)",
        "P_P (fraction)",
        "LC/veh (1/veh)",
        "LC/CAV (1/veh)",
        "LC/human (1/veh)",
    ]
    .iter()
    .map(|h| h.to_string())
    .collect();
    let mut trs = Vec::new();
    for k in STRATEGIES {
        let f = |m: Col, dec: usize| get(k, m).map_or("–".into(), |r| pm(&r.stats, dec));
        trs.push(vec![
            match k {
                StrategyKind::NONE => "baseline".into(),
                other => other.as_str().to_string(),
            },
            f(Metric::DISCHARGE_FLOW.into(), 1),
            f(Col::Derived("discharge_change_pct"), 2),
            f(Metric::AVG_PLATOON_LENGTH.into(), 2),
            f(Col::Derived("platoon_length_gain"), 2),
            f(Metric::PLATOONING_PROBABILITY.into(), 3),
            f(Metric::LANE_CHANGES_PER_VEHICLE.into(), 3),
            f(Metric::LANE_CHANGES_PER_CAV.into(), 3),
            f(Metric::LANE_CHANGES_PER_HUMAN.into(), 3),
        ]);
    }
    md.push_str(&md_table(&header, &trs));

    let mut checks = Vec::new();
    if let (Some(dq), Some(gain)) = (
        get(
            StrategyKind::FLOW_AWARE,
            Col::Derived("discharge_change_pct"),
        ),
        get(
            StrategyKind::FLOW_AWARE,
            Col::Derived("platoon_length_gain"),
        ),
    ) {
        checks.push(Check {
            statement: format!(
                "Flow-Aware keeps the discharge within {} % of the baseline: mean change {} % \
                 (95 % CI {})",
                num(TOLERANCE_PCT),
                table::signed(dq.stats.mean, 2),
                table::interval(&dq.stats, 2)
            ),
            passed: dq.stats.mean.abs() <= TOLERANCE_PCT,
        });
        checks.push(Check {
            statement: format!(
                "Flow-Aware raises L̄ above the baseline's: mean gain {} (95 % CI {})",
                table::signed(gain.stats.mean, 2),
                table::interval(&gain.stats, 2)
            ),
            passed: gain.stats.mean > 0.0,
        });
    }
    md.push_str("\n## Checks (the paper's findings)\n\n");
    md.push_str(&checks_md(&checks));
    (md, checks)
}
