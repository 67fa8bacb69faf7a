//! From a [`Spec`] to cells: the cartesian product of the axes (first axis outermost, last
//! fastest) less the skipped cells, each cell resolved by the scenario crate from the spec's `[set]` entries and the
//! cell's levels, passed as `--set` arguments, so a spec key is read and checked exactly as
//! `platoonsim run --set KEY=VALUE` reads and checks it. A key that fails is reported under
//! its spec key: the `[set]` entries are tried together and, if they fail, one by one; each
//! axis level is tried on top of them before the cells are built.

use super::spec::{label, set_arg, Spec, SpecError};
use crate::design::{Cell, Labels};
use platoonsim_scenario::{load_with, Overrides, ScenarioError};
use platoonsim_sim::Config;

/// The level indices of every cell, first axis outermost, without the skipped ones.
pub fn combinations(spec: &Spec) -> Vec<Vec<usize>> {
    spec.combinations()
}

/// The cells of a sweep, in [`combinations`] order; labels are the axis keys (a bundle's
/// name) with the levels as text ([`label`]).
pub fn cells(spec: &Spec) -> Result<Vec<Cell>, SpecError> {
    let fixed: Vec<String> = spec.set.iter().map(|(k, v)| set_arg(k, v)).collect();
    let load = |set: Vec<String>| -> Result<Config, ScenarioError> {
        load_with(
            &spec.scenario,
            &Overrides {
                set,
                ..Overrides::default()
            },
        )
    };
    let err = |key: String, e: ScenarioError| SpecError {
        origin: spec.origin.clone(),
        key,
        message: e.to_string(),
    };
    // The scenario itself, then each fixed key, then each level on top of the fixed keys.
    load(Vec::new()).map_err(|e| err("scenario".into(), e))?;
    if let Err(all) = load(fixed.clone()) {
        // Keys may depend on each other (a duration and its warm-up): blame a key only if it
        // fails on its own, else the combination.
        for (i, (k, _)) in spec.set.iter().enumerate() {
            load(vec![fixed[i].clone()]).map_err(|e| err(format!("set.\"{k}\""), e))?;
        }
        return Err(err("set (the keys together)".into(), all));
    }
    for a in &spec.axes {
        for (l, v) in a.levels.iter().enumerate() {
            let mut set = fixed.clone();
            set.extend(a.members(l).into_iter().map(|(k, v)| set_arg(k, v)));
            load(set).map_err(|e| err(format!("axes.\"{}\" = {v}", a.key), e))?;
        }
    }
    let mut cells = Vec::new();
    for combo in combinations(spec) {
        let set: Vec<String> = spec
            .settings(&combo)
            .iter()
            .map(|(k, v)| set_arg(k, v))
            .collect();
        let mut labels = Labels::new();
        for (a, &l) in spec.axes.iter().zip(&combo) {
            labels = labels.with(&a.key, label(&a.levels[l]));
        }
        let config = load(set).map_err(|e| {
            let levels: Vec<String> = labels.0.iter().map(|(k, v)| format!("{k} = {v}")).collect();
            err(format!("axes (the cell {})", levels.join(", ")), e)
        })?;
        cells.push(Cell { labels, config });
    }
    Ok(cells)
}
