//! Overrides applied to the parsed TOML document before it is read: `--set KEY=VALUE` with
//! dotted keys (`human.buffer_s=0.2`, `detectors[1].position_m=4800`), and the typed command-line
//! flags (penetration, demand, duration, warm-up, seed, strategy; a network's demand scale
//! travels as a `--set` of `network.demand_scale`, see [`demand_scale_set`]). Because they act
//! on the document, an override is checked exactly like the same value written in the file.

use crate::error::ScenarioError;
use toml::{Table, Value};

pub use platoonsim_sim::StrategyKind;

/// Everything the command line may change in a scenario. `set` is applied first, in order
/// (a later `--set` of the same key wins); the typed fields after it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    /// `run.penetration`.
    pub penetration: Option<f64>,
    /// `demand.vph_per_lane`.
    pub demand_vphpl: Option<f64>,
    /// `run.duration_s`.
    pub duration_s: Option<f64>,
    /// `run.warmup_s`.
    pub warmup_s: Option<f64>,
    /// `run.seed`.
    pub seed: Option<u64>,
    /// `strategy.kind`.
    pub strategy: Option<StrategyKind>,
    /// `KEY=VALUE` strings.
    pub set: Vec<String>,
}

impl Overrides {
    /// True if nothing is overridden.
    pub fn is_empty(&self) -> bool {
        *self == Overrides::default()
    }

    /// Apply to a parsed scenario document.
    pub fn apply(&self, doc: &mut Table) -> Result<(), ScenarioError> {
        for arg in &self.set {
            let (path, value) = parse_set(arg)?;
            if path[0].key == "network" && !doc.contains_key("network") {
                return Err(ScenarioError::Override {
                    arg: arg.clone(),
                    reason: "the scenario has no [network] section (it is not a freeway network), \
                             so network keys do not apply"
                        .into(),
                });
            }
            set_path(doc, &path, value).map_err(|reason| ScenarioError::Override {
                arg: arg.clone(),
                reason,
            })?;
        }
        let typed: [(&str, &str, Option<Value>); 5] = [
            (
                "--penetration",
                "run.penetration",
                self.penetration.map(Value::Float),
            ),
            (
                "--demand",
                "demand.vph_per_lane",
                self.demand_vphpl.map(Value::Float),
            ),
            (
                "--duration",
                "run.duration_s",
                self.duration_s.map(Value::Float),
            ),
            ("--warmup", "run.warmup_s", self.warmup_s.map(Value::Float)),
            (
                "--strategy",
                "strategy.kind",
                self.strategy.map(|k| Value::String(k.as_str().into())),
            ),
        ];
        for (flag, key, value) in typed {
            if let Some(value) = value {
                let path = parse_key(key).expect("built-in key");
                set_path(doc, &path, value).map_err(|reason| ScenarioError::Override {
                    arg: flag.to_string(),
                    reason,
                })?;
            }
        }
        if let Some(seed) = self.seed {
            let v = i64::try_from(seed).map_err(|_| ScenarioError::Override {
                arg: format!("--seed {seed}"),
                reason: format!("a seed must be at most {}", i64::MAX),
            })?;
            let path = parse_key("run.seed").expect("built-in key");
            set_path(doc, &path, Value::Integer(v)).map_err(|reason| ScenarioError::Override {
                arg: "--seed".into(),
                reason,
            })?;
        }
        Ok(())
    }
}

/// The `--set` argument of a network demand scale (`platoonsim run --demand-scale F`): sets
/// `network.demand_scale`, the run's multiplier on the network's entrance demands (on top of
/// `network.base_demand_multiplier`). On a scenario without a `[network]` it is an
/// [`ScenarioError::Override`] error with this argument.
pub fn demand_scale_set(scale: f64) -> String {
    format!("network.demand_scale={}", Value::Float(scale))
}

/// One step of a key path: a table key, optionally indexing into an array (`detectors[1]`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Segment {
    pub key: String,
    pub index: Option<usize>,
}

