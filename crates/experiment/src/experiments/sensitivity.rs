//! `sensitivity` (paper Table 3): 50 % CAV, demand 1000/1500/2000/2500 veh/h/lane, baseline
//! (no organization) vs PD lane, 60 min with the first 20 min as warm-up (PD acts after it,
//! in the control section). Metrics after the warm-up: lane changes per vehicle (and per CAV
//! and per human), L̄, P_P, discharge flow, and the relative discharge change
//! ΔQ = 100 (Q_PO − Q_B) / Q_B per seed pair (`discharge_change_pct`, on the PD cells).
//! Beside the paper's two strategies, the dedicated lane (ours; docs/organizers.md) in the
//! same set-up, with its ΔQ against the same baseline.

use super::{
    checks_md, find, metric_label, run_cells, Check, Done, Experiment, Part, Report, Results,
    Settings,
};
use crate::table::Col;
use crate::table::{self, decimals, fixed, md_table, paper_comparison, pm, signed, SummaryRow};
use platoonsim_runs::design::num;
use platoonsim_runs::metric::{Metric as M, Part as Share};
use platoonsim_runs::runner::{Outcome, Runner};
use platoonsim_runs::{Cell, Error};
use platoonsim_scenario::StrategyKind;
use platoonsim_sim::Counted;

pub const DEMANDS: [f64; 4] = [1000.0, 1500.0, 2000.0, 2500.0];
pub const PENETRATION: f64 = 0.5;
/// The baseline first: the others' ΔQ is against it.
pub const STRATEGIES: [StrategyKind; 3] = [
    StrategyKind::NONE,
    StrategyKind::PD,
    StrategyKind::DEDICATED,
];

pub(super) const EXPERIMENT: Experiment = Experiment {
    name: "sensitivity",
    title: "Platoon organization at various demands (paper Table 3)",
    help: "Table 3: baseline vs PD lane at 50 % CAV and 1000-2500 veh/h/lane.",
    part: Part::Road,
    default_seeds: 10,
    own_period: false,
    safety_group: Some(&["demand_vphpl"]),
    reuse_from: &[],
    total_runs: |s| s.seeds as usize * super::grid::cell_count(EXPERIMENT.name, SWEEP),
    run,
    report,
    quick: super::unchanged,
};

fn report(r: &Results<'_>) -> Result<Report, Error> {
    let (body, checks) = markdown(r.settings, r.cells, r.outcomes, r.rows);
    let figures = super::figures::sensitivity(r.dir, r.cells, r.rows, r.settings.preset)?;
    Ok(Report {
        body,
        checks,
        figures,
        ..Report::default()
    })
}

/// The grid: `sweeps/sensitivity.toml`.
pub const SWEEP: &str = include_str!("../../../../sweeps/sensitivity.toml");

pub(super) fn run(s: &Settings, runner: &Runner<'_>, seeds: &[u64]) -> Result<Done, Error> {
    let cells = super::grid::cells(EXPERIMENT.name, SWEEP, s)?;
    let mut outcomes = run_cells(runner, &cells, seeds, 0)?;
    let n = STRATEGIES.len();
    for i in (0..cells.len()).step_by(n) {
        for k in 1..n {
            table::add_paired(
                &mut outcomes,
                i,
                i + k,
                M::DISCHARGE_FLOW,
                "discharge_change_pct",
                true,
            );
            table::add_ratio(
                &mut outcomes,
                i,
                i + k,
                M::AVG_PLATOON_LENGTH,
                "platoon_length_ratio",
            );
            let lanes = f64::from(cells[i].config.road.lanes);
            super::mechanism::add_lane_split(
                &mut outcomes,
                i,
                i + k,
                "discharge_change_pct",
                lanes,
            );
        }
    }
    Ok(Done::new(cells, outcomes))
}

/// The columns this experiment derives (`run`) and the rear-end conflict rate.
const DQ: Col = Col::Derived("discharge_change_pct");
const RATIO: Col = Col::Derived("platoon_length_ratio");
const REAR_END: Col = Col::Metric(M::Counted(Counted::RearEndConflicts, Share::Rate));

