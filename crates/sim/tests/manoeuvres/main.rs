//! Single manoeuvres with vehicles placed by hand on an empty road or corridor (no arrivals),
//! in the manner of SUMO's small scenario tests (`tests/sumo/cf_model/…/follow_slow`): each
//! test pins one behaviour of the driver models as the engine runs them, and says what it saw
//! when it fails. docs/testing.md lists them with the rule each pins.

mod commands;
mod common;
mod following;
mod lane_changes;
mod organize;
mod platoons;
mod ramps;