/// Split `KEY=VALUE`; the value is read as a TOML value (`0.2`, `[[0.6, 1.0]]`, `"x"`,
/// `true`), or taken as a plain string if it is not one (`flow-aware`).
pub fn parse_set(arg: &str) -> Result<(Vec<Segment>, Value), ScenarioError> {
    let err = |reason: String| ScenarioError::Override {
        arg: arg.to_string(),
        reason,
    };
    // A value as large as a whole scenario file is refused before it is parsed, as a file is.
    if arg.len() > crate::limits::MAX_FILE_BYTES {
        let head: String = arg.chars().take(40).collect();
        return Err(ScenarioError::Override {
            arg: format!("{head}…"),
            reason: format!(
                "{} bytes: a --set argument must be at most {} bytes (1 MiB), like a scenario file",
                arg.len(),
                crate::limits::MAX_FILE_BYTES
            ),
        });
    }
    let (key, raw_value) = arg
        .split_once('=')
        .ok_or_else(|| err("expected KEY=VALUE, e.g. run.seed=3 or human.buffer_s=0.2".into()))?;
    let path = parse_key(key.trim()).map_err(err)?;
    Ok((path, parse_value(raw_value.trim())))
}

/// A value as TOML if it is one, otherwise the text as a string.
pub fn parse_value(text: &str) -> Value {
    let doc = format!("value = {text}");
    match doc.parse::<Table>() {
        Ok(mut t) if t.len() == 1 => t
            .remove("value")
            .unwrap_or_else(|| Value::String(text.into())),
        _ => Value::String(text.to_string()),
    }
}

/// Is `key` a well-formed dotted key path, as `--set` reads it (`a.b`, `detectors[2].name`)?
/// The error says why not (whether the key exists is checked when it is applied).
pub fn check_key(key: &str) -> Result<(), ScenarioError> {
    parse_key(key)
        .map(|_| ())
        .map_err(|reason| ScenarioError::Override {
            arg: key.to_string(),
            reason,
        })
}

/// Parse a dotted key path: `a.b`, `detectors[2].name`.
pub(crate) fn parse_key(key: &str) -> Result<Vec<Segment>, String> {
    if key.is_empty() {
        return Err("the key is empty; expected a dotted key such as run.seed".into());
    }
    let mut out = Vec::new();
    for part in key.split('.') {
        let (name, index) = match part.split_once('[') {
            None => (part, None),
            Some((name, rest)) => {
                let digits = rest
                    .strip_suffix(']')
                    .ok_or_else(|| format!("'{part}': an index is written name[N]"))?;
                let i = digits.parse::<usize>().map_err(|_| {
                    format!("'{part}': the index '{digits}' is not a non-negative integer")
                })?;
                (name, Some(i))
            }
        };
        let valid = !name.is_empty()
            && name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
        if !valid {
            return Err(format!(
                "'{part}' in '{key}' is not a key: keys are letters, digits, '_' and '-', joined by '.'"
            ));
        }
        out.push(Segment {
            key: name.to_string(),
            index,
        });
    }
    Ok(out)
}

/// The value at a dotted key (`human.buffer_s`, `network.on_ramps[0].demand_vph`) of a
/// scenario document, read with the `--set` key syntax; `None` where the document has no such
/// key. `Err` only for a key that is not well formed.
pub fn get<'a>(doc: &'a Table, key: &str) -> Result<Option<&'a Value>, ScenarioError> {
    let path = parse_key(key).map_err(|reason| ScenarioError::Override {
        arg: key.to_string(),
        reason,
    })?;
    let mut table = doc;
    let mut found = None;
    for (depth, seg) in path.iter().enumerate() {
        let Some(mut v) = table.get(&seg.key) else {
            return Ok(None);
        };
        if let Some(i) = seg.index {
            match v.as_array().and_then(|a| a.get(i)) {
                Some(item) => v = item,
                None => return Ok(None),
            }
        }
        if depth + 1 == path.len() {
            found = Some(v);
        } else {
            match v.as_table() {
                Some(t) => table = t,
                None => return Ok(None),
            }
        }
    }
    Ok(found)
}

fn describe(path: &[Segment]) -> String {
    path.iter()
        .map(|s| match s.index {
            Some(i) => format!("{}[{i}]", s.key),
            None => s.key.clone(),
        })
        .collect::<Vec<_>>()
        .join(".")
}

