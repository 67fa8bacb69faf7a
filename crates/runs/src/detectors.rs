//! Detector records kept beside a run file: `<runs>/<key>.detectors.csv`, in the format of
//! `platoonsim run`'s `detectors.csv` (same columns, same number text), restricted to a
//! [`Scope`]. The run file names the scope, the row count and the FNV-1a hash of the CSV's
//! bytes, so a detector file is used only with the run file that was written with it.

use crate::hash::fnv1a64;
use platoonsim_sim::DetectorRecord;
use serde::{Deserialize, Serialize};

/// Which detector records a run keeps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Scope {
    /// None (the summary only).
    #[default]
    None,
    /// The cross-section rows (`lane == "all"`) of every detector: speed contours, the
    /// bottleneck criterion.
    CrossSection,
    /// Every row (each lane too): the lane-by-lane figures.
    All,
}

impl Scope {
    /// Whether records kept with this scope hold everything `wanted` needs.
    pub fn covers(self, wanted: Scope) -> bool {
        self >= wanted
    }

    /// Whether a record belongs to this scope.
    pub fn keeps(self, r: &DetectorRecord) -> bool {
        match self {
            Scope::None => false,
            Scope::CrossSection => Lane::is_all(&r.lane),
            Scope::All => true,
        }
    }
}

/// What the run file says about its detector file.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct DetectorsRef {
    pub scope: Scope,
    pub rows: usize,
    /// FNV-1a 64 of the CSV file's bytes, 16 hex digits.
    pub hash: String,
}

impl DetectorsRef {
    /// The reference of a CSV file's bytes.
    pub fn of(scope: Scope, rows: usize, bytes: &[u8]) -> DetectorsRef {
        DetectorsRef {
            scope,
            rows,
            hash: format!("{:016x}", fnv1a64(bytes)),
        }
    }

    /// Whether `bytes` are the file this reference names.
    pub fn matches(&self, bytes: &[u8]) -> bool {
        self.hash == format!("{:016x}", fnv1a64(bytes))
    }
}

// The columns, in order (those of `platoonsim run`'s `detectors.csv`), and where the
// optional `clock` column goes: right after `interval_start_s`.
use platoonsim_rundir::{
    DetectorKind, Lane, DETECTOR_CLOCK_AT as CLOCK_AT, DETECTOR_COLUMNS as COLUMNS,
};

/// Detector records that cannot be written or read as CSV; the message says where and why.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct DetectorCsvError(pub String);

/// The records of `scope`, as CSV bytes, with how many rows were written. With `clock_start_s`
/// (the clock time of t = 0, s after midnight: `run.clock_start`) a `clock` column follows
/// `interval_start_s` with the interval's start as "HH:MM:SS"; without it the columns are
/// exactly [`COLUMNS`] (the runner's kept files, which [`from_csv`] reads, never have it).
pub fn to_csv(
    records: &[DetectorRecord],
    scope: Scope,
    clock_start_s: Option<u32>,
) -> Result<(Vec<u8>, usize), DetectorCsvError> {
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    let err = |e: csv::Error| DetectorCsvError(format!("cannot encode detector records: {e}"));
    let mut header = COLUMNS.to_vec();
    if clock_start_s.is_some() {
        header.insert(CLOCK_AT, "clock");
    }
    w.write_record(&header).map_err(err)?;
    let mut rows = 0;
    for r in records.iter().filter(|r| scope.keeps(r)) {
        let mut row = vec![
            r.detector.clone(),
            r.kind.clone(),
            format!("{}", r.position_m),
            r.lane.clone(),
            format!("{}", r.interval_start_s),
            format!("{}", r.interval_s),
            r.count.to_string(),
            r.cav_count.to_string(),
            format!("{}", r.flow_vph),
            r.speed_kmh.map(|v| format!("{v}")).unwrap_or_default(),
            format!("{}", r.occupancy),
        ];
        if let Some(start) = clock_start_s {
            row.insert(
                CLOCK_AT,
                platoonsim_scenario::clock::clock_at(start, r.interval_start_s),
            );
        }
        w.write_record(&row).map_err(err)?;
        rows += 1;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| DetectorCsvError(format!("cannot encode detector records: {e}")))?;
    Ok((bytes, rows))
}

