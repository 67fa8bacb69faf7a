//! Small helpers over roxmltree for SUMO's files: parsing with a node limit, typed attributes
//! with errors that name the file, line, element and attribute.

use crate::ImportError;
use roxmltree::{Document, Node, ParsingOptions};
use std::path::Path;

/// The most XML nodes one file may have (a whole-state OpenStreetMap network has a few
/// million); past it the parser stops instead of exhausting memory.
const MAX_NODES: u32 = 50_000_000;

/// The deepest nesting of elements accepted. SUMO's files nest at most 4 deep (`<net>`,
/// `<edge>`, `<lane>`, `<param>`); roxmltree recurses once per level, so a file nested 100,000
/// deep overflowed the stack and aborted the process (issue 48 D1).
pub const MAX_DEPTH: usize = 256;
/// The most attributes one element may have (SUMO's have fewer than 40); a million on one
/// element took roxmltree minutes (issue 48 D4).
pub const MAX_ATTRIBUTES: usize = 1_000;

/// One linear pass over the text before roxmltree sees it: refuses nesting deeper than
/// [`MAX_DEPTH`] and elements with more than [`MAX_ATTRIBUTES`] attributes, naming the file and
/// the line. It does not validate (roxmltree does): it only tracks tags, comments, CDATA,
/// processing instructions and quoted attribute values well enough to count correctly in a
/// well-formed file, and it never fails on one that roxmltree accepts.
fn check_shape(path: &Path, text: &str) -> Result<(), ImportError> {
    let b = text.as_bytes();
    let refuse = |at: usize, what: String, problem: String| ImportError::Invalid {
        path: path.to_path_buf(),
        line: Some(1 + b[..at].iter().filter(|&&c| c == b'\n').count() as u32),
        what,
        problem,
    };
    let find = |from: usize, pat: &[u8]| -> usize {
        b[from.min(b.len())..]
            .windows(pat.len())
            .position(|w| w == pat)
            .map_or(b.len(), |i| from + i + pat.len())
    };
    let (mut i, mut depth) = (0usize, 0usize);
    while let Some(off) = b[i..].iter().position(|&c| c == b'<') {
        let start = i + off;
        let rest = &b[start + 1..];
        if rest.starts_with(b"!--") {
            i = find(start + 4, b"-->");
        } else if rest.starts_with(b"![CDATA[") {
            i = find(start + 9, b"]]>");
        } else if rest.starts_with(b"?") {
            i = find(start + 2, b"?>");
        } else if rest.starts_with(b"!") {
            // A DOCTYPE (refused by the parser: DTDs are off); skip to its end.
            i = find(start + 2, b">");
        } else if rest.starts_with(b"/") {
            depth = depth.saturating_sub(1);
            i = find(start + 2, b">");
        } else {
            // A start tag: count the quoted values (attributes) up to its `>`.
            let (mut j, mut attributes, mut quote) = (start + 1, 0usize, None::<u8>);
            let mut empty = false;
            while j < b.len() {
                let c = b[j];
                match quote {
                    Some(q) if c == q => quote = None,
                    Some(_) => {}
                    None if c == b'"' || c == b'\'' => {
                        quote = Some(c);
                        attributes += 1;
                        if attributes > MAX_ATTRIBUTES {
                            return Err(refuse(
                                start,
                                "an element".into(),
                                format!(
                                    "more than {MAX_ATTRIBUTES} attributes; a SUMO element has \
                                     fewer than 40"
                                ),
                            ));
                        }
                    }
                    None if c == b'>' => {
                        empty = j > start && b[j - 1] == b'/';
                        break;
                    }
                    None => {}
                }
                j += 1;
            }
            if !empty {
                depth += 1;
                if depth > MAX_DEPTH {
                    return Err(refuse(
                        start,
                        "an element".into(),
                        format!(
                            "nested more than {MAX_DEPTH} elements deep; a SUMO file nests at \
                             most 4"
                        ),
                    ));
                }
            }
            i = j + 1;
        }
        if i >= b.len() {
            break;
        }
    }
    Ok(())
}

pub fn parse<'a>(path: &Path, text: &'a str) -> Result<Document<'a>, ImportError> {
    check_shape(path, text)?;
    let opt = ParsingOptions {
        allow_dtd: false,
        nodes_limit: MAX_NODES,
    };
    Document::parse_with_options(text, opt).map_err(|e| ImportError::Xml {
        path: path.to_path_buf(),
        msg: e.to_string(),
    })
}

/// Where an element is, for errors: the file and the element's line.
#[derive(Clone, Copy)]
pub struct At<'p, 'a, 'i> {
    pub path: &'p Path,
    pub node: Node<'a, 'i>,
}

impl<'p, 'a, 'i> At<'p, 'a, 'i> {
    pub fn new(path: &'p Path, node: Node<'a, 'i>) -> Self {
        At { path, node }
    }