/// Set `path` to `value` in `doc`, creating missing tables on the way. Arrays are indexed, never
/// grown. Errors say which part of the path is in the way.
pub(crate) fn set_path(doc: &mut Table, path: &[Segment], value: Value) -> Result<(), String> {
    let (last, parents) = path.split_last().ok_or("empty key")?;
    let mut table = doc;
    for (depth, seg) in parents.iter().enumerate() {
        let here = describe(&path[..=depth]);
        let entry = table
            .entry(seg.key.clone())
            .or_insert_with(|| Value::Table(Table::new()));
        let node = index_into(entry, seg, &here)?;
        table = match node {
            Value::Table(t) => t,
            other => {
                return Err(format!(
                    "'{here}' is a {}, not a table, so it has no key '{}'",
                    other.type_str(),
                    path[depth + 1].key
                ))
            }
        };
    }
    match last.index {
        None => {
            table.insert(last.key.clone(), value);
        }
        Some(_) => {
            let here = describe(path);
            let entry = table.get_mut(&last.key).ok_or_else(|| {
                format!("'{}' does not exist, so '{here}' cannot be set", last.key)
            })?;
            *index_into(entry, last, &here)? = value;
        }
    }
    Ok(())
}

fn index_into<'a>(v: &'a mut Value, seg: &Segment, here: &str) -> Result<&'a mut Value, String> {
    let Some(i) = seg.index else { return Ok(v) };
    match v {
        Value::Array(items) => {
            let n = items.len();
            items.get_mut(i).ok_or_else(|| {
                format!(
                    "'{here}': index {i} is out of range ('{}' has {n} entries)",
                    seg.key
                )
            })
        }
        other => Err(format!(
            "'{}' is a {}, not an array, so '{here}' does not exist",
            seg.key,
            other.type_str()
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_toml_or_else_strings() {
        assert_eq!(parse_value("3"), Value::Integer(3));
        assert_eq!(parse_value("0.2"), Value::Float(0.2));
        assert_eq!(parse_value("true"), Value::Boolean(true));
        assert_eq!(parse_value("\"pd\""), Value::String("pd".into()));
        assert_eq!(
            parse_value("flow-aware"),
            Value::String("flow-aware".into())
        );
        assert_eq!(parse_value(""), Value::String(String::new()));
        // A second key smuggled in by a newline stays one string.
        assert_eq!(
            parse_value("1\nfoo = 2"),
            Value::String("1\nfoo = 2".into())
        );
        let Value::Array(a) = parse_value("[[0.6, 1.0]]") else {
            panic!()
        };
        assert_eq!(a.len(), 1);
    }

    #[test]
    fn keys_split_on_dots_with_optional_index() {
        let k = parse_key("detectors[2].position_m").unwrap();
        assert_eq!(
            k,
            vec![
                Segment {
                    key: "detectors".into(),
                    index: Some(2)
                },
                Segment {
                    key: "position_m".into(),
                    index: None
                },
            ]
        );
        assert!(parse_key("a.").is_err());
        assert!(parse_key("a[1").is_err());
        assert!(parse_key("a b").is_err());
    }

    #[test]
    fn get_reads_what_set_writes() {
        let doc: Table = "[human]\nbuffer_s = 0.1\ndesired_speed_kmh = { mean = 110.0 }\n\
                          [[detectors]]\nposition_m = 5.0\n"
            .parse()
            .unwrap();
        let v = |k| get(&doc, k).unwrap().cloned();
        assert_eq!(v("human.buffer_s"), Some(Value::Float(0.1)));
        assert_eq!(v("human.desired_speed_kmh.mean"), Some(Value::Float(110.0)));
        assert_eq!(v("detectors[0].position_m"), Some(Value::Float(5.0)));
        assert_eq!(v("detectors[1].position_m"), None);
        assert_eq!(v("human.buffer_s.x"), None);
        assert_eq!(v("run.seed"), None);
        assert!(get(&doc, "a b").is_err());
    }

    #[test]
    fn set_path_creates_missing_tables() {
        let mut doc = Table::new();
        set_path(
            &mut doc,
            &parse_key("human.desired_speed_kmh.mean").unwrap(),
            Value::Float(100.0),
        )
        .unwrap();
        assert_eq!(
            doc["human"]["desired_speed_kmh"]["mean"],
            Value::Float(100.0)
        );
    }

    #[test]
    fn strategy_kind_names() {
        for k in StrategyKind::all() {
            assert_eq!(k.as_str().parse::<StrategyKind>(), Ok(k));
        }
        assert!("PD".parse::<StrategyKind>().is_err());
    }
}
