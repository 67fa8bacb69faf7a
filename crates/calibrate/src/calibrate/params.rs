//! The parameters file of `platoonsim calibrate` (`PARAMS.toml`): which scenario keys to fit
//! and in which bounds, how many replications and evaluations, the optimizer's seed, the
//! weights of the objective's terms, fixed overrides and the optional demand estimate. Keys
//! under `[params]` and `[set]` are the dotted keys of `platoonsim run --set`; they are checked
//! against the scenario later ([`super::space`]). Every error here names the file's key.
//!
//! ```toml
//! name = "my-fit"              # optional: the output directory's name (default: file stem)
//! replications = 3             # seeds 1..=3 per candidate (common random numbers)
//! budget = 60                  # candidates evaluated at most
//! population = 6               # CMA-ES lambda (default 4 + floor(3 ln n))
//! seed = 1                     # the optimizer's own seed
//! sigma = 0.3                  # initial step size in normalized coordinates (default 0.3)
//! [params]                     # the fitted keys: bounds, optional start (default: the scenario's value)
//! "human.buffer_s" = { min = 0.0, max = 0.6 }
//! "human.desired_speed_kmh.mean" = { min = 90, max = 125, start = 110 }
//! "network.behaviour[0].buffer_factor" = { min = 0, max = 5, prior_sd = 0.5 }  # kept near its start
//! [objective]                  # weights of the terms (super::objective)
//! speed_rmsne = 1.0
//! flow_geh = 0.1
//! [set]                        # fixed overrides, as in a sweep
//! "run.duration_s" = 1800
//! [demand]                     # optional: estimate the entrance demands first (super::demand)
//! "OR1" = "316140"             # ramp id = field station
//! ```
//!
//! | key | unit | default | allowed |
//! |---|---|---|---|
//! | `replications` | runs | 3 | 1 to 100 |
//! | `budget` | candidates | required | ≥ `population`, ≤ 100,000 |
//! | `population` | candidates per generation | 4 + ⌊3 ln n⌋ | 2 to 1,000 |
//! | `seed` | – | 1 | any non-negative integer |
//! | `sigma` | normalized | 0.3 | (0, 1] |

use super::objective::Weights;
use crate::sweep::spec::{check_key, read_bounded, SpecError};
use std::path::Path;
use toml::{Table, Value};

/// One fitted key with its bounds (in the key's own unit) and optional start value.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    pub key: String,
    pub min: f64,
    pub max: f64,
    pub start: Option<f64>,
    /// Width σ of a Gaussian prior around the start value, in the key's unit (the objective's
    /// `prior` term); `None`: no prior.
    pub prior_sd: Option<f64>,
}

/// A validated parameters file (scenario keys are checked against the scenario later).
#[derive(Clone, Debug, PartialEq)]
pub struct Params {
    /// The output directory's name.
    pub name: String,
    /// Where the file came from (for messages).
    pub origin: String,
    pub replications: u32,
    pub budget: usize,
    /// CMA-ES λ.
    pub population: usize,
    pub seed: u64,
    pub sigma: f64,
    pub params: Vec<Param>,
    pub weights: Weights,
    /// Fixed overrides in file order.
    pub set: Vec<(String, Value)>,
    /// On-ramp or off-ramp id → field station, for the demand estimate (empty: no estimate).
    pub demand: Vec<(String, String)>,
    /// The file's text, kept in the provenance.
    pub text: String,
}

/// The largest parameters file read.
pub const MAX_FILE_BYTES: u64 = 1 << 20;
/// The most candidates one calibration may evaluate.
pub const MAX_BUDGET: usize = 100_000;

impl Params {
    /// Read and validate a parameters file.
    pub fn from_file(path: &Path) -> Result<Params, SpecError> {
        let (text, origin, stem) =
            read_bounded(path, "a parameters file", MAX_FILE_BYTES, "calibrate")?;
        Params::from_toml(&text, &origin, &stem)
    }

