//! The axes of a sweep file (plain and bundle axes), its `[[skip]]` rules and the cells they
//! make. A plain axis is a dotted scenario key and its levels. A bundle axis moves several
//! keys together: it has a plain name and its levels are tables of scenario keys (every level
//! the same keys), each with an optional `name` that labels it. A skip rule leaves out the
//! cells whose keys all take one of its values.

use super::{check_key, label, SpecError};
use toml::{Table, Value};

/// One axis: a dotted scenario key (or a bundle's name) and its levels, in the file's order.
/// A bundle's levels are tables: the keys it sets together, and perhaps a `name`.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    pub key: String,
    pub levels: Vec<Value>,
}

impl Axis {
    /// A plain axis of `key` with these levels.
    pub fn plain(key: &str, levels: Vec<Value>) -> Axis {
        Axis {
            key: key.to_string(),
            levels,
        }
    }

    /// A bundle axis called `name` whose levels set these keys together.
    pub fn bundle(name: &str, levels: Vec<Vec<(&str, Value)>>) -> Axis {
        let levels = levels
            .into_iter()
            .map(|l| {
                Value::Table(
                    l.into_iter()
                        .map(|(k, v)| (k.to_string(), v))
                        .collect::<Table>(),
                )
            })
            .collect();
        Axis {
            key: name.to_string(),
            levels,
        }
    }

    /// Whether the axis moves several keys together.
    pub fn is_bundle(&self) -> bool {
        matches!(self.levels.first(), Some(Value::Table(_)))
    }

    /// The scenario keys and values a level sets: the axis key and the level, or a bundle
    /// level's keys (without its `name`).
    pub fn members(&self, level: usize) -> Vec<(&str, &Value)> {
        match &self.levels[level] {
            Value::Table(t) => t
                .iter()
                .filter(|(k, _)| k.as_str() != NAME)
                .map(|(k, v)| (k.as_str(), v))
                .collect(),
            v => vec![(self.key.as_str(), v)],
        }
    }

    /// The scenario keys the axis sets.
    pub fn keys(&self) -> Vec<&str> {
        self.members(0).into_iter().map(|(k, _)| k).collect()
    }
}

/// A bundle level's label key.
pub const NAME: &str = "name";

/// A `[[skip]]` rule: (key, the values that match, as labels); a cell matching every entry is
/// left out.
#[derive(Clone, Debug, PartialEq)]
pub struct Skip(pub Vec<(String, Vec<String>)>);

type Err<'a> = &'a dyn Fn(&str, String) -> SpecError;

fn scalar(v: &Value) -> bool {
    !matches!(v, Value::Table(_) | Value::Array(_))
}

/// A bundle's name: letters, digits, '_' and '-' (no dot, so it is never a scenario key).
fn bundle_name(s: &str) -> bool {
    !s.is_empty()
        && s.len() <= 100
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-'))
}

/// `[axes]`: each entry a plain or a bundle axis; no key set twice (by `[set]` or two axes).
pub(super) fn parse(
    doc: &Table,
    set: &[(String, Value)],
    err: Err<'_>,
) -> Result<Vec<Axis>, SpecError> {
    let t = match doc.get("axes") {
        None => return Ok(Vec::new()),
        Some(Value::Table(t)) => t,
        Some(v) => {
            return Err(err(
                "axes",
                format!(
                    "{v} is not a table of KEY = [LEVELS] (or NAME = [{{KEY = VALUE, ...}}, ...])"
                ),
            ))
        }
    };
    let mut out: Vec<Axis> = Vec::new();
    for (k, v) in t {
        let key = format!("axes.\"{k}\"");
        let levels = match v {
            Value::Array(a) if !a.is_empty() => a.clone(),
            _ => return Err(err(&key, format!("{v} is not a non-empty list of levels"))),
        };
        let bundle = levels.iter().any(|l| matches!(l, Value::Table(_)));
        if bundle {
            check_bundle(k, &levels).map_err(|m| err(&key, m))?;
        } else {
            check_key(k).map_err(|m| err(&key, m))?;
            if let Some(l) = levels.iter().find(|l| !scalar(l)) {
                return Err(err(
                    &key,
                    format!("the level {l} is not a number, string or boolean"),
                ));
            }
        }
        for (i, l) in levels.iter().enumerate() {
            if levels[..i].iter().any(|m| label(m) == label(l)) {
                return Err(err(&key, format!("the level {l} is listed twice")));
            }
        }
        let axis = Axis {
            key: k.clone(),
            levels,
        };
        for member in axis.keys() {
            if set.iter().any(|(s, _)| s == member) {
                return Err(err(
                    &key,
                    format!("{member} is also under [set]; a key is either fixed or an axis"),
                ));
            }
            if out
                .iter()
                .any(|a| a.key == member || a.keys().contains(&member))
            {
                return Err(err(
                    &key,
                    format!("{member} is moved by another axis too; a key is on one axis"),
                ));
            }
        }
        out.push(axis);
    }
    Ok(out)
}

