//! The replay viewer: [`build`] reads a run directory (`trajectories.csv` and `road.json`, with
//! `detectors.csv`, `trips.csv` and `collisions.csv` where present) and returns one
//! self-contained HTML page that replays the run on a Canvas 2D (no network access, no server).
//!
//! The page is the files under `assets/` (embedded at compile time) with two blocks filled
//! in: a JSON block (`page.rs`) describing the road, the frames and the tables, and a base64 block
//! with the vehicle samples packed into typed arrays and gzip-compressed (`tracks.rs`, `pack.rs`).
//! This crate depends on no engine crate (the file names and the road's type come from
//! `platoonsim-rundir`, which depends on none): it reads the tables by their header names, so a
//! file with extra columns still works, and draws the road the engine wrote (`road.json`), so
//! what it shows is what the run wrote.

mod bounded;
mod pack;
mod page;
mod road;
mod tables;
mod tracks;

use anyhow::{bail, Context, Result};
use platoonsim_rundir::{COLLISIONS, DETECTORS, TRAJECTORIES, TRIPS};
use std::path::Path;

/// A built page and what went into it.
pub struct View {
    pub html: String,
    /// Vehicle samples (rows of `trajectories.csv`).
    pub rows: usize,
    /// Distinct vehicle ids.
    pub vehicles: usize,
    /// Frames (sample times) of the replay.
    pub frames: usize,
    /// Whether platoon membership comes from the `platoon_pos` column (else it is inferred).
    pub platoon_column: bool,
}

/// Build the page for the run in `dir`. Errors name the file and, for a bad row, the line and
/// the column.
pub fn build(dir: &Path) -> Result<View> {
    let traj = TRAJECTORIES.csv_in(dir);
    if !traj.exists() {
        bail!(
            "{} not found: the viewer replays a run's trajectories; make them with `platoonsim \
             run ... --trajectories PERIOD_S --out {}`",
            traj.display(),
            dir.display()
        );
    }
    let road = road::read(dir)?;

    let file = bounded::open_records(
        &traj,
        bounded::MAX_RECORD_FILE_BYTES,
        bounded::MAX_RECORD_LINE_BYTES,
    )
    .with_context(|| format!("cannot read {}", traj.display()))?;
    let packed = tracks::read_and_pack(std::io::BufReader::new(file), &traj, &road)?;

    let detectors = tables::detectors(&DETECTORS.csv_in(dir))?;
    let trips = tables::trips(&TRIPS.csv_in(dir), &packed.ids)?;
    let collisions = tables::collisions(&dir.join(COLLISIONS))?;

    let meta = page::Meta {
        road: &road,
        packed: &packed,
        detectors: &detectors,
        trips: &trips,
        collisions: &collisions,
    };
    let html = page::render(&meta)?;
    Ok(View {
        html,
        rows: packed.rows,
        vehicles: packed.ids.len(),
        frames: packed.frames.len(),
        platoon_column: packed.platoon_column,
    })
}
