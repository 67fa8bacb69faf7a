//! Goodness of fit of simulated detector data to field data (`platoonsim compare`;
//! docs/compare.md).
//!
//! Simulated and field [`Obs`] are matched by station name and interval start; only stations
//! present on both sides are compared (the others are listed, [`Fit::sim_only_stations`],
//! [`Fit::field_only_stations`]). Nothing is filled in: an interval that one side lacks is
//! counted as missing ([`Coverage`]), never interpolated.
//!
//! * Flows: hourly volumes (aggregates of [`FLOW_INTERVAL_S`]) per station-hour, the
//!   [`geh`] statistic of each, the share with GEH < 5, the Toolbox's flow tolerance
//!   ([`flow_within_tolerance`]), and per clock hour the sum over the stations (its
//!   difference and GEH). Source: FHWA Traffic Analysis
//!   Toolbox Vol. III (Dowling, Skabardonis & Halkias 2004), section 5, Table 4 (after
//!   Wisconsin DOT 2002); GEH as in the UK DMRB Vol. 12. (The 2019 update of Vol. III frames
//!   acceptance differently, with analyst-set sigma bands; it is not implemented here.)
//! * Speeds: 15-min aggregates ([`SPEED_INTERVAL_S`]) per station-interval where both sides
//!   have a speed: RMSE (km/h), RMSNE ([`rmsne`]) and Pearson's correlation ([`pearson`]).
//!
//! | parameter | unit | default |
//! |---|---|---|
//! | flow interval | s | 3,600 ([`FLOW_INTERVAL_S`]) |
//! | speed interval | s | 900 ([`SPEED_INTERVAL_S`]) |
//! | GEH limit | — | 5 ([`GEH_LIMIT`]) |

mod measures;

pub use measures::{flow_within_tolerance, geh, pearson, rmse, rmsne, GEH_LIMIT};

use crate::Obs;
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};

/// Interval of the flows compared (s): hourly volumes, as GEH is defined.
pub const FLOW_INTERVAL_S: u32 = 3600;
/// Interval of the speeds compared (s).
pub const SPEED_INTERVAL_S: u32 = 900;

/// How many station-intervals were on both sides, and how many on one side only.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Coverage {
    /// On both sides: compared.
    pub matched: usize,
    /// Simulated, but no (complete) field interval: missing in the field data.
    pub missing_in_field: usize,
    /// In the field data, but not simulated (or not complete): missing in the simulation.
    pub missing_in_sim: usize,
}

/// One station-hour: the hourly volumes and their GEH.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HourFit {
    pub station: String,
    /// Start of the hour, s after midnight.
    pub start_s: u32,
    pub sim_vph: f64,
    pub field_vph: f64,
    pub geh: f64,
}

/// One clock hour: the sums of the hourly volumes of the stations compared in it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct HourSum {
    /// Start of the hour, s after midnight.
    pub start_s: u32,
    /// Stations compared in this hour.
    pub stations: usize,
    /// Σ M and Σ C (veh/h).
    pub sim_vph: f64,
    pub field_vph: f64,
    /// (Σ M − Σ C) / Σ C; `None` if Σ C = 0.
    pub diff: Option<f64>,
    /// GEH(Σ M, Σ C).
    pub geh: f64,
}

/// One 15-min station-interval where both sides have a speed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SpeedFit {
    pub station: String,
    /// Start of the interval, s after midnight.
    pub start_s: u32,
    pub sim_kmh: f64,
    pub field_kmh: f64,
}

/// The measures of one station (for the report's per-station table).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StationFit {
    pub station: String,
    /// Station-hours compared.
    pub hours: usize,
    /// Share (0-1) of its hours with GEH < 5; `None` without hours.
    pub geh_pass_share: Option<f64>,
    pub geh_max: Option<f64>,
    /// Total simulated and counted vehicles over its compared hours.
    pub sim_veh: f64,
    pub field_veh: f64,
    /// 15-min intervals with a speed on both sides.
    pub speed_intervals: usize,
    pub speed_rmse_kmh: Option<f64>,
    pub speed_rmsne: Option<f64>,
    /// Its 15-min intervals on one side only.
    pub quarters: Coverage,
}