/// (column title, metric, strategy) of the paper's Table 3, in its order.
const COLUMNS: [(&str, Col, StrategyKind); 9] = [
    (
        "LC/veh B (1/veh)",
        Col::Metric(M::LANE_CHANGES_PER_VEHICLE),
        StrategyKind::NONE,
    ),
    (
        "LC/veh PO (1/veh)",
        Col::Metric(M::LANE_CHANGES_PER_VEHICLE),
        StrategyKind::PD,
    ),
    (
        "L̄ B (veh)",
        Col::Metric(M::AVG_PLATOON_LENGTH),
        StrategyKind::NONE,
    ),
    (
        "L̄ PO (veh)",
        Col::Metric(M::AVG_PLATOON_LENGTH),
        StrategyKind::PD,
    ),
    (
        "P_P B (fraction)",
        Col::Metric(M::PLATOONING_PROBABILITY),
        StrategyKind::NONE,
    ),
    (
        "P_P PO (fraction)",
        Col::Metric(M::PLATOONING_PROBABILITY),
        StrategyKind::PD,
    ),
    (
        "Q_B (veh/h/lane)",
        Col::Metric(M::DISCHARGE_FLOW),
        StrategyKind::NONE,
    ),
    (
        "Q_PO (veh/h/lane)",
        Col::Metric(M::DISCHARGE_FLOW),
        StrategyKind::PD,
    ),
    ("ΔQ = (Q_PO − Q_B)/Q_B (%)", DQ, StrategyKind::PD),
];

