//! # platoonsim-rundir: the run directory's contract
//!
//! A run directory (`platoonsim run --out DIR`, `platoonsim.Run.write(DIR)` from Python) is
//! the project's main data contract: `compare` and `calibrate` read it, the viewer and
//! `time-space` read it, sweeps keep its detector records, users read it with pandas. This
//! crate names its files and their columns, and types the cells that are words (the detector
//! records' [`Lane`] and [`DetectorKind`]); [`trajectory`] is the one reader of
//! `trajectories.csv` (the viewer's and `time-space`'s); [`road`] types `road.json`, the road
//! as the engine built it. It depends on no engine crate (only on `csv` and `serde`), so that
//! every reader (the viewer too) and the one writer (`platoonsim_runs::run_dir`) use it.
//! docs/outputs.md describes the files; a test of the CLI holds it to this crate.
//!
//! Outside tests, the file names below are spelled out in this crate only.

mod cells;
#[cfg(test)]
mod doc_test;
pub mod road;
pub mod trajectory;

pub use cells::{DetectorKind, Lane};

use std::path::{Path, PathBuf};

/// `summary.json`, written last: a directory with one holds a finished run.
pub const SUMMARY: &str = "summary.json";
/// `scenario.json`: the resolved configuration.
pub const SCENARIO_JSON: &str = "scenario.json";
/// `scenario.toml`: the same as a complete scenario file.
pub const SCENARIO_TOML: &str = "scenario.toml";
/// `road.json`: the road as the engine built it ([`road::RoadSketch`]).
pub const ROAD_JSON: &str = "road.json";
/// `collisions.csv`: only if the run had collisions (its absence means "no collision").
pub const COLLISIONS: &str = "collisions.csv";
/// `view.html`: the replay page `platoonsim view` writes into the directory.
pub const VIEW: &str = "view.html";

/// A table of the run directory, written as CSV or (`--format parquet`) Parquet.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Table {
    /// The file name without extension.
    pub stem: &'static str,
    /// `<stem>.csv`.
    pub csv: &'static str,
    /// `<stem>.parquet`.
    pub parquet: &'static str,
}

impl Table {
    /// The file name with extension `ext` (`csv` or `parquet`).
    pub fn file(self, ext: &str) -> String {
        format!("{}.{ext}", self.stem)
    }

    /// The CSV file in `dir`.
    pub fn csv_in(self, dir: &Path) -> PathBuf {
        dir.join(self.csv)
    }
}

/// `detectors.csv`: one row per detector, lane and interval.
pub const DETECTORS: Table = Table {
    stem: "detectors",
    csv: "detectors.csv",
    parquet: "detectors.parquet",
};
/// `trips.csv`: one row per vehicle (with `--trips`).
pub const TRIPS: Table = Table {
    stem: "trips",
    csv: "trips.csv",
    parquet: "trips.parquet",
};
/// `trajectories.csv`: one row per vehicle and sample (with `--trajectories`).
pub const TRAJECTORIES: Table = Table {
    stem: "trajectories",
    csv: "trajectories.csv",
    parquet: "trajectories.parquet",
};

/// The tables, in the order they are written.
pub const TABLES: [Table; 3] = [DETECTORS, TRIPS, TRAJECTORIES];

/// Every file a run may write into its directory (the tables in both formats).
pub const RUN_FILES: [&str; 12] = [
    SUMMARY,
    SCENARIO_JSON,
    SCENARIO_TOML,
    ROAD_JSON,
    DETECTORS.csv,
    DETECTORS.parquet,
    TRIPS.csv,
    TRIPS.parquet,
    TRAJECTORIES.csv,
    TRAJECTORIES.parquet,
    COLLISIONS,
    VIEW,
];

/// The suffix of a run's detector records kept beside its run file by the experiment runner
/// (`<runs>/<key>.detectors.csv`, the columns of [`DETECTOR_COLUMNS`]).
pub fn kept_detectors(key: &str) -> String {
    format!("{key}.{}", DETECTORS.csv)
}

/// The columns of `detectors.csv`, in order (a `clock` column follows `interval_start_s` with
/// `run.clock_start`: [`DETECTOR_CLOCK_AT`]).
pub const DETECTOR_COLUMNS: [&str; 11] = [
    "detector",
    "kind",
    "position_m",
    "lane",
    "interval_start_s",
    "interval_s",
    "count",
    "cav_count",
    "flow_vph",
    "speed_kmh",
    "occupancy",
];

/// Where the optional `clock` column of `detectors.csv` goes: right after `interval_start_s`.
pub const DETECTOR_CLOCK_AT: usize = 5;

/// The columns of `trajectories.csv`, in order.
pub const TRAJECTORY_COLUMNS: [&str; 10] = [
    "t_s",
    "id",
    "kind",
    "lane",
    "x_m",
    "v_mps",
    "a_mps2",
    "mode",
    "platoon_pos",
    "regime",
];

/// The header line of `trajectories.csv` (without its line break).
pub const TRAJECTORY_HEADER: &str = "t_s,id,kind,lane,x_m,v_mps,a_mps2,mode,platoon_pos,regime";

/// The columns of `collisions.csv`, in order.
pub const COLLISION_COLUMNS: [&str; 11] = [
    "t_s",
    "kind",
    "lane",
    "x_m",
    "vehicle",
    "vehicle_kind",
    "v_mps",
    "other",
    "other_kind",
    "other_v_mps",
    "overlap_m",
];

/// The columns of `trips.csv`, in order.
pub const TRIP_COLUMNS: [&str; 15] = [
    "id",
    "kind",
    "origin",
    "destination",
    "status",
    "entered_s",
    "depart_delay_s",
    "left_s",
    "travel_time_s",
    "entry_x_m",
    "last_x_m",
    "lane_changes",
    "max_platoon",
    "max_platoon_tg2",
    "measured",
];

/// The columns `trips.csv` gains with `energy.enabled` (docs/energy.md): fuel (L) of a
/// combustion-engine vehicle, battery energy (kWh) of an electric one (the other empty), and
/// the share of its energy without drag reduction that drafting saved (%).
pub const TRIP_ENERGY_COLUMNS: [&str; 3] = ["fuel_l", "energy_kwh", "drag_saving_pct"];

/// The column every `trips.csv` ends with (after the energy columns, if any): the vehicle's
/// arrival at its entrance (s), `entered_s − depart_delay_s`.
pub const TRIP_ARRIVAL_COLUMN: &str = "entrance_arrival_s";

/// The columns appended last with `run.clock_start`: the clock times ("HH:MM:SS") of
/// `entered_s` and `left_s`.
pub const TRIP_CLOCK_COLUMNS: [&str; 2] = ["entered_clock", "left_clock"];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_names_agree_with_their_parts() {
        for t in TABLES {
            assert_eq!(t.csv, t.file("csv"));
            assert_eq!(t.parquet, t.file("parquet"));
            assert!(RUN_FILES.contains(&t.csv) && RUN_FILES.contains(&t.parquet));
        }
        assert_eq!(TRAJECTORY_HEADER, TRAJECTORY_COLUMNS.join(","));
        assert_eq!(DETECTOR_COLUMNS[DETECTOR_CLOCK_AT - 1], "interval_start_s");
        assert_eq!(kept_detectors("ab12"), "ab12.detectors.csv");
    }
}
