//! Import errors: each names the file (and line), the element or edge, what was found and what
//! is allowed.

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum ImportError {
    #[error("{}: {source}", path.display())]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{}: not a regular file (a {kind}); give a SUMO XML file", path.display())]
    NotRegular { path: PathBuf, kind: &'static str },
    #[error("{}: {size} bytes, more than the {limit} bytes a SUMO file may have here", path.display())]
    TooLarge {
        path: PathBuf,
        size: u64,
        limit: u64,
    },
    #[error("{}: not XML: {msg}", path.display())]
    Xml { path: PathBuf, msg: String },
    /// A file that is XML but not what was expected (wrong root, bad attribute).
    #[error("{}{}: {what}: {problem}", path.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
    Invalid {
        path: PathBuf,
        line: Option<u32>,
        what: String,
        problem: String,
    },
    /// The network has no corridor the importer can represent.
    #[error("not a corridor: {0}")]
    NotCorridor(String),
    /// A command-line value.
    #[error("{flag} {value}: {problem}")]
    Flag {
        flag: &'static str,
        value: String,
        problem: String,
    },
}
