//! Stations on a corridor: placed by postmile or from a table, and the rows of the placed ones.
//!
//! By postmile (PeMS metadata): x = (Abs_PM − origin_pm) × 1609.344 m, so the corridor's
//! x = 0 is at postmile `origin_pm` (SR-99: 287.230, data/pems-sr99/README.md). Stations of
//! every kind with `from_m <= x <= to_m` are kept, sorted by x, then ID.
//!
//! From a table (a corridor without postmiles, or a hand-made placement): a CSV with the header
//! `station,x_m,kind` and optionally `lanes` and `name` (any order):
//!
//! ```text
//! station,x_m,kind,lanes,name
//! 313190,104.6,ML,2,Elk Grove Blvd
//! ```
//!
//! `kind` is a PeMS type code: `ML`, `OR`, `FR`, `HV` or `FF`. Rows are sorted like
//! [`by_postmile`]'s.
//!
//! [`select`] keeps the rows of placed stations and reports the others (stations in the data
//! but not placed, placed stations without rows): a report, not an error. [`require`] is the
//! error for stations asked for by name that are not placed.

use std::collections::{BTreeSet, HashSet};
use std::path::Path;

use crate::error::{shorten, FieldError};
use crate::input::{Dialect, Rows};
use crate::{Obs, Placed, StationKind, StationMeta, METRES_PER_MILE};

/// The placed stations of `meta` between `from_m` and `to_m` (inclusive), sorted by x, then ID.
pub fn by_postmile(meta: &[StationMeta], origin_pm: f64, from_m: f64, to_m: f64) -> Vec<Placed> {
    let mut placed: Vec<Placed> = meta
        .iter()
        .map(|m| Placed {
            station: m.id.clone(),
            x_m: (m.abs_pm - origin_pm) * METRES_PER_MILE,
            kind: m.kind.clone(),
            lanes: m.lanes,
            name: m.name.clone(),
        })
        .filter(|p| from_m <= p.x_m && p.x_m <= to_m)
        .collect();
    sort(&mut placed);
    placed
}

fn sort(placed: &mut [Placed]) {
    placed.sort_by(|a, b| {
        a.x_m
            .total_cmp(&b.x_m)
            .then_with(|| a.station.cmp(&b.station))
    });
}

/// The kind codes a table may use.
const KINDS: [&str; 5] = ["ML", "OR", "FR", "HV", "FF"];

/// Reads a station table (CSV `station,x_m,kind[,lanes,name]`, plain or gzip).
pub fn from_table(path: &Path) -> Result<Vec<Placed>, FieldError> {
    let mut rows = Rows::open(path, Dialect::Csv)?;
    let file = rows.path().to_path_buf();
    let allowed = "station, x_m, kind and optionally lanes, name".to_string();
    let (header_line, names): (u64, Vec<String>) = match rows.next_row()? {
        Some((line, header)) => (line, header.iter().map(str::to_string).collect()),
        None => (1, Vec::new()),
    };
    let col = |name: &str| names.iter().position(|n| n == name);
    let missing: Vec<&str> = ["station", "x_m", "kind"]
        .into_iter()
        .filter(|c| col(c).is_none())
        .collect();
    if !missing.is_empty() {
        return Err(FieldError::Header {
            file,
            line: header_line,
            missing: missing.join(", "),
            header: shorten(&names.join(","), 120),
            allowed,
        });
    }
    let [station, x, kind] = ["station", "x_m", "kind"].map(|c| col(c).unwrap_or(0));
    let (lanes, name) = (col("lanes"), col("name"));
    let mut seen = HashSet::new();
    let mut placed = Vec::new();
    while let Some((line, row)) = rows.next_row()? {
        let get = |i: usize| row.get(i).unwrap_or("");
        let err = |i: usize, number: bool, allowed: &str| {
            let (field, value) = (names[i].clone(), get(i).to_string());
            let (file, allowed) = (file.clone(), allowed.to_string());
            if number {
                FieldError::Number {
                    file,
                    line,
                    field,
                    value,
                    allowed,
                }
            } else {
                FieldError::Value {
                    file,
                    line,
                    field,
                    value,
                    allowed,
                }
            }
        };
        let id = get(station);
        if id.is_empty() {
            return Err(err(station, false, "a station ID"));
        }
        if !seen.insert(id.to_string()) {
            return Err(err(station, false, "each station once"));
        }
        let x_m = get(x)
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| err(x, true, "a position in metres"))?;
        if !KINDS.contains(&get(kind)) {
            return Err(err(kind, false, "one of ML, OR, FR, HV, FF"));
        }
        let n_lanes = match lanes.map(get) {
            None | Some("") => 0,
            Some(s) => s.parse::<u32>().map_err(|_| {
                err(
                    lanes.unwrap_or(0),
                    true,
                    "a whole number of lanes, or empty",
                )
            })?,
        };
        placed.push(Placed {
            station: id.to_string(),
            x_m,
            kind: StationKind::from_code(get(kind)),
            lanes: n_lanes,
            name: name.map(get).unwrap_or("").to_string(),
        });
    }
    sort(&mut placed);
    Ok(placed)
}