/// A bundle: a plain name, every level a table of the same scenario keys (and perhaps a
/// `name`, on every level or on none).
fn check_bundle(name: &str, levels: &[Value]) -> Result<(), String> {
    if !bundle_name(name) {
        return Err(
            "a bundle axis (levels that are tables) is named by letters, digits, '_' or '-' \
             (no dot: the keys are inside the levels)"
                .into(),
        );
    }
    let mut first: Option<Vec<&str>> = None;
    let mut named: Option<bool> = None;
    for l in levels {
        let Value::Table(t) = l else {
            return Err(format!(
                "the level {l} is not a table; every level of a bundle is a table of KEY = VALUE"
            ));
        };
        let mut keys: Vec<&str> = Vec::new();
        for (k, v) in t {
            if k == NAME {
                if !matches!(v, Value::String(s) if !s.trim().is_empty()) {
                    return Err(format!(
                        "the level {l}: name = {v} is not a non-empty string"
                    ));
                }
                continue;
            }
            check_key(k).map_err(|m| format!("the level {l}: {k}: {m}"))?;
            if !scalar(v) {
                return Err(format!(
                    "the level {l}: {k} = {v} is not a number, string or boolean"
                ));
            }
            keys.push(k);
        }
        if keys.is_empty() {
            return Err(format!("the level {l} sets no scenario key"));
        }
        let has_name = t.contains_key(NAME);
        if *named.get_or_insert(has_name) != has_name {
            return Err(format!(
                "the level {l}: give every level a name, or none (then a level is labelled by \
                 its values)"
            ));
        }
        match &first {
            None => first = Some(keys),
            Some(f) if *f == keys => {}
            Some(f) => {
                return Err(format!(
                    "the level {l} sets {} but the first level sets {}; every level of a bundle \
                     sets the same keys, in the same order",
                    keys.join(", "),
                    f.join(", ")
                ))
            }
        }
    }
    Ok(())
}

/// `[[skip]]`: each rule a table of axis keys (a plain axis' key, a bundle's name or one of its
/// keys) and a value or a list of values, each a level of that key.
pub(super) fn parse_skip(doc: &Table, axes: &[Axis], err: Err<'_>) -> Result<Vec<Skip>, SpecError> {
    let rules = match doc.get("skip") {
        None => return Ok(Vec::new()),
        Some(Value::Array(a))
            if a.iter()
                .all(|r| matches!(r, Value::Table(t) if !t.is_empty())) =>
        {
            a
        }
        Some(v) => {
            return Err(err(
                "skip",
                format!("{v}: expected [[skip]] tables of KEY = VALUE or KEY = [VALUES]"),
            ))
        }
    };
    let mut out = Vec::new();
    for (i, r) in rules.iter().enumerate() {
        let Value::Table(t) = r else {
            unreachable!("checked above")
        };
        let mut entries = Vec::new();
        for (k, v) in t {
            let key = format!("skip[{}].\"{k}\"", i + 1);
            let levels = levels_of(axes, k).ok_or_else(|| {
                err(
                    &key,
                    format!(
                        "is not an axis key; the axes set {}",
                        axes.iter()
                            .flat_map(|a| {
                                let mut k = a.keys();
                                if a.is_bundle() {
                                    k.insert(0, &a.key);
                                }
                                k
                            })
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                )
            })?;
            let values: Vec<&Value> = match v {
                Value::Array(a) if !a.is_empty() => a.iter().collect(),
                Value::Array(_) => return Err(err(&key, "is an empty list".into())),
                v => vec![v],
            };
            let mut labels = Vec::new();
            for x in values {
                if !levels.contains(&label(x)) {
                    return Err(err(
                        &key,
                        format!("{x} is not one of its levels ({})", levels.join(", ")),
                    ));
                }
                labels.push(label(x));
            }
            entries.push((k.clone(), labels));
        }
        out.push(Skip(entries));
    }
    Ok(out)
}

/// The levels (as labels) that a key takes on the axes: a plain axis' levels, a bundle's level
/// labels, or the values of one of a bundle's keys.
fn levels_of(axes: &[Axis], key: &str) -> Option<Vec<String>> {
    for a in axes {
        if a.key == key {
            return Some(a.levels.iter().map(label).collect());
        }
        if a.is_bundle() && a.keys().contains(&key) {
            return Some(
                (0..a.levels.len())
                    .filter_map(|l| a.members(l).into_iter().find(|(k, _)| *k == key))
                    .map(|(_, v)| label(v))
                    .collect(),
            );
        }
    }
    None
}

/// The level indices of every cell, first axis outermost, without the skipped ones.
pub fn combinations(axes: &[Axis], skip: &[Skip]) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new()];
    for a in axes {
        let mut next = Vec::with_capacity(out.len() * a.levels.len());
        for prefix in &out {
            for l in 0..a.levels.len() {
                let mut c = prefix.clone();
                c.push(l);
                next.push(c);
            }
        }
        out = next;
    }
    out.retain(|c| {
        !skip.iter().any(|Skip(rule)| {
            rule.iter()
                .all(|(k, values)| value_label(axes, c, k).is_some_and(|v| values.contains(&v)))
        })
    });
    out
}

/// What an axis key is in a cell, as a label: a plain axis' level, a bundle's level label, or
/// the value of one of a bundle's keys.
pub fn value_label(axes: &[Axis], combo: &[usize], key: &str) -> Option<String> {
    for (a, &l) in axes.iter().zip(combo) {
        if a.key == key {
            return Some(label(&a.levels[l]));
        }
        if let Some((_, v)) = a.members(l).into_iter().find(|(k, _)| *k == key) {
            return Some(label(v));
        }
    }
    None
}
