//! `trajectories.csv` into packed columns. A track is one vehicle's run of samples in
//! consecutive frames; its rows are stored track after track, so that the position can be
//! coded as second differences (small numbers that compress well) and everything categorical
//! (lane, mode, platoon position, regime) as one byte per row (long runs of one value).
//!
//! Quantization: position to `x_res_m` (0.05 m unless a sample step is too long for 16-bit
//! differences), speed to 0.5 km/h (0 to 127.5 km/h), acceleration to 0.1 m/s² (±12.7).

use crate::pack::Blob;
use crate::road::Road;
use anyhow::{anyhow, bail, Result};
use platoonsim_rundir::trajectory::{read_samples, Bad, Stop};
use platoonsim_rundir::TRAJECTORIES;
use std::collections::HashMap;
use std::io::Read;
use std::path::Path;

/// Code of a missing category (no such column, or an empty cell).
pub const NONE: u8 = 255;

/// Speed unit of the packed speeds (km/h).
pub const SPEED_UNIT_KMH: f64 = 0.5;
/// Acceleration unit of the packed accelerations (m/s²).
pub const ACCEL_UNIT: f64 = 0.1;

/// The packed samples and what the page needs to unpack them.
pub struct Packed {
    pub blob: Blob,
    pub rows: usize,
    pub tracks: usize,
    /// Distinct vehicle ids, ascending.
    pub ids: Vec<u64>,
    /// Sample times (s), ascending.
    pub frames: Vec<f64>,
    pub x_res_m: f64,
    pub kinds: Vec<String>,
    pub modes: Vec<String>,
    pub regimes: Vec<String>,
    pub platoon_column: bool,
    pub accel_column: bool,
    /// Speed contour: `nt` x `nx` cells (time-major), mean speed in `SPEED_UNIT_KMH`, `NONE`
    /// where no sample fell.
    pub contour: Contour,
}

pub struct Contour {
    pub nt: usize,
    pub nx: usize,
    pub t0_s: f64,
    pub t1_s: f64,
    pub x0_m: f64,
    pub x1_m: f64,
}

struct Row {
    t: f64,
    id: u64,
    kind: u8,
    lane: u8,
    x: f64,
    v: f64,
    a: f64,
    mode: u8,
    pos: u8,
    regime: u8,
}

/// Interns category strings as byte codes (at most 254 distinct values).
#[derive(Default)]
struct Codes {
    names: Vec<String>,
    index: HashMap<String, u8>,
}

impl Codes {
    fn code(&mut self, s: &str, column: &str) -> Result<u8> {
        if s.is_empty() {
            return Ok(NONE);
        }
        if let Some(&c) = self.index.get(s) {
            return Ok(c);
        }
        if self.names.len() >= NONE as usize {
            bail!("column {column} has more than 254 distinct values");
        }
        let c = self.names.len() as u8;
        self.names.push(s.to_string());
        self.index.insert(s.to_string(), c);
        Ok(c)
    }
}

pub fn read_and_pack<R: Read>(input: R, path: &Path, road: &Road) -> Result<Packed> {
    let name = path.display().to_string();
    let (mut kinds, mut modes, mut regimes) =
        (Codes::default(), Codes::default(), Codes::default());
    let mut rows = Vec::new();
    // The one reader of the file (`platoonsim_rundir::trajectory`, shared with time-space);
    // what is checked here is what the viewer adds: the road's lanes, at most 254 codes.
    let header = read_samples(input, &name, |s| {
        if s.lane > road.lanes || s.lane >= u32::from(NONE) {
            return Err(Bad {
                column: "lane",
                what: format!(
                    "a lane of the road in {json} (1 to {}): {} and {json} are not from the \
                     same run",
                    road.lanes,
                    TRAJECTORIES.csv,
                    json = platoonsim_rundir::ROAD_JSON,
                ),
            }
            .into());
        }
        let code = |codes: &mut Codes, cell: Option<&str>, column: &str| match cell {
            Some(c) => codes
                .code(c, column)
                .map_err(|e| Stop::Other(format!("{name}: {e}"))),
            None => Ok(NONE),
        };
        rows.push(Row {
            t: s.t_s,
            id: s.id,
            kind: code(&mut kinds, Some(s.kind), "kind")?,
            lane: s.lane as u8,
            x: s.x_m,
            v: s.v_mps,
            a: s.a_mps2.unwrap_or(0.0),
            mode: code(&mut modes, s.mode, "mode")?,
            pos: s.platoon_pos.map_or(0, |p| p.clamp(1, 254) as u8),
            regime: code(&mut regimes, s.regime, "regime")?,
        });
        Ok(())
    })
    .map_err(anyhow::Error::msg)?;
    if rows.is_empty() {
        bail!("{name} has no samples (was the trajectory window or x range outside the run?)");
    }
    let frames = frame_times(&rows);
    pack(
        rows,
        frames,
        road,
        kinds,
        modes,
        regimes,
        header.iter().any(|h| h == "platoon_pos"),
        header.iter().any(|h| h == "a_mps2"),
        path,
    )
}

