//! The engine's error type. Bad input is caught by the scenario crate with file context; what
//! reaches the engine and still breaks an invariant it relies on is refused here, with a
//! message that names the field, the value and what is allowed.

/// Why the engine refused a config or a request, or stopped a run.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SimError {
    /// The config breaks an invariant of the engine ([`crate::Config::check`]).
    #[error("{0}")]
    Config(String),
    /// The road geometry of a network cannot be built from the config
    /// ([`crate::network::Geometry::new`]).
    #[error("{0}")]
    Geometry(String),
    /// A recording request that the engine cannot honour ([`crate::Recording::check`]).
    #[error("{0}")]
    Recording(String),
    /// A command that cannot be applied ([`crate::Simulation::command`]): no such vehicle on
    /// the road, or a value out of range.
    #[error("{0}")]
    Command(String),
    /// A set-up call made after the first step: [`crate::Simulation::record`],
    /// [`crate::Simulation::set_organizer`], [`crate::Simulation::observe`].
    #[error("{0} before the first step")]
    AfterFirstStep(&'static str),
    /// A vehicle's state stopped being finite during a step: an engine fault, never a result.
    #[error(
        "vehicle {vehicle} in lane {lane} has a non-finite state at t = {t_s:.1} s \
         (x = {x_m}, v = {v_mps}, a = {a_mps2})"
    )]
    NonFinite {
        vehicle: u64,
        /// Numbered from 1 (the rightmost lane), as in the outputs.
        lane: usize,
        t_s: f64,
        x_m: f64,
        v_mps: f64,
        a_mps2: f64,
    },
}