    /// Validate a parameters file's text; `default_name` names the output when the file does
    /// not.
    pub fn from_toml(text: &str, origin: &str, default_name: &str) -> Result<Params, SpecError> {
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
            "replications",
            "budget",
            "population",
            "seed",
            "sigma",
            "params",
            "objective",
            "set",
            "demand",
        ];
        for k in doc.keys() {
            if !KEYS.contains(&k.as_str()) {
                return Err(err(
                    k,
                    format!("unknown key; a parameters file has {}", KEYS.join(", ")),
                ));
            }
        }
        let name = crate::sweep::spec::name_of(&doc, default_name).map_err(|m| err("name", m))?;
        let int = |key: &str, default: Option<i64>, lo: i64, hi: i64| -> Result<i64, SpecError> {
            match (doc.get(key), default) {
                (None, Some(d)) => Ok(d),
                (None, None) => Err(err(
                    key,
                    format!("missing; give an integer in [{lo}, {hi}]"),
                )),
                (Some(Value::Integer(i)), _) if (lo..=hi).contains(i) => Ok(*i),
                (Some(v), _) => Err(err(key, format!("{v} is not an integer in [{lo}, {hi}]"))),
            }
        };
        let params = params(doc.get("params")).map_err(|(k, m)| err(&k, m))?;
        let n = params.len() as f64;
        let replications = int("replications", Some(3), 1, 100)? as u32;
        let default_pop = 4 + (3.0 * n.ln()).floor() as i64;
        let population = int("population", Some(default_pop), 2, 1000)? as usize;
        let budget = int("budget", None, 1, MAX_BUDGET as i64)? as usize;
        if budget < population {
            return Err(err(
                "budget",
                format!(
                    "{budget} is fewer candidates than one generation (population = \
                     {population}); give at least {population}"
                ),
            ));
        }
        let seed = int("seed", Some(1), 0, i64::MAX)? as u64;
        let sigma = match doc.get("sigma") {
            None => 0.3,
            Some(v) => match number(v) {
                Some(s) if s > 0.0 && s <= 1.0 => s,
                _ => return Err(err("sigma", format!("{v} is not a number in (0, 1]"))),
            },
        };
        let weights = match doc.get("objective") {
            None => Weights::default(),
            Some(Value::Table(t)) => Weights::from_table(t).map_err(|(k, m)| err(&k, m))?,
            Some(v) => return Err(err("objective", format!("{v} is not a table of weights"))),
        };
        let set = match doc.get("set") {
            None => Vec::new(),
            Some(Value::Table(t)) => {
                let mut out = Vec::new();
                for (k, v) in t {
                    let key = format!("set.\"{k}\"");
                    check_key(k).map_err(|m| err(&key, m))?;
                    if params.iter().any(|p| &p.key == k) {
                        return Err(err(
                            &key,
                            "is also under [params]; a key is either fixed or fitted".into(),
                        ));
                    }
                    if matches!(v, Value::Table(_)) {
                        return Err(err(
                            &key,
                            "is a table; write each key in full, quoted".into(),
                        ));
                    }
                    out.push((k.clone(), v.clone()));
                }
                out
            }
            Some(v) => return Err(err("set", format!("{v} is not a table of KEY = VALUE"))),
        };
        let demand = match doc.get("demand") {
            None => Vec::new(),
            Some(Value::Table(t)) => {
                let mut out = Vec::new();
                for (k, v) in t {
                    match v {
                        Value::String(s) if !s.trim().is_empty() => {
                            out.push((k.clone(), s.clone()))
                        }
                        Value::Integer(i) => out.push((k.clone(), i.to_string())),
                        _ => {
                            return Err(err(
                                &format!("demand.\"{k}\""),
                                format!("{v} is not a field station id (a string)"),
                            ))
                        }
                    }
                }
                out
            }
            Some(v) => {
                return Err(err(
                    "demand",
                    format!("{v} is not a table of RAMP_ID = \"STATION\""),
                ))
            }
        };
        Ok(Params {
            name,
            origin: origin.to_string(),
            replications,
            budget,
            population,
            seed,
            sigma,
            params,
            weights,
            set,
            demand,
            text: text.to_string(),
        })
    }

    /// The replication seeds, 1..=replications: the same for every candidate (common random
    /// numbers), so that candidates differ by their parameters, not by their luck.
    pub fn seeds(&self) -> Vec<u64> {
        (1..=u64::from(self.replications)).collect()
    }

    /// Whole generations within the budget.
    pub fn generations(&self) -> usize {
        self.budget / self.population
    }
}

/// A number (integer or float).
pub fn number(v: &Value) -> Option<f64> {
    match v {
        Value::Float(f) if f.is_finite() => Some(*f),
        Value::Integer(i) => Some(*i as f64),
        _ => None,
    }
}

