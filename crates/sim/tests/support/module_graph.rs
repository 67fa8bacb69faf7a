//! The module graph of a crate, built from its source, and its circles: shared by the
//! module-graph tests of `sim` (`crates/sim/tests/module_graph.rs`), `runs`, `scenario` and
//! `experiment` (each `tests/module_graph.rs`, including this file by path).
//!
//! The graph: a node per top-level module of `src/` (a folder module with its children is one
//! node), an edge A → B for every `crate::B…` path in A's code (in `use` groups too; an item
//! the crate root re-exports counts for the module that defines it) and every `super::…` path
//! of a top-level module (the root, resolved the same way). Comments, strings and
//! `#[cfg(test)]` items are left out: test code may build a whole simulation.

#![allow(dead_code)]

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// Fails (with the circle and its edges) if a strongly connected component of the graph of
/// `src` has more than `max` modules; else the graph, for further checks.
pub fn check_circles(src: &Path, max: usize) -> Graph {
    let graph = module_graph(src);
    let sccs = strongly_connected(&graph);
    let mut sizes: Vec<usize> = sccs.iter().map(Vec::len).collect();
    sizes.sort_unstable_by(|a, b| b.cmp(a));
    println!(
        "{} modules; component sizes {:?}; circles: {:?}",
        graph.len(),
        sizes,
        sccs.iter().filter(|c| c.len() > 1).collect::<Vec<_>>()
    );
    for c in &sccs {
        assert!(
            c.len() <= max,
            "modules {c:?} import each other in a circle of {} (at most {max} allowed); \
             edges inside it: {:?}",
            c.len(),
            c.iter()
                .map(|m| (
                    m,
                    graph[m]
                        .intersection(&c.iter().cloned().collect())
                        .cloned()
                        .collect::<Vec<_>>()
                ))
                .collect::<Vec<_>>()
        );
    }
    graph
}

pub type Graph = BTreeMap<String, BTreeSet<String>>;

/// Top-level modules and their `crate::`/`super::` references.
pub fn module_graph(src: &Path) -> Graph {
    let lib = strip(&fs::read_to_string(src.join("lib.rs")).unwrap());
    let mut modules = BTreeSet::new();
    let mut test_only = BTreeSet::new();
    let mut pending_test = false;
    for line in lib.lines() {
        let t = line.trim();
        if t.starts_with("#[cfg(test)]") {
            pending_test = true;
            continue;
        }
        if let Some(rest) = t
            .strip_prefix("pub mod ")
            .or_else(|| t.strip_prefix("mod "))
        {
            let name = rest.trim_end_matches(';').trim().to_string();
            if pending_test {
                test_only.insert(name);
            } else {
                modules.insert(name);
            }
        }
        if !t.is_empty() {
            pending_test = false;
        }
    }
    // Root re-exports: item name → module.
    let mut reexport = BTreeMap::new();
    for stmt in lib.split(';') {
        let s = stmt.trim();
        let Some(rest) = s.strip_prefix("pub use ") else {
            continue;
        };
        let rest: String = rest.split_whitespace().collect();
        let Some((head, tail)) = rest.split_once("::") else {
            continue;
        };
        if !modules.contains(head) {
            continue;
        }
        let tail = tail.trim_start_matches('{').trim_end_matches('}');
        for item in tail.split(',') {
            if let Some(name) = item.rsplit("::").next().filter(|n| !n.is_empty()) {
                reexport.insert(name.to_string(), head.to_string());
            }
        }
    }
    let resolve = |name: &str| -> Option<String> {
        if modules.contains(name) {
            Some(name.to_string())
        } else {
            reexport.get(name).cloned()
        }
    };
    let mut graph = Graph::new();
    for m in &modules {
        let mut files = Vec::new();
        let file = src.join(format!("{m}.rs"));
        let dir = src.join(m);
        if file.exists() {
            files.push((file, true));
        }
        if dir.is_dir() {
            collect(&dir, &mut files);
            if let Some(f) = files.iter_mut().find(|(p, _)| p == &dir.join("mod.rs")) {
                f.1 = true;
            }
        }
        let mut out = BTreeSet::new();
        for (path, top) in files {
            let code = drop_test_items(&strip(&fs::read_to_string(&path).unwrap()));
            for name in paths_after(&code, "crate::") {
                out.extend(resolve(&name));
            }
            if top {
                for name in paths_after(&code, "super::") {
                    out.extend(resolve(&name));
                }
            }
        }
        out.remove(m);
        graph.insert(m.clone(), out);
    }
    graph
}

