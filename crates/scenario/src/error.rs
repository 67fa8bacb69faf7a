//! Scenario errors. Every message names where the problem is (file, key path), the value found
//! and what is allowed.

use std::fmt;
use std::path::PathBuf;

/// One invalid value found by validation: `field = value: allowed`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Problem {
    /// Key path in the scenario file, e.g. `run.penetration` or `detectors[2].position_m`.
    pub field: String,
    /// The value as found (rendered as TOML), or `(missing)`.
    pub value: String,
    /// What is allowed, as a sentence fragment, e.g. `must be in [0, 1]`.
    pub allowed: String,
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // A value quoted from the input is cut to a readable length.
        let value = clip_lines(&self.value, MAX_ECHO_CHARS);
        write!(f, "{} = {}: {}", self.field, value, self.allowed)
    }
}

/// Everything that can go wrong between a scenario name or file and a validated
/// [`platoonsim_sim::Config`].
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The argument is neither a built-in scenario nor an existing file.
    #[error("unknown scenario '{name}': not a built-in scenario (built-ins: {builtins}) and no such file")]
    UnknownScenario { name: String, builtins: String },

    /// The argument names a directory, not a scenario file.
    #[error("{}: is a directory, not a scenario file: give the path of a scenario TOML file \
             (e.g. the scenario.toml that `run` writes) or a built-in name ({builtins})", path.display())]
    Directory { path: PathBuf, builtins: String },

    /// The file is JSON (or looks like it), not TOML.
    #[error(
        "{origin}: looks like JSON, but scenario files are TOML: use the scenario.toml \
             that `run` writes beside scenario.json, or write one with \
             `platoonsim show NAME --format toml > FILE.toml`"
    )]
    NotToml { origin: String },

    /// The file exists but cannot be read. The I/O error is part of the message and not a
    /// separate cause, so that a chain printed with its causes says it once.
    #[error("cannot read scenario file {}: {cause}", path.display())]
    Io {
        path: PathBuf,
        cause: std::io::Error,
    },

    /// Larger than [`crate::limits::MAX_FILE_BYTES`]; refused before parsing, so that a huge
    /// file cannot take gigabytes of memory first.
    #[error("{origin}: {bytes} bytes: a scenario must be at most {limit} bytes (1 MiB; docs/robustness.md)")]
    TooLarge {
        origin: String,
        /// The size found (at least; reading stops just past the limit).
        bytes: u64,
        limit: usize,
    },

    /// Not valid TOML (the parser's message carries the line and column).
    #[error("{origin}: not valid TOML: {message}")]
    Syntax { origin: String, message: String },

    /// Valid TOML, but a key is unknown or a value has the wrong type.
    #[error("{origin}: {path}: {}", clip_lines(message, MAX_ECHO_CHARS))]
    Structure {
        origin: String,
        /// Key path, e.g. `road.foo` or `human.headway_s`.
        path: String,
        message: String,
    },

    /// A `--set KEY=VALUE` (or typed) override that cannot be applied.
    #[error("invalid override '{}': {reason}", clip_lines(arg, MAX_ECHO_CHARS))]
    Override { arg: String, reason: String },

    /// Well-formed, but some values are out of range or inconsistent.
    #[error("{origin}: invalid scenario:{}", list(problems))]
    Invalid {
        origin: String,
        problems: Vec<Problem>,
    },
}

/// A table by CAV penetration that cannot be read or has no usable row ([`crate::tables`],
/// [`crate::thresholds::parse`], [`crate::demand_scales::parse`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TableError {
    /// The text is not valid TOML.
    #[error("not valid TOML: {0}")]
    Syntax(String),
    /// Neither a built-in table nor a path.
    #[error("no built-in table '{name}' (built-in tables: {builtins}) and not a path (a path contains '/' or ends in .toml)")]
    Unknown { name: String, builtins: String },
    /// The file cannot be read.
    #[error("cannot read {path}: {message}")]
    Read { path: String, message: String },
    /// No row has every column the table must have (rows with `feasible = false` are skipped).
    #[error("the table has no feasible row with {columns}")]
    NoRow { columns: &'static str },
}

fn list(problems: &[Problem]) -> String {
    let mut s = String::new();
    for p in problems {
        s.push_str("\n  ");
        s.push_str(&p.to_string());
    }
    s
}

impl ScenarioError {
    /// The validation problems, if this is an [`ScenarioError::Invalid`].
    pub fn problems(&self) -> &[Problem] {
        match self {
            ScenarioError::Invalid { problems, .. } => problems,
            _ => &[],
        }
    }
}

/// The most characters of one line an error message quotes from the input.
pub const MAX_ECHO_CHARS: usize = 200;

/// `message` with every line cut to `max` characters (and marked `…`): toml quotes the line of
/// a syntax error whole, and a 400 KB line of brackets is no help on a terminal.
pub fn clip_lines(message: &str, max: usize) -> String {
    message
        .lines()
        .map(|l| match l.char_indices().nth(max) {
            Some((at, _)) => format!("{}…", &l[..at]),
            None => l.to_string(),
        })
        .collect::<Vec<_>>()
        .join("\n")
}