    /// The element's line: counted from the file's start, so only for errors (issue 48 D2: a
    /// line per connection made parsing quadratic).
    pub fn line(&self) -> u32 {
        self.node
            .document()
            .text_pos_at(self.node.range().start)
            .row
    }

    /// `<edge id="x">`, naming an element in errors.
    pub fn element(&self) -> String {
        let tag = self.node.tag_name().name();
        match self.node.attribute("id") {
            Some(id) => format!("<{tag} id=\"{id}\">"),
            None => format!("<{tag}>"),
        }
    }

    pub fn invalid(&self, what: impl Into<String>, problem: impl Into<String>) -> ImportError {
        ImportError::Invalid {
            path: self.path.to_path_buf(),
            line: Some(self.line()),
            what: format!("{} {}", self.element(), what.into()),
            problem: problem.into(),
        }
    }

    pub fn req(&self, name: &str) -> Result<&'a str, ImportError> {
        self.node
            .attribute(name)
            .ok_or_else(|| self.invalid(format!("has no attribute {name}"), "it is required"))
    }

    /// An optional number attribute, finite and within [lo, hi].
    pub fn num(&self, name: &str, lo: f64, hi: f64) -> Result<Option<f64>, ImportError> {
        let Some(s) = self.node.attribute(name) else {
            return Ok(None);
        };
        match s.trim().parse::<f64>() {
            Ok(v) if v.is_finite() && (lo..=hi).contains(&v) => Ok(Some(v)),
            _ => Err(self.invalid(
                format!("attribute {name}=\"{s}\""),
                format!("must be a number in [{lo}, {hi}]"),
            )),
        }
    }

    pub fn req_num(&self, name: &str, lo: f64, hi: f64) -> Result<f64, ImportError> {
        self.num(name, lo, hi)?
            .ok_or_else(|| self.invalid(format!("has no attribute {name}"), "it is required"))
    }

    /// An optional whole number attribute within [0, hi].
    pub fn index(&self, name: &str, hi: usize) -> Result<Option<usize>, ImportError> {
        let Some(s) = self.node.attribute(name) else {
            return Ok(None);
        };
        match s.trim().parse::<usize>() {
            Ok(v) if v <= hi => Ok(Some(v)),
            _ => Err(self.invalid(
                format!("attribute {name}=\"{s}\""),
                format!("must be a whole number in [0, {hi}]"),
            )),
        }
    }
}

/// Checks the root element's name.
pub fn root<'a, 'i>(
    path: &Path,
    doc: &'a Document<'i>,
    names: &[&str],
    what: &str,
) -> Result<Node<'a, 'i>, ImportError> {
    let root = doc.root_element();
    let name = root.tag_name().name();
    if names.contains(&name) {
        Ok(root)
    } else {
        Err(ImportError::Invalid {
            path: path.to_path_buf(),
            line: Some(doc.text_pos_at(root.range().start).row),
            what: format!("the root element is <{name}>"),
            problem: format!("a {what} has <{}> at its root", names.join("> or <")),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        parse(Path::new("x.xml"), text).unwrap_err().to_string()
    }

    #[test]
    fn deep_nesting_is_refused_with_file_and_line_not_a_stack_overflow() {
        // Issue 48 D1: 100,000 levels (700 KB) aborted the process with a stack overflow.
        let deep = format!(
            "<net>\n{}{}</net>",
            "<a>".repeat(100_000),
            "</a>".repeat(100_000)
        );
        assert_eq!(
            err(&deep),
            "x.xml:2: an element: nested more than 256 elements deep; a SUMO file nests at most 4"
        );
        // At the limit it parses.
        let ok = format!("{}{}", "<a>".repeat(MAX_DEPTH), "</a>".repeat(MAX_DEPTH));
        parse(Path::new("x.xml"), &ok).unwrap();
        // Empty elements, comments, CDATA and quoted `>` do not count as levels.
        let flat = format!(
            "<?xml version=\"1.0\"?><!-- <a> --><net>{}</net>",
            "<e v=\"a>b\" w='c>'/><![CDATA[<x>]]>".repeat(10_000)
        );
        parse(Path::new("x.xml"), &flat).unwrap();
    }

    #[test]
    fn an_element_with_too_many_attributes_is_refused() {
        // Issue 48 D4: a million attributes on one element ran past 3 minutes.
        let attrs: String = (0..200_000).map(|i| format!(" a{i}=\"{i}\"")).collect();
        let started = std::time::Instant::now();
        assert_eq!(
            err(&format!("<net>\n\n<edge{attrs}/></net>")),
            "x.xml:3: an element: more than 1000 attributes; a SUMO element has fewer than 40"
        );
        assert!(started.elapsed().as_secs_f64() < 1.0);
        let ok: String = (0..MAX_ATTRIBUTES)
            .map(|i| format!(" a{i}=\"{i}\""))
            .collect();
        parse(Path::new("x.xml"), &format!("<net{ok}/>")).unwrap();
    }
}
