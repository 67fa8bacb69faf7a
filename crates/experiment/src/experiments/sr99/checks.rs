//! The checks of the `sr99` experiment's report: the paper's findings on Table 4 over the
//! penetrations run with all three strategies, and that no run had a stopped mainline section.

use super::*;

/// The paper's findings on Table 4, over the penetrations run with all three strategies.
pub(super) fn checks(cells: &[Cell], rows: &[SummaryRow], mid: &[f64]) -> Vec<Check> {
    if mid.is_empty() {
        return Vec::new();
    }
    let mean = |p: f64, k: StrategyKind, m: Col| {
        row(cells, rows, &num(p), k, m).map_or(f64::NAN, |r| r.stats.mean)
    };
    let list = |k: StrategyKind, m: Col| -> (Vec<f64>, String) {
        let v: Vec<f64> = mid.iter().map(|&p| mean(p, k, m)).collect();
        let text = v
            .iter()
            .zip(mid)
            .map(|(x, p)| format!("{} % at {} %", signed(*x, 1), num(100.0 * p)))
            .collect::<Vec<_>>()
            .join(", ");
        (v, text)
    };
    let pens = mid
        .iter()
        .map(|p| num(100.0 * p))
        .collect::<Vec<_>>()
        .join("/");
    let mut out = Vec::new();
    let (dq_pd, t) = list(StrategyKind::PD, Col::Derived("discharge_change_pct"));
    out.push(Check {
        statement: format!(
            "the PD lane lowers the network discharge at {pens} % CAV (paper: −0.1 to −7.3 %): {t}"
        ),
        passed: dq_pd.iter().all(|x| *x < 0.0),
    });
    let (dq_fa, t) = list(
        StrategyKind::FLOW_AWARE,
        Col::Derived("discharge_change_pct"),
    );
    out.push(Check {
        statement: format!(
            "the Flow-Aware PD lane keeps the network discharge within 0.5 % of the baseline at \
             {pens} % CAV (paper: within 0.1 %): {t}"
        ),
        passed: dq_fa.iter().all(|x| x.abs() <= 0.5),
    });
    let (dl_fa, t) = list(
        StrategyKind::FLOW_AWARE,
        Col::Derived("platoon_length_change_pct"),
    );
    out.push(Check {
        statement: format!(
            "the Flow-Aware PD lane raises L̄ above the baseline at {pens} % CAV (paper: +8.5 to \
             +20 %): {t}"
        ),
        passed: dl_fa.iter().all(|x| *x > 0.0),
    });
    let ordered = mid.iter().all(|&p| {
        let (b, pd, fa) = (
            mean(
                p,
                StrategyKind::NONE,
                Metric::LANE_CHANGES_PER_VEHICLE.into(),
            ),
            mean(p, StrategyKind::PD, Metric::LANE_CHANGES_PER_VEHICLE.into()),
            mean(
                p,
                StrategyKind::FLOW_AWARE,
                Metric::LANE_CHANGES_PER_VEHICLE.into(),
            ),
        );
        pd > fa && fa > b
    });
    out.push(Check {
        statement: format!(
            "lane changes per vehicle: PD > Flow-Aware PD > baseline at {pens} % CAV (as in the \
             paper)"
        ),
        passed: ordered,
    });
    out.push(stopped_sections(rows));
    out
}

/// No run has a stopped mainline section: an aggregation interval in which a mainline
/// detector counted no vehicle (a deadlock, or a queue standing for a whole interval).
fn stopped_sections(rows: &[SummaryRow]) -> Check {
    let name = Metric::Field(Field::ZeroFlowIntervals).name();
    let mut runs = 0usize;
    let mut stopped = Vec::new();
    for r in rows.iter().filter(|r| r.metric == name) {
        runs += r.stats.n;
        if r.stats.mean > 0.0 {
            let what = r
                .labels
                .0
                .iter()
                .map(|(k, v)| format!("{k} {v}"))
                .collect::<Vec<_>>()
                .join(", ");
            stopped.push(format!(
                "{what}: {} intervals over {} runs",
                fixed(r.stats.mean * r.stats.n as f64, 0),
                r.stats.n
            ));
        }
    }
    let found = if stopped.is_empty() {
        format!("none in {runs} runs")
    } else {
        stopped.join("; ")
    };
    Check {
        statement: format!(
            "no mainline detector counts zero vehicles in a 5-min interval of the measurement \
             window (a stopped section, e.g. a mutual wait): {found}"
        ),
        passed: stopped.is_empty(),
    }
}
