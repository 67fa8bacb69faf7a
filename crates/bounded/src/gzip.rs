//! The gzip mode (feature `gzip`): a file that starts with the gzip magic bytes `1f 8b`
//! (RFC 1952, section 2.3.1) is decompressed, whatever its name, so a renamed file still
//! reads. Both the file and the decompressed text are bounded, so a small "zip bomb" never
//! becomes an unbounded allocation. The SUMO importer and the field-data readers read through
//! it.

use std::fs::File;
use std::io::{self, BufRead, BufReader, Read};
use std::path::Path;

use flate2::bufread::MultiGzDecoder;

use crate::{describe, LineLimit};

/// The gzip magic bytes (RFC 1952, section 2.3.1).
pub const MAGIC: [u8; 2] = [0x1f, 0x8b];

/// Why a file could not be read; the caller names the path.
#[derive(Debug)]
pub enum Error {
    /// Not a regular file: what it is, in words ("FIFO", "character device", ...).
    NotRegular { kind: &'static str },
    /// The file, or its decompressed text, is larger than the bound.
    TooLarge { size: u64, limit: u64 },
    /// The file could not be opened or read.
    Io(io::Error),
    /// The gzip stream is broken (truncated, corrupt).
    Gzip(io::Error),
}

/// The size of `path` if it is a regular file of at most `limit` bytes.
fn check(path: &Path, limit: u64) -> Result<u64, Error> {
    let meta = std::fs::metadata(path).map_err(Error::Io)?;
    if !meta.is_file() {
        return Err(Error::NotRegular {
            kind: describe(&meta.file_type()),
        });
    }
    if meta.len() > limit {
        return Err(Error::TooLarge {
            size: meta.len(),
            limit,
        });
    }
    Ok(meta.len())
}

/// The whole of a regular file of at most `limit` bytes, decompressed if it is gzip (the text
/// at most `limit` bytes too).
pub fn read(path: &Path, limit: u64) -> Result<Vec<u8>, Error> {
    let size = check(path, limit)?;
    let mut raw = Vec::with_capacity(size as usize);
    File::open(path)
        .map_err(Error::Io)?
        .take(limit + 1)
        .read_to_end(&mut raw)
        .map_err(Error::Io)?;
    if raw.starts_with(&MAGIC) {
        let mut out = Vec::new();
        MultiGzDecoder::new(&raw[..])
            .take(limit + 1)
            .read_to_end(&mut out)
            .map_err(Error::Gzip)?;
        raw = out;
    }
    if raw.len() as u64 > limit {
        return Err(Error::TooLarge {
            size: raw.len() as u64,
            limit,
        });
    }
    Ok(raw)
}

/// A regular file of at most `max_file` bytes opened as lines of text: decompressed if it is
/// gzip, the text bounded through [`LineLimit`] (`max_line` per line, `max_text` in all).
pub struct Lines {
    /// Whether the file was gzip: a read error of `reader` is then a broken stream.
    pub gzip: bool,
    pub reader: Box<dyn BufRead>,
}

/// Opens `path` for [`Lines`].
pub fn open(path: &Path, max_file: u64, max_line: usize, max_text: u64) -> Result<Lines, Error> {
    check(path, max_file)?;
    let mut buf = BufReader::new(File::open(path).map_err(Error::Io)?);
    let gzip = buf.fill_buf().map_err(Error::Io)?.starts_with(&MAGIC);
    let text: Box<dyn Read> = if gzip {
        Box::new(MultiGzDecoder::new(buf))
    } else {
        Box::new(buf)
    };
    Ok(Lines {
        gzip,
        reader: Box::new(BufReader::new(LineLimit::new(text, max_line, max_text))),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use flate2::write::GzEncoder;
    use std::io::Write;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir =
            std::env::temp_dir().join(format!("platoonsim-gzip-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn gz(bytes: &[u8]) -> Vec<u8> {
        let mut e = GzEncoder::new(Vec::new(), flate2::Compression::default());
        e.write_all(bytes).unwrap();
        e.finish().unwrap()
    }

    #[test]
    fn gzip_is_told_by_its_magic_bytes_and_bounded_after_decompression() {
        let dir = scratch("read");
        let plain = dir.join("a.txt");
        std::fs::write(&plain, "a,b\n").unwrap();
        assert_eq!(read(&plain, 100).unwrap(), b"a,b\n");
        // A gzip file without the .gz name is decompressed all the same.
        let packed = dir.join("b.txt");
        std::fs::write(&packed, gz(&[b'x'; 1000])).unwrap();
        assert_eq!(read(&packed, 1000).unwrap().len(), 1000);
        // Small on disk, too large once decompressed.
        match read(&packed, 999) {
            Err(Error::TooLarge {
                size: 1000,
                limit: 999,
            }) => {}
            other => panic!("{other:?}"),
        }
        let mut broken = gz(b"hello, world");
        broken.truncate(broken.len() - 6);
        std::fs::write(&packed, broken).unwrap();
        assert!(matches!(read(&packed, 100), Err(Error::Gzip(_))));
        match read(Path::new("/dev/zero"), 100) {
            Err(Error::NotRegular { kind }) => assert_eq!(kind, "character device"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn lines_are_bounded_in_both_modes() {
        let dir = scratch("open");
        let packed = dir.join("c.csv.gz");
        std::fs::write(&packed, gz(b"a,b\n1,2,3,4,5\n")).unwrap();
        let mut lines = open(&packed, 100, 100, 100).unwrap();
        assert!(lines.gzip);
        let mut s = String::new();
        lines.reader.read_to_string(&mut s).unwrap();
        assert_eq!(s, "a,b\n1,2,3,4,5\n");
        let mut lines = open(&packed, 100, 4, 100).unwrap();
        let e = lines.reader.read_to_string(&mut s).unwrap_err();
        assert_eq!(
            e.to_string(),
            "line 2 is longer than 4 bytes (not a file of records)"
        );
        let plain = dir.join("d.csv");
        std::fs::write(&plain, "a,b\n").unwrap();
        assert!(!open(&plain, 100, 100, 100).unwrap().gzip);
        assert!(matches!(
            open(&plain, 3, 100, 100),
            Err(Error::TooLarge { size: 4, limit: 3 })
        ));
    }
}
