//! The run's small tables, each optional: `detectors.csv` (the 5-minute flow and speed shown
//! when hovering a detector), `trips.csv` (origin, destination and entry time of a clicked
//! vehicle) and `collisions.csv` (events marked on the road). Columns are found by header
//! name; a missing file gives an empty table.

use anyhow::{anyhow, bail, Context, Result};
use platoonsim_rundir::Lane;
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// One detector's cross-section records (`lane` = `all`), in file order.
#[derive(Debug, Serialize, Default)]
pub struct DetectorSeries {
    pub name: String,
    pub kind: String,
    pub x_m: f64,
    /// Distinct numbered lanes with records.
    pub lanes: usize,
    pub start_s: Vec<f64>,
    pub interval_s: Vec<f64>,
    pub flow_vph: Vec<f64>,
    /// `None` for an interval without vehicles.
    pub speed_kmh: Vec<Option<f64>>,
}

/// Trips of the vehicles in the replay, column by column.
#[derive(Debug, Serialize, Default)]
pub struct Trips {
    pub id: Vec<u64>,
    pub origin: Vec<String>,
    pub destination: Vec<String>,
    pub status: Vec<String>,
    pub entered_s: Vec<Option<f64>>,
    pub left_s: Vec<Option<f64>>,
}

#[derive(Debug, Serialize)]
pub struct Collision {
    pub t_s: f64,
    pub kind: String,
    pub lane: u32,
    pub x_m: f64,
    pub vehicle: String,
    pub other: String,
}

/// Reads a CSV with headers; `None` if the file does not exist.
fn open(path: &Path) -> Result<Option<(csv::StringRecord, Vec<csv::StringRecord>)>> {
    if !path.exists() {
        return Ok(None);
    }
    let file = crate::bounded::open_records(
        path,
        crate::bounded::MAX_TABLE_BYTES,
        crate::bounded::MAX_RECORD_LINE_BYTES,
    )
    .with_context(|| format!("cannot read {}", path.display()))?;
    if !ends_with_newline(path).with_context(|| format!("cannot read {}", path.display()))? {
        bail!(
            "{} is truncated (its last line has no line break): a run writes it whole; run \
             again to replace it",
            path.display()
        );
    }
    let mut r = csv::ReaderBuilder::new().from_reader(file);
    let header = r
        .headers()
        .with_context(|| format!("cannot read {}", path.display()))?
        .clone();
    let rows = r
        .records()
        .collect::<Result<Vec<_>, _>>()
        .with_context(|| format!("cannot read {}", path.display()))?;
    Ok(Some((header, rows)))
}

/// Whether the file is empty or its last byte is a line break (every table a run writes is).
fn ends_with_newline(path: &Path) -> std::io::Result<bool> {
    use std::io::{Read, Seek, SeekFrom};
    let mut f = std::fs::File::open(path)?;
    if f.metadata()?.len() == 0 {
        return Ok(true);
    }
    f.seek(SeekFrom::End(-1))?;
    let mut last = [0u8];
    f.read_exact(&mut last)?;
    Ok(last[0] == b'\n')
}

/// Column lookups with errors that name the file, line and column.
struct Cols<'a> {
    path: &'a Path,
    header: &'a csv::StringRecord,
}

impl Cols<'_> {
    fn find(&self, name: &str) -> Result<usize> {
        self.header
            .iter()
            .position(|h| h == name)
            .ok_or_else(|| anyhow!("{}: column {name} is missing", self.path.display()))
    }

    fn num(&self, row: &csv::StringRecord, line: usize, c: usize) -> Result<Option<f64>> {
        let s = row.get(c).unwrap_or("");
        if s.is_empty() {
            return Ok(None);
        }
        s.parse::<f64>().map(Some).map_err(|_| {
            anyhow!(
                "{} line {line}, column {}: '{s}' is not a number",
                self.path.display(),
                self.header.get(c).unwrap_or("?")
            )
        })
    }
}

