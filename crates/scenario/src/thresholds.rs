//! Default Flow-Aware thresholds by penetration (issue 3 item 4), read from the embedded
//! `scenarios/flow_aware_thresholds.toml` that `platoonsim experiment calibrate-flow-aware`
//! produces.

use toml::Value;

const TABLE: &str = include_str!("../scenarios/flow_aware_thresholds.toml");

/// One calibrated row.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    pub penetration: f64,
    pub flow_threshold_vphpl: f64,
    pub speed_threshold_kmh: f64,
}

/// The feasible rows of a thresholds file, sorted by penetration. Rows missing a number, or
/// with `feasible = false`, are skipped.
pub fn parse(text: &str) -> Result<Vec<Row>, String> {
    let doc: toml::Table = text.parse().map_err(|e| format!("{e}"))?;
    let mut rows = Vec::new();
    let Some(list) = doc.get("penetration").and_then(Value::as_array) else {
        return Ok(rows);
    };
    let num = |t: &toml::Table, k: &str| {
        t.get(k)
            .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
            .filter(|x| x.is_finite())
    };
    for t in list.iter().filter_map(Value::as_table) {
        if t.get("feasible").and_then(Value::as_bool) == Some(false) {
            continue;
        }
        if let (Some(p), Some(q), Some(v)) = (
            num(t, "penetration"),
            num(t, "flow_threshold_vphpl"),
            num(t, "speed_threshold_kmh"),
        ) {
            rows.push(Row {
                penetration: p,
                flow_threshold_vphpl: q,
                speed_threshold_kmh: v,
            });
        }
    }
    rows.sort_by(|a, b| a.penetration.total_cmp(&b.penetration));
    Ok(rows)
}

/// (ρ_q, ρ_v) at a penetration from rows: linear interpolation, nearest row outside;
/// `fallback` if there is no row.
pub fn at(rows: &[Row], penetration: f64, fallback: (f64, f64)) -> (f64, f64) {
    let (Some(first), Some(last)) = (rows.first(), rows.last()) else {
        return fallback;
    };
    if penetration <= first.penetration {
        return (first.flow_threshold_vphpl, first.speed_threshold_kmh);
    }
    if penetration >= last.penetration {
        return (last.flow_threshold_vphpl, last.speed_threshold_kmh);
    }
    for w in rows.windows(2) {
        let (a, b) = (w[0], w[1]);
        if penetration <= b.penetration {
            let f = (penetration - a.penetration) / (b.penetration - a.penetration);
            return (
                a.flow_threshold_vphpl + f * (b.flow_threshold_vphpl - a.flow_threshold_vphpl),
                a.speed_threshold_kmh + f * (b.speed_threshold_kmh - a.speed_threshold_kmh),
            );
        }
    }
    (last.flow_threshold_vphpl, last.speed_threshold_kmh)
}

/// The built-in defaults at a penetration.
pub fn default_at(penetration: f64, fallback: (f64, f64)) -> (f64, f64) {
    // The embedded table is checked by a test, so a parse error cannot reach users.
    at(&parse(TABLE).unwrap_or_default(), penetration, fallback)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_table_parses_and_has_rows() {
        assert!(!parse(TABLE).unwrap().is_empty());
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
