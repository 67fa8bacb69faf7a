//! Golden digests (issue 18 item 7): "outputs bit-identical" checked by CI, not by hand.
//!
//! Three short runs of the `platoonsim` binary, each with the defaults of its scenario
//! otherwise:
//!
//! | name | command |
//! |---|---|
//! | `homogeneous` | `platoonsim run homogeneous --duration 600 --warmup 120` (50 % CAV, 2,500 veh/h/lane, no strategy) |
//! | `homogeneous_pd` | the same with `--strategy pd` |
//! | `sr99` | `platoonsim run sr99 --duration 900` (05:00-05:15, 0 % CAV) |
//! | `lane_drop` | `platoonsim run crates/scenario/scenarios/lane_drop.toml --duration 600 --warmup 120` (50 % CAV) |
//!
//! For each, two FNV-1a 64-bit digests: `summary.json` without `wall_seconds` (parsed, the key
//! removed, written back canonically: keys sorted, no white space, numbers as serde_json
//! writes them, i.e. shortest round-trip, so equal text is equal bits), and `detectors.csv`
//! byte for byte. They are compared with `tests/golden/digests.txt` (one line per run: name,
//! summary digest, detectors digest; `#` lines are comments).
//!
//! Regenerate after a change that is meant to change the outputs:
//!
//! ```text
//! PLATOONSIM_BLESS=1 cargo test --release -p platoonsim --test golden
//! ```
//!
//! which rewrites the file instead of comparing. A commit that changes the digests must say
//! why the outputs changed (and a commit that claims "outputs bit-identical" must not change
//! them).

mod common;

use common::{platoonsim, s, scratch, stderr};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The environment variable that rewrites the digests file instead of comparing.
const BLESS: &str = "PLATOONSIM_BLESS";

fn digests_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden/digests.txt")
}

fn lane_drop_path() -> String {
    format!(
        "{}/../scenario/scenarios/lane_drop.toml",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// FNV-1a, 64 bits: small, stable across platforms and Rust versions.
fn fnv1a64(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// JSON with object keys sorted and no white space.
fn canonical(v: &serde_json::Value, out: &mut String) {
    use serde_json::Value;
    match v {
        Value::Object(m) => {
            let mut keys: Vec<&String> = m.keys().collect();
            keys.sort();
            out.push('{');
            for (i, k) in keys.into_iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                out.push_str(&serde_json::to_string(k).unwrap());
                out.push(':');
                canonical(&m[k], out);
            }
            out.push('}');
        }
        Value::Array(a) => {
            out.push('[');
            for (i, x) in a.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                canonical(x, out);
            }
            out.push(']');
        }
        other => out.push_str(&serde_json::to_string(other).unwrap()),
    }
}

/// `summary.json` without `wall_seconds`, canonical.
fn summary_text(dir: &Path) -> String {
    let mut v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("summary.json")).unwrap()).unwrap();
    let m = v.as_object_mut().expect("summary.json is an object");
    assert!(
        m.remove("wall_seconds").is_some(),
        "summary.json has no wall_seconds"
    );
    let mut out = String::new();
    canonical(&v, &mut out);
    out
}

struct Digest {
    name: &'static str,
    summary: u64,
    detectors: u64,
}

/// The golden runs: name and arguments after `run`.
fn runs() -> Vec<(&'static str, Vec<String>)> {
    let v = |a: &[&str]| a.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    vec![
        (
            "homogeneous",
            v(&["homogeneous", "--duration", "600", "--warmup", "120"]),
        ),
        (
            "homogeneous_pd",
            v(&[
                "homogeneous",
                "--duration",
                "600",
                "--warmup",
                "120",
                "--strategy",
                "pd",
            ]),
        ),
        ("sr99", v(&["sr99", "--duration", "900"])),
        (
            "lane_drop",
            v(&[&lane_drop_path(), "--duration", "600", "--warmup", "120"]),
        ),
    ]
}

