//! The sweep file (`SPEC.toml`): which scenario, which seeds, fixed overrides, the axes whose
//! cartesian product makes the cells (less the `[[skip]]`ped ones), and an optional reference
//! level for paired differences. Keys under `[set]`, `[axes]` and `[compare]` are the dotted
//! keys of `platoonsim run --set`; every value is checked by the scenario crate exactly as a
//! `--set` of it would be (`platoonsim_runs::sweep::plan`). Every error here names the spec
//! key. docs/sweeps.md describes the format.
//!
//! ```toml
//! name = "my-study"                    # optional: the output directory's name (default: file stem)
//! scenario = "my_corridor.toml"        # a built-in name, or a path relative to this file
//! seeds = 10                           # 1..=10, or a list such as [1, 2, 7]
//! metrics = ["discharge_flow_vphpl"]   # optional: the metrics of summary.md and the figures
//! [set]                                # fixed overrides, as --set
//! "run.duration_s" = 3600
//! [axes]                               # the cartesian product, first axis outermost
//! "run.penetration" = [0.2, 0.4]
//! driver = [                           # a bundle: keys that move together, a level each
//!     { name = "published", "lane_change.gap_rule" = "published" },
//!     { name = "safe", "lane_change.gap_rule" = "safe" },
//! ]
//! "strategy.kind" = ["none", "pd", "flow-aware"]
//! [[skip]]                             # cells left out: every key at one of its values
//! "run.penetration" = 0.2
//! "strategy.kind" = "flow-aware"
//! [compare]                            # paired differences against a reference level
//! "strategy.kind" = "none"
//! ```

mod axes;

pub use axes::{Axis, Skip};
use std::path::{Path, PathBuf};
use toml::{Table, Value};

/// Why a sweep file cannot be used. The message names the spec key (`axes."run.penetration"`),
/// the value and what is allowed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{origin}: {key}: {message}")]
pub struct SpecError {
    pub origin: String,
    pub key: String,
    pub message: String,
}

/// How many runs one sweep may ask for: far beyond any study, well short of exhausting
/// memory with run specs.
pub const MAX_RUNS: usize = 100_000;

/// The largest sweep file read (as for scenario files).
pub const MAX_FILE_BYTES: u64 = 1 << 20;

/// A validated sweep file (the scenario keys are checked later, when the cells are built).
#[derive(Clone, Debug, PartialEq)]
pub struct Spec {
    /// The output directory's name.
    pub name: String,
    /// Where the spec came from (for messages).
    pub origin: String,
    /// The file's `description`, if any (shown in `summary.md`).
    pub description: Option<String>,
    /// A built-in scenario name or a file path (resolved against the spec's directory).
    pub scenario: String,
    pub seeds: Vec<u64>,
    /// Fixed overrides in file order.
    pub set: Vec<(String, Value)>,
    pub axes: Vec<Axis>,
    /// The compared axis (an index into `axes`) and its reference level (an index into its
    /// levels).
    pub compare: Option<(usize, usize)>,
    /// The metrics shown in `summary.md` and drawn; empty = the default list.
    pub metrics: Vec<String>,
    /// `[labels]`: how an experiment's tables name the cells, (label, key of `[set]` or
    /// `[axes]`) in file order; the experiments read it, `platoonsim sweep` labels cells by
    /// their axis keys.
    pub labels: Vec<(String, String)>,
    /// `[[skip]]`: the cells left out of the product.
    pub skip: Vec<Skip>,
    /// The file's text, kept in the provenance.
    pub text: String,
}

/// The `[labels]` key that names the cell's scenario.
pub const SCENARIO: &str = "scenario";

