//! Bounded reading of a run directory's files (issue 35 item 5): what is not a regular file
//! is refused before it is opened (a FIFO would block the open, a device never ends), and the
//! bytes and the line length read are bounded before anything is allocated for them. (The
//! same rules as `platoonsim_scenario::bounded`; this crate depends on no platoonsim crate.)

use std::fs;
use std::io::{self, Read};
use std::path::Path;

/// The largest file of records read (trajectories, detectors, trips): 16 GiB, four times the
/// largest `trajectories.csv` a run may record.
pub const MAX_RECORD_FILE_BYTES: u64 = 16 << 30;
/// The longest line of a file of records: 64 KiB (a row is under 200 bytes; a corrupt file
/// without line breaks would otherwise become one record of its whole size).
pub const MAX_RECORD_LINE_BYTES: usize = 64 << 10;
/// The largest table read whole (detectors, trips, collisions): 2 GiB, above the detector
/// records' bound (5 million rows) and a trip for each of the 10 million arrivals a run may
/// bring.
pub const MAX_TABLE_BYTES: u64 = 2 << 30;
/// The largest `scenario.json` read (a resolved SR-99 is about 100 KiB).
pub const MAX_SCENARIO_BYTES: u64 = 16 << 20;

/// The metadata of `path` (links followed) if it is a regular file; otherwise an error
/// saying what it is. A missing path keeps the system's "No such file or directory".
pub(crate) fn regular_file(path: &Path) -> io::Result<fs::Metadata> {
    let meta = fs::metadata(path)?;
    if meta.is_file() {
        Ok(meta)
    } else {
        Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("not a regular file (a {})", describe(&meta.file_type())),
        ))
    }
}

/// What a file that is not regular is, in words.
pub(crate) fn describe(kind: &fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_char_device() {
            return "character device";
        }
        if kind.is_block_device() {
            return "block device";
        }
        if kind.is_fifo() {
            return "FIFO";
        }
        if kind.is_socket() {
            return "socket";
        }
    }
    if kind.is_dir() {
        "directory"
    } else {
        "special file"
    }
}

/// The whole of a regular file of at most `max` bytes (a file that grows while it is read is
/// caught too).
pub(crate) fn read(path: &Path, max: u64) -> io::Result<Vec<u8>> {
    let size = regular_file(path)?.len();
    let too_large = |bytes: u64| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!("{bytes} bytes: at most {max} bytes are read"),
        )
    };
    if size > max {
        return Err(too_large(size));
    }
    let mut bytes = Vec::with_capacity(size as usize);
    fs::File::open(path)?
        .take(max + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// [`read`] as UTF-8 text.
pub(crate) fn read_text(path: &Path, max: u64) -> io::Result<String> {
    String::from_utf8(read(path, max)?)
        .map_err(|e| io::Error::new(io::ErrorKind::InvalidData, format!("not UTF-8 text ({e})")))
}

/// A regular file of at most `max_bytes`, opened for streaming through [`LineLimit`].
pub(crate) fn open_records(
    path: &Path,
    max_bytes: u64,
    max_line: usize,
) -> io::Result<LineLimit<fs::File>> {
    let size = regular_file(path)?.len();
    if size > max_bytes {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            format!("{size} bytes: at most {max_bytes} bytes are read"),
        ));
    }
    Ok(LineLimit::new(fs::File::open(path)?, max_line, max_bytes))
}

/// A reader that fails once a line grows past `max_line` bytes or the stream past `max_total`,
/// so a CSV reader on top never buffers an unbounded record (a corrupt file without line
/// breaks) and a stream never exceeds its size bound.
#[derive(Debug)]
pub(crate) struct LineLimit<R> {
    inner: R,
    max_line: usize,
    max_total: u64,
    line_len: usize,
    total: u64,
    line: u64,
}

impl<R: Read> LineLimit<R> {
    pub(crate) fn new(inner: R, max_line: usize, max_total: u64) -> Self {
        LineLimit {
            inner,
            max_line,
            max_total,
            line_len: 0,
            total: 0,
            line: 1,
        }
    }
}

impl<R: Read> Read for LineLimit<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.total += n as u64;
        if self.total > self.max_total {
            return Err(io::Error::new(
                io::ErrorKind::InvalidData,
                format!("more than {} bytes", self.max_total),
            ));
        }
        for &b in &buf[..n] {
            if b == b'\n' {
                self.line += 1;
                self.line_len = 0;
            } else {
                self.line_len += 1;
                if self.line_len > self.max_line {
                    return Err(io::Error::new(
                        io::ErrorKind::InvalidData,
                        format!(
                            "line {} is longer than {} bytes (not a file of records)",
                            self.line, self.max_line
                        ),
                    ));
                }
            }
        }
        Ok(n)
    }
}