pub(super) fn markdown(
    s: &Settings,
    cells: &[Cell],
    _outcomes: &[Outcome],
    rows: &[SummaryRow],
) -> (String, Vec<Check>) {
    let mut md = format!(
        "Homogeneous road, {} % CAV, {} s with the first {} s as warm-up; B = baseline (no \
         platoon organization), PO = PD lane in the control section after the warm-up. All \
         quantities are measured after the warm-up. {} seeds per cell; ours = mean ± \
         half-width of the 95 % confidence interval (Student t); ΔQ is computed per seed pair \
         (same seed, B and PO) and then averaged. Paper values from its Table 3; difference = \
         ours − paper.\n\n",
        num(100.0 * PENETRATION),
        num(s.duration_s),
        num(s.warmup_s),
        s.seeds
    );
    let row_of = |demand: &str, strategy: StrategyKind, metric: Col| {
        find(
            cells,
            &[("demand_vphpl", demand), ("strategy", strategy.as_str())],
        )
        .and_then(|c| {
            rows.iter()
                .find(|r| r.cell == c && r.metric == metric.name())
        })
    };
    let mut header = vec!["Demand (veh/h/lane)".to_string(), String::new()];
    header.extend(COLUMNS.iter().map(|c| c.0.to_string()));
    let mut trs = Vec::new();
    for &d in &DEMANDS {
        let dem = num(d);
        let mut ours = vec![dem.clone(), "ours".into()];
        let mut paper = vec![String::new(), "paper".into()];
        let mut diff = vec![String::new(), "difference".into()];
        for (_, metric, strategy) in COLUMNS {
            let dec = decimals(&metric.name());
            let r = row_of(&dem, strategy, metric);
            ours.push(r.map_or("–".into(), |r| pm(&r.stats, dec)));
            let p = r.and_then(|r| r.paper);
            paper.push(p.map_or("–".into(), |p| fixed(p.value, dec)));
            diff.push(
                r.filter(|r| r.paper.is_some())
                    .map_or("–".into(), |r| signed(r.difference(), dec)),
            );
        }
        trs.push(ours);
        trs.push(paper);
        trs.push(diff);
    }
    md.push_str(&md_table(&header, &trs));

    md.push_str("\nLane changes by vehicle type (not in the paper; its note says both kinds change lanes more under PO):\n\n");
    let header2: Vec<String> = [
        "Demand (veh/h/lane)",
        "LC/CAV B (1/veh)",
        "LC/CAV PO (1/veh)",
        "LC/human B (1/veh)",
        "LC/human PO (1/veh)",
    ]
    .iter()
    .map(|h| h.to_string())
    .collect();
    let mut trs2 = Vec::new();
    for &d in &DEMANDS {
        let dem = num(d);
        let mut r = vec![dem.clone()];
        for (metric, strategy) in [
            (M::LANE_CHANGES_PER_CAV.into(), StrategyKind::NONE),
            (M::LANE_CHANGES_PER_CAV.into(), StrategyKind::PD),
            (M::LANE_CHANGES_PER_HUMAN.into(), StrategyKind::NONE),
            (M::LANE_CHANGES_PER_HUMAN.into(), StrategyKind::PD),
        ] {
            r.push(row_of(&dem, strategy, metric).map_or("–".into(), |x| pm(&x.stats, 3)));
        }
        trs2.push(r);
    }
    md.push_str(&md_table(&header2, &trs2));

    md.push_str("\n### PD's mechanism\n\n");
    md.push_str(&super::mechanism::legend(
        "the control section (where PD acts)",
    ));
    let keys: Vec<(String, String)> = DEMANDS
        .iter()
        .map(|&d| (num(d), format!("{} veh/h/lane", num(d))))
        .collect();
    md.push_str(&super::mechanism::table(
        &keys,
        StrategyKind::PD,
        DQ,
        true,
        &|k: &str, s, c| row_of(k, s, c),
    ));

    md.push_str(
        "\nThe dedicated lane (ours, not in the paper; docs/organizers.md): the same set-up, the \
         leftmost lane for CAVs only in the control section after the warm-up (human drivers \
         leave it before the zone and do not enter it); ΔQ per seed pair against the same \
         baseline. PO repeated for comparison.\n\n",
    );
    let header3: Vec<String> = [
        "Demand (veh/h/lane)",
        "LC/veh PO (1/veh)",
        "LC/veh DL (1/veh)",
        "L̄ PO (veh)",
        "L̄ DL (veh)",
        "P_P PO (fraction)",
        "P_P DL (fraction)",
        "ΔQ PO (%)",
        "ΔQ DL (%)",
        "rear-end conflicts PO (per 100 veh-km)",
        "rear-end conflicts DL (per 100 veh-km)",
    ]
    .iter()
    .map(|h| h.to_string())
    .collect();
    let mut trs3 = Vec::new();
    for &d in &DEMANDS {
        let dem = num(d);
        let mut r = vec![dem.clone()];
        for metric in [
            M::LANE_CHANGES_PER_VEHICLE.into(),
            M::AVG_PLATOON_LENGTH.into(),
            M::PLATOONING_PROBABILITY.into(),
            DQ,
            REAR_END,
        ] {
            for strategy in [StrategyKind::PD, StrategyKind::DEDICATED] {
                let dec = decimals(&metric.name());
                r.push(row_of(&dem, strategy, metric).map_or("–".into(), |x| pm(&x.stats, dec)));
            }
        }
        trs3.push(r);
    }
    md.push_str(&md_table(&header3, &trs3));

    // Issue 3's targets.
    let mean = |d: f64, st: StrategyKind, m: Col| {
        row_of(&num(d), st, m).map_or(f64::NAN, |r| r.stats.mean)
    };
    let mut checks = Vec::new();
    let ratios: Vec<(f64, f64)> = DEMANDS
        .iter()
        .map(|&d| {
            (
                d,
                mean(d, StrategyKind::PD, M::LANE_CHANGES_PER_VEHICLE.into())
                    / mean(d, StrategyKind::NONE, M::LANE_CHANGES_PER_VEHICLE.into()),
            )
        })
        .collect();
    checks.push(Check {
        statement: format!(
            "PD multiplies lane changes per vehicle by at least 5 at every demand (paper about \
             10): {}",
            ratios
                .iter()
                .map(|(d, r)| format!("×{} at {}", fixed(*r, 1), num(*d)))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        passed: ratios.iter().all(|(_, r)| *r >= 5.0),
    });
    let range_check = |metric: Col, lo: f64, hi: f64, paper: &str| {
        let v: Vec<(f64, f64)> = DEMANDS
            .iter()
            .map(|&d| (d, mean(d, StrategyKind::PD, metric)))
            .collect();
        Check {
            statement: format!(
                "PD raises {} to {}-{} (paper {}): {}",
                metric_label(&metric.name()),
                num(lo),
                num(hi),
                paper,
                v.iter()
                    .map(|(d, x)| format!("{} at {}", fixed(*x, decimals(&metric.name())), num(*d)))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            passed: v.iter().all(|(_, x)| (lo..=hi).contains(x)),
        }
    };
    checks.push(range_check(
        M::AVG_PLATOON_LENGTH.into(),
        4.0,
        6.0,
        "5.0-5.4",
    ));
    // The L̄ gain per seed pair (issue 29): the paper's Table 3 gives ×1.64 to ×1.92.
    let gains: Vec<(f64, f64)> = DEMANDS
        .iter()
        .map(|&d| (d, mean(d, StrategyKind::PD, RATIO)))
        .collect();
    checks.push(Check {
        statement: format!(
            "PD multiplies L̄ by at least 1.5 at every demand (paper ×1.92, ×1.70, ×1.82, ×1.64 \
             from its Table 3): {}",
            gains
                .iter()
                .map(|(d, r)| format!("×{} at {}", fixed(*r, 2), num(*d)))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        passed: gains.iter().all(|(_, r)| *r >= 1.5),
    });
    checks.push(range_check(
        M::PLATOONING_PROBABILITY.into(),
        0.85,
        0.95,
        "0.89-0.91",
    ));
    let dq = |d: f64| mean(d, StrategyKind::PD, DQ);
    checks.push(Check {
        statement: format!(
            "the discharge change is within ±1 % at 1,000 and 1,500 veh/h/lane: {} % and {} % \
             (paper +0.04 % and -0.34 %)",
            signed(dq(1000.0), 2),
            signed(dq(1500.0), 2)
        ),
        passed: dq(1000.0).abs() <= 1.0 && dq(1500.0).abs() <= 1.0,
    });
    checks.push(Check {
        statement: format!(
            "the discharge change is negative at 2,000 veh/h/lane: {} % (paper -1.89 %)",
            signed(dq(2000.0), 2)
        ),
        passed: dq(2000.0) < 0.0,
    });
    checks.push(Check {
        statement: format!(
            "the discharge change is -5 % or lower at 2,500 veh/h/lane: {} % (paper -9.54 %)",
            signed(dq(2500.0), 2)
        ),
        passed: dq(2500.0) <= -5.0,
    });

    let dl: Vec<(f64, f64, f64)> = DEMANDS
        .iter()
        .map(|&d| {
            (
                d,
                mean(d, StrategyKind::DEDICATED, M::AVG_PLATOON_LENGTH.into()),
                mean(d, StrategyKind::NONE, M::AVG_PLATOON_LENGTH.into()),
            )
        })
        .collect();
    checks.push(Check {
        statement: format!(
            "the dedicated lane raises L̄ above the baseline's at every demand (ours): {}",
            dl.iter()
                .map(|(d, x, b)| format!("{} vs {} at {}", fixed(*x, 2), fixed(*b, 2), num(*d)))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        passed: dl.iter().all(|(_, x, b)| x > b),
    });

    md.push_str("\n## Against the paper\n\n");
    md.push_str(&paper_comparison(rows, |r| {
        format!(
            "{}, {} veh/h/lane, {}",
            if r.labels.get("strategy") == Some(StrategyKind::PD.as_str()) {
                "PO"
            } else {
                "B"
            },
            r.labels.get("demand_vphpl").unwrap_or("?"),
            metric_label(&r.metric)
        )
    }));
    md.push_str("\n## Checks (the paper's findings)\n\n");
    md.push_str(&checks_md(&checks));
    (md, checks)
}