fn params(v: Option<&Value>) -> Result<Vec<Param>, (String, String)> {
    let t =
        match v {
            Some(Value::Table(t)) if !t.is_empty() => t,
            Some(v) => {
                return Err((
                    "params".into(),
                    format!("{v} is not a non-empty table of KEY = {{ min = .., max = .. }}"),
                ))
            }
            None => return Err((
                "params".into(),
                "missing; give the fitted keys, e.g. \"human.buffer_s\" = { min = 0.0, max = 0.6 }"
                    .into(),
            )),
        };
    let mut out = Vec::new();
    for (k, v) in t {
        let key = format!("params.\"{k}\"");
        check_key(k).map_err(|m| (key.clone(), m))?;
        let Value::Table(b) = v else {
            return Err((key, format!("{v} is not a table {{ min = .., max = .. }}")));
        };
        for f in b.keys() {
            if !["min", "max", "start", "prior_sd"].contains(&f.as_str()) {
                return Err((
                    format!("{key}.{f}"),
                    "unknown key; a fitted key has min, max, an optional start and an optional \
                     prior_sd"
                        .into(),
                ));
            }
        }
        let get = |f: &str| -> Result<Option<f64>, (String, String)> {
            match b.get(f) {
                None => Ok(None),
                Some(x) => number(x)
                    .map(Some)
                    .ok_or_else(|| (format!("{key}.{f}"), format!("{x} is not a finite number"))),
            }
        };
        let (Some(min), Some(max)) = (get("min")?, get("max")?) else {
            return Err((key, "needs both min and max".into()));
        };
        if min >= max {
            return Err((
                key,
                format!("min = {min} is not below max = {max}: the bounds must satisfy min < max"),
            ));
        }
        let start = get("start")?;
        if let Some(s) = start {
            if !(min..=max).contains(&s) {
                return Err((
                    format!("{key}.start"),
                    format!("{s} is outside [{min}, {max}]"),
                ));
            }
        }
        let prior_sd = get("prior_sd")?;
        if let Some(s) = prior_sd {
            if s <= 0.0 {
                return Err((
                    format!("{key}.prior_sd"),
                    format!("{s} is not a prior width: it must be > 0 (in the key's unit)"),
                ));
            }
        }
        out.push(Param {
            key: k.clone(),
            min,
            max,
            start,
            prior_sd,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Params, SpecError> {
        Params::from_toml(text, "p.toml", "p")
    }

    const OK: &str = "budget = 12\n[params]\n\"human.buffer_s\" = { min = 0.0, max = 0.6 }\n";

    #[test]
    fn a_default_name_that_is_no_name_is_refused() {
        // Issue 48 D12: a parameters file named `...toml` wrote into `--out/..`.
        for stem in ["..", ".", ".x", ""] {
            let e = Params::from_toml(OK, "p.toml", stem).unwrap_err();
            assert_eq!(e.key, "name", "{stem:?}");
            assert!(e.message.contains("which is not a name"), "{stem:?}: {e}");
        }
        let named = format!("name = \"fine\"\n{OK}");
        assert_eq!(
            Params::from_toml(&named, "p.toml", "..").unwrap().name,
            "fine"
        );
    }

    #[test]
    fn defaults() {
        let p = parse(OK).unwrap();
        assert_eq!(p.name, "p");
        assert_eq!((p.replications, p.budget, p.seed, p.sigma), (3, 12, 1, 0.3));
        // 4 + floor(3 ln 1) = 4
        assert_eq!(p.population, 4);
        assert_eq!(p.generations(), 3);
        assert_eq!(p.seeds(), [1, 2, 3]);
        let two = parse(
            "budget = 60\n[params]\n\"a\" = { min = 0, max = 1 }\n\"b\" = { min = 2, max = 3, start = 2.5 }\n",
        )
        .unwrap();
        // 4 + floor(3 ln 2) = 4 + 2
        assert_eq!(two.population, 6);
        assert_eq!(two.params[1].start, Some(2.5));
        assert_eq!(two.params[1].min, 2.0);
    }

    #[test]
    fn errors_name_the_key_and_value() {
        let cases = [
            (format!("bogus = 1\n{OK}"), "bogus", "unknown key"),
            (
                "budget = 0\n[params]\n\"a\" = { min = 0, max = 1 }\n".into(),
                "budget",
                "0",
            ),
            (
                "budget = 3\n[params]\n\"a\" = { min = 0, max = 1 }\n".into(),
                "budget",
                "population = 4",
            ),
            (
                "budget = 9\n[params]\n\"a\" = { min = 1, max = 1 }\n".into(),
                "params.\"a\"",
                "min = 1 is not below max = 1",
            ),
            (
                "budget = 9\n[params]\n\"a\" = { min = 2, max = 1 }\n".into(),
                "params.\"a\"",
                "min = 2",
            ),
            (
                "budget = 9\n[params]\n\"a\" = { min = 0, max = 1, start = 3 }\n".into(),
                "params.\"a\".start",
                "3",
            ),
            (
                "budget = 9\n[params]\n\"a\" = { min = 0, max = 1, step = 3 }\n".into(),
                "params.\"a\".step",
                "unknown key",
            ),
            (
                "budget = 9\n[params]\n\"a b\" = { min = 0, max = 1 }\n".into(),
                "params.\"a b\"",
                "a b",
            ),
            ("budget = 9\n".into(), "params", "missing"),
            (format!("replications = 0\n{OK}"), "replications", "0"),
            (format!("sigma = 2\n{OK}"), "sigma", "2"),
            (
                format!("{OK}[objective]\nspeed = 1\n"),
                "objective.speed",
                "unknown",
            ),
            (
                format!("{OK}[objective]\nflow_geh = -1\n"),
                "objective.flow_geh",
                "-1",
            ),
            (
                format!("{OK}[set]\n\"human.buffer_s\" = 1\n"),
                "set.\"human.buffer_s\"",
                "fitted",
            ),
            (
                format!("{OK}[demand]\nOR1 = 2.5\n"),
                "demand.\"OR1\"",
                "2.5",
            ),
        ];
        for (text, key, value) in cases {
            let e = parse(&text).unwrap_err();
            assert_eq!(e.key, key, "{text}: {e}");
            let m = e.to_string();
            assert!(m.contains(key) && m.contains(value), "{text}: {m}");
        }
    }
}
