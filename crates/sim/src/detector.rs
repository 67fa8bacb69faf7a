//! Loop detectors (issue 2 item 4): per lane and for the whole cross-section, counts, flow,
//! time-mean speed and occupancy aggregated over a fixed interval, kept as a time series.
//!
//! A crossing is the step in which a vehicle's front bumper passes the detector position
//! (x_prev < p ≤ x); its speed is interpolated linearly within the step. Occupancy is the
//! time the detector point lies under the vehicle body ([x − L, x)), integrated within each
//! step assuming constant speed over the step.

use serde::Serialize;

/// One vehicle's movement during one step: front bumper from `x0` to `x1` (x1 ≥ x0), speed from
/// `v0` to `v1`, vehicle length `len`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Passage {
    pub x0: f64,
    pub x1: f64,
    pub v0: f64,
    pub v1: f64,
    pub len: f64,
    /// The vehicle is a CAV.
    pub cav: bool,
}

/// Accumulators for one lane (or the cross-section) in one interval.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Acc {
    pub count: u64,
    /// Of which CAVs.
    pub cav_count: u64,
    pub speed_sum: f64,
    pub occupied_s: f64,
}

/// One detector's state.
#[derive(Clone, Debug)]
pub struct Detector {
    pub name: String,
    pub position_m: f64,
    /// "mainline", "off-ramp" or "on-ramp" (detectors.csv).
    pub kind: &'static str,
    /// Counts toward the network discharge.
    pub exit: bool,
    /// Lanes it covers: bit per lateral lane index (all lanes of a plain road; the through
    /// lanes open at its position on a network; lane 0 for an off-ramp counter).
    pub mask: u32,
    /// Lowest covered lane index: records number lanes from it (1 = rightmost covered lane).
    first_lane: usize,
    /// Number of covered lanes (flow per lane in broadcasts).
    covered: usize,
    /// Added to the position in the records (the network origin).
    origin_m: f64,
    lanes: usize,
    /// Accumulators of the running interval, per lane.
    current: Vec<Acc>,
    /// Completed intervals: `history[k][lane]`.
    history: Vec<Vec<Acc>>,
}

/// What a detector broadcasts (its latest completed interval, cross-section).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Broadcast {
    /// Flow per lane (veh/h/lane).
    pub flow_vphpl: f64,
    /// Time-mean speed (km/h); `None` if no vehicle crossed.
    pub speed_kmh: Option<f64>,
}

impl Detector {
    pub fn new(name: &str, position_m: f64, lanes: usize) -> Detector {
        Detector::covering(name, position_m, lanes, (1u32 << lanes) - 1, 0.0)
    }

    /// A detector over the lanes in `mask` (bit per lane index, lanes < `lanes`).
    pub fn covering(
        name: &str,
        position_m: f64,
        lanes: usize,
        mask: u32,
        origin_m: f64,
    ) -> Detector {
        Detector {
            name: name.to_string(),
            position_m,
            kind: "mainline",
            exit: false,
            mask,
            first_lane: mask.trailing_zeros() as usize,
            covered: (mask.count_ones() as usize).max(1),
            origin_m,
            lanes,
            current: vec![Acc::default(); lanes],
            history: Vec::new(),
        }
    }

    /// Record one vehicle's movement in one step of length `dt`, in `lane`.
    #[inline]
    pub fn observe(&mut self, lane: usize, m: Passage, dt: f64) {
        let Passage {
            x0,
            x1,
            v0,
            v1,
            len,
            cav,
        } = m;
        let p = self.position_m;
        let acc = &mut self.current[lane];
        if x0 < p && p <= x1 {
            let frac = if x1 > x0 { (p - x0) / (x1 - x0) } else { 1.0 };
            acc.count += 1;
            acc.cav_count += u64::from(cav);
            acc.speed_sum += v0 + (v1 - v0) * frac;
        }
        // Occupied while p ∈ [x − len, x), i.e. x ∈ (p, p + len].
        let lo = x0.max(p);
        let hi = x1.min(p + len);
        if x1 > x0 {
            if hi > lo {
                acc.occupied_s += dt * (hi - lo) / (x1 - x0);
            }
        } else if x0 > p && x0 <= p + len {
            acc.occupied_s += dt;
        }
    }

    /// A vehicle passes this ramp counter (leaves by its off-ramp, or enters from its
    /// on-ramp) at speed `v` (m/s).
    pub fn count_exit(&mut self, v: f64, cav: bool) {
        let acc = &mut self.current[self.first_lane];
        acc.count += 1;
        acc.cav_count += u64::from(cav);
        acc.speed_sum += v;
    }

    /// The occupancy of the running interval of `span_s` (share of it, mean over the covered
    /// lanes, as the records' `all` row), which then starts again: a ramp meter's detector,
    /// read every control period, keeps no history.
    pub(crate) fn take_occupancy(&mut self, span_s: f64) -> f64 {
        let occupied: f64 = self.current.iter().map(|a| a.occupied_s).sum();
        self.current.fill(Acc::default());
        (occupied / (span_s * self.covered as f64)).clamp(0.0, 1.0)
    }

    /// Close the running interval.
    pub fn close_interval(&mut self) {
        let done = std::mem::replace(&mut self.current, vec![Acc::default(); self.lanes]);
        self.history.push(done);
    }

    /// Number of lanes it covers.
    pub fn covered_lanes(&self) -> usize {
        self.covered
    }

    /// Completed intervals so far.
    pub fn intervals(&self) -> usize {
        self.history.len()
    }

