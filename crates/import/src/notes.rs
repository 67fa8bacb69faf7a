//! What an import kept, reduced and dropped: printed after every import and written into the
//! scenario file's header, so that a corridor never hides what it left out.

use std::fmt;

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Notes {
    /// Elements represented as they are.
    pub kept: Vec<String>,
    /// Elements represented approximately, each with how.
    pub reduced: Vec<String>,
    /// Elements left out, each with why.
    pub dropped: Vec<String>,
}

impl Notes {
    pub fn keep(&mut self, s: impl Into<String>) {
        self.kept.push(s.into());
    }
    pub fn reduce(&mut self, s: impl Into<String>) {
        self.reduced.push(s.into());
    }
    pub fn drop(&mut self, s: impl Into<String>) {
        self.dropped.push(s.into());
    }
}

impl fmt::Display for Notes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (title, items) in [
            ("kept", &self.kept),
            ("reduced", &self.reduced),
            ("dropped", &self.dropped),
        ] {
            writeln!(f, "{title} ({}):", items.len())?;
            for s in items {
                writeln!(f, "  - {s}")?;
            }
        }
        Ok(())
    }
}
