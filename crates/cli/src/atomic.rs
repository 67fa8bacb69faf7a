//! Atomic file writes: the one implementation lives in `platoonsim-bounded` (`output`,
//! re-exported by `platoonsim-runs` as `atomic`); the CLI's output files go through the same
//! function.

pub use platoonsim_runs::atomic::{check_output, check_writable_dir, refuse_input, write_atomic};
