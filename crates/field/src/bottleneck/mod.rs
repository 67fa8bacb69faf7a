//! Active bottlenecks from station speeds, after Chen, Skabardonis & Varaiya (2004),
//! "Systematic identification of freeway bottlenecks", Transportation Research Record 1867.
//!
//! Between two consecutive mainline stations u (upstream) and d (downstream), sorted by
//! position among the stations that have data, a bottleneck is **active** in a 5-min interval
//! when
//!
//! * the upstream speed is below a limit: v_u < 40 mph (64.4 km/h), and
//! * the speed rises downstream by at least a margin: v_d − v_u ≥ 20 mph (32.2 km/h)
//!
//! (Chen et al.'s rule: congested upstream, free flow downstream). The rest is this project's
//! (docs/compare.md), not the paper's: active intervals of one station pair are grouped into
//! episodes, bridging gaps of up to [`Params::max_gap_intervals`] inactive intervals; an
//! episode's **onset** is the start of its first active interval and its **clearance** the end
//! of its last; episodes shorter than [`Params::min_active_intervals`] active intervals are
//! dropped as noise (shorter than the 15-min tolerance of the comparison). An interval
//! without a speed at either station is not active (no data is not congestion), except a
//! station occupied more than half the interval with no vehicle crossing, which is a standing
//! queue (speed 0, as in the experiment crate's contours). An episode still active at the end
//! of the data is cut there.
//!
//! | parameter | unit | default |
//! |---|---|---|
//! | `upstream_max_kmh` | km/h | 64.37 (40 mph) |
//! | `min_rise_kmh` | km/h | 32.19 (20 mph) |
//! | `interval_s` | s | 300 (5 min) |
//! | `max_gap_intervals` | intervals | 2 |
//! | `min_active_intervals` | intervals | 3 |
//!
//! [`compare`] pairs simulated with field bottlenecks (matching.rs).

mod matching;

pub use matching::{all_within, compare, MatchParams, Pair};

use crate::{Obs, Placed, StationKind, METRES_PER_MILE};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};

/// Kilometres per hour in one mile per hour.
const KMH_PER_MPH: f64 = METRES_PER_MILE / 1000.0;

/// Occupancy above which an interval without crossings is a standing queue (speed 0).
pub const STANDING_OCCUPANCY: f64 = 0.5;

/// The identification's parameters (see the module doc's table).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Params {
    /// The upstream speed must be below this (km/h).
    pub upstream_max_kmh: f64,
    /// The downstream speed must exceed the upstream one by at least this (km/h).
    pub min_rise_kmh: f64,
    /// Interval the speeds are taken over (s).
    pub interval_s: u32,
    /// Inactive intervals bridged inside one episode.
    pub max_gap_intervals: u32,
    /// Fewest active intervals of an episode kept.
    pub min_active_intervals: u32,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            upstream_max_kmh: 40.0 * KMH_PER_MPH,
            min_rise_kmh: 20.0 * KMH_PER_MPH,
            interval_s: 300,
            max_gap_intervals: 2,
            min_active_intervals: 3,
        }
    }
}

/// One episode of an active bottleneck between two stations.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Bottleneck {
    pub upstream: String,
    pub downstream: String,
    /// Midway between the two stations (m, corridor coordinate).
    pub x_m: f64,
    /// Start of the first active interval (s after midnight).
    pub onset_s: u32,
    /// End of the last active interval (s after midnight).
    pub clearance_s: u32,
    /// Active time (min), bridged gaps not counted.
    pub active_minutes: f64,
}

/// A speed for the rule (and for contours): the measured one, 0 for a standing queue (no
/// vehicle crossed, occupancy above [`STANDING_OCCUPANCY`]), `None` for no data.
pub fn rule_speed(o: &Obs) -> Option<f64> {
    match (o.speed_kmh, o.occupancy) {
        (Some(v), _) => Some(v),
        (None, Some(occ)) if occ > STANDING_OCCUPANCY => Some(0.0),
        _ => None,
    }
}

/// The active bottlenecks in `obs` at the mainline stations of `stations` (others are
/// ignored), ordered by position, then onset.
pub fn identify(obs: &[Obs], stations: &[Placed], p: &Params) -> Vec<Bottleneck> {
    let agg = crate::aggregate::to_interval(obs, p.interval_s);
    let mut speed: BTreeMap<&str, BTreeMap<u32, f64>> = BTreeMap::new();
    let mut seen: BTreeSet<&str> = BTreeSet::new();
    for o in &agg {
        seen.insert(&o.station);
        if let Some(v) = rule_speed(o) {
            speed
                .entry(&o.station)
                .or_default()
                .insert(o.start_s / p.interval_s, v);
        }
    }
    let mut line: Vec<&Placed> = stations
        .iter()
        .filter(|s| s.kind == StationKind::Mainline && seen.contains(s.station.as_str()))
        .collect();
    line.sort_by(|a, b| a.x_m.total_cmp(&b.x_m).then(a.station.cmp(&b.station)));
    let none = BTreeMap::new();
    let mut out = Vec::new();
    for w in line.windows(2) {
        let (u, d) = (w[0], w[1]);
        let su = speed.get(u.station.as_str()).unwrap_or(&none);
        let sd = speed.get(d.station.as_str()).unwrap_or(&none);
        let active: Vec<u32> = su
            .iter()
            .filter(|&(k, &vu)| {
                sd.get(k)
                    .is_some_and(|&vd| vu < p.upstream_max_kmh && vd - vu >= p.min_rise_kmh)
            })
            .map(|(&k, _)| k)
            .collect();
        for (first, last, n) in episodes(&active, p.max_gap_intervals) {
            if n < p.min_active_intervals as usize {
                continue;
            }
            out.push(Bottleneck {
                upstream: u.station.clone(),
                downstream: d.station.clone(),
                x_m: (u.x_m + d.x_m) / 2.0,
                onset_s: first * p.interval_s,
                clearance_s: (last + 1) * p.interval_s,
                active_minutes: n as f64 * f64::from(p.interval_s) / 60.0,
            });
        }
    }
    out.sort_by(|a, b| a.x_m.total_cmp(&b.x_m).then(a.onset_s.cmp(&b.onset_s)));
    out
}

/// Runs of sorted interval indices with gaps of at most `max_gap` missing indices between
/// neighbours: (first, last, how many active).
fn episodes(active: &[u32], max_gap: u32) -> Vec<(u32, u32, usize)> {
    let mut out: Vec<(u32, u32, usize)> = Vec::new();
    for &k in active {
        match out.last_mut() {
            Some((_, last, n)) if k - *last - 1 <= max_gap => {
                *last = k;
                *n += 1;
            }
            _ => out.push((k, k, 1)),
        }
    }
    out
}

#[cfg(test)]
mod tests;
