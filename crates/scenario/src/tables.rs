//! The tables by CAV penetration that a scenario may name: `network.demand_scale_table` (the
//! default of `network.demand_scale`) and `strategy.thresholds_table` (the default of the
//! Flow-Aware thresholds). Nothing applies a table that the scenario does not name: a corridor
//! of the user's own runs at `demand_scale = 1` and has no Flow-Aware thresholds unless it
//! sets them or names a table (docs/network-scenarios.md, "Demand scale and Flow-Aware
//! thresholds").
//!
//! A reference is the name of a built-in table ([`BUILTIN_TABLES`]) or the path of a table
//! file; as for scenarios, a reference with a path separator or ending in `.toml` is always a
//! path. A relative path is read from the directory of the scenario file that names it (from
//! the current directory for a built-in scenario or text without a file).

use crate::error::TableError;
use crate::{demand_scales, thresholds};
use std::path::{Path, PathBuf};

/// A table shipped inside the binary.
#[derive(Clone, Copy, Debug)]
pub struct BuiltinTable {
    pub name: &'static str,
    /// Its source in the repository (what the calibration experiments' `--write-table`
    /// replaces).
    pub path: &'static str,
    pub text: &'static str,
}

/// The paper's SR-99 demand scales (`network.demand_scale_table`).
pub const SR99_DEMAND_SCALES: &str = "sr99_demand_scales";
/// The Flow-Aware thresholds calibrated on the homogeneous road (`strategy.thresholds_table`).
pub const FLOW_AWARE_THRESHOLDS: &str = "flow_aware_thresholds";
/// The Flow-Aware thresholds calibrated on the SR-99 corridor (`strategy.thresholds_table` of
/// `sr99`).
pub const FLOW_AWARE_THRESHOLDS_SR99: &str = "flow_aware_thresholds_sr99";

/// The built-in tables.
pub const BUILTIN_TABLES: &[BuiltinTable] = &[
    BuiltinTable {
        name: SR99_DEMAND_SCALES,
        path: demand_scales::TABLE_PATH,
        text: demand_scales::TABLE,
    },
    BuiltinTable {
        name: FLOW_AWARE_THRESHOLDS,
        path: thresholds::TABLE_PATH,
        text: thresholds::TABLE,
    },
    BuiltinTable {
        name: FLOW_AWARE_THRESHOLDS_SR99,
        path: thresholds::TABLE_SR99_PATH,
        text: thresholds::TABLE_SR99,
    },
];

/// The built-in names, for messages.
pub fn builtin_names() -> String {
    BUILTIN_TABLES
        .iter()
        .map(|t| t.name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// The text of the table `reference` names: a built-in table, or a file (relative paths from
/// `base_dir`, if given).
pub fn text(reference: &str, base_dir: Option<&Path>) -> Result<String, TableError> {
    let looks_like_path = reference.contains(['/', '\\']) || reference.ends_with(".toml");
    if !looks_like_path {
        return BUILTIN_TABLES
            .iter()
            .find(|t| t.name == reference)
            .map(|t| t.text.to_string())
            .ok_or_else(|| TableError::Unknown {
                name: reference.to_string(),
                builtins: builtin_names(),
            });
    }
    let path = match base_dir {
        Some(dir) if Path::new(reference).is_relative() => dir.join(reference),
        _ => PathBuf::from(reference),
    };
    crate::read_limited(&path).map_err(|e| TableError::Read {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}

/// The demand-scale rows of the table `reference` names; at least one.
pub fn demand_scales(
    reference: &str,
    base_dir: Option<&Path>,
) -> Result<Vec<demand_scales::Row>, TableError> {
    let rows = demand_scales::parse(&text(reference, base_dir)?)?;
    if rows.is_empty() {
        return Err(TableError::NoRow {
            columns: "penetration, demand_scale",
        });
    }
    Ok(rows)
}

/// The Flow-Aware threshold rows of the table `reference` names; at least one.
pub fn thresholds(
    reference: &str,
    base_dir: Option<&Path>,
) -> Result<Vec<thresholds::Row>, TableError> {
    let rows = thresholds::parse(&text(reference, base_dir)?)?;
    if rows.is_empty() {
        return Err(TableError::NoRow {
            columns: "penetration, flow_threshold_vphpl, speed_threshold_kmh",
        });
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_tables_are_found_by_name_and_have_rows() {
        assert_eq!(demand_scales(SR99_DEMAND_SCALES, None).unwrap().len(), 6);
        assert_eq!(thresholds(FLOW_AWARE_THRESHOLDS, None).unwrap().len(), 3);
        let sr99 = thresholds(FLOW_AWARE_THRESHOLDS_SR99, None).unwrap();
        let pens: Vec<f64> = sr99.iter().map(|r| r.penetration).collect();
        assert_eq!(pens, [0.2, 0.4, 0.6, 0.8]);
        assert_eq!(
            (sr99[3].flow_threshold_vphpl, sr99[3].speed_threshold_kmh),
            (1500.0, 97.0)
        );
        let e = thresholds("homogeneous_thresholds", None).unwrap_err();
        assert_eq!(
            e.to_string(),
            "no built-in table 'homogeneous_thresholds' (built-in tables: sr99_demand_scales, \
             flow_aware_thresholds, flow_aware_thresholds_sr99) and not a path (a path contains '/' or ends in .toml)"
        );
    }

    #[test]
    fn a_table_of_the_wrong_kind_has_no_row() {
        let e = thresholds(SR99_DEMAND_SCALES, None).unwrap_err();
        assert_eq!(
            e.to_string(),
            "the table has no feasible row with penetration, flow_threshold_vphpl, \
             speed_threshold_kmh"
        );
    }

    #[test]
    fn relative_paths_are_read_from_the_base_directory() {
        let dir = std::env::temp_dir().join(format!("platoonsim-tables-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(
            dir.join("scales.toml"),
            "[[penetration]]\npenetration = 0.5\ndemand_scale = 1.2\n",
        )
        .unwrap();
        let rows = demand_scales("./scales.toml", Some(&dir)).unwrap();
        assert_eq!(rows[0].demand_scale, 1.2);
        let e = demand_scales("missing.toml", Some(&dir)).unwrap_err();
        assert!(
            e.to_string().starts_with("cannot read ") && e.to_string().contains("missing.toml"),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
