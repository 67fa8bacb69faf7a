//! Flow-Aware thresholds by penetration (issue 3 item 4): the format of the tables that
//! `platoonsim experiment calibrate-flow-aware` writes, and the built-in one calibrated on the
//! homogeneous road (`scenarios/flow_aware_thresholds.toml`) and the one calibrated on the SR-99
//! corridor (`scenarios/flow_aware_thresholds_sr99.toml`). A scenario uses a table only if
//! it names one in `strategy.thresholds_table` ([`crate::tables`]).

/// The embedded table's text.
pub const TABLE: &str = include_str!("../scenarios/flow_aware_thresholds.toml");
/// The embedded table's source in the repository (what `--write-table` replaces).
pub const TABLE_PATH: &str = "crates/scenario/scenarios/flow_aware_thresholds.toml";
/// The table calibrated on the SR-99 corridor (issue 43 item 5, `sweeps/flow-aware-sr99.toml`).
pub const TABLE_SR99: &str = include_str!("../scenarios/flow_aware_thresholds_sr99.toml");
/// Its source in the repository.
pub const TABLE_SR99_PATH: &str = "crates/scenario/scenarios/flow_aware_thresholds_sr99.toml";

/// One calibrated row.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    pub penetration: f64,
    pub flow_threshold_vphpl: f64,
    pub speed_threshold_kmh: f64,
}

/// The value columns of a thresholds file.
const COLUMNS: [&str; 2] = ["flow_threshold_vphpl", "speed_threshold_kmh"];

/// The feasible rows of a thresholds file, sorted by penetration. Rows missing a number, or
/// with `feasible = false`, are skipped.
pub fn parse(text: &str) -> Result<Vec<Row>, crate::error::TableError> {
    Ok(crate::pen_table::parse(text, COLUMNS)?
        .into_iter()
        .map(|(p, [q, v])| Row {
            penetration: p,
            flow_threshold_vphpl: q,
            speed_threshold_kmh: v,
        })
        .collect())
}

/// (ρ_q, ρ_v) at a penetration from rows: linear interpolation, nearest row outside;
/// `fallback` if there is no row.
pub fn at(rows: &[Row], penetration: f64, fallback: (f64, f64)) -> (f64, f64) {
    let table: Vec<(f64, [f64; 2])> = rows
        .iter()
        .map(|r| {
            (
                r.penetration,
                [r.flow_threshold_vphpl, r.speed_threshold_kmh],
            )
        })
        .collect();
    crate::pen_table::at(&table, penetration).map_or(fallback, |[q, v]| (q, v))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_table_parses_and_has_rows() {
        assert_eq!(parse(TABLE).unwrap().len(), 3);
        assert_eq!(at(&parse(TABLE).unwrap(), 0.5, (0.0, 0.0)), (2750.0, 97.0));
    }

    #[test]
    fn interpolates_between_rows_and_holds_outside() {
        let rows = parse(
            "[[penetration]]\npenetration = 0.25\nflow_threshold_vphpl = 1000\nspeed_threshold_kmh = 80\n\
             [[penetration]]\npenetration = 0.75\nfeasible = true\nflow_threshold_vphpl = 2000\nspeed_threshold_kmh = 100\n\
             [[penetration]]\npenetration = 0.5\nfeasible = false\nflow_threshold_vphpl = 9\nspeed_threshold_kmh = 9\n",
        )
        .unwrap();
        assert_eq!(rows.len(), 2);
        assert_eq!(at(&rows, 0.5, (0.0, 0.0)), (1500.0, 90.0));
        assert_eq!(at(&rows, 0.0, (0.0, 0.0)), (1000.0, 80.0));
        assert_eq!(at(&rows, 1.0, (0.0, 0.0)), (2000.0, 100.0));
        assert_eq!(at(&[], 0.3, (1800.0, 90.0)), (1800.0, 90.0));
    }
}
