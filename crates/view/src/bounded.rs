//! Bounded reading of a run directory's files: the `platoonsim-bounded` crate, and the
//! viewer's own limits.

pub(crate) use platoonsim_bounded::{open_records, MAX_RECORD_FILE_BYTES, MAX_RECORD_LINE_BYTES};
#[allow(unused_imports)]
pub(crate) use platoonsim_bounded::{read, read_text, regular_file};

/// The largest table read whole (detectors, trips, collisions): 2 GiB, above the detector
/// records' bound (5 million rows) and a trip for each of the 10 million arrivals a run may
/// bring.
pub const MAX_TABLE_BYTES: u64 = 2 << 30;
/// The largest `road.json` read (SR-99's is about 15 KiB).
pub const MAX_ROAD_BYTES: u64 = 16 << 20;
