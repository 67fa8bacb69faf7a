//! The paper's values (Woo & Skabardonis, "Flow-aware platoon formation of CAVs in mixed
//! traffic"), as data, each with where it comes from. A value belongs to an experiment, a
//! cell (a subset of the cell's labels) and a column (a metric of the runs, or one the
//! experiment derives).
//!
//! Fig. 4 (capacity vs penetration) is not available as a figure; only the values stated in
//! the text of the Preliminary Study are given. Table 3's and Table 4's (SR-99, the appendix
//! table `tab:network_result_v3`) values are as printed, the percentages in parentheses too
//! (they are rounded from the paper's own unrounded results, so they may differ from the
//! printed values' ratio in the last digit).

pub use platoonsim_runs::table::{CellSel, PaperValue};

use crate::table::Col;
use platoonsim_runs::Metric;
use platoonsim_scenario::StrategyKind;

const FIG4_TEXT: &str = "Preliminary Study, text on Fig. 4 (approximate, read from prose)";
const TABLE3: &str = "Table 3";

macro_rules! v {
    ($exp:expr, $kind:expr, [$($k:expr => $val:expr),*], $metric:expr, $value:expr, $src:expr) => {
        PaperValue {
            experiment: $exp,
            cell: CellSel::of($kind, &[$(($k, $val)),*]),
            metric: $metric,
            value: $value,
            source: $src,
        }
    };
}

/// One row of Table 3: the baseline and PO cells, then LC/veh B, PO; L̄ B, PO; P_P B, PO;
/// Q_B, Q_PO; ΔQ (%).
struct Table3Row {
    b: CellSel,
    po: CellSel,
    v: [f64; 9],
}

const TABLE3_ROWS: [Table3Row; 4] = [
    Table3Row {
        b: CellSel::of(StrategyKind::NONE, &[("demand_vphpl", "1000")]),
        po: CellSel::of(StrategyKind::PD, &[("demand_vphpl", "1000")]),
        v: [0.05, 0.49, 2.6, 5.0, 0.73, 0.89, 1006.3, 1006.7, 0.04],
    },
    Table3Row {
        b: CellSel::of(StrategyKind::NONE, &[("demand_vphpl", "1500")]),
        po: CellSel::of(StrategyKind::PD, &[("demand_vphpl", "1500")]),
        v: [0.07, 0.51, 3.0, 5.1, 0.74, 0.89, 1483.4, 1478.3, -0.34],
    },
    Table3Row {
        b: CellSel::of(StrategyKind::NONE, &[("demand_vphpl", "2000")]),
        po: CellSel::of(StrategyKind::PD, &[("demand_vphpl", "2000")]),
        v: [0.05, 0.53, 2.8, 5.1, 0.74, 0.89, 1961.7, 1924.6, -1.89],
    },
    Table3Row {
        b: CellSel::of(StrategyKind::NONE, &[("demand_vphpl", "2500")]),
        po: CellSel::of(StrategyKind::PD, &[("demand_vphpl", "2500")]),
        v: [0.04, 0.56, 3.3, 5.4, 0.78, 0.91, 2260.6, 2045.0, -9.54],
    },
];

/// The capacity experiment's measure: the highest 5-min discharge.
const CAPACITY_METRIC: Col = Col::Metric(Metric::MAX_SUSTAINED_FLOW);

/// The capacity experiment's values (Fig. 4, from the text): the baseline capacity (stage
/// 1) and the PD capacity (stage 2).
pub const CAPACITY: [PaperValue; 3] = [
    v!("capacity", StrategyKind::NONE, ["stage" => "baseline", "penetration" => "0"], CAPACITY_METRIC, 2000.0, FIG4_TEXT),
    v!("capacity", StrategyKind::PD, ["penetration" => "0.25"], CAPACITY_METRIC, 1800.0, FIG4_TEXT),
    v!("capacity", StrategyKind::PD, ["penetration" => "0.5"], CAPACITY_METRIC, 2000.0, FIG4_TEXT),
];

const TABLE4: &str = "Table 4 (SR-99)";

