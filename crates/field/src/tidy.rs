//! The tidy CSV of field data: one row per station and interval.
//!
//! ```text
//! station,time,flow_vph,speed_kmh,occupancy,interval_s
//! 312425,07:00:00,5316,72.4,0.118,300
//! 312425,07:05:00,5208,,0.121,300
//! ```
//!
//! | column | meaning | unit |
//! |---|---|---|
//! | `station` | station ID or detector name | |
//! | `time` | start of the interval, local clock, `HH:MM` or `HH:MM:SS` | |
//! | `flow_vph` | flow over all lanes, >= 0 | veh/h |
//! | `speed_kmh` | mean speed, >= 0; empty where none | km/h |
//! | `occupancy` | 0-1; empty where none | |
//! | `interval_s` | optional: interval length, > 0 | s |
//!
//! Columns are found by header name (any order, `"` quotes); a header with another column or
//! without a required one is an `UnknownFormat` error. Without `interval_s`, a station's
//! interval is the smallest spacing of its rows, and every spacing must be a multiple of it (a
//! gap is missing data); a station with one row takes the interval the other stations share.
//! Each station's rows must go forward in time without repeating or overlapping.
//! [`write()`] always writes `interval_s` and `HH:MM:SS`, so what it writes reads back equal.

use std::collections::HashMap;
use std::io::Write;
use std::path::Path;

use crate::clock;
use crate::error::{shorten, FieldError};
use crate::input::{Dialect, Rows};
use crate::Obs;

/// The required columns.
pub const COLUMNS: [&str; 5] = ["station", "time", "flow_vph", "speed_kmh", "occupancy"];
/// The optional interval column.
pub const INTERVAL_COLUMN: &str = "interval_s";

/// Whether a first line is a tidy header (it names `station` and `time`), for sniffing.
pub(crate) fn looks_like_header(fields: &[&str]) -> bool {
    fields.contains(&"station") && fields.contains(&"time")
}

/// A row read, before its interval is known.
struct Row {
    line: u64,
    obs: Obs,
    /// The `interval_s` column, if the file has it.
    interval: Option<u32>,
}

/// What a flow may be (the tidy and the PeMS readers).
pub(crate) const FLOW_ALLOWED: &str =
    "veh/h in [0, 30000] (a station's flow over all lanes: ten lanes at 3,000 veh/h/lane)";
/// What a speed may be.
pub(crate) const SPEED_ALLOWED: &str = "km/h in [0, 200], or empty";

pub(crate) fn too_many(file: &Path, line: u64, what: &'static str, limit: usize) -> FieldError {
    FieldError::TooMany {
        file: file.to_path_buf(),
        line,
        what,
        limit,
    }
}

/// Reads a tidy CSV (plain or gzip), in file order.
pub fn read(path: &Path) -> Result<Vec<Obs>, FieldError> {
    let mut rows = Rows::open(path, Dialect::Csv)?;
    let file = rows.path().to_path_buf();
    let allowed = format!(
        "a tidy header with the columns {} and optionally {INTERVAL_COLUMN}",
        COLUMNS.join(",")
    );
    let unknown = |line: u64, value: String| FieldError::UnknownFormat {
        file: file.clone(),
        line,
        value: shorten(&value, 120),
        allowed: allowed.clone(),
    };
    let Some((header_line, header)) = rows.next_row()? else {
        return Err(unknown(1, String::new()));
    };
    let names: Vec<String> = header.iter().map(str::to_string).collect();
    let known = |n: &String| COLUMNS.contains(&n.as_str()) || n == INTERVAL_COLUMN;
    let complete = COLUMNS.iter().all(|c| names.iter().any(|n| n == c));
    let mut distinct = names.clone();
    distinct.sort();
    distinct.dedup();
    if !complete || !names.iter().all(known) || distinct.len() != names.len() {
        return Err(unknown(header_line, names.join(",")));
    }
    let col = |name: &str| names.iter().position(|n| n == name);
    let [station, time, flow, speed, occ] = COLUMNS.map(|c| col(c).unwrap_or(0));
    let interval = col(INTERVAL_COLUMN);

    let mut read_rows = Vec::new();
    let mut stations: std::collections::HashSet<String> = std::collections::HashSet::new();
    while let Some((line, row)) = rows.next_row()? {
        if row.len() != names.len() {
            return Err(FieldError::Columns {
                file,
                line,
                found: row.len(),
                value: shorten(&row.iter().collect::<Vec<_>>().join(","), 80),
                expected: format!("{} comma-separated fields, as the header", names.len()),
            });
        }
        let bad = |i: usize, allowed: &str| FieldError::Number {
            file: file.clone(),
            line,
            field: names[i].clone(),
            value: row[i].to_string(),
            allowed: allowed.into(),
        };
        if row[station].is_empty() {
            return Err(FieldError::Value {
                file,
                line,
                field: "station".into(),
                value: String::new(),
                allowed: "a station ID or detector name".into(),
            });
        }
        let start_s = clock::parse(&row[time]).ok_or_else(|| FieldError::Timestamp {
            file: file.clone(),
            line,
            field: "time".into(),
            value: row[time].to_string(),
            allowed: "HH:MM or HH:MM:SS (hour 0-23, minute and second 00-59)".into(),
        })?;
        let number = |i: usize, max: f64| {
            row[i]
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && (0.0..=max).contains(v))
        };
        let optional = |i: usize, max: f64, allowed: &str| match &row[i] {
            "" => Ok(None),
            _ => number(i, max).map(Some).ok_or_else(|| bad(i, allowed)),
        };
        let flow_vph =
            number(flow, crate::MAX_STATION_FLOW_VPH).ok_or_else(|| bad(flow, FLOW_ALLOWED))?;
        let speed_kmh = optional(speed, crate::MAX_SPEED_KMH, SPEED_ALLOWED)?;
        let occupancy = optional(occ, 1.0, "a number in 0-1, or empty")?;
        let interval = match interval {
            Some(i) => Some(
                row[i]
                    .parse::<u32>()
                    .ok()
                    .filter(|v| *v > 0)
                    .ok_or_else(|| bad(i, "a whole number of seconds > 0"))?,
            ),
            None => None,
        };
        if read_rows.len() >= crate::MAX_ROWS {
            return Err(too_many(&file, line, "rows", crate::MAX_ROWS));
        }
        if !stations.contains(&row[station]) {
            if stations.len() >= crate::MAX_STATIONS {
                return Err(too_many(&file, line, "stations", crate::MAX_STATIONS));
            }
            stations.insert(row[station].to_string());
        }
        read_rows.push(Row {
            line,
            obs: Obs {
                station: row[station].to_string(),
                start_s,
                interval_s: interval.unwrap_or(0),
                flow_vph,
                speed_kmh,
                occupancy,
            },
            interval,
        });
    }
    check_order(&file, &read_rows)?;
    if interval.is_none() {
        infer_intervals(&file, &mut read_rows)?;
    }
    Ok(read_rows.into_iter().map(|r| r.obs).collect())
}

