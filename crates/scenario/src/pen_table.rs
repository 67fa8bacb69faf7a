//! Tables of values by CAV penetration, shared by the Flow-Aware thresholds
//! ([`crate::thresholds`]) and the network demand scales ([`crate::demand_scales`]): a TOML
//! file of `[[penetration]]` blocks, each with `penetration` and the table's value columns,
//! read into rows sorted by penetration and interpolated linearly between them.

use crate::error::TableError;
use toml::Value;

/// The feasible rows of a table with value columns `columns`, sorted by penetration: each row
/// is (penetration, values in column order). Rows missing a number, with a non-finite one, or
/// with `feasible = false`, are skipped.
pub(crate) fn parse<const N: usize>(
    text: &str,
    columns: [&str; N],
) -> Result<Vec<(f64, [f64; N])>, TableError> {
    let doc: toml::Table = text.parse().map_err(|e: toml::de::Error| {
        TableError::Syntax(crate::error::clip_lines(
            e.to_string().trim_end(),
            crate::error::MAX_ECHO_CHARS,
        ))
    })?;
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
        let Some(p) = num(t, "penetration") else {
            continue;
        };
        let mut values = [0.0; N];
        if columns
            .iter()
            .zip(values.iter_mut())
            .all(|(c, v)| num(t, c).map(|x| *v = x).is_some())
        {
            rows.push((p, values));
        }
    }
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(rows)
}

/// The values at `penetration`: linear interpolation between the rows, the nearest row
/// outside them; `None` if there is no row.
pub(crate) fn at<const N: usize>(rows: &[(f64, [f64; N])], penetration: f64) -> Option<[f64; N]> {
    let (first, last) = (rows.first()?, rows.last()?);
    if penetration <= first.0 {
        return Some(first.1);
    }
    if penetration >= last.0 {
        return Some(last.1);
    }
    for w in rows.windows(2) {
        let ((pa, a), (pb, b)) = (w[0], w[1]);
        if penetration <= pb {
            let f = (penetration - pa) / (pb - pa);
            return Some(std::array::from_fn(|i| a[i] + f * (b[i] - a[i])));
        }
    }
    Some(last.1)
}
