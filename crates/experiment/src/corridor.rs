//! What the SR-99 figures and the demand-scale search read from a run's detector records:
//! the speed contour (time × mainline detector), the lane-by-lane CAV flow ratio and speed
//! at one detector, and the recurrent-bottleneck criterion.
//!
//! A 5-min interval in which no vehicle crossed a detector has no speed. It counts as a
//! standing queue (speed 0) if the detector was occupied for more than half of the interval
//! ([`STANDING_OCCUPANCY`]), and as "no data" (an empty road) otherwise.

use platoonsim_sim::DetectorRecord;

/// Occupancy above which an interval without crossings is a standing queue.
pub const STANDING_OCCUPANCY: f64 = 0.5;

/// The detector just upstream of the second Florin Rd on-ramp (OR11, Florin Rd WB): the
/// paper's bottleneck "upstream of the second on-ramp at Florin Road" and its Fig. 7.
pub const FLORIN_DETECTOR: &str = "OR11-up";

/// The stretch watched for the bottleneck "downstream of Elk Grove Blvd": every mainline
/// detector from `OR1-down` (50 m downstream of the Elk Grove Blvd on-ramp) to `OR5-up`
/// (50 m upstream of the Sheldon Rd WB on-ramp), the 3-lane section before the lane add at
/// Calvine Rd where its queue forms.
pub const SOUTH_FIRST: &str = "OR1-down";
pub const SOUTH_LAST: &str = "OR5-up";

/// A record's speed for contours and the criterion: the time-mean speed, 0 for a standing
/// queue, NaN for no data.
pub fn speed(r: &DetectorRecord) -> f64 {
    match r.speed_kmh {
        Some(v) => v,
        None if r.occupancy > STANDING_OCCUPANCY => 0.0,
        None => f64::NAN,
    }
}

/// The mainline detectors of `records` (names and positions), sorted by position (upstream
/// first).
pub fn mainline_detectors(records: &[DetectorRecord]) -> Vec<(String, f64)> {
    let mut out: Vec<(String, f64)> = Vec::new();
    for r in records.iter().filter(|r| r.kind == "mainline") {
        if !out.iter().any(|(n, _)| *n == r.detector) {
            out.push((r.detector.clone(), r.position_m));
        }
    }
    out.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
    out
}

/// Interval starts (s) over all records, sorted, each once.
fn interval_starts(records: &[DetectorRecord]) -> Vec<f64> {
    let mut t: Vec<f64> = records.iter().map(|r| r.interval_start_s).collect();
    t.sort_by(f64::total_cmp);
    t.dedup();
    t
}

/// A speed contour: `speed_kmh[i][j]` at interval `i` (centre `times_min[i]`, minutes
/// from the start) and mainline detector `j` (`detectors[j]`, index j + 1 counted from
/// upstream, as in the paper's Fig. 6).
#[derive(Clone, Debug, PartialEq)]
pub struct Contour {
    pub times_min: Vec<f64>,
    pub detectors: Vec<(String, f64)>,
    pub speed_kmh: Vec<Vec<f64>>,
}

/// The cross-section speed contour of the mainline detectors.
pub fn contour(records: &[DetectorRecord]) -> Contour {
    let detectors = mainline_detectors(records);
    let cross: Vec<&DetectorRecord> = records
        .iter()
        .filter(|r| r.kind == "mainline" && r.lane == "all")
        .collect();
    let starts = interval_starts(records);
    let mut speed_kmh = vec![vec![f64::NAN; detectors.len()]; starts.len()];
    let mut times_min: Vec<f64> = starts.iter().map(|t| t / 60.0).collect();
    for r in cross {
        let i = starts.partition_point(|&t| t < r.interval_start_s);
        if let Some(j) = detectors.iter().position(|(n, _)| *n == r.detector) {
            speed_kmh[i][j] = speed(r);
            times_min[i] = (r.interval_start_s + r.interval_s / 2.0) / 60.0;
        }
    }
    Contour {
        times_min,
        detectors,
        speed_kmh,
    }
}

/// One lane at one detector over time.
#[derive(Clone, Debug, PartialEq)]
pub struct LaneSeries {
    /// "1" = the rightmost through lane at the detector.
    pub lane: String,
    /// Interval centres (min).
    pub times_min: Vec<f64>,
    /// CAVs / all vehicles that crossed in the interval (NaN if none crossed).
    pub cav_ratio: Vec<f64>,
    /// As [`speed`].
    pub speed_kmh: Vec<f64>,
}

