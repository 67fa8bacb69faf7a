//! The run directory's tables as Parquet (`--format parquet`): the CSV files' columns with
//! types (numbers as float64, counts as uint64, words as strings, flags as booleans); an
//! empty CSV cell is a null. Written by `platoonsim-columnar` (arrow + parquet, snappy).

use crate::atomic::write_atomic_file;
use crate::Error;
use platoonsim_columnar::{from_csv, Kind, Table, Values, Writer, ROW_GROUP_ROWS};
use platoonsim_sim::TrajectoryPoint;
use std::path::Path;

/// The column types of `detectors.csv`.
pub fn detector_kind(column: &str) -> Kind {
    match column {
        "detector" | "kind" | "lane" | "clock" => Kind::Str,
        "count" | "cav_count" => Kind::U64,
        _ => Kind::F64,
    }
}

/// The column types of `trips.csv`.
pub fn trip_kind(column: &str) -> Kind {
    match column {
        "kind" | "origin" | "destination" | "status" | "entered_clock" | "left_clock" => Kind::Str,
        "id" | "lane_changes" | "max_platoon" | "max_platoon_tg2" => Kind::U64,
        "measured" => Kind::Bool,
        _ => Kind::F64,
    }
}

/// A CSV table's bytes as Parquet bytes.
pub fn csv_to_parquet(csv: &[u8], kind: &dyn Fn(&str) -> Kind) -> Result<Vec<u8>, Error> {
    let table = from_csv(csv, kind).map_err(|e| Error::Other(e.to_string()))?;
    platoonsim_columnar::parquet_bytes(&table).map_err(|e| Error::Other(e.to_string()))
}

/// The trajectory samples as a table with the columns of `trajectories.csv` (lane counted
/// from 1; `regime` null where the CSV cell is empty).
fn trajectories_table(rows: &[TrajectoryPoint]) -> Table {
    let mut t = Table::default();
    t.push(
        "t_s",
        Values::F64(rows.iter().map(|r| Some(r.t_s)).collect()),
    );
    t.push("id", Values::U64(rows.iter().map(|r| Some(r.id)).collect()));
    t.push(
        "kind",
        Values::Str(
            rows.iter()
                .map(|r| Some(r.kind.as_str().to_string()))
                .collect(),
        ),
    );
    t.push(
        "lane",
        Values::U64(rows.iter().map(|r| Some(u64::from(r.lane) + 1)).collect()),
    );
    t.push(
        "x_m",
        Values::F64(rows.iter().map(|r| Some(r.x_m)).collect()),
    );
    t.push(
        "v_mps",
        Values::F64(rows.iter().map(|r| Some(r.v_mps)).collect()),
    );
    t.push(
        "a_mps2",
        Values::F64(rows.iter().map(|r| Some(r.a_mps2)).collect()),
    );
    t.push(
        "mode",
        Values::Str(
            rows.iter()
                .map(|r| Some(r.mode.as_str().to_string()))
                .collect(),
        ),
    );
    t.push(
        "platoon_pos",
        Values::U64(
            rows.iter()
                .map(|r| Some(u64::from(r.platoon_pos)))
                .collect(),
        ),
    );
    // Null where the CSV cell is empty: a vehicle that is not an automated CAV.
    t.push(
        "regime",
        Values::Str(
            rows.iter()
                .map(|r| r.regime.map(|m| m.as_str().to_string()))
                .collect(),
        ),
    );
    t
}

/// Write `trajectories.parquet` atomically, a row group at a time (a 4-hour corridor run
/// has tens of millions of samples).
pub fn write_trajectories_parquet(path: &Path, rows: &[TrajectoryPoint]) -> Result<(), Error> {
    write_atomic_file(path, |f| {
        let mut w = Writer::new(f, &trajectories_table(&[])).map_err(std::io::Error::other)?;
        // Small batches keep the per-row text of the batch being built small; the writer
        // still makes row groups of ROW_GROUP_ROWS.
        for chunk in rows.chunks(ROW_GROUP_ROWS / 8) {
            w.write(&trajectories_table(chunk))
                .map_err(std::io::Error::other)?;
        }
        w.finish().map_err(std::io::Error::other)
    })
    .map_err(|e| Error::Other(format!("cannot write {}: {e}", path.display())))
}
