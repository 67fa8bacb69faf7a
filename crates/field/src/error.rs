//! The errors of reading field data.
//!
//! Every variant about a file names the file and, where there is one, the 1-based line, the
//! field, the value found and what is allowed, so a user can fix the file from the message
//! alone. Missing data (an interval without a row, a station without rows) is not an error: it
//! is reported (`aggregate::missing`, `place::Selection`), never filled in.

use std::path::PathBuf;

/// An error in a field-data file or request.
#[derive(Debug, thiserror::Error)]
pub enum FieldError {
    /// The file cannot be opened or read.
    #[error("{}: cannot read the file: {source}", .file.display())]
    Io {
        /// The file.
        file: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A gzip file is truncated or corrupt.
    #[error(
        "{}: near line {line}: the gzip stream is truncated or corrupt ({detail}); expected a whole \
         gzip stream (download or compress the file again)",
        .file.display()
    )]
    Gzip {
        /// The file.
        file: PathBuf,
        /// The line of the decompressed text being read when the stream broke (reading is
        /// buffered, so the break may come later in the file).
        line: u64,
        /// What broke, e.g. "file ended inside the gzip stream".
        detail: String,
    },
    /// A line is not UTF-8 text.
    #[error("{}: line {line}: not UTF-8 text; expected a text file", .file.display())]
    Encoding {
        /// The file.
        file: PathBuf,
        /// The line.
        line: u64,
    },
    /// A row has the wrong number of fields.
    #[error(
        "{}: line {line}: {found} field(s) in {value:?}; expected {expected}",
        .file.display()
    )]
    Columns {
        /// The file.
        file: PathBuf,
        /// The line.
        line: u64,
        /// Fields found.
        found: usize,
        /// The row (shortened).
        value: String,
        /// What is expected, e.g. "at least 12 comma-separated fields (PeMS station_5min)".
        expected: String,
    },
    /// A date or time that does not parse or is out of range.
    #[error(
        "{}: line {line}: field `{field}` is {value:?}, not a valid time; expected {allowed}",
        .file.display()
    )]
    Timestamp {
        /// The file.
        file: PathBuf,
        /// The line.
        line: u64,
        /// The field's name.
        field: String,
        /// The value found.
        value: String,
        /// The format and ranges allowed.
        allowed: String,
    },
    /// A number that does not parse or is out of range.
    #[error("{}: line {line}: field `{field}` is {value:?}; expected {allowed}", .file.display())]
    Number {
        /// The file.
        file: PathBuf,
        /// The line.
        line: u64,
        /// The field's name.
        field: String,
        /// The value found.
        value: String,
        /// What is allowed, e.g. "a number in 0-1".
        allowed: String,
    },
    /// Any other bad value: an empty station, an unknown kind code, a repeated station ID, an
    /// interval that cannot be told or is inconsistent (station tables, metadata, tidy files).
    #[error("{}: line {line}: field `{field}` is {value:?}; expected {allowed}", .file.display())]
    Value {
        /// The file.
        file: PathBuf,
        /// The line.
        line: u64,
        /// The field's name.
        field: String,
        /// The value found.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// A header lacks a required column (metadata, station tables).
    #[error(
        "{}: line {line}: the header {header:?} has no column {missing}; expected columns {allowed}",
        .file.display()
    )]
    Header {
        /// The file.
        file: PathBuf,
        /// The header's line.
        line: u64,
        /// The missing column(s).
        missing: String,
        /// The header found (shortened).
        header: String,
        /// The columns expected.
        allowed: String,
    },
    /// A station's intervals go back in time, repeat or overlap.
    #[error(
        "{}: line {line}: station {station}: the interval at {time} follows the one at \
         {previous} (line {previous_line}); expected each station's intervals to go forward in \
         time without repeating or overlapping",
        .file.display()
    )]
    NonMonotonic {
        /// The file.
        file: PathBuf,
        /// The line of the later row.
        line: u64,
        /// The station.
        station: String,
        /// Start of the station's previous interval (HH:MM:SS).
        previous: String,
        /// The line of the station's previous row.
        previous_line: u64,
        /// Start of this row's interval (HH:MM:SS).
        time: String,
    },
    /// A file (or a set of PeMS files loaded together) holds more than one day.
    #[error(
        "{}: line {line}: field `Timestamp` has the date {found}, but {first_where} has {first}; \
         expected one day (one file per day, all files of one load on the same day)",
        .file.display()
    )]
    MixedDates {
        /// The file.
        file: PathBuf,
        /// The line with the other date.
        line: u64,
        /// The date found (YYYY-MM-DD).
        found: String,
        /// The first date seen (YYYY-MM-DD).
        first: String,
        /// Where the first date was seen, e.g. "line 1" or "day1.txt line 1".
        first_where: String,
    },
    /// The same station and interval (or overlapping intervals) in two files.
    #[error(
        "{}: station {station}: the interval at {time} overlaps one of {}; expected each \
         station's interval in one file only",
        .file.display(), .other.display()
    )]
    Overlap {
        /// The later file.
        file: PathBuf,
        /// The station.
        station: String,
        /// Start of the interval (HH:MM:SS).
        time: String,
        /// The earlier file.
        other: PathBuf,
    },
    /// Stations asked for that are not known.
    #[error("station(s) {stations} not in {place}; known: {known}")]
    UnknownStation {
        /// The unknown stations, comma-separated.
        stations: String,
        /// Where they were looked for, e.g. "the placed stations".
        place: String,
        /// The known stations (the first few).
        known: String,
    },
    /// More rows or stations than one load may hold ([`crate::MAX_ROWS`],
    /// [`crate::MAX_STATIONS`]).
    #[error(
        "{}: line {line}: more than {limit} {what} in one load; split the data (by day or \
         corridor) or keep only the stations of the corridor",
        .file.display()
    )]
    TooMany {
        /// The file.
        file: PathBuf,
        /// The line where the limit was passed.
        line: u64,
        /// "rows" or "stations".
        what: &'static str,
        /// The limit.
        limit: usize,
    },
    /// A file that is neither a PeMS station_5min file nor a tidy CSV.
    #[error("{}: line {line}: {value:?} is not a known layout; expected {allowed}", .file.display())]
    UnknownFormat {
        /// The file.
        file: PathBuf,
        /// The line looked at (1).
        line: u64,
        /// The line found (shortened).
        value: String,
        /// The layouts allowed.
        allowed: String,
    },
}

/// Shortens a line for a message (whole characters, at most `max` of them).
pub(crate) fn shorten(s: &str, max: usize) -> String {
    if s.chars().count() <= max {
        s.to_string()
    } else {
        let head: String = s.chars().take(max).collect();
        format!("{head}…")
    }
}
