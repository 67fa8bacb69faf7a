//! Golden digests (issue 18 item 7): "outputs bit-identical" checked by CI, not by hand.
//!
//! Eight short runs of the `platoonsim` binary, each with the defaults of its scenario
//! otherwise:
//!
//! | name | command |
//! |---|---|
//! | `homogeneous` | `platoonsim run homogeneous --duration 600 --warmup 120` (50 % CAV, 2,500 veh/h/lane, no strategy) |
//! | `homogeneous_pd` | the same with `--strategy pd` |
//! | `sr99` | `platoonsim run sr99 --duration 900` (05:00-05:15, 0 % CAV) |
//! | `lane_drop` | `platoonsim run crates/scenario/scenarios/lane_drop.toml --duration 600 --warmup 120` (50 % CAV) |
//! | `<name>_spec` | each of the four with `--set cav.cacc_law=spec` (the published CACC law) |
//!
//! For each, two FNV-1a 64-bit digests: `summary.json` without `wall_seconds` (parsed, the key
//! removed, written back canonically: keys sorted, no white space, numbers as serde_json
//! writes them, i.e. shortest round-trip, so equal text is equal bits), and `detectors.csv`
//! byte for byte. They are compared with `tests/golden/digests.txt` (one line per run: name,
//! summary digest, detectors digest; `#` lines are comments).
//!
//! Beside the digests, readable copies of each run: `tests/golden/<name>.summary.txt` (the
//! summary without `wall_seconds`, one `path = value` line per figure, sorted) and
//! `tests/golden/<name>.detectors.csv` (the header and the cross-section rows), so that a
//! failure prints which figures moved, stored against now.
//!
//! Regenerate after a change that is meant to change the outputs:
//!
//! ```text
//! PLATOONSIM_BLESS=1 cargo test --release -p platoonsim --test golden
//! ```
//!
//! which rewrites the digests and the text copies instead of comparing. A commit that changes the digests must say
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

/// `summary.json` without `wall_seconds` (which it must have).
fn summary_value(dir: &Path) -> serde_json::Value {
    let mut v: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("summary.json")).unwrap()).unwrap();
    let m = v.as_object_mut().expect("summary.json is an object");
    assert!(
        m.remove("wall_seconds").is_some(),
        "summary.json has no wall_seconds"
    );
    v
}

/// A summary (as [`summary_value`] gives it) as canonical JSON text.
fn summary_text(v: &serde_json::Value) -> String {
    let mut out = String::new();
    canonical(v, &mut out);
    out
}

/// A summary (as [`summary_value`] gives it) as one `path = value` line per leaf, sorted by
/// path: the readable copy of the summary digest, so that a failure shows which figures moved.
fn flat_summary(v: &serde_json::Value) -> String {
    fn walk(v: &serde_json::Value, path: String, out: &mut Vec<String>) {
        use serde_json::Value;
        match v {
            Value::Object(m) => {
                for (k, x) in m {
                    let p = if path.is_empty() {
                        k.clone()
                    } else {
                        format!("{path}.{k}")
                    };
                    walk(x, p, out);
                }
            }
            Value::Array(a) if !a.is_empty() => {
                for (i, x) in a.iter().enumerate() {
                    walk(x, format!("{path}[{i}]"), out);
                }
            }
            other => out.push(format!(
                "{path} = {}",
                serde_json::to_string(other).unwrap()
            )),
        }
    }
    let mut lines = Vec::new();
    walk(v, String::new(), &mut lines);
    lines.sort();
    lines.iter().map(|l| format!("{l}\n")).collect()
}

/// The header and the cross-section rows (`lane` = `all`) of `detectors.csv`: the readable
/// excerpt of the detectors digest.
fn cross_sections(csv: &str) -> String {
    let mut lines = csv.lines();
    let header = lines.next().unwrap_or_default();
    let lane = header
        .split(',')
        .position(|c| c == "lane")
        .expect("detectors.csv has a lane column");
    std::iter::once(header)
        .chain(lines.filter(|l| l.split(',').nth(lane) == Some("all")))
        .map(|l| format!("{l}\n"))
        .collect()
}