/// One row of Table 4: penetration label, strategy, network discharge (veh/h), lane changes
/// per vehicle, L̄ (NaN: not applicable), and for PD / Flow-Aware PD the changes to the
/// baseline at the same penetration (%).
type Table4Row = (&'static str, StrategyKind, f64, f64, f64, Option<[f64; 3]>);

const TABLE4_ROWS: [Table4Row; 14] = [
    ("0", StrategyKind::NONE, 10675.8, 2.40, f64::NAN, None),
    ("0.2", StrategyKind::NONE, 10687.3, 2.35, 1.87, None),
    (
        "0.2",
        StrategyKind::PD,
        10675.8,
        3.40,
        4.47,
        Some([-0.1, 45.0, 138.9]),
    ),
    (
        "0.2",
        StrategyKind::FLOW_AWARE,
        10687.8,
        2.58,
        2.25,
        Some([0.0, 9.7, 20.0]),
    ),
    ("0.4", StrategyKind::NONE, 11739.8, 2.40, 3.28, None),
    (
        "0.4",
        StrategyKind::PD,
        11402.0,
        4.90,
        6.81,
        Some([-2.9, 103.9, 107.2]),
    ),
    (
        "0.4",
        StrategyKind::FLOW_AWARE,
        11733.8,
        2.93,
        3.94,
        Some([-0.1, 22.0, 20.0]),
    ),
    ("0.6", StrategyKind::NONE, 12449.3, 2.15, 4.27, None),
    (
        "0.6",
        StrategyKind::PD,
        11780.3,
        5.55,
        7.12,
        Some([-5.4, 157.6, 66.6]),
    ),
    (
        "0.6",
        StrategyKind::FLOW_AWARE,
        12446.8,
        3.06,
        4.98,
        Some([0.0, 42.2, 16.6]),
    ),
    ("0.8", StrategyKind::NONE, 13347.0, 2.03, 5.97, None),
    (
        "0.8",
        StrategyKind::PD,
        12378.8,
        5.24,
        7.78,
        Some([-7.3, 157.9, 30.4]),
    ),
    (
        "0.8",
        StrategyKind::FLOW_AWARE,
        13356.8,
        2.66,
        6.47,
        Some([0.1, 30.9, 8.5]),
    ),
    ("1", StrategyKind::NONE, 13069.0, 1.82, 7.55, None),
];

/// The paper's SR-99 demand scales by penetration (Table 4 and the Results text).
pub const SR99_DEMAND_SCALES: [(f64, f64); 6] = [
    (0.0, 1.00),
    (0.2, 1.00),
    (0.4, 1.10),
    (0.6, 1.17),
    (0.8, 1.25),
    (1.0, 1.27),
];

/// The paper's SR-99 demand scale at a penetration (one of its six).
pub fn sr99_demand_scale(penetration: f64) -> Option<f64> {
    SR99_DEMAND_SCALES
        .iter()
        .find(|(p, _)| (p - penetration).abs() < 1e-9)
        .map(|(_, s)| *s)
}

/// The SR-99 values (experiment `sr99`): cells by `penetration` and `strategy`.
fn table4() -> Vec<PaperValue> {
    let mut out = Vec::new();
    for (i, &(_, _, q, lc, lbar, change)) in TABLE4_ROWS.iter().enumerate() {
        let cell = table4_cell(i);
        let mut push = |metric: Col, value: f64| {
            if value.is_finite() {
                out.push(PaperValue {
                    experiment: "sr99",
                    cell,
                    metric,
                    value,
                    source: TABLE4,
                });
            }
        };
        push(Metric::NETWORK_DISCHARGE.into(), q);
        push(Metric::LANE_CHANGES_PER_VEHICLE.into(), lc);
        push(Metric::AVG_PLATOON_LENGTH.into(), lbar);
        if let Some([dq, dlc, dl]) = change {
            push(Col::Derived("discharge_change_pct"), dq);
            push(Col::Derived("lane_changes_change_pct"), dlc);
            push(Col::Derived("platoon_length_change_pct"), dl);
        }
    }
    out
}

/// The cell selector of Table 4's row `i` (static, for [`PaperValue::cell`]).
fn table4_cell(i: usize) -> CellSel {
    const fn sel(i: usize) -> CellSel {
        CellSel::of(TABLE4_ROWS[i].1, &PENETRATIONS[i])
    }
    const PENETRATIONS: [[(&str, &str); 1]; 14] = {
        let mut out = [[("penetration", "")]; 14];
        let mut i = 0;
        while i < 14 {
            out[i] = [("penetration", TABLE4_ROWS[i].0)];
            i += 1;
        }
        out
    };
    const CELLS: [CellSel; 14] = [
        sel(0),
        sel(1),
        sel(2),
        sel(3),
        sel(4),
        sel(5),
        sel(6),
        sel(7),
        sel(8),
        sel(9),
        sel(10),
        sel(11),
        sel(12),
        sel(13),
    ];
    CELLS[i]
}

/// Every value of the paper used here.
pub fn all() -> Vec<PaperValue> {
    let mut out: Vec<PaperValue> = CAPACITY.to_vec();
    out.extend(table4());
    for row in &TABLE3_ROWS {
        let v = row.v;
        let metrics = [
            (Metric::LANE_CHANGES_PER_VEHICLE, v[0], v[1]),
            (Metric::AVG_PLATOON_LENGTH, v[2], v[3]),
            (Metric::PLATOONING_PROBABILITY, v[4], v[5]),
            (Metric::DISCHARGE_FLOW, v[6], v[7]),
        ];
        for (metric, b, po) in metrics {
            for (cell, value) in [(row.b, b), (row.po, po)] {
                out.push(PaperValue {
                    experiment: "sensitivity",
                    cell,
                    metric: metric.into(),
                    value,
                    source: TABLE3,
                });
            }
        }
        out.push(PaperValue {
            experiment: "sensitivity",
            cell: row.po,
            metric: Col::Derived("discharge_change_pct"),
            value: v[8],
            source: TABLE3,
        });
    }
    out
}

/// The paper's value for a cell (by its labels) and metric, if the paper gives one.
pub fn lookup(
    experiment: &str,
    labels: &platoonsim_runs::Labels,
    metric: &str,
) -> Option<PaperValue> {
    all()
        .into_iter()
        .find(|p| p.experiment == experiment && p.metric.name() == metric && p.cell.matches(labels))
}

#[cfg(test)]
mod tests {
    use super::*;
    use platoonsim_runs::Labels;

    #[test]
    fn table3_and_fig4_values_are_found_by_labels() {
        let pd2500 = Labels::new()
            .with("penetration", "0.5")
            .with("demand_vphpl", "2500")
            .with("strategy", "pd");
        assert_eq!(
            lookup("sensitivity", &pd2500, "discharge_change_pct")
                .unwrap()
                .value,
            -9.54
        );
        assert_eq!(
            lookup("sensitivity", &pd2500, "avg_platoon_length")
                .unwrap()
                .value,
            5.4
        );
        assert_eq!(
            lookup("sensitivity", &pd2500, "discharge_flow_vphpl")
                .unwrap()
                .value,
            2045.0
        );
        assert!(lookup("sensitivity", &pd2500, "lane_changes_per_cav").is_none());
        let b1500 = Labels::new()
            .with("demand_vphpl", "1500")
            .with("strategy", "none");
        assert_eq!(
            lookup("sensitivity", &b1500, "lane_changes_per_vehicle")
                .unwrap()
                .value,
            0.07
        );
        assert!(lookup("sensitivity", &b1500, "discharge_change_pct").is_none());
        let cap = Labels::new()
            .with("stage", "pd")
            .with("penetration", "0.25")
            .with("strategy", "pd");
        let v = lookup("capacity", &cap, "max_sustained_flow_vphpl").unwrap();
        assert_eq!(v.value, 1800.0);
        assert!(v.source.contains("Fig. 4"));
        let cap75 = Labels::new()
            .with("stage", "pd")
            .with("penetration", "0.75")
            .with("strategy", "pd");
        assert!(lookup("capacity", &cap75, "max_sustained_flow_vphpl").is_none());
        // 3 Fig. 4 values + 4 demands × (4 metrics × 2 strategies + ΔQ) + Table 4: 14 rows ×
        // 3 (no L̄ at 0 %) + 8 × 3 changes.
        assert_eq!(all().len(), 3 + 4 * 9 + 14 * 3 - 1 + 8 * 3);
    }

    #[test]
    fn table4_values_are_found_by_labels() {
        let l = |p: &str, k: &str| {
            Labels::new()
                .with("penetration", p)
                .with("demand_scale", "1.1")
                .with("strategy", k)
        };
        let get = |p: &str, k: &str, m: &str| lookup("sr99", &l(p, k), m).map(|v| v.value);
        assert_eq!(get("0.4", "none", "network_discharge_vph"), Some(11739.8));
        assert_eq!(get("0.4", "pd", "discharge_change_pct"), Some(-2.9));
        assert_eq!(
            get("0.8", "flow-aware", "platoon_length_change_pct"),
            Some(8.5)
        );
        assert_eq!(get("0.2", "pd", "lane_changes_change_pct"), Some(45.0));
        assert_eq!(get("1", "none", "avg_platoon_length"), Some(7.55));
        assert_eq!(get("0", "none", "avg_platoon_length"), None);
        assert_eq!(get("0.4", "none", "discharge_change_pct"), None);
        assert_eq!(get("0.5", "none", "network_discharge_vph"), None);
        assert!(lookup("sr99", &l("0.6", "pd"), "lane_changes_per_vehicle")
            .unwrap()
            .source
            .contains("Table 4"));
        assert_eq!(sr99_demand_scale(0.6), Some(1.17));
        assert_eq!(sr99_demand_scale(0.5), None);
    }
}