/// The lanes of `detector`, rightmost first (numeric lane order), each over its intervals.
pub fn lane_series(records: &[DetectorRecord], detector: &str) -> Vec<LaneSeries> {
    let mine: Vec<&DetectorRecord> = records
        .iter()
        .filter(|r| r.detector == detector && r.lane != "all")
        .collect();
    let mut lanes: Vec<&str> = Vec::new();
    for r in &mine {
        if !lanes.contains(&r.lane.as_str()) {
            lanes.push(&r.lane);
        }
    }
    lanes.sort_by_key(|l| (l.parse::<u32>().unwrap_or(u32::MAX), l.to_string()));
    lanes
        .into_iter()
        .map(|lane| {
            let mut rs: Vec<&&DetectorRecord> = mine.iter().filter(|r| r.lane == lane).collect();
            rs.sort_by(|a, b| a.interval_start_s.total_cmp(&b.interval_start_s));
            LaneSeries {
                lane: lane.to_string(),
                times_min: rs
                    .iter()
                    .map(|r| (r.interval_start_s + r.interval_s / 2.0) / 60.0)
                    .collect(),
                cav_ratio: rs
                    .iter()
                    .map(|r| {
                        if r.count > 0 {
                            r.cav_count as f64 / r.count as f64
                        } else {
                            f64::NAN
                        }
                    })
                    .collect(),
                speed_kmh: rs.iter().map(|r| speed(r)).collect(),
            }
        })
        .collect()
}

/// The longest stretch of consecutive intervals (s) in which the cross-section speed at
/// `detector` is below `speed_kmh` (0 if the detector is missing). No data is not below.
pub fn longest_below_s(records: &[DetectorRecord], detector: &str, speed_kmh: f64) -> f64 {
    let mut rs: Vec<&DetectorRecord> = records
        .iter()
        .filter(|r| r.detector == detector && r.lane == "all")
        .collect();
    rs.sort_by(|a, b| a.interval_start_s.total_cmp(&b.interval_start_s));
    let (mut best, mut run) = (0.0f64, 0.0f64);
    for r in rs {
        if speed(r) < speed_kmh {
            run += r.interval_s;
            best = best.max(run);
        } else {
            run = 0.0;
        }
    }
    best
}

/// The recurrent-bottleneck criterion of the demand-scale search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Criterion {
    /// A detector is congested in an interval whose 5-min mean speed is below this (km/h).
    pub speed_kmh: f64,
    /// A bottleneck is active if a watched detector stays congested this long (min).
    pub minutes: f64,
}

/// Both bottlenecks in one run.
#[derive(Clone, Debug, PartialEq)]
pub struct Bottlenecks {
    /// Longest congested stretch at [`FLORIN_DETECTOR`] (min).
    pub florin_min: f64,
    /// Longest congested stretch at any detector from [`SOUTH_FIRST`] to [`SOUTH_LAST`]
    /// (min), and where (empty if none was congested).
    pub south_min: f64,
    pub south_at: String,
}

impl Bottlenecks {
    pub fn florin(&self, c: &Criterion) -> bool {
        self.florin_min >= c.minutes
    }

    pub fn south(&self, c: &Criterion) -> bool {
        self.south_min >= c.minutes
    }

    /// Both recurrent bottlenecks show.
    pub fn active(&self, c: &Criterion) -> bool {
        self.florin(c) && self.south(c)
    }
}

