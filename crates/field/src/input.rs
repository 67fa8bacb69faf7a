//! Opening a field file as rows of text: plain or gzip, told apart by the gzip magic bytes
//! `1f 8b` (RFC 1952), not by the file name, so a renamed file still reads.
//!
//! Rows come from the `csv` crate without quoting for PeMS files (their names may hold `"`) and
//! with it for tidy and table files; blank lines are skipped. Read errors become
//! [`FieldError`]s naming the file and line: a broken gzip stream is a `Gzip` error.

use std::fs::File;
use std::io::{BufRead, BufReader, ErrorKind};
use std::path::{Path, PathBuf};

use flate2::bufread::MultiGzDecoder;

use crate::error::FieldError;

/// The gzip magic bytes (RFC 1952, section 2.3.1).
const GZIP_MAGIC: [u8; 2] = [0x1f, 0x8b];

/// An open field file: decompressed text and whether it was gzip.
pub(crate) struct Input {
    pub path: PathBuf,
    pub gzip: bool,
    pub reader: Box<dyn BufRead>,
}

/// Opens `path`, decompressing it if it starts with the gzip magic bytes.
pub(crate) fn open(path: &Path) -> Result<Input, FieldError> {
    let io = |source| FieldError::Io {
        file: path.to_path_buf(),
        source,
    };
    let mut buf = BufReader::new(File::open(path).map_err(io)?);
    let head = buf.fill_buf().map_err(io)?;
    let gzip = head.starts_with(&GZIP_MAGIC);
    let reader: Box<dyn BufRead> = if gzip {
        Box::new(BufReader::new(MultiGzDecoder::new(buf)))
    } else {
        Box::new(buf)
    };
    Ok(Input {
        path: path.to_path_buf(),
        gzip,
        reader,
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
