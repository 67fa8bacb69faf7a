//! Loading field data from any mix of PeMS `station_5min` files and tidy CSVs.
//!
//! Each file is sniffed from its first line (after gzip decompression, if it starts with the
//! gzip magic bytes): a line naming `station` and `time` columns is a tidy header
//! ([`crate::tidy`]), a line starting with a `MM/DD/YYYY` date is a PeMS row
//! ([`crate::pems`]); anything else is an `UnknownFormat` error. The rows are concatenated in
//! the order of the files. All PeMS files of one load must be of the same day, and no station
//! may have the same (or an overlapping) interval in two files.

use std::collections::HashMap;
use std::io::BufRead;
use std::path::{Path, PathBuf};

use crate::error::{shorten, FieldError};
use crate::{clock, input, pems, tidy, Obs};

/// A field file's layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// PeMS `station_5min`.
    PemsStation5min,
    /// The tidy CSV.
    Tidy,
}

/// Tells a file's layout from its first line.
pub fn sniff(path: &Path) -> Result<Format, FieldError> {
    let mut input = input::open(path)?;
    let mut first = Vec::new();
    if let Err(e) = input.reader.read_until(b'\n', &mut first) {
        return Err(if input.gzip {
            FieldError::Gzip {
                file: path.to_path_buf(),
                line: 1,
                detail: e.to_string(),
            }
        } else {
            FieldError::Io {
                file: path.to_path_buf(),
                source: e,
            }
        });
    }
    let line = String::from_utf8_lossy(&first);
    // A UTF-8 byte order mark (spreadsheets write one) is not part of the first field.
    let line = line
        .trim_start_matches('\u{feff}')
        .trim_end_matches(['\n', '\r']);
    let fields: Vec<&str> = line
        .split(',')
        .map(|f| f.trim().trim_matches('"'))
        .collect();
    if tidy::looks_like_header(&fields) {
        return Ok(Format::Tidy);
    }
    if pems_like(fields[0]) {
        return Ok(Format::PemsStation5min);
    }
    Err(FieldError::UnknownFormat {
        file: path.to_path_buf(),
        line: 1,
        value: shorten(line, 120),
        allowed: format!(
            "a PeMS station_5min row (MM/DD/YYYY HH:MM:SS,station,...) or a tidy header ({})",
            tidy::COLUMNS.join(",")
        ),
    })
}

/// Whether a field starts like a PeMS timestamp: `NN/NN/NNNN`.
fn pems_like(field: &str) -> bool {
    let b = field.as_bytes();
    b.len() >= 10
        && b[..10].iter().enumerate().all(|(i, c)| {
            if i == 2 || i == 5 {
                *c == b'/'
            } else {
                c.is_ascii_digit()
            }
        })
}

/// Reads every file and concatenates the rows (file order, then each file's order).
pub fn load(files: &[PathBuf]) -> Result<Vec<Obs>, FieldError> {
    let mut all = Vec::new();
    // Which file each row came from, for the overlap check.
    let mut origin = Vec::new();
    let mut day: Option<(pems::Date, &Path)> = None;
    for (k, path) in files.iter().enumerate() {
        let obs = match sniff(path)? {
            Format::Tidy => tidy::read(path)?,
            Format::PemsStation5min => {
                let read = pems::read_day(path)?;
                match (day, read.date) {
                    (Some((first, first_file)), Some(date)) if date != first => {
                        return Err(FieldError::MixedDates {
                            file: path.clone(),
                            line: 1,
                            found: date.to_string(),
                            first: first.to_string(),
                            first_where: format!("{} line 1", first_file.display()),
                        });
                    }
                    (None, Some(date)) => day = Some((date, path)),
                    _ => {}
                }
                read.obs
            }
        };
        origin.extend(std::iter::repeat_n(k, obs.len()));
        all.extend(obs);
        // Each reader bounds its own file; the load as a whole is bounded the same way.
        if all.len() > crate::MAX_ROWS {
            return Err(crate::tidy::too_many(path, 0, "rows", crate::MAX_ROWS));
        }
    }
    check_overlaps(files, &all, &origin)?;
    Ok(all)
}

/// No station has overlapping intervals (from two files: each reader checks its own file).
fn check_overlaps(files: &[PathBuf], obs: &[Obs], origin: &[usize]) -> Result<(), FieldError> {
    let mut by_station: HashMap<&str, Vec<usize>> = HashMap::new();
    for (i, o) in obs.iter().enumerate() {
        by_station.entry(o.station.as_str()).or_default().push(i);
    }
    let mut clash: Option<(usize, usize)> = None;
    for idx in by_station.values_mut() {
        idx.sort_by_key(|&i| (obs[i].start_s, origin[i]));
        for w in idx.windows(2) {
            let (a, b) = (&obs[w[0]], &obs[w[1]]);
            if b.start_s < a.start_s.saturating_add(a.interval_s.max(1)) {
                // Report the clash of the earliest row in load order, whatever the hashing.
                let (earlier, later) = if w[0] < w[1] {
                    (w[0], w[1])
                } else {
                    (w[1], w[0])
                };
                if clash.is_none_or(|(_, l)| later < l) {
                    clash = Some((earlier, later));
                }
            }
        }
    }
    match clash {
        None => Ok(()),
        Some((earlier, later)) => Err(FieldError::Overlap {
            file: files[origin[later]].clone(),
            station: obs[later].station.clone(),
            time: clock::format(obs[later].start_s),
            other: files[origin[earlier]].clone(),
        }),
    }
}
