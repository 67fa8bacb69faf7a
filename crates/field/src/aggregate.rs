//! Longer intervals from shorter ones, and the intervals that are missing.
//!
//! An aggregate interval of length T starts at a multiple of T since midnight. It exists only
//! if the station's rows inside it tile it exactly (every sub-interval present, none
//! overlapping or crossing its bounds); otherwise it is missing, and [`missing`] lists it.
//! Nothing is interpolated: missing data is reported, never invented. With sub-intervals i of
//! length dᵢ (s), flow qᵢ (veh/h), speed vᵢ and occupancy oᵢ:
//!
//! * flow q = Σ qᵢ dᵢ / T (the vehicles counted, per hour);
//! * speed v = Σ qᵢ dᵢ vᵢ / Σ qᵢ dᵢ, the mean over the vehicles: each vᵢ is already a mean
//!   over its qᵢ dᵢ / 3600 vehicles. It is `None` if a sub-interval with vehicles has no
//!   speed. If no vehicle passed, v = Σ dᵢ vᵢ / T (the plain mean), `None` unless every
//!   sub-interval has a speed;
//! * occupancy o = Σ dᵢ oᵢ / T (the share of time occupied), `None` unless every
//!   sub-interval has one.
//!
//! With equal sub-intervals these are the plain mean flow, the flow-weighted mean speed and the
//! mean occupancy.

use std::collections::BTreeMap;

use crate::Obs;

/// An interval of a station without (complete) data.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Missing {
    /// The station.
    pub station: String,
    /// Start of the interval (s since midnight).
    pub start_s: u32,
}

/// Each station's rows, by the start of the aggregate interval they fall in (sorted by start).
fn buckets(obs: &[Obs], interval_s: u32) -> BTreeMap<&str, BTreeMap<u32, Vec<&Obs>>> {
    let mut out: BTreeMap<&str, BTreeMap<u32, Vec<&Obs>>> = BTreeMap::new();
    for o in obs {
        let start = o.start_s - o.start_s % interval_s;
        out.entry(o.station.as_str())
            .or_default()
            .entry(start)
            .or_default()
            .push(o);
    }
    for station in out.values_mut() {
        for subs in station.values_mut() {
            subs.sort_by_key(|o| o.start_s);
        }
    }
    out
}

/// Whether `subs` (sorted by start) tile `[start, start + len)` exactly.
fn complete(subs: &[&Obs], start: u32, len: u32) -> bool {
    let mut at = u64::from(start);
    for o in subs {
        if u64::from(o.start_s) != at || o.interval_s == 0 {
            return false;
        }
        at += u64::from(o.interval_s);
    }
    at == u64::from(start) + u64::from(len)
}

/// The rows at interval `interval_s` (s): one per station and complete interval, sorted by
/// station, then start. Empty for `interval_s` = 0.
pub fn to_interval(obs: &[Obs], interval_s: u32) -> Vec<Obs> {
    if interval_s == 0 {
        return Vec::new();
    }
    let len = f64::from(interval_s);
    let mut out = Vec::new();
    for (station, by_start) in buckets(obs, interval_s) {
        for (start, subs) in by_start {
            if !complete(&subs, start, interval_s) {
                continue;
            }
            // q dᵢ: vehicles × 3600 in each sub-interval.
            let weight = |o: &Obs| o.flow_vph * f64::from(o.interval_s);
            let all = |f: &dyn Fn(&Obs) -> Option<f64>| -> Option<f64> {
                subs.iter()
                    .map(|o| f(o).map(|v| v * f64::from(o.interval_s)))
                    .sum::<Option<f64>>()
                    .map(|s| s / len)
            };
            let vehicles: f64 = subs.iter().map(|o| weight(o)).sum();
            let speed_kmh = if vehicles > 0.0 {
                subs.iter()
                    .filter(|o| weight(o) > 0.0)
                    .map(|o| o.speed_kmh.map(|v| v * weight(o)))
                    .sum::<Option<f64>>()
                    .map(|s| s / vehicles)
            } else {
                all(&|o| o.speed_kmh)
            };
            out.push(Obs {
                station: station.to_string(),
                start_s: start,
                interval_s,
                flow_vph: vehicles / len,
                speed_kmh,
                occupancy: all(&|o| o.occupancy),
            });
        }
    }
    out
}

/// The intervals of length `interval_s` inside `[from_s, to_s)` (starting at multiples of
/// `interval_s`, ending by `to_s`) that each station of `obs` lacks or has only in part,
/// sorted by station, then start. A station without any row is not in `obs` and so not
/// listed here (`place::select` reports it). Empty for `interval_s` = 0.
pub fn missing(obs: &[Obs], from_s: u32, to_s: u32, interval_s: u32) -> Vec<Missing> {
    if interval_s == 0 {
        return Vec::new();
    }
    let step = u64::from(interval_s);
    let first = u64::from(from_s).div_ceil(step) * step;
    let mut out = Vec::new();
    for (station, by_start) in buckets(obs, interval_s) {
        let mut t = first;
        while t + step <= u64::from(to_s) {
            // t < to_s <= u32::MAX, so the cast is exact.
            let start = t as u32;
            let ok = by_start
                .get(&start)
                .is_some_and(|subs| complete(subs, start, interval_s));
            if !ok {
                out.push(Missing {
                    station: station.to_string(),
                    start_s: start,
                });
            }
            t += step;
        }
    }
    out
}
