//! PeMS clearinghouse text files: `station_5min` (one row per station and 5-minute interval)
//! and the station metadata ([`read_meta`], in `pems/meta.rs`).
//!
//! A `station_5min` row is comma-separated, no header; its first 12 fields are
//!
//! | # | field | used as |
//! |---|---|---|
//! | 1 | Timestamp `MM/DD/YYYY HH:MM:SS` (local, start of the interval) | `start_s`; the date must be the same on every row |
//! | 2 | Station | `station` |
//! | 3-9 | District, Freeway, Direction, Lane Type, Station Length, Samples, % Observed | ignored |
//! | 10 | Total Flow (vehicles in the 5 minutes, all lanes) | `flow_vph` = count × 3600 / 300 |
//! | 11 | Avg Occupancy (0-1) | `occupancy`; empty or `nan` -> `None` |
//! | 12 | Avg Speed (mph) | `speed_kmh` = mph × 1.609344; empty or `nan` -> `None` |
//!
//! Full PeMS files append five fields per lane (Samples, Flow, Avg Occ, Avg Speed, Observed);
//! they are accepted and ignored. A row whose Total Flow is empty or `nan` has no data: it is
//! left out, so the interval shows as missing (`aggregate::missing`), never filled in.
//! Each station's intervals must go forward in time without repeating or overlapping.
//!
//! | parameter | value | unit |
//! |---|---|---|
//! | [`INTERVAL_S`] | 300 | s |
//! | [`KMH_PER_MPH`] | 1.609344 | (km/h)/mph |

use std::collections::HashMap;
use std::fmt;
use std::path::Path;

use crate::clock;
use crate::error::{shorten, FieldError};
use crate::input::{Dialect, Rows};
use crate::Obs;

mod meta;
pub use meta::read_meta;

/// Interval of a `station_5min` file (s).
pub const INTERVAL_S: u32 = 300;
/// km/h per mph (international mile: 1609.344 m).
pub const KMH_PER_MPH: f64 = 1.609344;
/// Fields of a `station_5min` row before the per-lane ones.
pub const MIN_FIELDS: usize = 12;

const TIMESTAMP: &str = "MM/DD/YYYY HH:MM:SS (month 01-12, day of that month, hour 00-23)";

/// A calendar date (the day of a field file).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Date {
    /// Year, e.g. 2014.
    pub year: u16,
    /// Month, 1-12.
    pub month: u8,
    /// Day of the month, 1-31.
    pub day: u8,
}

impl fmt::Display for Date {
    /// ISO 8601: `YYYY-MM-DD`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:04}-{:02}-{:02}", self.year, self.month, self.day)
    }
}

/// A `station_5min` file read: its day and its rows.
#[derive(Clone, Debug, PartialEq)]
pub struct PemsDay {
    /// The day of every row; `None` for a file without rows.
    pub date: Option<Date>,
    /// The rows with data, in file order.
    pub obs: Vec<Obs>,
}

/// Reads a PeMS `station_5min` file (plain or gzip) into tidy rows, in file order.
pub fn read_station_5min(path: &Path) -> Result<Vec<Obs>, FieldError> {
    Ok(read_day(path)?.obs)
}