/// The rows of the placed stations, and what was left out.
#[derive(Clone, Debug, PartialEq)]
pub struct Selection {
    /// The rows of placed stations, in the order given.
    pub obs: Vec<Obs>,
    /// Stations with rows that are not placed (sorted).
    pub ignored_stations: Vec<String>,
    /// Placed stations without rows (in the placed order).
    pub without_data: Vec<String>,
}

/// Keeps the rows of placed stations; reports the stations left out on either side.
pub fn select(obs: &[Obs], placed: &[Placed]) -> Selection {
    let ids: HashSet<&str> = placed.iter().map(|p| p.station.as_str()).collect();
    let with_data: HashSet<&str> = obs.iter().map(|o| o.station.as_str()).collect();
    let ignored: BTreeSet<&str> = with_data
        .iter()
        .filter(|s| !ids.contains(*s))
        .copied()
        .collect();
    Selection {
        obs: obs
            .iter()
            .filter(|o| ids.contains(o.station.as_str()))
            .cloned()
            .collect(),
        ignored_stations: ignored.into_iter().map(str::to_string).collect(),
        without_data: placed
            .iter()
            .filter(|p| !with_data.contains(p.station.as_str()))
            .map(|p| p.station.clone())
            .collect(),
    }
}

/// `Ok` if every ID is a placed station, else `UnknownStation` listing those that are not.
pub fn require<S: AsRef<str>>(placed: &[Placed], ids: &[S]) -> Result<(), FieldError> {
    let known: HashSet<&str> = placed.iter().map(|p| p.station.as_str()).collect();
    let unknown: Vec<&str> = ids
        .iter()
        .map(AsRef::as_ref)
        .filter(|id| !known.contains(id))
        .collect();
    if unknown.is_empty() {
        return Ok(());
    }
    let listed: Vec<&str> = placed.iter().take(12).map(|p| p.station.as_str()).collect();
    let more = placed.len().saturating_sub(listed.len());
    Err(FieldError::UnknownStation {
        stations: unknown.join(", "),
        place: "the stations placed on the corridor".into(),
        known: if more > 0 {
            format!("{} and {more} more", listed.join(", "))
        } else if listed.is_empty() {
            "none".into()
        } else {
            listed.join(", ")
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn meta(id: &str, abs_pm: f64) -> StationMeta {
        StationMeta {
            id: id.into(),
            freeway: "99".into(),
            direction: "N".into(),
            abs_pm,
            kind: StationKind::Mainline,
            lanes: 2,
            name: String::new(),
        }
    }

    #[test]
    fn by_postmile_keeps_both_bounds_and_sorts_ties_by_id() {
        // x = (pm - 100) × 1609.344: -1609.344, 0, 0, 1609.344, 3218.688.
        let stations = [
            meta("e", 102.0),
            meta("b", 100.0),
            meta("a", 100.0),
            meta("lo", 99.0),
            meta("hi", 101.0),
        ];
        let placed = by_postmile(&stations, 100.0, -METRES_PER_MILE, METRES_PER_MILE);
        let got: Vec<(&str, f64)> = placed.iter().map(|p| (p.station.as_str(), p.x_m)).collect();
        assert_eq!(
            got,
            [
                ("lo", -METRES_PER_MILE),
                ("a", 0.0),
                ("b", 0.0),
                ("hi", METRES_PER_MILE)
            ]
        );
    }
}
