//! Reading an input file whole, bounded: a regular file (or a symlink to one), at most
//! [`MAX_BYTES`], gzip-compressed or plain (SUMO writes `.net.xml.gz` on request), and UTF-8.

use crate::ImportError;
use flate2::read::MultiGzDecoder;
use std::fs::File;
use std::io::Read;
use std::path::Path;

/// The largest file (and decompressed text) read: a whole-state freeway network from
/// OpenStreetMap is tens of MB; the XML tree takes several times the text.
pub const MAX_BYTES: u64 = 512 << 20;

pub fn text(path: &Path) -> Result<String, ImportError> {
    let io = |source| ImportError::Io {
        path: path.to_path_buf(),
        source,
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    let ft = meta.file_type();
    if !ft.is_file() {
        return Err(ImportError::NotRegular {
            path: path.to_path_buf(),
            kind: platoonsim_scenario::bounded::describe(&ft),
        });
    }
    if meta.len() > MAX_BYTES {
        return Err(too_large(path, meta.len()));
    }
    let mut raw = Vec::with_capacity(meta.len() as usize);
    File::open(path)
        .map_err(io)?
        .take(MAX_BYTES + 1)
        .read_to_end(&mut raw)
        .map_err(io)?;
    if raw.starts_with(&[0x1f, 0x8b]) {
        let mut out = Vec::new();
        MultiGzDecoder::new(&raw[..])
            .take(MAX_BYTES + 1)
            .read_to_end(&mut out)
            .map_err(|e| ImportError::Xml {
                path: path.to_path_buf(),
                msg: format!("a broken gzip stream: {e}"),
            })?;
        raw = out;
    }
    if raw.len() as u64 > MAX_BYTES {
        return Err(too_large(path, raw.len() as u64));
    }
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