/// The frame times: a regular grid from the first to the last sample time when every time lies
/// on one (the usual case, so that a moment without vehicles is still a frame), else the
/// distinct times.
fn frame_times(rows: &[Row]) -> Vec<f64> {
    let mut ts: Vec<f64> = rows.iter().map(|r| r.t).collect();
    ts.sort_by(f64::total_cmp);
    ts.dedup();
    let step = ts
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    if ts.len() < 2 || !step.is_finite() || step <= 0.0 {
        return ts;
    }
    let t0 = ts[0];
    // The grid's length in floating point first: times far apart on a fine step (found by
    // fuzzing: 0, 1, 2e19) would overflow the count.
    let span = ((ts[ts.len() - 1] - t0) / step).round();
    if !(span.is_finite() && span + 1.0 <= 4.0 * ts.len() as f64) {
        return ts;
    }
    let n = span as usize + 1;
    let on_grid = ts.iter().all(|&t| {
        let k = ((t - t0) / step).round();
        (t0 + k * step - t).abs() <= 1e-6 * step.max(1.0)
    });
    if on_grid {
        // Rounded to the microsecond, so that 0.1-s steps print as the CSV's times.
        (0..n)
            .map(|k| ((t0 + k as f64 * step) * 1e6).round() / 1e6)
            .collect()
    } else {
        ts
    }
}

fn frame_of(frames: &[f64], t: f64) -> usize {
    let i = frames.partition_point(|&f| f < t - 1e-7);
    if i < frames.len() && (frames[i] - t).abs() <= 1e-6 {
        i
    } else if i > 0 && (frames[i - 1] - t).abs() <= 1e-6 {
        i - 1
    } else {
        // Every sample time is a frame (frame_times), within rounding.
        i.min(frames.len() - 1)
    }
}