/// Evaluate both bottlenecks on a run's records (cross-section rows suffice).
pub fn bottlenecks(records: &[DetectorRecord], c: &Criterion) -> Bottlenecks {
    let florin_min = longest_below_s(records, FLORIN_DETECTOR, c.speed_kmh) / 60.0;
    let dets = mainline_detectors(records);
    let pos = |name: &str| dets.iter().find(|(n, _)| n == name).map(|(_, x)| *x);
    let (mut south_min, mut south_at) = (0.0, String::new());
    if let (Some(a), Some(b)) = (pos(SOUTH_FIRST), pos(SOUTH_LAST)) {
        for (name, x) in &dets {
            if *x >= a && *x <= b {
                let m = longest_below_s(records, name, c.speed_kmh) / 60.0;
                if m > south_min {
                    south_min = m;
                    south_at = name.clone();
                }
            }
        }
    }
    Bottlenecks {
        florin_min,
        south_min,
        south_at,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cross-section record (lane "all") of a mainline detector.
    fn rec(det: &str, x: f64, lane: &str, t: f64, speed: Option<f64>) -> DetectorRecord {
        DetectorRecord {
            detector: det.into(),
            kind: "mainline".into(),
            position_m: x,
            lane: lane.into(),
            interval_start_s: t,
            interval_s: 300.0,
            count: 20,
            cav_count: 5,
            flow_vph: 240.0,
            speed_kmh: speed,
            occupancy: 0.1,
        }
    }

    /// Detectors A (x = 0) .. C (x = 200) over 4 intervals; `slow(det, interval)` gives the
    /// speed.
    fn synthetic(slow: impl Fn(&str, usize) -> Option<f64>) -> Vec<DetectorRecord> {
        let mut out = Vec::new();
        // Written out of order on purpose: C first.
        for (d, x) in [("C", 200.0), ("A", 0.0), ("B", 100.0)] {
            for i in 0..4 {
                out.push(rec(d, x, "all", 300.0 * i as f64, slow(d, i)));
            }
        }
        out
    }

    #[test]
    fn contour_sorts_detectors_by_position_and_times() {
        let mut recs = synthetic(|d, i| match (d, i) {
            ("B", 2) => Some(20.0),
            ("C", 0) => None,
            _ => Some(100.0),
        });
        // A standing queue: nobody crossed, occupied most of the interval.
        let standing = recs
            .iter_mut()
            .find(|r| r.detector == "A" && r.interval_start_s == 900.0)
            .unwrap();
        standing.speed_kmh = None;
        standing.occupancy = 0.9;
        recs.push(DetectorRecord {
            kind: "off-ramp".into(),
            ..rec("X-off", 50.0, "all", 0.0, Some(50.0))
        });
        let c = contour(&recs);
        let names: Vec<&str> = c.detectors.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, ["A", "B", "C"]);
        assert_eq!(c.times_min, [2.5, 7.5, 12.5, 17.5]);
        assert_eq!(c.speed_kmh[2][1], 20.0);
        assert!(c.speed_kmh[0][2].is_nan());
        assert_eq!(c.speed_kmh[3][0], 0.0);
        assert_eq!(c.speed_kmh[1][0], 100.0);
    }

    #[test]
    fn lane_series_gives_the_cav_ratio_per_lane() {
        let mut recs = Vec::new();
        for (lane, cavs) in [("2", 10), ("10", 0), ("1", 5), ("all", 15)] {
            for i in 0..3 {
                let mut r = rec("OR11-up", 11197.0, lane, 300.0 * i as f64, Some(90.0));
                r.cav_count = cavs;
                if lane == "1" && i == 1 {
                    r.count = 0;
                    r.cav_count = 0;
                    r.speed_kmh = None;
                }
                recs.push(r);
            }
        }
        recs.push(rec("other", 0.0, "1", 0.0, Some(1.0)));
        let s = lane_series(&recs, "OR11-up");
        let lanes: Vec<&str> = s.iter().map(|l| l.lane.as_str()).collect();
        assert_eq!(lanes, ["1", "2", "10"]);
        assert_eq!(s[0].cav_ratio[0], 0.25);
        assert!(s[0].cav_ratio[1].is_nan() && s[0].speed_kmh[1].is_nan());
        assert_eq!(s[1].cav_ratio, [0.5, 0.5, 0.5]);
        assert_eq!(s[2].cav_ratio[2], 0.0);
        assert_eq!(s[1].times_min, [2.5, 7.5, 12.5]);
        assert!(lane_series(&recs, "missing").is_empty());
    }

    #[test]
    fn bottleneck_criterion_needs_both_long_enough() {
        let crit = Criterion {
            speed_kmh: 60.0,
            minutes: 10.0,
        };
        let names = [
            ("OR1-up", -50.0),
            ("OR1-down", 50.0),
            ("OR3-up", 1948.0),
            ("OR5-up", 3482.0),
            ("OR5-down", 3582.0),
            ("OR11-up", 11197.0),
        ];
        let make = |slow: &dyn Fn(&str, usize) -> Option<f64>| {
            let mut out = Vec::new();
            for (d, x) in names {
                for i in 0..6 {
                    out.push(rec(d, x, "all", 300.0 * i as f64, slow(d, i)));
                }
            }
            out
        };
        // Florin slow for 3 intervals (15 min) but not consecutively beyond 2 in the south;
        // OR5-down (outside the south stretch) slow throughout.
        let recs = make(&|d, i| match (d, i) {
            ("OR11-up", 1..=3) => Some(30.0),
            ("OR3-up", 0 | 1) | ("OR3-up", 4) => Some(40.0),
            ("OR5-down", _) => Some(10.0),
            ("OR1-up", _) => Some(5.0),
            _ => Some(100.0),
        });
        let b = bottlenecks(&recs, &crit);
        assert_eq!(b.florin_min, 15.0);
        assert_eq!((b.south_min, b.south_at.as_str()), (10.0, "OR3-up"));
        assert!(b.active(&crit));
        let strict = Criterion {
            minutes: 15.0,
            ..crit
        };
        assert!(b.florin(&strict) && !b.south(&strict) && !b.active(&strict));

        // No data is not congestion; exactly the threshold is not below it.
        let recs = make(&|d, _| match d {
            "OR11-up" => None,
            "OR5-up" => Some(60.0),
            _ => Some(100.0),
        });
        let b = bottlenecks(&recs, &crit);
        assert_eq!((b.florin_min, b.south_min), (0.0, 0.0));
        assert_eq!(b.south_at, "");
        assert!(!b.active(&crit));
        assert_eq!(longest_below_s(&recs, "nowhere", 60.0), 0.0);
    }
}