/// The text of a spec file of at most `max` bytes (`what` names it in the error), with its
/// origin for messages and its stem (`default_stem` if it has none).
pub fn read_bounded(
    path: &Path,
    what: &str,
    max: u64,
    default_stem: &str,
) -> Result<(String, String, String), SpecError> {
    let origin = path.display().to_string();
    let err = |message: String| SpecError {
        origin: origin.clone(),
        key: "(file)".into(),
        message,
    };
    use crate::bounded;
    // Regular files only (a FIFO blocks the open, /dev/zero never ends), size checked first.
    let meta = bounded::regular_file(path).map_err(|e| err(format!("cannot read it: {e}")))?;
    if meta.len() > max {
        return Err(err(format!(
            "{} bytes: {what} must be at most {max} bytes",
            meta.len()
        )));
    }
    let text = bounded::read_text(path, max).map_err(|e| err(format!("cannot read it: {e}")))?;
    let stem = path.file_stem().map_or_else(
        || default_stem.to_string(),
        |s| s.to_string_lossy().into_owned(),
    );
    Ok((text, origin, stem))
}

impl Spec {
    /// Read and validate a sweep file.
    pub fn from_file(path: &Path) -> Result<Spec, SpecError> {
        let (text, origin, stem) = read_bounded(path, "a sweep file", MAX_FILE_BYTES, "sweep")?;
        let mut spec = Spec::from_toml(&text, &origin, &stem)?;
        // A scenario path is relative to the sweep file, so a spec and its corridor travel
        // together.
        if looks_like_path(&spec.scenario) || crate::builtin(&spec.scenario).is_none() {
            let p = PathBuf::from(&spec.scenario);
            if p.is_relative() {
                let dir = path.parent().unwrap_or(Path::new(""));
                spec.scenario = dir.join(p).display().to_string();
            }
        }
        Ok(spec)
    }

