//! Reading an input file whole, bounded: a regular file (or a symlink to one), at most
//! [`MAX_BYTES`], gzip-compressed or plain (SUMO writes `.net.xml.gz` on request), and UTF-8.

//! The reading itself is the bounded crate's gzip mode (`platoonsim_bounded::gzip`), shared
//! with the field-data readers.

use crate::ImportError;
use platoonsim_bounded::gzip;
use std::path::Path;

/// The largest file (and decompressed text) read: a whole-state freeway network from
/// OpenStreetMap is tens of MB; the XML tree takes several times the text.
pub const MAX_BYTES: u64 = 512 << 20;

pub fn text(path: &Path) -> Result<String, ImportError> {
    let raw = gzip::read(path, MAX_BYTES).map_err(|e| match e {
        gzip::Error::NotRegular { kind } => ImportError::NotRegular {
            path: path.to_path_buf(),
            kind,
        },
        gzip::Error::TooLarge { size, .. } => too_large(path, size),
        gzip::Error::Io(source) => ImportError::Io {
            path: path.to_path_buf(),
            source,
        },
        gzip::Error::Gzip(e) => ImportError::Xml {
            path: path.to_path_buf(),
            msg: format!("a broken gzip stream: {e}"),
        },
    })?;
    String::from_utf8(raw).map_err(|e| ImportError::Xml {
        path: path.to_path_buf(),
        msg: format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to()),
    })
}

/// Every file of `paths` read with [`text`], in order, with its path.
pub fn texts(
    paths: &[std::path::PathBuf],
) -> Result<Vec<(std::path::PathBuf, String)>, ImportError> {
    paths.iter().map(|p| Ok((p.clone(), text(p)?))).collect()
}

fn too_large(path: &Path, size: u64) -> ImportError {
    ImportError::TooLarge {
        path: path.to_path_buf(),
        size,
        limit: MAX_BYTES,
    }
}
