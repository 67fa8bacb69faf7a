//! The paper's values (Woo & Skabardonis, "Flow-aware platoon formation of CAVs in mixed
//! traffic"), as data, each with where it comes from. A value belongs to an experiment, a
//! cell (a subset of the cell's labels) and a metric (a run field name).
//!
//! Fig. 4 (capacity vs penetration) is not available as a figure; only the values stated in
//! the text of the Preliminary Study are given. Table 3's values are as printed.

/// One value of the paper.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PaperValue {
    pub experiment: &'static str,
    /// Labels the cell must have.
    pub cell: CellSel,
    pub metric: &'static str,
    pub value: f64,
    pub source: &'static str,
}

const FIG4_TEXT: &str = "Preliminary Study, text on Fig. 4 (approximate, read from prose)";
const TABLE3: &str = "Table 3";

macro_rules! v {
    ($exp:expr, [$($k:expr => $val:expr),*], $metric:expr, $value:expr, $src:expr) => {
        PaperValue {
            experiment: $exp,
            cell: &[$(($k, $val)),*],
            metric: $metric,
            value: $value,
            source: $src,
        }
    };
}

type CellSel = &'static [(&'static str, &'static str)];

/// One row of Table 3: the baseline and PO cells, then LC/veh B, PO; L̄ B, PO; P_P B, PO;
/// Q_B, Q_PO; ΔQ (%).
struct Table3Row {
    b: CellSel,
    po: CellSel,
    v: [f64; 9],
}

const TABLE3_ROWS: [Table3Row; 4] = [
    Table3Row {
        b: &[("demand_vphpl", "1000"), ("strategy", "none")],
        po: &[("demand_vphpl", "1000"), ("strategy", "pd")],
        v: [0.05, 0.49, 2.6, 5.0, 0.73, 0.89, 1006.3, 1006.7, 0.04],
    },
    Table3Row {
        b: &[("demand_vphpl", "1500"), ("strategy", "none")],
        po: &[("demand_vphpl", "1500"), ("strategy", "pd")],
        v: [0.07, 0.51, 3.0, 5.1, 0.74, 0.89, 1483.4, 1478.3, -0.34],
    },
    Table3Row {
        b: &[("demand_vphpl", "2000"), ("strategy", "none")],
        po: &[("demand_vphpl", "2000"), ("strategy", "pd")],
        v: [0.05, 0.53, 2.8, 5.1, 0.74, 0.89, 1961.7, 1924.6, -1.89],
    },
    Table3Row {
        b: &[("demand_vphpl", "2500"), ("strategy", "none")],
        po: &[("demand_vphpl", "2500"), ("strategy", "pd")],
        v: [0.04, 0.56, 3.3, 5.4, 0.78, 0.91, 2260.6, 2045.0, -9.54],
    },
];

/// The capacity experiment's values (Fig. 4, from the text).
pub const CAPACITY: [PaperValue; 3] = [
    v!("capacity", ["stage" => "baseline", "penetration" => "0"], "max_sustained_flow_vphpl", 2000.0, FIG4_TEXT),
    v!("capacity", ["stage" => "pd", "penetration" => "0.25"], "max_sustained_flow_vphpl", 1800.0, FIG4_TEXT),
    v!("capacity", ["stage" => "pd", "penetration" => "0.5"], "max_sustained_flow_vphpl", 2000.0, FIG4_TEXT),
];

/// Every value of the paper used here.
pub fn all() -> Vec<PaperValue> {
    let mut out: Vec<PaperValue> = CAPACITY.to_vec();
    for row in &TABLE3_ROWS {
        let v = row.v;
        let metrics = [
            ("lane_changes_per_vehicle", v[0], v[1]),
            ("avg_platoon_length", v[2], v[3]),
            ("platooning_probability", v[4], v[5]),
            ("discharge_flow_vphpl", v[6], v[7]),
        ];
        for (metric, b, po) in metrics {
            for (cell, value) in [(row.b, b), (row.po, po)] {
                out.push(PaperValue {
                    experiment: "sensitivity",
                    cell,
                    metric,
                    value,
                    source: TABLE3,
                });
            }
        }
        out.push(PaperValue {
            experiment: "sensitivity",
            cell: row.po,
            metric: "discharge_change_pct",
            value: v[8],
            source: TABLE3,
        });
    }
    out
}

/// The paper's value for a cell (by its labels) and metric, if the paper gives one.
pub fn lookup(experiment: &str, labels: &crate::Labels, metric: &str) -> Option<PaperValue> {
    all()
        .into_iter()
        .find(|p| p.experiment == experiment && p.metric == metric && labels.matches(p.cell))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Labels;

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
            .with("penetration", "0.25");
        let v = lookup("capacity", &cap, "max_sustained_flow_vphpl").unwrap();
        assert_eq!(v.value, 1800.0);
        assert!(v.source.contains("Fig. 4"));
        let cap75 = Labels::new()
            .with("stage", "pd")
            .with("penetration", "0.75");
        assert!(lookup("capacity", &cap75, "max_sustained_flow_vphpl").is_none());
        // 3 Fig. 4 values + 4 demands × (4 metrics × 2 strategies + ΔQ).
        assert_eq!(all().len(), 3 + 4 * 9);
    }
}
