//! Small helpers over roxmltree for SUMO's files: parsing with a node limit, typed attributes
//! with errors that name the file, line, element and attribute.

use crate::ImportError;
use roxmltree::{Document, Node, ParsingOptions};
use std::path::Path;

/// The most XML nodes one file may have (a whole-state OpenStreetMap network has a few
/// million); past it the parser stops instead of exhausting memory.
const MAX_NODES: u32 = 50_000_000;

pub fn parse<'a>(path: &Path, text: &'a str) -> Result<Document<'a>, ImportError> {
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
