//! PeMS station metadata (`dNN_text_meta_YYYY_MM_DD.txt`): tab-separated, one header line.
//!
//! Columns are found by their header name, so their order may vary and extra columns (e.g.
//! `User_ID_1`) are ignored. Required: `ID`, `Fwy`, `Dir`, `Abs_PM` (absolute postmile,
//! miles), `Type` (`ML`, `OR`, `FR`, `HV`, `FF`; other codes are kept as
//! `StationKind::Other`), `Lanes` and `Name`. Optional fields may be empty (County, City,
//! Latitude, ... are not read); an empty `Lanes` reads as 0 (unknown), an empty `Name` as "".
//! A station ID may appear once.

use std::collections::HashSet;
use std::path::Path;

use crate::error::{shorten, FieldError};
use crate::input::{Dialect, Rows};
use crate::{StationKind, StationMeta};

/// The columns read, by header name.
const COLUMNS: [&str; 7] = ["ID", "Fwy", "Dir", "Abs_PM", "Type", "Lanes", "Name"];

/// Reads a PeMS station metadata file (plain or gzip), in file order.
pub fn read_meta(path: &Path) -> Result<Vec<StationMeta>, FieldError> {
    let mut rows = Rows::open(path, Dialect::PemsTab)?;
    let file = rows.path().to_path_buf();
    let Some((header_line, header)) = rows.next_row()? else {
        return Err(header_error(&file, 1, COLUMNS.join(", "), ""));
    };
    let names: Vec<String> = header.iter().map(str::to_string).collect();
    let missing: Vec<&str> = COLUMNS
        .iter()
        .filter(|c| !names.iter().any(|n| n == *c))
        .copied()
        .collect();
    if !missing.is_empty() {
        return Err(header_error(
            &file,
            header_line,
            missing.join(", "),
            &names.join("\t"),
        ));
    }
    let col = |name: &str| names.iter().position(|n| n == name).unwrap_or(0);
    let [id, fwy, dir, abs_pm, kind, lanes, name] = COLUMNS.map(col);
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    while let Some((line, row)) = rows.next_row()? {
        let get = |i: usize| row.get(i).unwrap_or("");
        let value = |field: &str, allowed: &str| FieldError::Value {
            file: file.clone(),
            line,
            field: field.into(),
            value: get(col(field)).into(),
            allowed: allowed.into(),
        };
        if get(id).is_empty() {
            return Err(value("ID", "a station ID"));
        }
        if !seen.insert(get(id).to_string()) {
            return Err(value("ID", "each station ID once"));
        }
        let number = |field: &str, allowed: &str| FieldError::Number {
            file: file.clone(),
            line,
            field: field.into(),
            value: get(col(field)).into(),
            allowed: allowed.into(),
        };
        let pm = get(abs_pm)
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| number("Abs_PM", "an absolute postmile (miles)"))?;
        let n_lanes = match get(lanes) {
            "" => 0,
            s => s
                .parse::<u32>()
                .map_err(|_| number("Lanes", "a whole number of lanes, or empty"))?,
        };
        if get(kind).is_empty() {
            return Err(value(
                "Type",
                "a station type code: ML, OR, FR, HV, FF, ...",
            ));
        }
        out.push(StationMeta {
            id: get(id).to_string(),
            freeway: get(fwy).to_string(),
            direction: get(dir).to_string(),
            abs_pm: pm,
            kind: StationKind::from_code(get(kind)),
            lanes: n_lanes,
            name: get(name).to_string(),
        });
    }
    Ok(out)
}

fn header_error(file: &Path, line: u64, missing: String, header: &str) -> FieldError {
    FieldError::Header {
        file: file.to_path_buf(),
        line,
        missing,
        header: shorten(header, 120),
        allowed: format!(
            "{} (tab-separated, PeMS station metadata)",
            COLUMNS.join(", ")
        ),
    }
}
