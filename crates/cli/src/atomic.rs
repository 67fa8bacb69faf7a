//! Atomic file writes: the one implementation lives in `platoonsim-runs` (whose result files
//! need it too; `platoonsim-experiment` re-exports it); the CLI's output files go through the
//! same function.

pub use platoonsim_experiment::atomic::{
    check_output, check_writable_dir, refuse_input, remove_output, write_atomic, write_atomic_with,
};
