//! Atomic file writes and checked removals: the one implementation lives in
//! `platoonsim-bounded` (`output`, re-exported by the scenario crate as
//! `platoonsim_scenario::bounded::output`), so that the plot crate, which depends on no
//! platoonsim crate but that one, writes through it too. Every result file goes through
//! [`write_atomic`] (or [`write_atomic_with`] for one written piecewise), every stale output
//! is removed by [`remove_output`].

pub use platoonsim_scenario::bounded::output::{
    check_output, check_writable_dir, output_target, refuse_input, remove_output, same_file,
    write_atomic, write_atomic_file, write_atomic_with,
};
