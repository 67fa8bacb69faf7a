//! Bounded reading of input files: the `platoonsim-bounded` crate, re-exported for the
//! crates that reach it through this one.

pub use platoonsim_bounded::*;
