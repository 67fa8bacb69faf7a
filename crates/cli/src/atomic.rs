//! Atomic file writes: the one implementation lives in `platoonsim-experiment` (whose result
//! files need it too); the CLI's output files go through the same function.

pub use platoonsim_experiment::atomic::{write_atomic, write_atomic_with};
