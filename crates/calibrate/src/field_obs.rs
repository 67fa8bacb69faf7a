//! A run's detector records as field observations ([`platoonsim_field::Obs`]), so that
//! simulated and field data go through the same measures (`platoonsim compare`, `calibrate`).
//!
//! * One [`Obs`] per detector and interval, from its cross-section row (`lane == "all"`):
//!   flow over all lanes (veh/h), time-mean speed of the vehicles that crossed (km/h, `None`
//!   if none crossed) and the occupancy averaged over the lanes (0-1), which is what a PeMS
//!   station reports for its lanes.
//! * `start_s` is clock time: the run's `run.clock_start` (s after midnight) plus the
//!   interval's start in simulated time.
//! * Replications (seeds) are averaged per station and interval by [`mean_over_runs`], as the
//!   FHWA Toolbox III compares the mean of the replications with the field: flow the mean,
//!   speed the flow-weighted mean (the space-mean of the pooled vehicles when every seed's
//!   speed is a time mean), occupancy the mean. An interval is kept only if every run has it.

use platoonsim_field::Obs;
use platoonsim_sim::DetectorRecord;
use std::collections::BTreeMap;

/// The cross-section records of a run as observations at clock time.
pub fn to_obs(records: &[DetectorRecord], clock_start_s: u32) -> Vec<Obs> {
    records
        .iter()
        .filter(|r| platoonsim_rundir::Lane::is_all(&r.lane))
        .map(|r| Obs {
            station: r.detector.clone(),
            start_s: clock_start_s + r.interval_start_s.round() as u32,
            interval_s: r.interval_s.round() as u32,
            flow_vph: r.flow_vph,
            speed_kmh: r.speed_kmh,
            occupancy: Some(r.occupancy),
        })
        .collect()
}

/// The mean of several runs' observations per station and interval (see the module doc), in
/// (station, start) order. Intervals missing from any run are dropped.
pub fn mean_over_runs(runs: &[Vec<Obs>]) -> Vec<Obs> {
    let mut cells: BTreeMap<(&str, u32), Vec<&Obs>> = BTreeMap::new();
    for run in runs {
        for o in run {
            cells.entry((&o.station, o.start_s)).or_default().push(o);
        }
    }
    cells
        .into_values()
        .filter(|v| v.len() == runs.len())
        .map(|v| mean(&v))
        .collect()
}

fn mean(v: &[&Obs]) -> Obs {
    let n = v.len() as f64;
    let flow: f64 = v.iter().map(|o| o.flow_vph).sum();
    let speed_kmh = platoonsim_field::flow_weighted_speed(v.iter().copied());
    let occ: Vec<f64> = v.iter().filter_map(|o| o.occupancy).collect();
    Obs {
        station: v[0].station.clone(),
        start_s: v[0].start_s,
        interval_s: v[0].interval_s,
        flow_vph: flow / n,
        speed_kmh,
        occupancy: (!occ.is_empty()).then(|| occ.iter().sum::<f64>() / occ.len() as f64),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rec(det: &str, lane: &str, t: f64, flow: f64, speed: Option<f64>) -> DetectorRecord {
        DetectorRecord {
            detector: det.into(),
            kind: "mainline".into(),
            position_m: 0.0,
            lane: lane.into(),
            interval_start_s: t,
            interval_s: 300.0,
            count: (flow / 12.0) as u64,
            cav_count: 0,
            flow_vph: flow,
            speed_kmh: speed,
            occupancy: 0.1,
        }
    }

    fn obs(t: u32, flow: f64, speed: Option<f64>) -> Obs {
        Obs {
            station: "S".into(),
            start_s: t,
            interval_s: 300,
            flow_vph: flow,
            speed_kmh: speed,
            occupancy: Some(0.1),
        }
    }

    #[test]
    fn cross_section_rows_at_clock_time() {
        let recs = [
            rec("S", "1", 300.0, 600.0, Some(90.0)),
            rec("S", "all", 300.0, 1200.0, Some(95.0)),
        ];
        let o = to_obs(&recs, 18_000);
        assert_eq!(o, vec![obs(18_300, 1200.0, Some(95.0))]);
    }

    #[test]
    fn replications_average_flow_and_weight_speed_by_flow() {
        let a = vec![obs(0, 1000.0, Some(100.0)), obs(300, 500.0, None)];
        let b = vec![obs(0, 3000.0, Some(60.0))];
        let m = mean_over_runs(&[a, b]);
        // 300 s is missing from run b: dropped, not invented.
        assert_eq!(m.len(), 1);
        assert_eq!(m[0].flow_vph, 2000.0);
        // (100 x 1000 + 60 x 3000) / 4000 = 70
        assert_eq!(m[0].speed_kmh, Some(70.0));
    }
}