#[allow(clippy::too_many_arguments)]
fn pack(
    mut rows: Vec<Row>,
    frames: Vec<f64>,
    road: &Road,
    kinds: Codes,
    modes: Codes,
    regimes: Codes,
    platoon_column: bool,
    accel_column: bool,
    path: &Path,
) -> Result<Packed> {
    let mut frame: Vec<u32> = rows.iter().map(|r| frame_of(&frames, r.t) as u32).collect();
    let mut order: Vec<usize> = (0..rows.len()).collect();
    order.sort_by_key(|&i| (rows[i].id, frame[i]));
    // Reorder rows and frames into track order.
    let mut sorted = Vec::with_capacity(rows.len());
    let mut sorted_frame = Vec::with_capacity(rows.len());
    {
        let mut taken: Vec<Option<Row>> = rows.drain(..).map(Some).collect();
        for &i in &order {
            sorted.push(taken[i].take().expect("each row once"));
            sorted_frame.push(frame[i]);
        }
    }
    let rows = sorted;
    frame = sorted_frame;

    // Tracks: a new one at a new id or a gap in the frames.
    let mut starts = Vec::new();
    for i in 0..rows.len() {
        if i > 0 && rows[i].id == rows[i - 1].id {
            if frame[i] == frame[i - 1] {
                bail!(
                    "{}: vehicle {} has two samples at t = {} s",
                    path.display(),
                    rows[i].id,
                    rows[i].t
                );
            }
            if frame[i] == frame[i - 1] + 1 {
                continue;
            }
        }
        starts.push(i);
    }
    let n_tracks = starts.len();
    let ends: Vec<usize> = starts.iter().skip(1).copied().chain([rows.len()]).collect();

    // Position resolution: second differences must fit in 16 bits.
    let mut max_step = 0.0f64;
    for (&s, &e) in starts.iter().zip(&ends) {
        for k in s + 1..e {
            max_step = max_step.max((rows[k].x - rows[k - 1].x).abs());
        }
    }
    let x_res = (max_step / 15_000.0).max(0.05);
    let q = |x: f64| (x / x_res).round() as i64;

    let mut track_id = Vec::with_capacity(n_tracks);
    let mut track_first = Vec::with_capacity(n_tracks);
    let mut track_len = Vec::with_capacity(n_tracks);
    let mut track_x0 = Vec::with_capacity(n_tracks);
    let mut track_kind = Vec::with_capacity(n_tracks);
    let n = rows.len();
    let (mut ddx_lo, mut ddx_hi) = (vec![0u8; n], vec![0u8; n]);
    let mut v = vec![0u8; n];
    let mut a = vec![0u8; n];
    let mut lane = vec![0u8; n];
    let mut mode = vec![0u8; n];
    let mut pos = vec![0u8; n];
    let mut regime = vec![0u8; n];
    for (&s, &e) in starts.iter().zip(&ends) {
        let id = u32::try_from(rows[s].id).map_err(|_| {
            anyhow!(
                "{}: vehicle id {} is above 2^32 - 1",
                path.display(),
                rows[s].id
            )
        })?;
        track_id.push(id);
        track_first.push(frame[s]);
        track_len.push((e - s) as u32);
        let x0 = i32::try_from(q(rows[s].x)).map_err(|_| {
            anyhow!(
                "{}: position {} m is out of range",
                path.display(),
                rows[s].x
            )
        })?;
        track_x0.push(x0);
        track_kind.push(rows[s].kind);
        let mut prev_dq = 0i64;
        for k in s..e {
            let dq = if k == s {
                0
            } else {
                q(rows[k].x) - q(rows[k - 1].x)
            };
            let dd =
                i16::try_from(dq - prev_dq).expect("x_res keeps second differences in 16 bits");
            prev_dq = dq;
            let [lo, hi] = dd.to_le_bytes();
            ddx_lo[k] = lo;
            ddx_hi[k] = hi;
            let r = &rows[k];
            v[k] = (r.v.max(0.0) * 3.6 / SPEED_UNIT_KMH).round().min(254.0) as u8;
            a[k] = ((r.a / ACCEL_UNIT).round().clamp(-127.0, 127.0) as i8) as u8;
            lane[k] = r.lane;
            mode[k] = r.mode;
            pos[k] = r.pos;
            regime[k] = r.regime;
        }
    }

    let contour = Contour {
        nt: frames.len().clamp(1, 240),
        nx: (((road.end_m - road.start_m) / 50.0).ceil() as usize).clamp(1, 240),
        t0_s: frames[0],
        t1_s: *frames.last().expect("non-empty"),
        x0_m: road.start_m,
        x1_m: road.end_m,
    };
    let cells = contour_cells(&rows, &contour);

    let mut ids: Vec<u64> = rows.iter().map(|r| r.id).collect();
    ids.dedup();

    // The order the page reads the sections in (assets/viewer.js, `unpack`): 4-byte columns
    // first so that each typed array starts aligned.
    let mut blob = Blob::default();
    blob.u32s("track_id", &track_id);
    blob.u32s("track_first", &track_first);
    blob.u32s("track_len", &track_len);
    blob.i32s("track_x0", &track_x0);
    blob.bytes("track_kind", &track_kind);
    blob.bytes("ddx_lo", &ddx_lo);
    blob.bytes("ddx_hi", &ddx_hi);
    blob.bytes("v", &v);
    blob.bytes("a", &a);
    blob.bytes("lane", &lane);
    blob.bytes("mode", &mode);
    blob.bytes("pos", &pos);
    blob.bytes("regime", &regime);
    blob.bytes("contour", &cells);

    Ok(Packed {
        blob,
        rows: n,
        tracks: n_tracks,
        ids,
        frames,
        x_res_m: x_res,
        kinds: kinds.names,
        modes: modes.names,
        regimes: regimes.names,
        platoon_column,
        accel_column,
        contour,
    })
}