/// The lines of `now` that differ from `stored`, side by side (at most 40), or `None`.
fn line_diff(stored: &str, now: &str) -> Option<String> {
    let (a, b): (Vec<&str>, Vec<&str>) = (stored.lines().collect(), now.lines().collect());
    let mut out = Vec::new();
    for i in 0..a.len().max(b.len()) {
        let (x, y) = (a.get(i).copied(), b.get(i).copied());
        if x != y {
            out.push(format!(
                "    line {}: stored {}\n    {:>width$}  now    {}",
                i + 1,
                x.unwrap_or("(none)"),
                "",
                y.unwrap_or("(none)"),
                width = (i + 1).to_string().len() + 5
            ));
        }
    }
    let n = out.len();
    out.truncate(40);
    (n > 0).then(|| format!("{} line(s) differ:\n{}", n, out.join("\n")))
}

/// The readable copies of run `name`: (flattened summary, detectors excerpt).
fn text_files(name: &str) -> (PathBuf, PathBuf) {
    let dir = digests_file().parent().unwrap().to_path_buf();
    (
        dir.join(format!("{name}.summary.txt")),
        dir.join(format!("{name}.detectors.csv")),
    )
}

struct Digest {
    name: &'static str,
    summary: u64,
    detectors: u64,
    /// The readable copies: the summary flattened, the detectors' cross-section rows.
    summary_lines: String,
    detectors_lines: String,
}

/// The golden runs: name and arguments after `run`.
fn runs() -> Vec<(&'static str, Vec<String>)> {
    let v = |a: &[&str]| a.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let mut runs = vec![
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
    ];
    // The same runs under the published CACC law (`cav.cacc_law = "spec"`): their digests
    // are those of the engine before the field law, bit for bit, but for summary.json's
    // take-over request fields (all 0 under that law).
    let spec: Vec<(&'static str, Vec<String>)> = runs
        .iter()
        .zip([
            "homogeneous_spec",
            "homogeneous_pd_spec",
            "sr99_spec",
            "lane_drop_spec",
        ])
        .map(|((_, a), name)| {
            let mut a = a.clone();
            a.extend(["--set".to_string(), "cav.cacc_law=spec".to_string()]);
            (name, a)
        })
        .collect();
    runs.extend(spec);
    runs
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
                    let detectors = std::fs::read(out.join("detectors.csv")).unwrap();
                    let summary = summary_value(&out);
                    Digest {
                        name,
                        summary: fnv1a64(summary_text(&summary).as_bytes()),
                        detectors: fnv1a64(&detectors),
                        summary_lines: flat_summary(&summary),
                        detectors_lines: cross_sections(&String::from_utf8(detectors).unwrap()),
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
        for d in &digests {
            let (sum, det) = text_files(d.name);
            std::fs::write(sum, &d.summary_lines).unwrap();
            std::fs::write(det, &d.detectors_lines).unwrap();
        }
        eprintln!(
            "{BLESS}: wrote {} and the runs' text copies",
            path.display()
        );
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
        let (sum_file, det_file) = text_files(d.name);
        let read = |p: &Path| std::fs::read_to_string(p).unwrap_or_default();
        if &now_sum != sum {
            changed.push(format!(
                "{}: summary.json (without wall_seconds) changed: stored {sum}, now {now_sum}; {}",
                d.name,
                line_diff(&read(&sum_file), &d.summary_lines)
                    .unwrap_or_else(|| format!("{} is out of date", sum_file.display()))
            ));
        }
        if &now_det != det {
            changed.push(format!(
                "{}: detectors.csv changed: stored {det}, now {now_det}; cross-sections: {}",
                d.name,
                line_diff(&read(&det_file), &d.detectors_lines)
                    .unwrap_or_else(|| "equal (a per-lane row changed)".into())
            ));
        }
        // The text copies are part of the golden state: stale copies fail too.
        for (file, now) in [
            (&sum_file, &d.summary_lines),
            (&det_file, &d.detectors_lines),
        ] {
            if &read(file) != now {
                changed.push(format!(
                    "{}: {} differs from this run",
                    d.name,
                    file.display()
                ));
            }
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
    assert_eq!(
        summary_text(&summary_value(&dir)),
        r#"{"a":[1,null,"x"],"b":1.5}"#
    );
}
