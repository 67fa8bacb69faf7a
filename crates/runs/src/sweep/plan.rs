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

#[cfg(test)]
mod tests {
    use super::*;
    use platoonsim_scenario::StrategyKind;

    #[test]
    fn a_bundle_level_sets_its_keys_and_skipped_cells_are_not_planned() {
        let spec = Spec::from_toml(
            "scenario = \"homogeneous\"\nseeds = 1\n\
             [set]\n\"run.duration_s\" = 600.0\n\"run.warmup_s\" = 100.0\n\
             [axes]\n\
             point = [\n\
               { \"run.penetration\" = 0.0, \"demand.vph_per_lane\" = 1000.0 },\n\
               { \"run.penetration\" = 0.5, \"demand.vph_per_lane\" = 2000.0 },\n\
             ]\n\
             \"strategy.kind\" = [\"none\", \"pd\"]\n\
             [[skip]]\n\"run.penetration\" = 0.0\n\"strategy.kind\" = \"pd\"\n",
            "s.toml",
            "s",
        )
        .unwrap();
        let cells = cells(&spec).unwrap();
        let got: Vec<(f64, f64, StrategyKind, String)> = cells
            .iter()
            .map(|c| {
                (
                    c.config.penetration,
                    c.config.demand.vph_per_lane,
                    c.config.strategy.kind,
                    c.labels.get("point").unwrap().to_string(),
                )
            })
            .collect();
        assert_eq!(
            got,
            [
                (0.0, 1000.0, StrategyKind::NONE, "0, 1000".to_string()),
                (0.5, 2000.0, StrategyKind::NONE, "0.5, 2000".to_string()),
                (0.5, 2000.0, StrategyKind::PD, "0.5, 2000".to_string()),
            ]
        );
        // A bundle level that the scenario refuses is blamed on the axis and the level.
        let mut bad = spec.clone();
        bad.axes[0].levels[1]
            .as_table_mut()
            .unwrap()
            .insert("run.penetration".into(), toml::Value::Float(1.5));
        let e = super::cells(&bad).unwrap_err();
        assert!(e.key.starts_with("axes.\"point\" = "), "{e}");
        assert!(e.message.contains("run.penetration"), "{e}");
    }
}
