//! Demand scale of a network scenario by CAV penetration (issue 4): the format of the tables
//! that `network.demand_scale_table` names ([`crate::tables`]), and the built-in one of SR-99,
//! `scenarios/sr99_demand_scales.toml` (the paper's values until a calibration replaces them),
//! which `sr99.toml` names. Mirrors [`crate::thresholds`]: [`parse`] reads a table,
//! [`to_toml`] writes one in the same format (for a calibration experiment), [`at`]
//! interpolates.

use toml::Value;

/// The embedded table's text.
pub const TABLE: &str = include_str!("../scenarios/sr99_demand_scales.toml");

/// The embedded table's path in the repository (where a calibrated table is copied).
pub const TABLE_PATH: &str = "crates/scenario/scenarios/sr99_demand_scales.toml";

/// No scaling: the demand scale of a network that names no table.
pub const FALLBACK: f64 = 1.0;

/// One calibrated row.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    pub penetration: f64,
    /// Multiplier on the network's entrance demands (on top of the base multiplier).
    pub demand_scale: f64,
}

/// The feasible rows of a demand-scale file, sorted by penetration. Rows missing a number,
/// with a non-finite one, or with `feasible = false`, are skipped.
pub fn parse(text: &str) -> Result<Vec<Row>, crate::error::TableError> {
    Ok(crate::pen_table::parse(text, ["demand_scale"])?
        .into_iter()
        .map(|(p, [s])| Row {
            penetration: p,
            demand_scale: s,
        })
        .collect())
}

/// A table in the embedded file's format: `header` (each line prefixed with `# `), then one
/// `[[penetration]]` block per row. [`parse`] reads it back.
pub fn to_toml(header: &str, rows: &[Row]) -> String {
    let mut t = String::new();
    for line in header.lines() {
        if line.is_empty() {
            t.push_str("#\n");
        } else {
            t.push_str(&format!("# {line}\n"));
        }
    }
    for r in rows {
        t.push_str(&format!(
            "\n[[penetration]]\npenetration = {}\ndemand_scale = {}\n",
            Value::Float(r.penetration),
            Value::Float(r.demand_scale)
        ));
    }
    t
}

/// The scale at a penetration from rows: linear interpolation, nearest row outside;
/// `fallback` if there is no row.
pub fn at(rows: &[Row], penetration: f64, fallback: f64) -> f64 {
    let table: Vec<(f64, [f64; 1])> = rows
        .iter()
        .map(|r| (r.penetration, [r.demand_scale]))
        .collect();
    crate::pen_table::at(&table, penetration).map_or(fallback, |[s]| s)
}

/// The embedded table's rows.
pub fn embedded() -> Vec<Row> {
    // The embedded table is checked by a test, so a parse error cannot reach users.
    parse(TABLE).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_table_has_the_papers_scales() {
        let rows = parse(TABLE).unwrap();
        let got: Vec<(f64, f64)> = rows
            .iter()
            .map(|r| (r.penetration, r.demand_scale))
            .collect();
        assert_eq!(
            got,
            vec![
                (0.0, 1.0),
                (0.2, 1.0),
                (0.4, 1.1),
                (0.6, 1.17),
                (0.8, 1.25),
                (1.0, 1.27)
            ]
        );
        assert_eq!(at(&rows, 0.0, FALLBACK), 1.0);
        assert_eq!(at(&rows, 1.0, FALLBACK), 1.27);
        assert!((at(&rows, 0.5, FALLBACK) - 1.135).abs() < 1e-12);
        assert!((at(&rows, 0.3, FALLBACK) - 1.05).abs() < 1e-12);
    }

    #[test]
    fn written_tables_read_back_and_interpolate() {
        let rows = vec![
            Row {
                penetration: 0.0,
                demand_scale: 1.0,
            },
            Row {
                penetration: 0.5,
                demand_scale: 1.2,
            },
        ];
        let text = to_toml("Calibrated by a test.\n\nSecond paragraph.", &rows);
        assert!(text.starts_with("# Calibrated by a test.\n#\n# Second paragraph.\n"));
        assert_eq!(parse(&text).unwrap(), rows);
        assert!((at(&rows, 0.25, 9.0) - 1.1).abs() < 1e-12);
        assert_eq!(at(&rows, -1.0, 9.0), 1.0);
        assert_eq!(at(&rows, 0.9, 9.0), 1.2);
        assert_eq!(at(&[], 0.3, 9.0), 9.0);
        let skipped = parse(
            "[[penetration]]\npenetration = 0.5\nfeasible = false\ndemand_scale = 3\n\
             [[penetration]]\npenetration = 1\ndemand_scale = 2\n",
        )
        .unwrap();
        assert_eq!(
            skipped,
            vec![Row {
                penetration: 1.0,
                demand_scale: 2.0
            }]
        );
        assert!(parse("not toml [").is_err());
    }
}