/// The `.rs` files under `dir`, each marked as not top-level (`super::` is the parent).
fn collect(dir: &Path, out: &mut Vec<(PathBuf, bool)>) {
    for e in fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            collect(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push((p, false));
        }
    }
}

/// The first segment after every `prefix` (`crate::a::B` → `a`), every group member of
/// `prefix{a, b::c}` → `a`, `b`.
fn paths_after(code: &str, prefix: &str) -> Vec<String> {
    let mut names = Vec::new();
    let bytes = code.as_bytes();
    let mut i = 0;
    while let Some(k) = code[i..].find(prefix) {
        let at = i + k;
        i = at + prefix.len();
        let before = code[..at].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        if bytes.get(i) == Some(&b'{') {
            let mut depth = 0;
            let mut item_start = true;
            let mut j = i;
            while j < bytes.len() {
                match bytes[j] {
                    b'{' => {
                        depth += 1;
                        item_start = depth == 1;
                    }
                    b'}' => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    b',' if depth == 1 => item_start = true,
                    c if item_start && depth == 1 && (c.is_ascii_alphabetic() || c == b'_') => {
                        let end = code[j..]
                            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                            .map_or(code.len(), |e| j + e);
                        names.push(code[j..end].to_string());
                        item_start = false;
                        j = end;
                        continue;
                    }
                    _ => {}
                }
                j += 1;
            }
        } else {
            let end = code[i..]
                .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                .map_or(code.len(), |e| i + e);
            names.push(code[i..end].to_string());
        }
    }
    names
}

/// `code` without its `#[cfg(test)]` items (through the item's `;` or its closing brace).
fn drop_test_items(code: &str) -> String {
    let mut out = String::new();
    let mut rest = code;
    while let Some(k) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..k]);
        let item = &rest[k..];
        let mut depth = 0;
        let mut end = item.len();
        for (j, c) in item.char_indices().skip("#[cfg(test)]".len()) {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = j + 1;
                        break;
                    }
                }
                ';' if depth == 0 => {
                    end = j + 1;
                    break;
                }
                _ => {}
            }
        }
        rest = &item[end..];
    }
    out.push_str(rest);
    out
}

/// `src` with comments, string and char literals blanked out (so that braces and paths in
/// them do not count).
fn strip(src: &str) -> String {
    let b: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
            out.push(' ');
        } else if c == 'r'
            && (next == Some('"') || next == Some('#'))
            && !(i > 0 && (b[i - 1].is_alphanumeric() || b[i - 1] == '_'))
        {
            let mut j = i + 1;
            let mut hashes = 0;
            while b.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if b.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            j += 1;
            loop {
                if j >= b.len() {
                    break;
                }
                if b[j] == '"' && (0..hashes).all(|h| b.get(j + 1 + h) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            out.push_str("\"\"");
            i = j;
        } else if c == '"' {
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' {
                    i += 1;
                }
                i += 1;
            }
            i += 1;
            out.push_str("\"\"");
        } else if c == '\'' {
            // A char literal ('x', '\n', '\u{..}') or a lifetime ('a).
            if next == Some('\\') {
                let mut j = i + 2;
                while j < b.len() && b[j] != '\'' {
                    j += 1;
                }
                i = j + 1;
                out.push_str("' '");
            } else if b.get(i + 2) == Some(&'\'') {
                i += 3;
                out.push_str("' '");
            } else {
                out.push(c);
                i += 1;
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// Tarjan's strongly connected components, each sorted, in a fixed order.
pub fn strongly_connected(g: &Graph) -> Vec<Vec<String>> {
    struct T<'a> {
        g: &'a Graph,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on: BTreeSet<&'a str>,
        next: usize,
        out: Vec<Vec<String>>,
    }
    fn visit<'a>(t: &mut T<'a>, v: &'a str) {
        t.index.insert(v, t.next);
        t.low.insert(v, t.next);
        t.next += 1;
        t.stack.push(v);
        t.on.insert(v);
        for w in &t.g[v] {
            let w = w.as_str();
            if !t.g.contains_key(w) {
                continue;
            }
            if !t.index.contains_key(w) {
                visit(t, w);
                let lw = t.low[w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if t.on.contains(w) {
                let iw = t.index[w];
                let lv = t.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if t.low[v] == t.index[v] {
            let mut c = Vec::new();
            loop {
                let w = t.stack.pop().unwrap();
                t.on.remove(w);
                c.push(w.to_string());
                if w == v {
                    break;
                }
            }
            c.sort();
            t.out.push(c);
        }
    }
    let mut t = T {
        g,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in g.keys() {
        if !t.index.contains_key(v.as_str()) {
            visit(&mut t, v);
        }
    }
    t.out
}
