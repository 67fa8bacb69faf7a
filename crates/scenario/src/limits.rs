//! Upper limits of every rate, length, duration and count a scenario may give, so that no input
//! can make a run hang or exhaust memory (issue 18 item 6; the table with the reasons is in
//! docs/robustness.md). The time step, duration, demand and length limits are the engine's own
//! ([`platoonsim_sim::config::limits`]), re-exported here so that each is defined once.

pub use platoonsim_sim::config::limits::{
    DT_MAX_S, DT_MIN_S, DT_REASON, MAX_DEMAND_VPHPL, MAX_DURATION_S, MAX_LENGTH_M,
};

/// Largest scenario file, and largest `--set` value (bytes), checked before parsing: a TOML
/// array of 25 million numbers takes gigabytes before any range check could refuse it. The
/// built-in `sr99.toml`, the largest, is about 12 KiB.
pub const MAX_FILE_BYTES: usize = 1 << 20;
/// Largest magnitude of a corridor coordinate (m): positions far from 0 lose the precision
/// of an f64 at the centimetre scale the engine works at.
pub const MAX_COORDINATE_M: f64 = 10_000_000.0;
/// Longest ramp roadway or acceleration lane (m).
pub const MAX_RAMP_LENGTH_M: f64 = 10_000.0;
/// Most `[[detectors]]` entries (the sr99 corridor generates about 60 more).
pub const MAX_DETECTORS: usize = 1_000;
/// Most `[[network.lanes]]` stretches.
pub const MAX_STRETCHES: usize = 1_000;
/// Most on-ramps, and most off-ramps (sr99 has 16 and 11).
pub const MAX_RAMPS: usize = 200;
/// Most intervals in a demand series: 7 days of one-minute intervals.
pub const MAX_INTERVALS: usize = 10_080;
/// Most values of all demand series together after `network.demand_offset_s` has refined
/// them (16 MB of f64).
pub const MAX_SERIES_VALUES: usize = 2_000_000;
/// Shortest demand interval (s).
pub const MIN_INTERVAL_S: f64 = 1.0;
/// Most detector records a run may produce (detector intervals × detectors × (lanes + 1));
/// each is held in memory until the end of the run and is one row of detectors.csv.
pub const MAX_DETECTOR_RECORDS: f64 = 5_000_000.0;
/// Most `[time gap, share]` pairs in `cav.time_gap_shares`.
pub const MAX_TIME_GAP_SHARES: usize = 100;
/// Most entries of `network.lane_speed_limits_kmh`.
pub const MAX_LANE_SPEED_LIMITS: usize = 16;
/// Largest CACC string (`cav.max_platoon`, vehicles); the paper's is 10.
pub const MAX_PLATOON: u32 = 100;
/// Largest magnitude of any number in `[human]`, `[cav]`, `[lane_change]` and `[safety]`: a
/// bound far above every physical parameter (speeds in km/h, distances in m, gains).
pub const MAX_MODEL_MAGNITUDE: f64 = 1_000_000.0;
/// Highest `strategy.flow_threshold_vphpl` (veh/h/lane) and `strategy.speed_threshold_kmh`
/// (km/h) that mean anything.
pub const MAX_FLOW_THRESHOLD_VPHPL: f64 = MAX_DEMAND_VPHPL;
pub const MAX_SPEED_THRESHOLD_KMH: f64 = 1_000.0;
/// Most vehicles a run may bring (the expected arrivals at every entrance over the run):
/// 350 times the 4-hour SR-99 run. A vehicle waiting in an entry queue takes some 300 bytes,
/// so an entrance overloaded for days could otherwise take gigabytes.
pub const MAX_ARRIVALS: f64 = 10_000_000.0;
/// Longest `cav.actuator_lag_s`, `cav.comm_delay_s` and `cav.beacon_timeout_s` (s, spec 9.3):
/// far above the literature's tenths of a second; the V2V log keeps (delay + timeout)/Δt
/// speeds per vehicle.
pub const MAX_CAV_REALISM_S: f64 = 10.0;