    /// Validate a sweep file's text; `default_name` names the output when the file does not.
    pub fn from_toml(text: &str, origin: &str, default_name: &str) -> Result<Spec, SpecError> {
        let err = |key: &str, message: String| SpecError {
            origin: origin.to_string(),
            key: key.to_string(),
            message,
        };
        let doc: Table = text
            .parse()
            .map_err(|e: toml::de::Error| err("(syntax)", e.to_string().trim_end().to_string()))?;
        const KEYS: [&str; 10] = [
            "name",
            "description",
            "scenario",
            "seeds",
            "metrics",
            "set",
            "axes",
            "compare",
            "labels",
            "skip",
        ];
        for k in doc.keys() {
            if !KEYS.contains(&k.as_str()) {
                return Err(err(
                    k,
                    format!("unknown key; a sweep file has {}", KEYS.join(", ")),
                ));
            }
        }
        let name = name_of(&doc, default_name).map_err(|m| err("name", m))?;
        let description = match doc.get("description") {
            None => None,
            Some(Value::String(d)) => Some(d.clone()),
            Some(v) => return Err(err("description", format!("{v} is not a string"))),
        };
        let scenario = match doc.get("scenario") {
            Some(Value::String(s)) if !s.trim().is_empty() => s.clone(),
            Some(v) => {
                return Err(err(
                    "scenario",
                    format!("{v} is not a built-in scenario name or a file path (a string)"),
                ))
            }
            None => {
                return Err(err(
                    "scenario",
                    "missing; give a built-in name (\"homogeneous\", \"sr99\") or a scenario \
                     file path"
                        .into(),
                ))
            }
        };
        let seeds = seeds(doc.get("seeds")).map_err(|m| err("seeds", m))?;
        let set = match doc.get("set") {
            None => Vec::new(),
            Some(Value::Table(t)) => {
                let mut out = Vec::new();
                for (k, v) in t {
                    let key = format!("set.\"{k}\"");
                    check_key(k).map_err(|m| err(&key, m))?;
                    if matches!(v, Value::Table(_)) {
                        return Err(err(
                            &key,
                            "is a table; write each key in full, quoted (\"run.duration_s\" = 3600)"
                                .into(),
                        ));
                    }
                    out.push((k.clone(), v.clone()));
                }
                out
            }
            Some(v) => return Err(err("set", format!("{v} is not a table of KEY = VALUE"))),
        };
        let axes = axes::parse(&doc, &set, &err)?;
        let cells = axes
            .iter()
            .try_fold(1usize, |n, a| n.checked_mul(a.levels.len()));
        match cells.and_then(|c| c.checked_mul(seeds.len())) {
            Some(runs) if runs <= MAX_RUNS => {}
            _ => {
                return Err(err(
                    "axes",
                    format!("the sweep would have more than {MAX_RUNS} runs (cells x seeds)"),
                ))
            }
        }
        let skip = axes::parse_skip(&doc, &axes, &err)?;
        if axes::combinations(&axes, &skip).is_empty() {
            return Err(err("skip", "the rules leave out every cell".into()));
        }
        let compare = match doc.get("compare") {
            None => None,
            Some(Value::Table(t)) if t.len() == 1 => {
                let (k, v) = t.iter().next().expect("one entry");
                let key = format!("compare.\"{k}\"");
                let Some(a) = axes.iter().position(|a| &a.key == k) else {
                    return Err(err(
                        &key,
                        format!(
                            "is not an axis; the axes are {}",
                            axes.iter()
                                .map(|a| a.key.as_str())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    ));
                };
                let Some(l) = axes[a].levels.iter().position(|x| label(x) == label(v)) else {
                    return Err(err(
                        &key,
                        format!(
                            "{v} is not one of the axis' levels ({})",
                            axes[a]
                                .levels
                                .iter()
                                .map(label)
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    ));
                };
                Some((a, l))
            }
            Some(v) => {
                return Err(err(
                    "compare",
                    format!("{v}: expected one entry, an axis and its reference level"),
                ))
            }
        };
        let metrics = match doc.get("metrics") {
            None => Vec::new(),
            Some(Value::Array(a)) if a.iter().all(Value::is_str) && !a.is_empty() => a
                .iter()
                .filter_map(|v| v.as_str().map(str::to_string))
                .collect(),
            Some(v) => {
                return Err(err(
                    "metrics",
                    format!("{v} is not a non-empty list of metric names"),
                ))
            }
        };
        let labels = match doc.get("labels") {
            None => Vec::new(),
            Some(Value::Table(t)) => {
                let mut out = Vec::new();
                for (name, v) in t {
                    let key = match v {
                        Value::String(k)
                            if k == SCENARIO
                                || set.iter().any(|(s, _)| s == k)
                                || axes
                                    .iter()
                                    .any(|a| &a.key == k || a.keys().contains(&k.as_str())) =>
                        {
                            k.clone()
                        }
                        _ => {
                            return Err(err(
                                &format!("labels.{name}"),
                                format!(
                                    "{v}: expected, as a string, \"scenario\", a key of [set] or \
                                     one that an axis sets, or an axis' name"
                                ),
                            ))
                        }
                    };
                    if !valid_name(name) {
                        return Err(err(
                            &format!("labels.{name}"),
                            "a label name is letters, digits, '_', '-' or '.'".into(),
                        ));
                    }
                    out.push((name.clone(), key));
                }
                out
            }
            Some(v) => {
                return Err(err(
                    "labels",
                    format!("{v}: expected a table of label names and keys"),
                ))
            }
        };
        Ok(Spec {
            name,
            origin: origin.to_string(),
            description,
            scenario,
            seeds,
            set,
            axes,
            compare,
            metrics,
            labels,
            skip,
            text: text.to_string(),
        })
    }

    /// The level indices of every cell, first axis outermost (last fastest), without the
    /// skipped ones.
    pub fn combinations(&self) -> Vec<Vec<usize>> {
        axes::combinations(&self.axes, &self.skip)
    }

    /// The number of cells (1 without axes).
    pub fn cell_count(&self) -> usize {
        self.combinations().len()
    }

    /// The scenario keys and values of a cell: the `[set]` entries, then each axis' in axis
    /// order.
    pub fn settings(&self, combo: &[usize]) -> Vec<(String, Value)> {
        let mut out = self.set.clone();
        for (a, &l) in self.axes.iter().zip(combo) {
            out.extend(
                a.members(l)
                    .into_iter()
                    .map(|(k, v)| (k.to_string(), v.clone())),
            );
        }
        out
    }

    /// The text of a `[labels]` key in a cell: the scenario's name for `"scenario"`, a
    /// `[set]` value, or what an axis gives the key (a level, a bundle level's label or one
    /// of its values).
    pub fn label_of(&self, combo: &[usize], key: &str) -> Option<String> {
        if key == SCENARIO {
            return Some(self.scenario.clone());
        }
        if let Some((_, v)) = self.set.iter().find(|(k, _)| k == key) {
            return Some(label(v));
        }
        axes::value_label(&self.axes, combo, key)
    }
}

/// Whether the scenario argument is a path rather than a built-in name.
fn looks_like_path(s: &str) -> bool {
    s.contains(['/', '\\']) || s.ends_with(".toml")
}

/// A file's `name`: the key's value, or `default_name` (the file's stem) when the key is left
/// out; each must be a [`valid_name`], since it names the output directory. Shared by sweep
/// and calibration-parameter files; `Err` is the message for the key `name`.
pub fn name_of(doc: &toml::Table, default_name: &str) -> Result<String, String> {
    match doc.get("name") {
        None if !valid_name(default_name) => Err(format!(
            "missing, and the file's name gives {default_name:?}, which is not a name: letters, \
             digits, '_', '-' and '.', not starting with '.' (it names the output directory; \
             set name = \"...\")"
        )),
        None => Ok(default_name.to_string()),
        Some(toml::Value::String(s)) if valid_name(s) => Ok(s.clone()),
        Some(v) => Err(format!(
            "{v} is not a name: letters, digits, '_', '-' and '.', not starting with '.' (it \
             names the output directory)"
        )),
    }
}

/// A name that can name an output directory: letters, digits, `_`, `-` and `.`, not starting
/// with `.`, at most 100 characters.
pub fn valid_name(s: &str) -> bool {
    !s.is_empty()
        && !s.starts_with('.')
        && s.len() <= 100
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'))
}

/// A dotted scenario key, as `--set` reads it; the seed is the sweep's own.
pub fn check_key(k: &str) -> Result<(), String> {
    if let Err(crate::ScenarioError::Override { reason, .. }) = crate::overrides::check_key(k) {
        return Err(reason);
    }
    if k == "run.seed" {
        return Err("the seed is set by the sweep's `seeds`, not as a scenario key".into());
    }
    Ok(())
}

fn seeds(v: Option<&Value>) -> Result<Vec<u64>, String> {
    let positive = |i: i64| -> Result<u64, String> {
        u64::try_from(i)
            .ok()
            .filter(|&s| s >= 1)
            .ok_or_else(|| format!("{i} is not a seed: seeds are integers from 1"))
    };
    match v {
        None => Err("missing; give a count N (seeds 1..=N) or a list of seeds".into()),
        Some(Value::Integer(n)) => {
            let n = positive(*n)?;
            if n as usize > MAX_RUNS {
                return Err(format!("{n} seeds: at most {MAX_RUNS}"));
            }
            Ok((1..=n).collect())
        }
        Some(Value::Array(a)) if !a.is_empty() => {
            let mut out: Vec<u64> = Vec::with_capacity(a.len());
            for x in a {
                let s = match x {
                    Value::Integer(i) => positive(*i)?,
                    other => return Err(format!("{other} is not an integer seed")),
                };
                if out.contains(&s) {
                    return Err(format!("the seed {s} is listed twice"));
                }
                out.push(s);
            }
            Ok(out)
        }
        Some(other) => Err(format!(
            "{other}: expected a count N (seeds 1..=N) or a non-empty list of seeds"
        )),
    }
}

/// A level as it appears in the tables: strings bare, numbers in their shortest form
/// (`0.5`, `2500`), booleans as `true`/`false`.
/// A bundle's level is its `name`, or its values joined by ", ".
pub fn label(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        Value::Table(t) => match t.get(axes::NAME) {
            Some(n) => label(n),
            None => t.values().map(label).collect::<Vec<_>>().join(", "),
        },
        Value::Float(f) => format!("{f}"),
        Value::Integer(i) => i.to_string(),
        other => other.to_string(),
    }
}

/// A level as the value of a `--set KEY=VALUE` argument (TOML, so the scenario crate reads
/// back the same value).
pub fn set_arg(key: &str, v: &Value) -> String {
    format!("{key}={v}")
}

/// The level as a number, if it is one.
pub fn number(v: &Value) -> Option<f64> {
    match v {
        Value::Float(f) => Some(*f),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

#[cfg(test)]
mod tests;