/// Read records written by [`to_csv`] (or `platoonsim run`'s `detectors.csv`).
pub fn from_csv(bytes: &[u8]) -> Result<Vec<DetectorRecord>, DetectorCsvError> {
    from_csv_text(bytes).map_err(DetectorCsvError)
}

fn from_csv_text(bytes: &[u8]) -> Result<Vec<DetectorRecord>, String> {
    let mut r = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_reader(bytes);
    let header: Vec<String> = r
        .headers()
        .map_err(|e| e.to_string())?
        .iter()
        .map(String::from)
        .collect();
    // `platoonsim run` writes a `clock` column when the scenario sets `run.clock_start`: a
    // label of the outputs, dropped here (the clock follows from interval_start_s).
    let with_clock = header.len() == COLUMNS.len() + 1 && header[CLOCK_AT] == "clock" && {
        let mut h = header.clone();
        h.remove(CLOCK_AT);
        h == COLUMNS
    };
    if header != COLUMNS && !with_clock {
        return Err(format!(
            "unexpected columns {header:?}; expected {COLUMNS:?} (a `clock` column after interval_start_s allowed)"
        ));
    }
    let mut out = Vec::new();
    for (i, rec) in r.records().enumerate() {
        let mut rec = rec.map_err(|e| e.to_string())?;
        if with_clock {
            rec = rec
                .iter()
                .enumerate()
                .filter(|&(k, _)| k != CLOCK_AT)
                .map(|(_, v)| v)
                .collect();
        }
        let row = i + 2;
        let f = |k: usize| -> Result<f64, String> {
            rec[k]
                .parse::<f64>()
                .map_err(|_| format!("line {row}: {} is not a number", COLUMNS[k]))
        };
        let u = |k: usize| -> Result<u64, String> {
            rec[k]
                .parse::<u64>()
                .map_err(|_| format!("line {row}: {} is not a count", COLUMNS[k]))
        };
        // The word cells are typed: a file that is not the writer's is refused here, not
        // matched by text later.
        let kind: DetectorKind = rec[1]
            .parse()
            .map_err(|e| format!("line {row}: kind: {e}"))?;
        let lane: Lane = rec[3]
            .parse()
            .map_err(|e| format!("line {row}: lane: {e}"))?;
        out.push(DetectorRecord {
            detector: rec[0].to_string(),
            kind: kind.to_string(),
            position_m: f(2)?,
            lane: lane.to_string(),
            interval_start_s: f(4)?,
            interval_s: f(5)?,
            count: u(6)?,
            cav_count: u(7)?,
            flow_vph: f(8)?,
            speed_kmh: if rec[9].is_empty() { None } else { Some(f(9)?) },
            occupancy: f(10)?,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(det: &str, lane: &str, t: f64, speed: Option<f64>) -> DetectorRecord {
        DetectorRecord {
            detector: det.into(),
            kind: "mainline".into(),
            position_m: 100.5,
            lane: lane.into(),
            interval_start_s: t,
            interval_s: 300.0,
            count: 10,
            cav_count: 4,
            flow_vph: 120.0,
            speed_kmh: speed,
            occupancy: 0.125,
        }
    }

    #[test]
    fn csv_round_trip_by_scope() {
        let recs = vec![
            record("A", "1", 0.0, Some(101.25)),
            record("A", "all", 0.0, None),
            record("A", "2", 300.0, Some(0.1)),
        ];
        let (all, n) = to_csv(&recs, Scope::All, None).unwrap();
        assert_eq!(n, 3);
        assert_eq!(from_csv(&all).unwrap(), recs);
        let text = String::from_utf8(all.clone()).unwrap();
        assert!(text.starts_with("detector,kind,position_m,lane,interval_start_s,"));
        assert!(text.contains("A,mainline,100.5,all,0,300,10,4,120,,0.125\n"));
        let (cross, n) = to_csv(&recs, Scope::CrossSection, None).unwrap();
        assert_eq!(n, 1);
        assert_eq!(from_csv(&cross).unwrap(), vec![recs[1].clone()]);
        assert_eq!(to_csv(&recs, Scope::None, None).unwrap().1, 0);

        let r = DetectorsRef::of(Scope::All, 3, &all);
        assert!(r.matches(&all) && !r.matches(&cross));
        assert!(Scope::All.covers(Scope::CrossSection));
        assert!(!Scope::CrossSection.covers(Scope::All));
        assert!(Scope::CrossSection.covers(Scope::None));
        assert!(from_csv(b"a,b\n1,2\n").is_err());
        assert!(from_csv(&all[..all.len() - 8]).is_err());
    }

    #[test]
    fn the_word_cells_are_read_typed() {
        // Every lane and kind the writer uses reads back; another word is refused at its line
        // instead of being matched by text (or silently skipped) by a reader later.
        let mut recs = vec![record("A", "all", 0.0, None), record("A", "12", 0.0, None)];
        for (i, kind) in ["on-ramp", "off-ramp"].into_iter().enumerate() {
            recs.push(DetectorRecord {
                kind: kind.into(),
                ..record("R", &(i + 1).to_string(), 0.0, None)
            });
        }
        let (bytes, _) = to_csv(&recs, Scope::All, None).unwrap();
        assert_eq!(from_csv(&bytes).unwrap(), recs);
        let text = String::from_utf8(bytes).unwrap();
        let e = from_csv(text.replacen(",all,", ",All,", 1).as_bytes()).unwrap_err();
        assert!(
            e.0.starts_with("line 2: lane: 'All' is not a lane"),
            "{}",
            e.0
        );
        let e = from_csv(text.replacen(",12,", ",0,", 1).as_bytes()).unwrap_err();
        assert!(
            e.0.starts_with("line 3: lane: '0' is not a lane"),
            "{}",
            e.0
        );
        let e = from_csv(text.replacen("on-ramp", "onramp", 1).as_bytes()).unwrap_err();
        assert!(
            e.0.starts_with("line 4: kind: 'onramp' is not a detector kind"),
            "{}",
            e.0
        );
    }

    #[test]
    fn a_clock_start_adds_the_clock_column_after_the_interval_start() {
        let recs = vec![
            record("A", "1", 0.0, Some(101.25)),
            record("A", "all", 300.0, None),
        ];
        // 05:00 is 18,000 s after midnight.
        let (bytes, n) = to_csv(&recs, Scope::All, Some(18_000)).unwrap();
        assert_eq!(n, 2);
        assert_eq!(
            String::from_utf8(bytes).unwrap(),
            "detector,kind,position_m,lane,interval_start_s,clock,interval_s,count,cav_count,\
             flow_vph,speed_kmh,occupancy\n\
             A,mainline,100.5,1,0,05:00:00,300,10,4,120,101.25,0.125\n\
             A,mainline,100.5,all,300,05:05:00,300,10,4,120,,0.125\n"
        );
    }

    #[test]
    fn a_run_file_with_the_clock_column_reads_back_the_same_records() {
        let recs = vec![
            record("A", "1", 0.0, Some(101.25)),
            record("A", "all", 300.0, None),
        ];
        let (bytes, _) = to_csv(&recs, Scope::All, Some(18_000)).unwrap();
        assert_eq!(from_csv(&bytes).unwrap(), recs);
        // A `clock` column anywhere else is not the run's layout.
        let moved = String::from_utf8(bytes).unwrap().replacen(
            "interval_start_s,clock",
            "clock,interval_start_s",
            1,
        );
        assert!(from_csv(moved.as_bytes()).is_err());
    }
}
