//! PD's mechanism in the reports (issue 43 item 4): the engine's mechanism measures
//! (`measurement.mechanism`, docs/outputs.md) of Table 3's and Table 4's runs, baseline beside
//! the organizing strategy, and on the plain road the discharge change split by lane.
//!
//! The split, per seed pair (same seed, baseline B and strategy PO), with Q the measurement
//! detector's flow over the window (veh/h), n its lanes and q_o the organized lane's flow:
//!
//! ```text
//! ΔQ (%) = 100 (Q_PO − Q_B) / Q_B = 100 (q_o,PO − q_o,B) / Q_B + the other lanes' part
//! Q_B    = n · discharge_flow_vphpl(B)
//! ```

use crate::table::{fixed, md_table, pm, Col, SummaryRow};
use platoonsim_runs::metric::{MechanismField as F, Metric as M};
use platoonsim_runs::runner::Outcome;
use platoonsim_scenario::StrategyKind;

/// The organized lane's part of ΔQ (%), per seed pair.
pub const DQ_ORGANIZED: Col = Col::Derived("discharge_change_organized_lane_pct");
/// The other lanes' part of ΔQ (%), per seed pair.
pub const DQ_OTHERS: Col = Col::Derived("discharge_change_other_lanes_pct");

const WAIT_SHARE: Col = Col::Metric(M::Mechanism(F::CavWaitShare));
const WAIT: Col = Col::Metric(M::Mechanism(F::CavWait));
const CHANGES: Col = Col::Metric(M::Mechanism(F::SectionLaneChanges));
const DISTURBED: Col = Col::Metric(M::Mechanism(F::DisturbedFollowers));
const LC_PER_CAV: Col = Col::Metric(M::Mechanism(F::SectionLaneChangesPerCav));
const NEED: Col = Col::Metric(M::Mechanism(F::LaneNeedPerCav));

/// Add [`DQ_ORGANIZED`] and [`DQ_OTHERS`] to the runs of `cell` against those of `base` with
/// the same seed; `dq` is the cell's ΔQ (%) column, `lanes` the measurement detector's lanes.
/// NaN where a partner or a measure is missing (runs without `measurement.mechanism`).
pub fn add_lane_split(outcomes: &mut [Outcome], base: usize, cell: usize, dq: &str, lanes: f64) {
    let org = M::Mechanism(F::OrganizedLaneDischarge);
    let reference: Vec<(u64, Option<f64>, Option<f64>)> = outcomes
        .iter()
        .filter(|o| o.cell == base)
        .map(|o| {
            (
                o.seed,
                o.fields.metric(org),
                o.fields.metric(M::DISCHARGE_FLOW),
            )
        })
        .collect();
    for o in outcomes.iter_mut().filter(|o| o.cell == cell) {
        let b = reference.iter().find(|r| r.0 == o.seed);
        let (part, rest) = match (b, o.fields.metric(org), o.fields.get(dq)) {
            (Some(&(_, Some(org_b), Some(q_b))), Some(org_x), Some(dq)) if q_b > 0.0 => {
                let part = 100.0 * (org_x - org_b) / (lanes * q_b);
                (part, dq - part)
            }
            _ => (f64::NAN, f64::NAN),
        };
        o.fields.set(&DQ_ORGANIZED.name(), part);
        o.fields.set(&DQ_OTHERS.name(), rest);
    }
}

/// The report's table: one row per `(key, label)`, `row(key, strategy, column)` finding the
/// summary row; `po` the organizing strategy; `dq` its ΔQ column, split by lane if `split`.
pub fn table<'a>(
    keys: &[(String, String)],
    po: StrategyKind,
    dq: Col,
    split: bool,
    row: &dyn Fn(&str, StrategyKind, Col) -> Option<&'a SummaryRow>,
) -> String {
    let mean = |k: &str, s, c| row(k, s, c).map_or(f64::NAN, |r| r.stats.mean);
    let cell = |k: &str, s, c, dec| row(k, s, c).map_or("–".into(), |r| pm(&r.stats, dec));
    let both = |k: &str, c, dec| {
        format!(
            "{} → {}",
            fixed(mean(k, StrategyKind::NONE, c), dec),
            fixed(mean(k, po, c), dec)
        )
    };
    let mut header: Vec<String> = vec!["".into(), "ΔQ (%)".into()];
    if split {
        header.push("of which the organized lane / the others (%)".into());
    }
    header.extend(
        [
            "CAVs waiting for a gap: share of the section's veh-s, B → PO",
            "CAVs waiting (veh-s per h), PO",
            "lane changes in the section (per h), B → PO",
            "new followers braking beyond 2 m/s² within 5 s (per h), B → PO",
            "LC per CAV in the section / lanes to the organized lane, PO",
        ]
        .map(String::from),
    );
    let rows: Vec<Vec<String>> = keys
        .iter()
        .map(|(k, label)| {
            let mut r = vec![label.clone(), cell(k, po, dq, 2)];
            if split {
                r.push(format!(
                    "{} / {}",
                    fixed(mean(k, po, DQ_ORGANIZED), 2),
                    fixed(mean(k, po, DQ_OTHERS), 2)
                ));
            }
            r.push(both(k, WAIT_SHARE, 3));
            r.push(fixed(mean(k, po, WAIT), 0));
            r.push(both(k, CHANGES, 0));
            r.push(both(k, DISTURBED, 0));
            r.push(format!(
                "{} / {}",
                fixed(mean(k, po, LC_PER_CAV), 2),
                fixed(mean(k, po, NEED), 2)
            ));
            r
        })
        .collect();
    md_table(&header, &rows)
}

/// The paragraph that says what the table's columns are.
pub fn legend(section: &str) -> String {
    format!(
        "Where the organizing strategy's discharge change comes from (the engine's mechanism \
         measures, `measurement.mechanism`, docs/outputs.md), over {section} in the \
         measurement window, means over the seeds: the share of the vehicle-seconds in the \
         section spent by CAVs waiting for a gap (in a `blc` mode), the lane changes made in \
         it, the new followers of those changes that brake beyond 2 m/s² within 5 s, and the \
         CAVs' lane changes in the section beside the lanes between their lane where they \
         entered it and the organized lane. B = baseline, PO = the organizing strategy.\n\n"
    )
}
