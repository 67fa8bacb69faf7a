//! The model reference (`docs/model-reference.md`) against the repository that cites it.
//!
//! * Every "spec N.M" in a `.rs`, `.md` or `.toml` file of the repository names a section of
//!   the reference: a heading `N.M`, or an item of one. "spec N.M.K" is numbered item K of
//!   section N.M, and "spec 6.K" is row 6.K of the open-questions table of section 6 (the
//!   reference's own rule, stated in its opening paragraph).
//! * The parameter tables of section 8 list every field of the tables in the opening comments
//!   of `crates/model/src/human.rs`, `cav.rs` and `lanechange.rs` with the same default.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn reference() -> String {
    std::fs::read_to_string(root().join("docs/model-reference.md")).unwrap()
}

/// The `.rs`, `.md` and `.toml` files of the repository (no build output, no hidden folders).
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if path.is_dir() {
            if !name.starts_with('.') && name != "target" && name != "node_modules" {
                sources(&path, out);
            }
        } else if [".rs", ".md", ".toml"].iter().any(|e| name.ends_with(e)) {
            out.push(path);
        }
    }
}

/// A section number: digits separated by single dots, not ending in a dot.
fn number_at(s: &str) -> Option<&str> {
    let end = s
        .char_indices()
        .find(|&(i, c)| {
            !(c.is_ascii_digit()
                || (c == '.' && s[i + 1..].starts_with(|d: char| d.is_ascii_digit())))
        })
        .map_or(s.len(), |(i, _)| i);
    let n = &s[..end];
    (!n.is_empty() && n.starts_with(|c: char| c.is_ascii_digit())).then_some(n)
}

/// The section numbers cited in `text`: "spec 2.3", and the lists "spec 1, 2.2, 2.7",
/// "spec 2.5/4.6", "spec 3.6 and 4.5" (list items after the first must have a dot, so that
/// "spec 6.1, 2,000 veh/h" cites only 6.1).
fn citations(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let lower = text.to_lowercase();
    let mut from = 0;
    while let Some(i) = lower[from..].find("spec ") {
        let at = from + i;
        from = at + 5;
        let boundary = at == 0 || !lower[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_');
        let Some(first) = number_at(&text[from..]) else {
            continue;
        };
        if !boundary {
            continue;
        }
        out.push(first.to_string());
        let mut rest = &text[from + first.len()..];
        while let Some(after) = [", ", " and ", "/"]
            .iter()
            .find_map(|sep| rest.strip_prefix(sep))
        {
            // A list item has a dot and is not the start of a number like "2,000".
            let Some(n) = number_at(after).filter(|n| n.contains('.')) else {
                break;
            };
            let tail = &after[n.len()..];
            if tail.starts_with(',') && tail[1..].starts_with(|d: char| d.is_ascii_digit()) {
                break;
            }
            out.push(n.to_string());
            rest = tail;
        }
    }
    out
}

/// The reference's sections: heading number → the section's text up to the next heading.
fn sections(md: &str) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    let mut current: Option<String> = None;
    for line in md.lines() {
        if line.starts_with('#') {
            let title = line.trim_start_matches('#').trim();
            current = number_at(title).map(|n| n.trim_end_matches('.').to_string());
            if let Some(n) = &current {
                out.insert(n.clone(), String::new());
            }
        } else if let Some(n) = &current {
            let body = out.get_mut(n).unwrap();
            body.push_str(line);
            body.push('\n');
        }
    }
    out
}

fn resolves(c: &str, secs: &BTreeMap<String, String>) -> bool {
    if secs.contains_key(c) {
        return true;
    }
    let parts: Vec<&str> = c.split('.').collect();
    match parts.as_slice() {
        [a, b, k] => secs.get(&format!("{a}.{b}")).is_some_and(|body| {
            body.lines()
                .any(|l| l.trim_start().starts_with(&format!("{k}. ")))
        }),
        ["6", _] => secs["6"]
            .lines()
            .any(|l| l.starts_with(&format!("| {c} |"))),
        _ => false,
    }
}

#[test]
fn every_spec_citation_names_a_section_of_the_reference() {
    let secs = sections(&reference());
    assert!(secs.contains_key("2.3") && secs.contains_key("6") && secs.contains_key("8"));
    let mut files = Vec::new();
    sources(&root(), &mut files);
    files.sort();
    let mut cited = 0;
    let mut missing = Vec::new();
    let mut seen = BTreeSet::new();
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap_or_default();
        for (ln, line) in text.lines().enumerate() {
            for c in citations(line) {
                cited += 1;
                seen.insert(c.clone());
                if !resolves(&c, &secs) {
                    let rel = f.strip_prefix(root()).unwrap_or(f);
                    missing.push(format!("{}:{}: spec {c}", rel.display(), ln + 1));
                }
            }
        }
    }
    assert!(
        missing.is_empty(),
        "citations without a section:\n{}",
        missing.join("\n")
    );
    // The repository cites the reference a few hundred times; a scan that finds almost none
    // has stopped looking (wrong root, or a broken parser).
    assert!(
        cited > 300 && seen.len() > 40,
        "{cited} citations of {} sections",
        seen.len()
    );
}

#[test]
fn citation_parsing() {
    assert_eq!(citations("(spec 1, 2.2, 2.7)"), ["1", "2.2", "2.7"]);
    assert_eq!(citations("spec 6.1, 2,000 veh/h"), ["6.1"]);
    assert_eq!(
        citations("Spec 2.5/4.6; the spec's values (4.9)"),
        ["2.5", "4.6"]
    );
    assert_eq!(citations("spec 3.6.4)."), ["3.6.4"]);
    assert_eq!(
        citations("a sweep spec key, respec 2.1"),
        Vec::<String>::new()
    );
    let secs = sections("## 3. A\n### 3.6 B\n1. one\n2. two\n## 6. Q\n| 6.1 | x |\n");
    assert!(resolves("3.6", &secs) && resolves("3.6.2", &secs) && resolves("6.1", &secs));
    assert!(!resolves("3.6.3", &secs) && !resolves("6.2", &secs) && !resolves("3.7", &secs));
}

/// `field` → default of the parameter tables (`| symbol | \`field\` | default | …`) in `text`,
/// whose lines start with `prefix` (`//! ` in the code, nothing in the reference). A row that
/// names two fields (`\`a\`, \`b\``) maps both to the same default cell.
fn table_defaults(text: &str, prefix: &str) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    for line in text.lines() {
        let Some(row) = line.strip_prefix(prefix) else {
            continue;
        };
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        if cells.len() < 5 || !cells[2].starts_with('`') {
            continue;
        }
        for field in cells[2].split(',') {
            out.insert(
                field.trim().trim_matches('`').to_string(),
                cells[3].to_string(),
            );
        }
    }
    out
}

#[test]
fn the_parameter_tables_of_the_reference_match_the_code() {
    let md = reference();
    let secs = sections(&md);
    for (file, section) in [
        ("human.rs", "8.1"),
        ("cav.rs", "8.2"),
        ("lanechange.rs", "8.3"),
    ] {
        let code = std::fs::read_to_string(root().join("crates/model/src").join(file)).unwrap();
        let want = table_defaults(&code, "//! ");
        let have = table_defaults(&secs[section], "");
        assert!(want.len() >= 10, "{file}: {} rows", want.len());
        for (field, default) in &want {
            assert_eq!(
                have.get(field),
                Some(default),
                "docs/model-reference.md section {section} and crates/model/src/{file} disagree on `{field}`"
            );
        }
    }
}