/// Every measure of one comparison; serialized as `fit.json`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Fit {
    /// Stations compared (on both sides), sorted.
    pub stations_compared: Vec<String>,
    /// Stations with simulated data but no field data.
    pub sim_only_stations: Vec<String>,
    /// Stations with field data but no simulated detector of the same name.
    pub field_only_stations: Vec<String>,
    /// Station-hours matched and missing on either side.
    pub hour_coverage: Coverage,
    /// 15-min station-intervals matched and missing on either side.
    pub quarter_coverage: Coverage,
    /// Matched 15-min intervals where one side has no speed (left out of the speed measures).
    pub quarters_without_speed: usize,
    /// Share (0-1) of station-hours with GEH < 5.
    pub geh_pass_share: Option<f64>,
    pub geh_mean: Option<f64>,
    pub geh_max: Option<f64>,
    /// Share (0-1) of station-hours within the Toolbox's flow tolerance.
    pub flow_tolerance_share: Option<f64>,
    /// Sum of the simulated and of the counted hourly volumes over the compared
    /// station-hours (veh).
    pub total_sim_veh: f64,
    pub total_field_veh: f64,
    /// (Σ M − Σ C) / Σ C over the whole period; `None` if Σ C = 0.
    pub total_flow_diff: Option<f64>,
    /// Per clock hour, the sums over the stations compared in that hour (the Toolbox's "sum
    /// of all link flows" is an hourly flow).
    pub hour_sums: Vec<HourSum>,
    /// The hourly sum farthest from the counts: (Σ M − Σ C) / Σ C of largest magnitude.
    pub hour_sum_diff_worst: Option<f64>,
    /// The largest GEH of an hourly sum.
    pub hour_sum_geh_max: Option<f64>,
    /// Pooled over all compared 15-min station-intervals with speeds.
    pub speed_intervals: usize,
    pub speed_rmse_kmh: Option<f64>,
    pub speed_rmsne: Option<f64>,
    pub speed_correlation: Option<f64>,
    pub per_station: Vec<StationFit>,
    pub hours: Vec<HourFit>,
    pub speeds: Vec<SpeedFit>,
}

impl Fit {
    /// A scalar to minimize (calibration): the mean GEH of the station-hours over its limit 5
    /// plus the 15-min speed RMSNE; both dimensionless and 0 at a perfect fit, so the sum is
    /// ≈ 1 when flows sit at the GEH limit on average or speeds are off by ≈ 100 % (RMS).
    /// `None` if there is no matched hour or no matched speed (nothing to judge).
    pub fn objective(&self) -> Option<f64> {
        Some(self.geh_mean? / GEH_LIMIT + self.speed_rmsne?)
    }
}

/// Keep observations inside `[from_s, to_s)`: intervals that start at or after `from_s` and
/// end at or before `to_s` (s after midnight).
pub fn within(obs: &[Obs], from_s: u32, to_s: u32) -> Vec<Obs> {
    obs.iter()
        .filter(|o| o.start_s >= from_s && o.start_s + o.interval_s <= to_s)
        .cloned()
        .collect()
}

/// Compare simulated and field observations (see the module doc).
pub fn fit(sim: &[Obs], field: &[Obs]) -> Fit {
    let names = |o: &[Obs]| -> BTreeSet<String> { o.iter().map(|o| o.station.clone()).collect() };
    let (sim_names, field_names) = (names(sim), names(field));
    let common: BTreeSet<&String> = sim_names.intersection(&field_names).collect();
    let keep = |o: &[Obs]| -> Vec<Obs> {
        o.iter()
            .filter(|o| common.contains(&o.station))
            .cloned()
            .collect()
    };
    let (sim, field) = (keep(sim), keep(field));

    let (hour_pairs, hour_coverage, _) = pair(&sim, &field, FLOW_INTERVAL_S);
    let (quarter_pairs, quarter_coverage, quarter_cov_st) = pair(&sim, &field, SPEED_INTERVAL_S);

    let hours: Vec<HourFit> = hour_pairs
        .iter()
        .map(|(m, c)| HourFit {
            station: m.station.clone(),
            start_s: m.start_s,
            sim_vph: m.flow_vph,
            field_vph: c.flow_vph,
            geh: geh(m.flow_vph, c.flow_vph),
        })
        .collect();
    let speeds: Vec<SpeedFit> = quarter_pairs
        .iter()
        .filter_map(|(m, c)| {
            Some(SpeedFit {
                station: m.station.clone(),
                start_s: m.start_s,
                sim_kmh: m.speed_kmh?,
                field_kmh: c.speed_kmh?,
            })
        })
        .collect();

    let per_station = common
        .iter()
        .map(|s| {
            let h: Vec<&HourFit> = hours.iter().filter(|h| &&h.station == s).collect();
            let v: Vec<(f64, f64)> = speeds
                .iter()
                .filter(|v| &&v.station == s)
                .map(|v| (v.sim_kmh, v.field_kmh))
                .collect();
            StationFit {
                station: s.to_string(),
                hours: h.len(),
                geh_pass_share: share(&h, |h| h.geh < GEH_LIMIT),
                geh_max: h.iter().map(|h| h.geh).reduce(f64::max),
                sim_veh: h.iter().map(|h| h.sim_vph).sum(),
                field_veh: h.iter().map(|h| h.field_vph).sum(),
                speed_intervals: v.len(),
                speed_rmse_kmh: rmse(&v),
                speed_rmsne: rmsne(&v),
                quarters: quarter_cov_st.get(s.as_str()).copied().unwrap_or_default(),
            }
        })
        .collect();

    let all: Vec<&HourFit> = hours.iter().collect();
    let (total_sim_veh, total_field_veh) = (
        hours.iter().map(|h| h.sim_vph).sum::<f64>(),
        hours.iter().map(|h| h.field_vph).sum::<f64>(),
    );
    let v: Vec<(f64, f64)> = speeds.iter().map(|v| (v.sim_kmh, v.field_kmh)).collect();
    let hour_sums = sums_by_hour(&hours);
    Fit {
        stations_compared: common.iter().map(|s| s.to_string()).collect(),
        sim_only_stations: sim_names.difference(&field_names).cloned().collect(),
        field_only_stations: field_names.difference(&sim_names).cloned().collect(),
        hour_coverage,
        quarter_coverage,
        quarters_without_speed: quarter_pairs.len() - speeds.len(),
        geh_pass_share: share(&all, |h| h.geh < GEH_LIMIT),
        geh_mean: (!hours.is_empty())
            .then(|| hours.iter().map(|h| h.geh).sum::<f64>() / hours.len() as f64),
        geh_max: hours.iter().map(|h| h.geh).reduce(f64::max),
        flow_tolerance_share: share(&all, |h| flow_within_tolerance(h.sim_vph, h.field_vph)),
        total_sim_veh,
        total_field_veh,
        total_flow_diff: (total_field_veh > 0.0)
            .then(|| (total_sim_veh - total_field_veh) / total_field_veh),
        hour_sum_diff_worst: hour_sums.iter().filter_map(|h| h.diff).reduce(|a, b| {
            if b.abs() > a.abs() {
                b
            } else {
                a
            }
        }),
        hour_sum_geh_max: hour_sums.iter().map(|h| h.geh).reduce(f64::max),
        hour_sums,
        speed_intervals: v.len(),
        speed_rmse_kmh: rmse(&v),
        speed_rmsne: rmsne(&v),
        speed_correlation: pearson(&v),
        per_station,
        hours,
        speeds,
    }
}

