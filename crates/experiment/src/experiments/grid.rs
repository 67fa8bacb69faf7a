//! A grid experiment's cells from its sweep file (`sweeps/<name>.toml`, embedded in the
//! binary): the file's `[set]` and `[axes]` resolved as `platoonsim sweep` resolves them
//! (so the runs, their keys and results are the sweep's), with the settings' duration and
//! warm-up in place of the file's `run.duration_s` and `run.warmup_s`, and labelled as the
//! file's `[labels]` say. The seeds are the settings' (`--seeds`, `reproduce --quick`), not
//! the file's. An experiment whose settings choose levels (`--penetrations`, the demand
//! scales) puts them in the spec before it is planned ([`levels`], [`fix`]).

use super::Settings;
use platoonsim_runs::design::Cell;
use platoonsim_runs::sweep::plan;
use platoonsim_runs::sweep::spec::{Axis, Spec};
use platoonsim_runs::{Error, Labels};
use platoonsim_scenario::preset;
use toml::Value;

/// The sweep file of a grid experiment, parsed (it is part of the binary: a failure is a
/// bug, reported as an error naming the file), with the settings' duration and warm-up.
pub(crate) fn spec(name: &str, text: &str, s: &Settings) -> Result<Spec, Error> {
    let mut spec = parse(name, text)?;
    for (k, v) in &mut spec.set {
        match k.as_str() {
            "run.duration_s" => *v = Value::Float(s.duration_s),
            "run.warmup_s" => *v = Value::Float(s.warmup_s),
            _ => {}
        }
    }
    if s.preset != Settings::default().preset {
        fix(
            &mut spec,
            preset::KEY,
            Value::String(s.preset.as_str().into()),
        );
    }
    Ok(spec)
}

fn parse(name: &str, text: &str) -> Result<Spec, Error> {
    Spec::from_toml(text, &format!("sweeps/{name}.toml"), name)
        .map_err(|e| Error::Other(e.to_string()))
}

/// Fix a key for every cell: its `[set]` value replaced, or added last.
pub(crate) fn fix(spec: &mut Spec, key: &str, v: Value) {
    match spec.set.iter_mut().find(|(k, _)| k == key) {
        Some((_, old)) => *old = v,
        None => spec.set.push((key.to_string(), v)),
    }
}

/// Replace the levels of the axis `key` (a bundle's levels: tables of its keys).
pub(crate) fn levels(spec: &mut Spec, key: &str, levels: Vec<Value>) -> Result<(), Error> {
    let axis: &mut Axis = spec
        .axes
        .iter_mut()
        .find(|a| a.key == key)
        .ok_or_else(|| Error::Other(format!("{}: no axis {key}", spec.origin)))?;
    axis.levels = levels;
    Ok(())
}

/// The cells of a spec, in the sweep's order (first axis outermost), labelled by its
/// `[labels]`.
pub(crate) fn cells_of(spec: &Spec) -> Result<Vec<Cell>, Error> {
    let cells = plan::cells(spec).map_err(|e| Error::Other(e.to_string()))?;
    Ok(cells
        .into_iter()
        .zip(spec.combinations())
        .map(|(c, combo)| {
            let mut labels = Labels::new();
            for (l, key) in &spec.labels {
                labels = labels.with(l, spec.label_of(&combo, key).unwrap_or_default());
            }
            Cell {
                labels,
                config: c.config,
            }
        })
        .collect())
}

/// The cells of a grid experiment with these settings.
pub(crate) fn cells(name: &str, text: &str, s: &Settings) -> Result<Vec<Cell>, Error> {
    cells_of(&spec(name, text, s)?)
}

/// The number of cells of the grid (0 if the file does not parse, which its test catches).
pub(crate) fn cell_count(name: &str, text: &str) -> usize {
    parse(name, text).map_or(0, |s| s.cell_count())
}

/// A number as a level.
pub(crate) fn float(v: f64) -> Value {
    Value::Float(v)
}

#[cfg(test)]
mod tests {
    use super::super::{behaviour, capacity, energy, sr99};
    use super::*;

    fn as_shipped(name: &str, text: &str) -> Vec<Cell> {
        cells_of(&parse(name, text).unwrap()).unwrap()
    }

    /// `platoonsim sweep sweeps/NAME.toml` plans the experiment's cells at its defaults: the
    /// files' levels are the settings' defaults and the embedded demand-scale table.
    #[test]
    fn the_shipped_files_are_the_experiments_default_grids() {
        let s = Settings::default();
        assert_eq!(as_shipped("sr99", sr99::SWEEP), sr99::cells(&s).unwrap());
        let mut both = as_shipped("energy", energy::SWEEP);
        both.extend(as_shipped("energy-sr99", energy::SWEEP_SR99));
        assert_eq!(both, energy::cells(&s).unwrap().0);
        assert_eq!(
            as_shipped("behaviour", behaviour::SWEEP),
            cells("behaviour", behaviour::SWEEP, &s).unwrap()
        );
        let stage1 = as_shipped("capacity", capacity::SWEEP);
        assert_eq!(stage1, cells_of(&capacity::stage1(&s).unwrap()).unwrap());
        // The report's table and figure go by these penetrations.
        let pens: Vec<f64> = stage1.iter().map(|c| c.config.penetration).collect();
        assert_eq!(pens, capacity::PENETRATIONS);
    }
}
