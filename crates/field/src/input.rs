//! Opening a field file as rows of text: plain or gzip, told apart by the gzip magic bytes
//! `1f 8b` (RFC 1952), not by the file name, so a renamed file still reads.
//!
//! Rows come from the `csv` crate without quoting for PeMS files (their names may hold `"`) and
//! with it for tidy and table files; blank lines are skipped. Read errors become
//! [`FieldError`]s naming the file and line: a broken gzip stream is a `Gzip` error.

use std::io::{BufRead, ErrorKind};
use std::path::{Path, PathBuf};

use platoonsim_bounded::gzip;

use crate::bounded;
use crate::error::FieldError;

/// An open field file: decompressed text and whether it was gzip.
pub(crate) struct Input {
    pub path: PathBuf,
    pub gzip: bool,
    pub reader: Box<dyn BufRead>,
}

/// Opens `path`, decompressing it if it starts with the gzip magic bytes (the bounded crate's
/// gzip mode, shared with the SUMO importer). The text (decompressed if need be) is bounded in
/// line length and in total, so a corrupt file never becomes one unbounded record.
pub(crate) fn open(path: &Path) -> Result<Input, FieldError> {
    let io = |source| FieldError::Io {
        file: path.to_path_buf(),
        source,
    };
    let lines = gzip::open(
        path,
        bounded::MAX_FILE_BYTES,
        bounded::MAX_LINE_BYTES,
        bounded::MAX_TEXT_BYTES,
    )
    .map_err(|e| match e {
        // Never open what is not a regular file (a FIFO blocks the open, a device never ends).
        gzip::Error::NotRegular { kind } => io(std::io::Error::new(
            ErrorKind::InvalidInput,
            format!("not a regular file (a {kind})"),
        )),
        gzip::Error::TooLarge { size, limit } => io(std::io::Error::new(
            ErrorKind::InvalidData,
            format!("{size} bytes: a field file must be at most {limit} bytes"),
        )),
        gzip::Error::Io(source) | gzip::Error::Gzip(source) => io(source),
    })?;
    Ok(Input {
        path: path.to_path_buf(),
        gzip: lines.gzip,
        reader: lines.reader,
    })
}

/// The row separator and whether `"` quotes.
#[derive(Clone, Copy)]
pub(crate) enum Dialect {
    /// PeMS station_5min: commas, no quoting.
    PemsComma,
    /// PeMS metadata: tabs, no quoting.
    PemsTab,
    /// Tidy and table files: commas, `"` quotes.
    Csv,
}

/// Rows of a field file with their 1-based line numbers.
pub(crate) struct Rows {
    path: PathBuf,
    gzip: bool,
    reader: csv::Reader<Box<dyn BufRead>>,
    record: csv::StringRecord,
}

impl Rows {
    pub fn open(path: &Path, dialect: Dialect) -> Result<Rows, FieldError> {
        let input = open(path)?;
        let mut builder = csv::ReaderBuilder::new();
        builder
            .has_headers(false)
            .flexible(true)
            .trim(csv::Trim::All);
        match dialect {
            Dialect::PemsComma => builder.quoting(false),
            Dialect::PemsTab => builder.quoting(false).delimiter(b'\t'),
            Dialect::Csv => &mut builder,
        };
        Ok(Rows {
            path: input.path,
            gzip: input.gzip,
            reader: builder.from_reader(input.reader),
            record: csv::StringRecord::new(),
        })
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The next row and its line, or `None` at the end.
    pub fn next_row(&mut self) -> Result<Option<(u64, &csv::StringRecord)>, FieldError> {
        match self.reader.read_record(&mut self.record) {
            Ok(true) => {
                let line = self.record.position().map_or(0, |p| p.line());
                Ok(Some((line, &self.record)))
            }
            Ok(false) => Ok(None),
            Err(e) => Err(self.error(e)),
        }
    }

    fn error(&self, e: csv::Error) -> FieldError {
        let line = self.reader.position().line();
        let file = self.path.clone();
        match e.into_kind() {
            csv::ErrorKind::Utf8 { pos, .. } => FieldError::Encoding {
                file,
                line: pos.map_or(line, |p| p.line()),
            },
            csv::ErrorKind::Io(source) if self.gzip => FieldError::Gzip {
                file,
                line,
                detail: if source.kind() == ErrorKind::UnexpectedEof {
                    "file ended inside the gzip stream".to_string()
                } else {
                    source.to_string()
                },
            },
            csv::ErrorKind::Io(source) => FieldError::Io { file, source },
            other => FieldError::Io {
                file,
                source: std::io::Error::other(format!("{other:?}")),
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn special_files_and_endless_lines_are_refused() {
        // Issue 35 item 5: a FIFO blocked the open; a line without end became one record.
        let dir =
            std::env::temp_dir().join(format!("platoonsim-field-input-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let e = Rows::open(Path::new("/dev/zero"), Dialect::PemsComma)
            .err()
            .unwrap()
            .to_string();
        assert_eq!(
            e,
            "/dev/zero: cannot read the file: not a regular file (a character device)"
        );
        let long = dir.join("long.txt");
        std::fs::write(&long, format!("a,b\n{}\n", "9".repeat(100_000))).unwrap();
        let mut rows = Rows::open(&long, Dialect::PemsComma).unwrap();
        assert!(rows.next_row().unwrap().is_some());
        let e = rows.next_row().unwrap_err().to_string();
        assert!(
            e.ends_with("line 2 is longer than 65536 bytes (not a file of records)"),
            "{e}"
        );
    }
}
