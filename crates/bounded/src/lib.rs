//! Bounded reading of input files (issue 35 item 5): a reader refuses what is not a regular
//! file before opening it (a FIFO would block the open forever, `/dev/zero` never ends), and
//! bounds the bytes and the line length it reads before it allocates for them. The errors say
//! what is wrong ("not a regular file (a FIFO)"); the caller names the path.
//!
//! One crate with no dependency, so that every reader uses it: the scenario, sweep,
//! calibration and table readers (through `platoonsim_scenario::bounded`), the CLI's record
//! readers, the viewer's and the field data's readers, the SUMO importer, and the atomic
//! writer's refusal of special files.

#[cfg(feature = "gzip")]
pub mod gzip;
pub mod output;

use std::fs;
use std::io::{self, Read};
use std::path::Path;

/// The largest file of records read (trajectories, detectors, trips): 16 GiB, four times the
/// largest `trajectories.csv` a run may record (its 4 GiB memory bound, docs/robustness.md).
pub const MAX_RECORD_FILE_BYTES: u64 = 16 << 30;
/// The longest line of a file of records: 64 KiB (a trajectory or trip row is under 200 bytes;
/// a corrupt file without line breaks would otherwise become one record of its whole size).
pub const MAX_RECORD_LINE_BYTES: usize = 64 << 10;

/// The metadata of `path` (links followed) if it is a regular file; otherwise an error
/// saying what it is. A missing path keeps the system's "No such file or directory".
pub fn regular_file(path: &Path) -> io::Result<fs::Metadata> {
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
pub fn describe(kind: &fs::FileType) -> &'static str {
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
pub fn read(path: &Path, max: u64) -> io::Result<Vec<u8>> {
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
pub fn read_text(path: &Path, max: u64) -> io::Result<String> {
    String::from_utf8(read(path, max)?)
        .map_err(|e| io::Error::new(io::ErrorKind::InvalidData, format!("not UTF-8 text ({e})")))
}

/// A regular file of at most `max_bytes`, opened for streaming through [`LineLimit`].
pub fn open_records(
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
pub struct LineLimit<R> {
    inner: R,
    max_line: usize,
    max_total: u64,
    line_len: usize,
    total: u64,
    line: u64,
}

impl<R: Read> LineLimit<R> {
    pub fn new(inner: R, max_line: usize, max_total: u64) -> Self {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir =
            std::env::temp_dir().join(format!("platoonsim-bounded-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[cfg(unix)]
    #[test]
    fn special_files_are_refused_before_they_are_opened() {
        let dir = scratch("special");
        let fifo = dir.join("fifo");
        assert!(std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success());
        // Opening a FIFO without a writer would block forever: the check comes first.
        let e = read(&fifo, 100).unwrap_err().to_string();
        assert_eq!(e, "not a regular file (a FIFO)");
        let e = read(Path::new("/dev/zero"), 100).unwrap_err().to_string();
        assert_eq!(e, "not a regular file (a character device)");
        let e = read(&dir, 100).unwrap_err().to_string();
        assert_eq!(e, "not a regular file (a directory)");
        let e = open_records(&fifo, 100, 10).unwrap_err().to_string();
        assert_eq!(e, "not a regular file (a FIFO)");
        let e = read(&dir.join("missing"), 100).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::NotFound);
    }

    #[test]
    fn sizes_and_lines_are_bounded() {
        let dir = scratch("sizes");
        let f = dir.join("f.csv");
        fs::write(&f, "a,b\n1,2\n").unwrap();
        assert_eq!(read_text(&f, 8).unwrap(), "a,b\n1,2\n");
        assert_eq!(
            read(&f, 7).unwrap_err().to_string(),
            "8 bytes: at most 7 bytes are read"
        );
        let mut s = String::new();
        open_records(&f, 8, 3)
            .unwrap()
            .read_to_string(&mut s)
            .unwrap();
        assert_eq!(s, "a,b\n1,2\n");
        fs::write(&f, "a,b\n1,2,3,4\n").unwrap();
        let e = open_records(&f, 100, 3)
            .unwrap()
            .read_to_string(&mut s)
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "line 2 is longer than 3 bytes (not a file of records)"
        );
        let e = LineLimit::new(io::repeat(b'\n'), 3, 1000)
            .read_to_end(&mut Vec::new())
            .unwrap_err();
        assert_eq!(e.to_string(), "more than 1000 bytes");
    }
}