pub fn detectors(path: &Path) -> Result<Vec<DetectorSeries>> {
    let Some((header, rows)) = open(path)? else {
        return Ok(vec![]);
    };
    let c = Cols {
        path,
        header: &header,
    };
    let (name, kind, pos, lane) = (
        c.find("detector")?,
        c.find("kind")?,
        c.find("position_m")?,
        c.find("lane")?,
    );
    let (start, len, flow, speed) = (
        c.find("interval_start_s")?,
        c.find("interval_s")?,
        c.find("flow_vph")?,
        c.find("speed_kmh")?,
    );
    let mut out: Vec<DetectorSeries> = vec![];
    let mut index: BTreeMap<String, usize> = BTreeMap::new();
    let mut lanes: Vec<BTreeSet<String>> = vec![];
    for (i, row) in rows.iter().enumerate() {
        let line = i + 2;
        let n = row.get(name).unwrap_or("").to_string();
        let k = *index.entry(n.clone()).or_insert_with(|| {
            out.push(DetectorSeries {
                name: n.clone(),
                kind: row.get(kind).unwrap_or("").to_string(),
                x_m: 0.0,
                ..Default::default()
            });
            lanes.push(BTreeSet::new());
            out.len() - 1
        });
        let d = &mut out[k];
        d.x_m = c.num(row, line, pos)?.unwrap_or(d.x_m);
        let l = row.get(lane).unwrap_or("");
        match l.parse::<Lane>() {
            Ok(Lane::All) => {}
            Ok(Lane::Index(_)) => {
                lanes[k].insert(l.to_string());
                continue;
            }
            Err(e) => bail!("{} line {line}, column lane: {e}", path.display()),
        }
        d.start_s.push(c.num(row, line, start)?.unwrap_or(0.0));
        d.interval_s.push(c.num(row, line, len)?.unwrap_or(0.0));
        d.flow_vph.push(c.num(row, line, flow)?.unwrap_or(0.0));
        d.speed_kmh.push(c.num(row, line, speed)?);
    }
    for (d, l) in out.iter_mut().zip(&lanes) {
        d.lanes = l.len();
    }
    Ok(out)
}

/// The trips of the vehicles in `ids` (sorted ascending).
pub fn trips(path: &Path, ids: &[u64]) -> Result<Trips> {
    let mut t = Trips::default();
    let Some((header, rows)) = open(path)? else {
        return Ok(t);
    };
    let c = Cols {
        path,
        header: &header,
    };
    let id = c.find("id")?;
    let opt = |n: &str| header.iter().position(|h| h == n);
    let (origin, dest, status) = (opt("origin"), opt("destination"), opt("status"));
    let (entered, left) = (opt("entered_s"), opt("left_s"));
    let text = |row: &csv::StringRecord, col: Option<usize>| {
        col.and_then(|c| row.get(c)).unwrap_or("").to_string()
    };
    for (i, row) in rows.iter().enumerate() {
        let line = i + 2;
        let s = row.get(id).unwrap_or("");
        let v: u64 = s.parse().map_err(|_| {
            anyhow!(
                "{} line {line}, column id: '{s}' is not a vehicle id",
                path.display()
            )
        })?;
        if ids.binary_search(&v).is_err() {
            continue;
        }
        t.id.push(v);
        t.origin.push(text(row, origin));
        t.destination.push(text(row, dest));
        t.status.push(text(row, status));
        t.entered_s.push(match entered {
            Some(col) => c.num(row, line, col)?,
            None => None,
        });
        t.left_s.push(match left {
            Some(col) => c.num(row, line, col)?,
            None => None,
        });
    }
    Ok(t)
}

pub fn collisions(path: &Path) -> Result<Vec<Collision>> {
    let Some((header, rows)) = open(path)? else {
        return Ok(vec![]);
    };
    let c = Cols {
        path,
        header: &header,
    };
    let (t, kind, lane, x) = (
        c.find("t_s")?,
        c.find("kind")?,
        c.find("lane")?,
        c.find("x_m")?,
    );
    let (vehicle, other) = (c.find("vehicle")?, c.find("other")?);
    let mut out = vec![];
    for (i, row) in rows.iter().enumerate() {
        let line = i + 2;
        out.push(Collision {
            t_s: c.num(row, line, t)?.unwrap_or(0.0),
            kind: row.get(kind).unwrap_or("").to_string(),
            lane: c.num(row, line, lane)?.unwrap_or(1.0) as u32,
            x_m: c.num(row, line, x)?.unwrap_or(0.0),
            vehicle: row.get(vehicle).unwrap_or("").to_string(),
            other: row.get(other).unwrap_or("").to_string(),
        });
    }
    Ok(out)
}
