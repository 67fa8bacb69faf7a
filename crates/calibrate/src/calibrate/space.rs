//! The search space: the fitted keys in normalized coordinates. CMA-ES searches in ℝⁿ; a
//! coordinate x is folded into [0, 1] by reflection at 0 and 1 (y = x mod 2, then 2 − y where
//! y > 1) and mapped to the key's bounds, value = min + y (max − min). Reflection keeps the
//! objective continuous and free of the flat plateaus that clamping would create outside the
//! box, and every candidate is inside the bounds. Normalizing gives every key the same initial
//! step (`sigma`), whatever its unit.
//!
//! Every value goes through the scenario crate's `--set` machinery, exactly as a sweep's keys:
//! the fixed `[set]` keys are checked as a sweep checks them ([`crate::sweep::plan::cells`]);
//! each fitted key is then checked at its min and at its max on top of them, so a bound the key
//! does not allow is an error naming `params."KEY".min` (or `.max`) and the value.

use super::params::{number, Param, Params};
use crate::sweep::spec::{set_arg, Spec, SpecError};
use platoonsim_scenario::{load_with, Overrides, ScenarioError};
use platoonsim_sim::Config;
use toml::Value;

/// The fitted keys over a scenario with its fixed overrides.
#[derive(Clone, Debug)]
pub struct Space {
    pub scenario: String,
    /// The `[set]` entries as `--set` arguments.
    pub fixed: Vec<String>,
    pub params: Vec<Param>,
    /// The scenario with the fixed keys (the seed is each run's).
    pub base: Config,
    /// The start point, normalized.
    pub start: Vec<f64>,
}

/// Fold a coordinate into [0, 1] by reflection at the bounds.
pub fn reflect(x: f64) -> f64 {
    let y = x.rem_euclid(2.0);
    if y > 1.0 {
        2.0 - y
    } else {
        y
    }
}

impl Space {
    /// Check the scenario, the fixed keys and every bound; find the start point.
    pub fn new(scenario: &str, p: &Params) -> Result<Space, SpecError> {
        let spec = Spec {
            name: p.name.clone(),
            origin: p.origin.clone(),
            description: None,
            scenario: scenario.to_string(),
            seeds: p.seeds(),
            set: p.set.clone(),
            axes: Vec::new(),
            compare: None,
            metrics: Vec::new(),
            labels: Vec::new(),
            skip: Vec::new(),
            text: p.text.clone(),
        };
        let cells = crate::sweep::plan::cells(&spec)?;
        let base = cells.into_iter().next().expect("no axes: one cell").config;
        let fixed: Vec<String> = p.set.iter().map(|(k, v)| set_arg(k, v)).collect();
        let err = |key: String, message: String| SpecError {
            origin: p.origin.clone(),
            key,
            message,
        };
        let resolved: toml::Table = platoonsim_scenario::to_toml(&base)
            .parse()
            .map_err(|e| err("scenario".into(), format!("cannot read it back: {e}")))?;
        let mut start = Vec::with_capacity(p.params.len());
        for q in &p.params {
            let key = format!("params.\"{}\"", q.key);
            for (which, v) in [("min", q.min), ("max", q.max)] {
                let mut set = fixed.clone();
                set.push(set_arg(&q.key, &Value::Float(v)));
                load(scenario, set)
                    .map_err(|e| err(format!("{key}.{which} = {v}"), e.to_string()))?;
            }
            let s = match q.start {
                Some(s) => s,
                None => {
                    let current = platoonsim_scenario::overrides::get(&resolved, &q.key)
                        .map_err(|e| err(key.clone(), e.to_string()))?;
                    match current.and_then(number) {
                        Some(s) if (q.min..=q.max).contains(&s) => s,
                        Some(s) => {
                            return Err(err(
                                key,
                                format!(
                                    "the scenario's value {s} is outside [{}, {}]: widen the \
                                     bounds or give a start",
                                    q.min, q.max
                                ),
                            ))
                        }
                        None => {
                            return Err(err(
                                key,
                                "the scenario has no number at this key to start from; give \
                                 start = VALUE"
                                    .into(),
                            ))
                        }
                    }
                }
            };
            start.push((s - q.min) / (q.max - q.min));
        }
        Ok(Space {
            scenario: scenario.to_string(),
            fixed,
            params: p.params.clone(),
            base,
            start,
        })
    }

