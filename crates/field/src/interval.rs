//! The aggregation the fit uses, behind one private call so that it can be swapped for
//! `crate::aggregate::to_interval` (the agreed signature `to_interval(obs, interval_s)`).
//!
//! Until then, a minimal implementation of the same rule: per station, intervals aligned on
//! multiples of `interval_s` since midnight; an aggregate exists only if its sub-intervals
//! cover it exactly (no gap, no overlap), flow the time-weighted mean (veh/h), speed the
//! flow-weighted mean of the sub-intervals that have one (their plain mean if none carried
//! vehicles), occupancy the mean.

use crate::Obs;
use std::collections::BTreeMap;

/// `obs` aggregated to `interval_s` (see the module doc), in (station, start) order.
pub(crate) fn to_interval(obs: &[Obs], interval_s: u32) -> Vec<Obs> {
    if interval_s == 0 {
        return Vec::new();
    }
    let mut cells: BTreeMap<(&str, u32), Vec<&Obs>> = BTreeMap::new();
    for o in obs {
        let start = o.start_s / interval_s * interval_s;
        cells.entry((&o.station, start)).or_default().push(o);
    }
    cells
        .into_iter()
        .filter_map(|((station, start), mut subs)| {
            subs.sort_by_key(|o| o.start_s);
            let mut t = start;
            for o in &subs {
                if o.start_s != t || o.interval_s == 0 {
                    return None;
                }
                t += o.interval_s;
            }
            (t == start + interval_s).then(|| merge(station, start, interval_s, &subs))
        })
        .collect()
}

fn merge(station: &str, start_s: u32, interval_s: u32, subs: &[&Obs]) -> Obs {
    let flow = subs
        .iter()
        .map(|o| o.flow_vph * f64::from(o.interval_s))
        .sum::<f64>()
        / f64::from(interval_s);
    let speeds: Vec<(f64, f64)> = subs
        .iter()
        .filter_map(|o| {
            o.speed_kmh
                .map(|v| (v, o.flow_vph * f64::from(o.interval_s)))
        })
        .collect();
    let weight: f64 = speeds.iter().map(|s| s.1).sum();
    let speed_kmh = if speeds.is_empty() {
        None
    } else if weight > 0.0 {
        Some(speeds.iter().map(|&(v, w)| v * w).sum::<f64>() / weight)
    } else {
        Some(speeds.iter().map(|s| s.0).sum::<f64>() / speeds.len() as f64)
    };
    let occ: Vec<f64> = subs.iter().filter_map(|o| o.occupancy).collect();
    Obs {
        station: station.to_string(),
        start_s,
        interval_s,
        flow_vph: flow,
        speed_kmh,
        occupancy: (!occ.is_empty()).then(|| occ.iter().sum::<f64>() / occ.len() as f64),
    }
}