/// Each station's rows go forward in time; with an `interval_s` column, without overlapping.
fn check_order(file: &Path, rows: &[Row]) -> Result<(), FieldError> {
    let mut last: HashMap<&str, (u32, u32, u64)> = HashMap::new();
    for r in rows {
        let station = r.obs.station.as_str();
        if let Some(&(prev, len, prev_line)) = last.get(station) {
            if r.obs.start_s < prev.saturating_add(len.max(1)) {
                return Err(FieldError::NonMonotonic {
                    file: file.to_path_buf(),
                    line: r.line,
                    station: station.to_string(),
                    previous: clock::format(prev),
                    previous_line: prev_line,
                    time: clock::format(r.obs.start_s),
                });
            }
        }
        last.insert(station, (r.obs.start_s, r.interval.unwrap_or(0), r.line));
    }
    Ok(())
}

/// Sets each station's interval from the spacing of its rows (see the module docs).
fn infer_intervals(file: &Path, rows: &mut [Row]) -> Result<(), FieldError> {
    // Rows of each station are in increasing time (check_order), so the spacings are > 0.
    // Stations in order of first appearance, so the error reported does not depend on hashing.
    let mut slot: HashMap<&str, usize> = HashMap::new();
    let mut by_station: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        let k = *slot.entry(r.obs.station.as_str()).or_insert_with(|| {
            by_station.push((r.obs.station.clone(), Vec::new()));
            by_station.len() - 1
        });
        by_station[k].1.push(i);
    }
    let mut interval: HashMap<&str, u32> = HashMap::new();
    for (station, idx) in &by_station {
        let spacing = |w: &[usize]| rows[w[1]].obs.start_s - rows[w[0]].obs.start_s;
        let Some(smallest) = idx.windows(2).map(spacing).min() else {
            continue;
        };
        if let Some(w) = idx.windows(2).find(|w| spacing(w) % smallest != 0) {
            let (prev, this) = (&rows[w[0]], &rows[w[1]]);
            return Err(FieldError::Value {
                file: file.to_path_buf(),
                line: this.line,
                field: "time".into(),
                value: clock::format(this.obs.start_s),
                allowed: format!(
                    "station {station}: a multiple of its interval ({smallest} s, its smallest \
                     spacing) after its previous row at {} (or an interval_s column)",
                    clock::format(prev.obs.start_s)
                ),
            });
        }
        interval.insert(station, smallest);
    }
    let mut shared: Vec<u32> = interval.values().copied().collect();
    shared.sort_unstable();
    shared.dedup();
    let mut single = Vec::new();
    for (station, idx) in &by_station {
        let len = match interval.get(station.as_str()) {
            Some(len) => *len,
            None if shared.len() == 1 => shared[0],
            None => {
                single.push(idx[0]);
                continue;
            }
        };
        for &i in idx {
            rows[i].obs.interval_s = len;
        }
    }
    if let Some(&i) = single.iter().min() {
        let r = &rows[i];
        return Err(FieldError::Value {
            file: file.to_path_buf(),
            line: r.line,
            field: "time".into(),
            value: clock::format(r.obs.start_s),
            allowed: format!(
                "station {}: a second row to tell its interval from, or an interval_s column \
                 (its only row; the other stations do not share one interval)",
                r.obs.station
            ),
        });
    }
    Ok(())
}

/// Writes rows as a tidy CSV (with `interval_s`, times as `HH:MM:SS`), in the order given.
/// Floats are written in the shortest form that reads back to the same value.
pub fn write<W: Write>(w: W, obs: &[Obs]) -> std::io::Result<()> {
    let mut out = csv::Writer::from_writer(w);
    let mut header = COLUMNS.to_vec();
    header.push(INTERVAL_COLUMN);
    out.write_record(&header)?;
    let opt = |v: Option<f64>| v.map_or(String::new(), |v| v.to_string());
    for o in obs {
        out.write_record([
            o.station.clone(),
            clock::format(o.start_s),
            o.flow_vph.to_string(),
            opt(o.speed_kmh),
            opt(o.occupancy),
            o.interval_s.to_string(),
        ])?;
    }
    out.flush()
}