/// Run every golden run (two at a time) and digest its files.
fn compute() -> Vec<Digest> {
    let base = scratch("golden");
    let runs = runs();
    let results: Vec<Digest> = std::thread::scope(|sc| {
        let handles: Vec<_> = runs
            .iter()
            .map(|(name, args)| {
                let out = base.join(name);
                sc.spawn(move || {
                    let mut a: Vec<&str> = vec!["run", "--quiet"];
                    a.extend(args.iter().map(String::as_str));
                    a.extend(["--out", s(&out)]);
                    let o = platoonsim(&a);
                    assert!(o.status.success(), "{name}: {a:?}\n{}", stderr(&o));
                    Digest {
                        name,
                        summary: fnv1a64(summary_text(&out).as_bytes()),
                        detectors: fnv1a64(&std::fs::read(out.join("detectors.csv")).unwrap()),
                    }
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let _ = std::fs::remove_dir_all(&base);
    results
}

fn render(digests: &[Digest]) -> String {
    let mut text = String::from(
        "# Golden digests of short runs (crates/cli/tests/golden.rs): name, FNV-1a 64 of\n\
         # summary.json without wall_seconds (canonical JSON), FNV-1a 64 of detectors.csv.\n\
         # Regenerate: PLATOONSIM_BLESS=1 cargo test --release -p platoonsim --test golden\n\
         # A commit that changes a line here must say why the outputs changed.\n",
    );
    for d in digests {
        writeln!(text, "{} {:016x} {:016x}", d.name, d.summary, d.detectors).unwrap();
    }
    text
}

/// (name, summary digest, detectors digest) per line of the stored file.
fn parse(text: &str) -> Vec<(String, String, String)> {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            assert_eq!(f.len(), 3, "bad line in digests.txt: {l:?}");
            (f[0].to_string(), f[1].to_string(), f[2].to_string())
        })
        .collect()
}

#[test]
fn outputs_match_the_golden_digests() {
    let digests = compute();
    let path = digests_file();
    if std::env::var_os(BLESS).is_some_and(|v| !v.is_empty() && v != "0") {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, render(&digests)).unwrap();
        eprintln!("{BLESS}: wrote {}", path.display());
        return;
    }
    let stored = std::fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "cannot read {}: {e}; generate it with {BLESS}=1 cargo test --release -p platoonsim --test golden",
            path.display()
        )
    });
    let stored = parse(&stored);
    let how = format!(
        "If the change is intended, regenerate with `{BLESS}=1 cargo test --release -p \
         platoonsim --test golden` and say in the commit message why the outputs changed."
    );
    let names: Vec<&str> = stored.iter().map(|(n, _, _)| n.as_str()).collect();
    let want: Vec<&str> = digests.iter().map(|d| d.name).collect();
    assert_eq!(names, want, "the runs in {} differ. {how}", path.display());
    let mut changed = Vec::new();
    for (d, (_, sum, det)) in digests.iter().zip(&stored) {
        let (now_sum, now_det) = (
            format!("{:016x}", d.summary),
            format!("{:016x}", d.detectors),
        );
        if &now_sum != sum {
            changed.push(format!(
                "{}: summary.json (without wall_seconds) changed: stored {sum}, now {now_sum}",
                d.name
            ));
        }
        if &now_det != det {
            changed.push(format!(
                "{}: detectors.csv changed: stored {det}, now {now_det}",
                d.name
            ));
        }
    }
    assert!(
        changed.is_empty(),
        "outputs are not bit-identical to the golden digests ({}):\n  {}\n{how}",
        path.display(),
        changed.join("\n  ")
    );
}

#[test]
fn fnv1a64_matches_the_reference_values() {
    // The published FNV-1a 64 test vectors.
    assert_eq!(fnv1a64(b""), 0xcbf2_9ce4_8422_2325);
    assert_eq!(fnv1a64(b"a"), 0xaf63_dc4c_8601_ec8c);
    assert_eq!(fnv1a64(b"foobar"), 0x8594_4171_f739_67e8);
}

#[test]
fn canonical_summary_ignores_wall_time_and_key_order() {
    let dir = scratch("canonical");
    std::fs::write(
        dir.join("summary.json"),
        "{\n  \"b\": 1.5,\n  \"wall_seconds\": 0.25,\n  \"a\": [1, null, \"x\"]\n}",
    )
    .unwrap();
    assert_eq!(summary_text(&dir), r#"{"a":[1,null,"x"],"b":1.5}"#);
}
