//! A grid experiment's cells from its sweep file (`sweeps/<name>.toml`, embedded in the
//! binary): the file's `[set]` and `[axes]` resolved as `platoonsim sweep` resolves them
//! (so the runs, their keys and results are the sweep's), with the settings' duration and
//! warm-up in place of the file's `run.duration_s` and `run.warmup_s`, and labelled as the
//! file's `[labels]` say. The seeds are the settings' (`--seeds`, `reproduce --quick`), not
//! the file's.

use super::Settings;
use crate::design::Cell;
use crate::sweep::plan;
use crate::sweep::spec::{label, Spec};
use crate::{Error, Labels};
use toml::Value;

/// The sweep file of a grid experiment, parsed (it is part of the binary: a failure is a
/// bug, reported as an error naming the file).
pub(crate) fn spec(name: &str, text: &str) -> Result<Spec, Error> {
    Spec::from_toml(text, &format!("sweeps/{name}.toml"), name)
        .map_err(|e| Error::Other(e.to_string()))
}

/// The cells of the grid, in the sweep's order (first axis outermost).
pub(crate) fn cells(name: &str, text: &str, s: &Settings) -> Result<Vec<Cell>, Error> {
    let mut spec = spec(name, text)?;
    for (k, v) in &mut spec.set {
        match k.as_str() {
            "run.duration_s" => *v = Value::Float(s.duration_s),
            "run.warmup_s" => *v = Value::Float(s.warmup_s),
            _ => {}
        }
    }
    let cells = plan::cells(&spec).map_err(|e| Error::Other(e.to_string()))?;
    let value = |cell: &Cell, key: &str| -> String {
        match spec.set.iter().find(|(k, _)| k == key) {
            Some((_, v)) => label(v),
            None => cell.labels.get(key).unwrap_or_default().to_string(),
        }
    };
    Ok(cells
        .into_iter()
        .map(|c| {
            let mut labels = Labels::new();
            for (l, key) in &spec.labels {
                labels = labels.with(l, value(&c, key));
            }
            Cell {
                labels,
                config: c.config,
            }
        })
        .collect())
}

/// The number of cells of the grid (0 if the file does not parse, which its test catches).
pub(crate) fn cell_count(name: &str, text: &str) -> usize {
    spec(name, text).map_or(0, |s| s.cell_count())
}
