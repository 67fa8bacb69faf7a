//! Networks of other tools in, as ordinary platoonsim scenario files (docs/import.md).
//!
//! [`sumo`] reads a SUMO network (`.net.xml`), routes (`.rou.xml`) and additional files
//! (`.add.xml`: induction loops) and writes a `[network]` corridor: the mainline as lane
//! stretches, the on- and off-ramps with their acceleration lanes, the detectors, the demand
//! per interval and the vehicle-type parameters that map onto the model's. What it cannot
//! represent it reduces (with a note) or refuses (with an error naming the edge or junction);
//! the [`Notes`] say what was kept, reduced and dropped.

mod error;
mod notes;
mod read;
pub mod sumo;

pub use error::ImportError;
pub use notes::Notes;
