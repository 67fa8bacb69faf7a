//! A small, deterministic part of the fuzz campaign (the full one is `scripts/fuzz_scenarios.py`,
//! docs/robustness.md): the built-in scenarios mutated value by value, by `--set` and as text,
//! read and validated. Nothing may panic, every validation problem names a key path, and a
//! scenario that validation accepts must pass the engine's own check.

use platoonsim_scenario::{from_toml, Overrides, ScenarioError, BUILTINS};
use std::panic::{catch_unwind, AssertUnwindSafe};
use toml::{Table, Value};

/// xorshift64*: a fixed sequence for a fixed seed, no dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// The values a mutation puts in place of a number, string or array.
fn mutant(r: &mut Rng) -> Value {
    let v = [
        "0",
        "-1",
        "1e300",
        "-1e300",
        "1e-300",
        "nan",
        "inf",
        "-inf",
        "4294967296",
        "9223372036854775807",
        "\"x\"",
        "[]",
        "[1, 2]",
        "[[0.6, 1.0]]",
        "true",
        "{ a = 1 }",
        "0.05",
        "0.11",
        "1e12",
    ];
    platoonsim_scenario::overrides::parse_value(v[r.below(v.len())])
}

/// Every leaf key path of a document, as `--set` keys (`a.b`, `a[2].c`).
fn leaves(prefix: &str, v: &Value, out: &mut Vec<String>) {
    match v {
        Value::Table(t) => {
            for (k, v) in t {
                let p = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                leaves(&p, v, out);
            }
        }
        Value::Array(a) if a.iter().all(Value::is_table) && !a.is_empty() => {
            for (i, v) in a.iter().enumerate() {
                leaves(&format!("{prefix}[{i}]"), v, out);
            }
        }
        _ => out.push(prefix.to_string()),
    }
}

/// Remove or replace the value at a `--set`-style path in a document.
fn mutate_at(doc: &mut Table, path: &str, new: Option<Value>) {
    let mut parts: Vec<(String, Option<usize>)> = path
        .split('.')
        .map(|s| match s.split_once('[') {
            Some((k, i)) => (k.to_string(), i.trim_end_matches(']').parse().ok()),
            None => (s.to_string(), None),
        })
        .collect();
    let (last, _) = parts.pop().unwrap();
    let mut t = doc;
    for (k, i) in parts {
        let v = t.get_mut(&k).unwrap();
        t = match i {
            Some(i) => v.as_array_mut().unwrap()[i].as_table_mut().unwrap(),
            None => v.as_table_mut().unwrap(),
        };
    }
    match new {
        Some(v) => {
            t.insert(last, v);
        }
        None => {
            t.remove(&last);
        }
    }
}

/// Read and validate; panics are caught and returned as `Err`.
fn attempt(text: &str, sets: &[String]) -> Result<Result<(), ScenarioError>, String> {
    let o = Overrides {
        set: sets.to_vec(),
        ..Overrides::default()
    };
    catch_unwind(AssertUnwindSafe(|| {
        from_toml(text, "fuzz.toml", "fuzz", &o).map(|c| {
            // What validation accepts, the engine must accept too.
            if let Err(e) = c.check() {
                panic!("validated, but the engine's check refuses: {e}");
            }
        })
    }))
    .map_err(|p| {
        p.downcast_ref::<String>()
            .cloned()
            .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default()
    })
}

#[test]
fn mutated_builtins_never_panic_and_errors_name_a_field() {
    // PLATOONSIM_FUZZ_CASES runs a longer campaign (e.g. 100000) with the same sequence.
    let cases: usize = std::env::var("PLATOONSIM_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(600);
    let mut r = Rng(0x5eed_0018);
    let mut counts = [0usize; 2]; // accepted, refused (a panic fails at once)
    for case in 0..cases {
        let b = &BUILTINS[case % BUILTINS.len()];
        let doc: Table = b.toml.parse().unwrap();
        let mut paths = Vec::new();
        leaves("", &Value::Table(doc.clone()), &mut paths);
        let path = paths[r.below(paths.len())].clone();
        let (text, sets) = match r.below(5) {
            // A value replaced in the file.
            0 => {
                let mut d = doc.clone();
                mutate_at(&mut d, &path, Some(mutant(&mut r)));
                (d.to_string(), vec![])
            }
            // A key deleted.
            1 => {
                let mut d = doc.clone();
                mutate_at(&mut d, &path, None);
                (d.to_string(), vec![])
            }
            // A --set override (the value as text, as the command line gives it).
            2 => {
                let v = mutant(&mut r).to_string();
                (b.toml.to_string(), vec![format!("{path}={v}")])
            }
            // The file truncated.
            3 => {
                let mut n = r.below(b.toml.len());
                while !b.toml.is_char_boundary(n) {
                    n -= 1;
                }
                (b.toml[..n].to_string(), vec![])
            }
            // A byte changed.
            _ => {
                let mut bytes = b.toml.as_bytes().to_vec();
                let i = r.below(bytes.len());
                let set = b"0-9e.[]=\"x\n#";
                bytes[i] = set[r.below(set.len())];
                (String::from_utf8_lossy(&bytes).into_owned(), vec![])
            }
        };
        match attempt(&text, &sets) {
            Err(panic) => panic!("case {case} ({path}, {sets:?}) panicked: {panic}\n{text}"),
            Ok(Ok(())) => counts[0] += 1,
            Ok(Err(e)) => {
                counts[1] += 1;
                for p in e.problems() {
                    assert!(
                        !p.field.is_empty() && p.field != "(engine check)" && !p.allowed.is_empty(),
                        "case {case}: a problem without a field: {p}"
                    );
                }
                if let ScenarioError::Structure { path, .. } = &e {
                    assert!(!path.is_empty(), "case {case}: {e}");
                }
            }
        }
    }
    eprintln!(
        "{cases} cases: {} accepted, {} refused",
        counts[0], counts[1]
    );
    // Both outcomes occur: the mutations are neither all harmless nor all fatal.
    assert!(counts[0] > 0 && counts[1] > cases / 2, "{counts:?}");
}