/// Mean speed of the samples in each (time, position) cell.
fn contour_cells(rows: &[Row], c: &Contour) -> Vec<u8> {
    let mut sum = vec![0.0f64; c.nt * c.nx];
    let mut count = vec![0u32; c.nt * c.nx];
    let span_t = (c.t1_s - c.t0_s).max(1e-9);
    let span_x = (c.x1_m - c.x0_m).max(1e-9);
    for r in rows {
        let it = (((r.t - c.t0_s) / span_t * c.nt as f64) as usize).min(c.nt - 1);
        let fx = (r.x - c.x0_m) / span_x;
        if !(0.0..=1.0).contains(&fx) {
            continue;
        }
        let ix = ((fx * c.nx as f64) as usize).min(c.nx - 1);
        sum[it * c.nx + ix] += r.v * 3.6;
        count[it * c.nx + ix] += 1;
    }
    sum.iter()
        .zip(&count)
        .map(|(&s, &n)| {
            if n == 0 {
                NONE
            } else {
                (s / n as f64 / SPEED_UNIT_KMH).round().min(254.0) as u8
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows_of(csv: &str) -> Result<Packed> {
        let road = crate::road::plain(2, 1000.0);
        read_and_pack(csv.as_bytes(), Path::new("trajectories.csv"), &road)
    }

    fn row(t: f64) -> Row {
        Row {
            t,
            id: 0,
            kind: 0,
            lane: 1,
            x: 0.0,
            v: 0.0,
            a: 0.0,
            mode: NONE,
            pos: 0,
            regime: NONE,
        }
    }

    #[test]
    fn frame_times_of_far_apart_samples_are_the_samples() {
        // Found by fuzzing (issue 35): a grid of 2e19 steps overflowed its count (a panic with
        // overflow checks, an empty frame list without).
        let rows: Vec<Row> = [0.0, 1.0, 2e19].into_iter().map(row).collect();
        assert_eq!(frame_times(&rows), vec![0.0, 1.0, 2e19]);
        let rows: Vec<Row> = [0.0, 0.5, 1.5].into_iter().map(row).collect();
        assert_eq!(frame_times(&rows), vec![0.0, 0.5, 1.0, 1.5]);
    }

    #[test]
    fn tracks_split_at_gaps_and_extra_columns_are_ignored() {
        let csv = "t_s,id,kind,lane,x_m,v_mps,a_mps2,mode,extra\n\
                   0.5,7,cav,1,10,30,0.5,cf-auto,x\n\
                   0.5,8,human,2,20,20,-1,cf,x\n\
                   1,7,cav,2,25,30,0,cf-auto,x\n\
                   2,7,cav,2,55,30,0,cf-auto,x\n";
        let p = rows_of(csv).unwrap();
        assert_eq!(p.rows, 4);
        assert_eq!(p.frames, vec![0.5, 1.0, 1.5, 2.0]);
        // Vehicle 7 misses t = 1.5: two tracks; vehicle 8 one.
        assert_eq!(p.tracks, 3);
        assert_eq!(p.ids, vec![7, 8]);
        assert!(!p.platoon_column);
        assert_eq!(p.kinds, vec!["cav", "human"]);
    }

    #[test]
    fn a_bad_cell_names_line_and_column() {
        let csv = "t_s,id,kind,lane,x_m,v_mps\n0,1,cav,1,10,30\n0.5,1,cav,0,20,30\n";
        let e = rows_of(csv).err().unwrap().to_string();
        assert!(e.contains("line 3, column lane: '0'"), "{e}");
        let e = rows_of("t_s,id,kind,x_m,v_mps\n")
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("column lane is missing"), "{e}");
        let e = rows_of("t_s,id,kind,lane,x_m,v_mps\n0,1,cav,1,1,1\n0,1,cav,1,2,1\n")
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("vehicle 1 has two samples at t = 0 s"), "{e}");
    }

    #[test]
    fn the_contour_averages_speed_per_cell() {
        let csv = "t_s,id,kind,lane,x_m,v_mps\n0,1,cav,1,10,10\n0,2,cav,1,12,20\n1,1,cav,1,20,10\n";
        let p = rows_of(csv).unwrap();
        // Two frames (nt = 2), 1000 m in 50-m cells (nx = 20): cell (0, 0) holds 36 and 72 km/h.
        assert_eq!((p.contour.nt, p.contour.nx), (2, 20));
        let cells = p.blob.section("contour").unwrap();
        assert_eq!(cells[0], (54.0 / SPEED_UNIT_KMH) as u8);
        assert_eq!(cells[1], NONE);
    }
}