#[cfg(test)]
mod tests;

/// The hourly volumes summed over the stations of each hour.
fn sums_by_hour(hours: &[HourFit]) -> Vec<HourSum> {
    let mut by: BTreeMap<u32, (usize, f64, f64)> = BTreeMap::new();
    for h in hours {
        let e = by.entry(h.start_s).or_default();
        e.0 += 1;
        e.1 += h.sim_vph;
        e.2 += h.field_vph;
    }
    by.into_iter()
        .map(|(start_s, (stations, m, c))| HourSum {
            start_s,
            stations,
            sim_vph: m,
            field_vph: c,
            diff: (c > 0.0).then(|| (m - c) / c),
            geh: geh(m, c),
        })
        .collect()
}

/// Share of `items` for which `test` holds; `None` if empty.
fn share<T>(items: &[&T], test: impl Fn(&T) -> bool) -> Option<f64> {
    (!items.is_empty())
        .then(|| items.iter().filter(|i| test(i)).count() as f64 / items.len() as f64)
}

type Pairs = Vec<(Obs, Obs)>;

/// Both sides aggregated to `interval_s` and matched by (station, start): the pairs in
/// (station, start) order, the coverage, and the coverage per station.
fn pair(
    sim: &[Obs],
    field: &[Obs],
    interval_s: u32,
) -> (Pairs, Coverage, BTreeMap<String, Coverage>) {
    let index = |o: Vec<Obs>| -> BTreeMap<(String, u32), Obs> {
        o.into_iter()
            .map(|o| ((o.station.clone(), o.start_s), o))
            .collect()
    };
    let s = index(crate::aggregate::to_interval(sim, interval_s));
    let f = index(crate::aggregate::to_interval(field, interval_s));
    let mut pairs = Vec::new();
    let mut total = Coverage::default();
    let mut by_station: BTreeMap<String, Coverage> = BTreeMap::new();
    let keys: BTreeSet<&(String, u32)> = s.keys().chain(f.keys()).collect();
    for key in keys {
        let c = by_station.entry(key.0.clone()).or_default();
        match (s.get(key), f.get(key)) {
            (Some(m), Some(o)) => {
                pairs.push((m.clone(), o.clone()));
                total.matched += 1;
                c.matched += 1;
            }
            (Some(_), None) => {
                total.missing_in_field += 1;
                c.missing_in_field += 1;
            }
            _ => {
                total.missing_in_sim += 1;
                c.missing_in_sim += 1;
            }
        }
    }
    (pairs, total, by_station)
}
