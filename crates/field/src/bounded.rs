//! Bounds on a field file (issue 35 item 5): what is not a regular file is refused before it
//! is opened (a FIFO would block the open, a device never ends); the file's size, the
//! decompressed stream and the line length are bounded before anything is allocated for them.
//! (The rules of `platoonsim_scenario::bounded`; this crate depends on no platoonsim crate.)

use std::fs;
use std::io::{self, Read};
use std::path::Path;

/// The largest field file opened (as stored, gzip or not): 16 GiB, a year of a district's
/// PeMS station_5min files in one.
pub const MAX_FILE_BYTES: u64 = 16 << 30;
/// The most text a file may decompress to: 64 GiB (a gzip stream that inflates beyond is
/// refused rather than read to the end).
pub const MAX_TEXT_BYTES: u64 = 64 << 30;
/// The longest line: 64 KiB (a PeMS row is under 2 KiB even with every lane's columns).
pub const MAX_LINE_BYTES: usize = 64 << 10;

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