/// Reads a PeMS `station_5min` file (plain or gzip) with its day.
pub fn read_day(path: &Path) -> Result<PemsDay, FieldError> {
    let mut rows = Rows::open(path, Dialect::PemsComma)?;
    let file = rows.path().to_path_buf();
    let mut first: Option<(Date, u64)> = None;
    // Each station's latest interval start and its line, to check time goes forward.
    let mut last: HashMap<String, (u32, u64)> = HashMap::new();
    let mut obs = Vec::new();
    while let Some((line, row)) = rows.next_row()? {
        if row.len() < MIN_FIELDS {
            let text: Vec<&str> = row.iter().collect();
            return Err(FieldError::Columns {
                file,
                line,
                found: row.len(),
                value: shorten(&text.join(","), 80),
                expected: format!(
                    "at least {MIN_FIELDS} comma-separated fields (PeMS station_5min: Timestamp, \
                     Station, District, Freeway, Direction, Lane Type, Station Length, Samples, \
                     % Observed, Total Flow, Avg Occupancy, Avg Speed)"
                ),
            });
        }
        let bad_time = || FieldError::Timestamp {
            file: file.clone(),
            line,
            field: "Timestamp".into(),
            value: row[0].to_string(),
            allowed: TIMESTAMP.into(),
        };
        let (date, start_s) = parse_timestamp(&row[0]).ok_or_else(bad_time)?;
        match first {
            None => first = Some((date, line)),
            Some((d, l)) if d != date => {
                return Err(FieldError::MixedDates {
                    file,
                    line,
                    found: date.to_string(),
                    first: d.to_string(),
                    first_where: format!("line {l}"),
                })
            }
            Some(_) => {}
        }
        let station = &row[1];
        if station.is_empty() {
            return Err(FieldError::Value {
                file,
                line,
                field: "Station".into(),
                value: String::new(),
                allowed: "a station ID".into(),
            });
        }
        if let Some(&(prev, prev_line)) = last.get(station) {
            if start_s < prev + INTERVAL_S {
                return Err(FieldError::NonMonotonic {
                    file,
                    line,
                    station: station.to_string(),
                    previous: clock::format(prev),
                    previous_line: prev_line,
                    time: clock::format(start_s),
                });
            }
        }
        last.insert(station.to_string(), (start_s, line));
        if last.len() > crate::MAX_STATIONS {
            return Err(crate::tidy::too_many(
                &file,
                line,
                "stations",
                crate::MAX_STATIONS,
            ));
        }
        let number = |i: usize, field: &str, max: f64, allowed: &str| {
            optional_number(&row[i], max).map_err(|()| FieldError::Number {
                file: file.clone(),
                line,
                field: field.into(),
                value: row[i].to_string(),
                allowed: allowed.into(),
            })
        };
        let count = number(
            9,
            "Total Flow",
            crate::MAX_STATION_FLOW_VPH * f64::from(INTERVAL_S) / 3600.0,
            "a vehicle count in [0, 2500] (30,000 veh/h over all lanes for 5 minutes), or empty",
        )?;
        let occupancy = number(10, "Avg Occupancy", 1.0, "a number in 0-1, empty or nan")?;
        let speed_mph = number(
            11,
            "Avg Speed",
            crate::MAX_SPEED_KMH / KMH_PER_MPH,
            "mph in [0, 124.3] (200 km/h), empty or nan",
        )?;
        let Some(count) = count else { continue };
        if obs.len() >= crate::MAX_ROWS {
            return Err(crate::tidy::too_many(&file, line, "rows", crate::MAX_ROWS));
        }
        obs.push(Obs {
            station: station.to_string(),
            start_s,
            interval_s: INTERVAL_S,
            flow_vph: count * 3600.0 / f64::from(INTERVAL_S),
            speed_kmh: speed_mph.map(|v| v * KMH_PER_MPH),
            occupancy,
        });
    }
    Ok(PemsDay {
        date: first.map(|(d, _)| d),
        obs,
    })
}

/// A number in `0..=max`, `None` for empty or `nan`; `Err` otherwise.
fn optional_number(s: &str, max: f64) -> Result<Option<f64>, ()> {
    if s.is_empty() || s.eq_ignore_ascii_case("nan") {
        return Ok(None);
    }
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && (0.0..=max).contains(&v) => Ok(Some(v)),
        _ => Err(()),
    }
}

/// Parses `MM/DD/YYYY HH:MM:SS` into the date and seconds since midnight.
pub fn parse_timestamp(s: &str) -> Option<(Date, u32)> {
    let (date, time) = s.split_once(' ')?;
    let parts: Vec<&str> = date.split('/').collect();
    let [m, d, y] = parts.as_slice() else {
        return None;
    };
    let digits = |p: &str, n: usize| p.len() == n && p.bytes().all(|b| b.is_ascii_digit());
    if !(digits(m, 2) && digits(d, 2) && digits(y, 4)) || time.len() != 8 {
        return None;
    }
    let (year, month, day) = (y.parse().ok()?, m.parse().ok()?, d.parse().ok()?);
    if !(1..=12).contains(&month) || day < 1 || day > days_in_month(year, month) {
        return None;
    }
    Some((Date { year, month, day }, clock::parse(time)?))
}

/// Days in a month of the Gregorian calendar.
fn days_in_month(year: u16, month: u8) -> u8 {
    match month {
        2 if (year.is_multiple_of(4) && !year.is_multiple_of(100)) || year.is_multiple_of(400) => {
            29
        }
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timestamps_parse_with_calendar_ranges() {
        let (d, s) = parse_timestamp("09/18/2014 07:35:00").unwrap();
        assert_eq!(d.to_string(), "2014-09-18");
        assert_eq!(s, 7 * 3600 + 35 * 60);
        assert!(parse_timestamp("02/29/2016 00:00:00").is_some());
        for bad in [
            "02/29/2014 00:00:00",
            "13/45/2014 00:00:00",
            "13/01/2014 00:00:00",
            "00/01/2014 00:00:00",
            "01/00/2014 00:00:00",
            "04/31/2014 00:00:00",
            "9/18/2014 00:00:00",
            "09/18/2014 24:00:00",
            "09/18/2014 07:35",
            "2014-09-18 07:35:00",
        ] {
            assert_eq!(parse_timestamp(bad), None, "{bad}");
        }
    }

    #[test]
    fn optional_numbers_allow_empty_and_nan_only() {
        assert_eq!(optional_number("", 1.0), Ok(None));
        assert_eq!(optional_number("nan", 1.0), Ok(None));
        assert_eq!(optional_number("0.5", 1.0), Ok(Some(0.5)));
        assert_eq!(optional_number("1.5", 1.0), Err(()));
        assert_eq!(optional_number("-1", 1.0), Err(()));
        assert_eq!(optional_number("x", 1.0), Err(()));
        assert_eq!(optional_number("inf", f64::INFINITY), Err(()));
    }
}