    /// Counts of the covered lanes over the completed intervals from `first` on, the lowest
    /// covered lane first (the order of the records' lane numbers), with that lane's index.
    pub fn lane_counts(&self, first: usize) -> (usize, Vec<u64>) {
        let counts = (0..self.lanes)
            .filter(|&l| self.mask & (1 << l) != 0)
            .map(|l| self.history.iter().skip(first).map(|h| h[l].count).sum())
            .collect();
        (self.first_lane, counts)
    }

    /// Cross-section count of completed interval `k`.
    pub fn total_count(&self, k: usize) -> u64 {
        self.history[k].iter().map(|a| a.count).sum()
    }

    /// The latest completed interval as broadcast (cross-section), if any.
    pub fn broadcast(&self, interval_s: f64) -> Option<Broadcast> {
        let last = self.history.last()?;
        let total = sum(last);
        Some(Broadcast {
            flow_vphpl: total.count as f64 * 3600.0 / interval_s / self.covered as f64,
            speed_kmh: mean_speed_kmh(&total),
        })
    }

    /// Tidy records: one per lane (1-based from the right) and one "all" per interval.
    pub fn records(&self, interval_s: f64, out: &mut Vec<DetectorRecord>) {
        for (k, lanes) in self.history.iter().enumerate() {
            let start = k as f64 * interval_s;
            let mut push = |lane: String, a: &Acc, n_lanes: usize| {
                out.push(DetectorRecord {
                    detector: self.name.clone(),
                    kind: self.kind.into(),
                    position_m: self.position_m + self.origin_m,
                    lane,
                    interval_start_s: start,
                    interval_s,
                    count: a.count,
                    cav_count: a.cav_count,
                    flow_vph: a.count as f64 * 3600.0 / interval_s,
                    speed_kmh: mean_speed_kmh(a),
                    occupancy: (a.occupied_s / (interval_s * n_lanes as f64)).clamp(0.0, 1.0),
                });
            };
            for (l, a) in lanes.iter().enumerate() {
                if self.mask & (1 << l) != 0 {
                    push((l - self.first_lane + 1).to_string(), a, 1);
                }
            }
            push("all".to_string(), &sum(lanes), self.covered);
        }
    }
}

fn sum(lanes: &[Acc]) -> Acc {
    lanes.iter().fold(Acc::default(), |s, a| Acc {
        count: s.count + a.count,
        cav_count: s.cav_count + a.cav_count,
        speed_sum: s.speed_sum + a.speed_sum,
        occupied_s: s.occupied_s + a.occupied_s,
    })
}

fn mean_speed_kmh(a: &Acc) -> Option<f64> {
    (a.count > 0).then(|| a.speed_sum / a.count as f64 * 3.6)
}

/// One detector, lane and aggregation interval (`detectors.csv`). `lane` is the lane number
/// from the right starting at 1, or "all" for the cross-section.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DetectorRecord {
    pub detector: String,
    /// "mainline", "off-ramp" or "on-ramp".
    pub kind: String,
    /// Output coordinate (engine x + the network origin).
    pub position_m: f64,
    pub lane: String,
    pub interval_start_s: f64,
    pub interval_s: f64,
    pub count: u64,
    /// Of which CAVs.
    pub cav_count: u64,
    pub flow_vph: f64,
    /// Time-mean speed of the vehicles that crossed (km/h); empty (NaN-free: `None`) if none.
    pub speed_kmh: Option<f64>,
    /// Share of the interval the detector was occupied, in [0, 1].
    pub occupancy: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_one_crossing_with_interpolated_speed_and_occupancy() {
        let mut d = Detector::new("d", 100.0, 2);
        // A 4 m car at 20 m/s passes in 0.1 s steps: front from 90 to 120.
        let mut x = 90.0;
        while x < 120.0 {
            let m = Passage {
                x0: x,
                x1: x + 2.0,
                v0: 20.0,
                v1: 20.0,
                len: 4.0,
                cav: false,
            };
            d.observe(1, m, 0.1);
            x += 2.0;
        }
        d.close_interval();
        let mut recs = Vec::new();
        d.records(60.0, &mut recs);
        let lane2 = recs.iter().find(|r| r.lane == "2").unwrap();
        assert_eq!(lane2.count, 1);
        assert!((lane2.speed_kmh.unwrap() - 72.0).abs() < 1e-9);
        // occupied for 4 m / 20 m/s = 0.2 s of 60 s
        assert!((lane2.occupancy - 0.2 / 60.0).abs() < 1e-12);
        let all = recs.iter().find(|r| r.lane == "all").unwrap();
        assert_eq!(all.count, 1);
        assert!((all.flow_vph - 60.0).abs() < 1e-9);
        assert_eq!(recs.iter().find(|r| r.lane == "1").unwrap().speed_kmh, None);
    }

    #[test]
    fn stopped_vehicle_over_detector_occupies_it() {
        let mut d = Detector::new("d", 100.0, 1);
        for _ in 0..10 {
            let m = Passage {
                x0: 102.0,
                x1: 102.0,
                v0: 0.0,
                v1: 0.0,
                len: 4.0,
                cav: false,
            };
            d.observe(0, m, 0.1);
        }
        d.close_interval();
        let b = d.broadcast(1.0).unwrap();
        assert_eq!(b.flow_vphpl, 0.0);
        assert_eq!(b.speed_kmh, None);
        let mut recs = Vec::new();
        d.records(1.0, &mut recs);
        assert!((recs[0].occupancy - 1.0).abs() < 1e-12);
    }
}