    /// The keys' values at a point of ℝⁿ (reflected into the bounds).
    pub fn values(&self, x: &[f64]) -> Vec<f64> {
        self.params
            .iter()
            .zip(x)
            .map(|(q, &x)| q.min + reflect(x) * (q.max - q.min))
            .collect()
    }

    /// The `--set` arguments of a candidate: the fixed keys, then the fitted ones.
    pub fn set_args(&self, values: &[f64]) -> Vec<String> {
        let mut set = self.fixed.clone();
        for (q, &v) in self.params.iter().zip(values) {
            set.push(set_arg(&q.key, &Value::Float(v)));
        }
        set
    }

    /// The scenario of a candidate (the seed is the scenario's; each run sets its own).
    pub fn config(&self, values: &[f64]) -> Result<Config, ScenarioError> {
        load(&self.scenario, self.set_args(values))
    }
}

fn load(scenario: &str, set: Vec<String>) -> Result<Config, ScenarioError> {
    load_with(
        scenario,
        &Overrides {
            set,
            ..Overrides::default()
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflection_folds_into_the_unit_interval() {
        for (x, y) in [
            (0.25, 0.25),
            (1.0, 1.0),
            (1.25, 0.75),
            (2.5, 0.5),
            (-0.25, 0.25),
            (-1.5, 0.5),
            (0.0, 0.0),
        ] {
            assert!((reflect(x) - y).abs() < 1e-12, "{x}: {}", reflect(x));
        }
    }

    fn params(text: &str) -> Params {
        Params::from_toml(text, "p.toml", "p").unwrap()
    }

    #[test]
    fn start_from_the_scenario_and_bounds_checked_by_the_scenario() {
        let p = params(
            "budget = 8\n[set]\n\"run.duration_s\" = 600\n\"run.warmup_s\" = 100\n[params]\n\
             \"human.buffer_s\" = { min = 0.0, max = 0.4 }\n\
             \"human.desired_speed_kmh.mean\" = { min = 100, max = 120, start = 105 }\n",
        );
        let s = Space::new("homogeneous", &p).unwrap();
        // homogeneous: buffer_s = 0.1 -> 0.25 of [0, 0.4]
        assert!((s.start[0] - 0.25).abs() < 1e-12);
        assert!((s.start[1] - 0.25).abs() < 1e-12);
        assert_eq!(s.values(&[1.5, 0.5]), vec![0.2, 110.0]);
        let c = s.config(&[0.3, 112.0]).unwrap();
        assert_eq!(c.duration_s, 600.0);
        let bad = params("budget = 8\n[params]\n\"run.penetration\" = { min = 0.5, max = 1.5 }\n");
        let e = Space::new("homogeneous", &bad).unwrap_err();
        assert_eq!(e.key, "params.\"run.penetration\".max = 1.5", "{e}");
        let unknown = params("budget = 8\n[params]\n\"human.bogus\" = { min = 0, max = 1 }\n");
        let e = Space::new("homogeneous", &unknown).unwrap_err();
        assert!(e.key.starts_with("params.\"human.bogus\""), "{e}");
        let outside =
            params("budget = 8\n[params]\n\"human.buffer_s\" = { min = 0.2, max = 0.4 }\n");
        let e = Space::new("homogeneous", &outside).unwrap_err();
        assert!(e.to_string().contains("0.1 is outside [0.2, 0.4]"), "{e}");
    }
}
