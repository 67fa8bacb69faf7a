//! The demand step of a calibration (`[demand]` in the parameters file): before the
//! behaviour fit, the scenario's entrance demands and exit fractions are estimated from the
//! field counts ([`platoonsim_field::demand`]) and set as fixed keys, so every candidate and
//! `calibrated.toml` carry them.
//!
//! * The corridor comes from the scenario's `[network]` (entrance, on- and off-ramps by id).
//! * Mainline stations: with a placement (`--origin-pm`, `--stations`), the field stations
//!   placed as mainline (`ML`) inside the corridor; without one, the field stations named like
//!   a mainline detector of the scenario, at that detector's position. Ramp stations: the
//!   `[demand]` table, ramp id = station.
//! * Intervals: the network's `interval_s`, from `run.clock_start`, as many as cover
//!   `run.duration_s`. A station's count in an interval is the mean flow of its field
//!   intervals inside it, used only if they cover it entirely (a gap is never filled).
//! * Storage (issue 45 item 4): a station's density in an interval is the mean of q/v over its
//!   5-min data (all of them with a speed, else none); the vehicles stored between the
//!   entrance and each station ([`platoonsim_field::demand::stored_vehicles`]) are differenced
//!   between the neighbouring intervals (centred; one-sided at the ends), and that growth rate
//!   is added to the station's count: inside a growing queue the demand is what passed plus
//!   what queued. `demand.csv` reports the growth at the last station (`storage_vph`).
//! * Set keys: `network.mainline_vph`, `network.on_ramps[i].demand_vph`,
//!   `network.off_ramps[j].exit_fraction`, and `network.demand_offset_s = 0`,
//!   `network.base_demand_multiplier = 1`, `network.demand_scale = 1` (the estimate is the
//!   flow itself, at clock time).

use platoonsim_field::demand::{estimate, stored_vehicles, Corridor, Counts, Estimate};
use platoonsim_field::{Obs, StationKind};
use platoonsim_scenario::network::split_name;
use platoonsim_sim::{Config, DetectorKind};
use std::collections::BTreeMap;
use toml::Value;

/// The fixed keys that carry the estimate, and the estimate itself (for `demand.csv`).
pub struct Demand {
    pub set: Vec<(String, Value)>,
    pub estimate: Estimate,
    /// Interval starts (s after midnight).
    pub starts: Vec<u32>,
    /// Per interval, the growth rate of the vehicles stored on the corridor up to its last
    /// station with a count (veh/h): what the estimate added for queues.
    pub storage_vph: Vec<f64>,
    /// On-ramp and off-ramp ids, in corridor order.
    pub on_ids: Vec<String>,
    pub off_ids: Vec<String>,
}

/// Estimate the demand of `config` (loaded with `network.demand_offset_s = 0`) from the field.
pub fn demand(
    config: &Config,
    data: &super::Field,
    ramps: &[(String, String)],
) -> Result<Demand, String> {
    let field = &data.obs[..];
    let net = config.road.network.as_ref().ok_or(
        "[demand] estimates a network's entrance demands, and the scenario has no [network]",
    )?;
    let clock = config
        .clock_start_s
        .ok_or("[demand] needs run.clock_start to place the field counts")?;
    let id = |engine: &str| split_name(engine).0;
    let corridor = Corridor {
        entrance_x: 0.0,
        on_ramps: net.on_ramps.iter().map(|r| (id(&r.name), r.x_m)).collect(),
        off_ramps: net.off_ramps.iter().map(|r| (id(&r.name), r.x_m)).collect(),
    };
    for (ramp, station) in ramps {
        let known = corridor
            .on_ramps
            .iter()
            .chain(&corridor.off_ramps)
            .any(|(r, _)| r == ramp);
        if !known {
            let ids: Vec<&str> = corridor
                .on_ramps
                .iter()
                .chain(&corridor.off_ramps)
                .map(|(r, _)| r.as_str())
                .collect();
            return Err(format!(
                "demand.\"{ramp}\" = \"{station}\": the scenario has no ramp '{ramp}'; its ramps are {}",
                ids.join(", ")
            ));
        }
        if !field.iter().any(|o| &o.station == station) {
            return Err(format!(
                "demand.\"{ramp}\" = \"{station}\": the field data have no station '{station}'"
            ));
        }
    }
    // Engine coordinates (0 at the entrance); a placement is in the corridor's own.
    let mainline: BTreeMap<&str, f64> = if data.places.is_empty() {
        config
            .detectors
            .iter()
            .filter(|d| d.kind == DetectorKind::Mainline)
            .map(|d| (d.name.as_str(), d.position_m))
            .collect()
    } else {
        data.places
            .iter()
            .filter(|p| p.kind == StationKind::Mainline)
            .map(|p| (p.station.as_str(), p.x_m - net.origin_m))
            .filter(|&(_, x)| x > 0.0 && x < config.road.length_m)
            .collect()
    };
    let interval = net.interval_s;
    let n = (config.duration_s / interval).ceil().max(1.0) as usize;
    let starts: Vec<u32> = (0..n)
        .map(|k| clock + (k as f64 * interval).round() as u32)
        .collect();
    // Vehicles stored up to each station, per interval (None: no density for the interval).
    let stored: Vec<BTreeMap<&str, f64>> = starts
        .iter()
        .map(|&t0| {
            let t1 = t0 + interval.round() as u32;
            let mut k: Vec<(f64, f64)> = mainline
                .iter()
                .filter_map(|(st, &x)| covering_density(field, st, t0, t1).map(|d| (x, d)))
                .collect();
            k.sort_by(|a, b| a.0.total_cmp(&b.0));
            mainline
                .iter()
                .map(|(st, &x)| (*st, stored_vehicles(&k, x)))
                .collect()
        })
        .collect();
    let growth = |k: usize, station: &str| -> f64 {
        let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
        if a == b {
            return 0.0;
        }
        let (na, nb) = (stored[a].get(station), stored[b].get(station));
        match (na, nb) {
            (Some(na), Some(nb)) => (nb - na) / ((b - a) as f64 * interval / 3600.0),
            _ => 0.0,
        }
    };
    let mut storage_vph = Vec::with_capacity(n);
    let mut counts = Vec::with_capacity(n);
    for (k, &t0) in starts.iter().enumerate() {
        let t1 = t0 + interval.round() as u32;
        let mean = |station: &str| covering_mean(field, station, t0, t1);
        let mut c = Counts::default();
        let mut last: Option<(f64, f64)> = None;
        for (station, &x) in &mainline {
            if let Some(q) = mean(station) {
                c.mainline.push((x, q));
                let g = growth(k, station);
                c.storage_vph.push(g);
                if last.is_none_or(|(xl, _)| x > xl) {
                    last = Some((x, g));
                }
            }
        }
        storage_vph.push(last.map_or(0.0, |(_, g)| g));
        for (ramp, station) in ramps {
            if let Some(q) = mean(station) {
                c.ramps.push((ramp.clone(), q));
            }
        }
        counts.push(c);
    }
    let est = estimate(&corridor, &counts).map_err(|e| {
        format!(
            "{e} (intervals of {interval} s from {}; mainline stations are the field stations named \
             like the scenario's detectors: {})",
            platoonsim_scenario::clock::format_clock(clock),
            mainline.keys().copied().collect::<Vec<_>>().join(", ")
        )
    })?;
    let series = |v: &[f64]| Value::Array(v.iter().map(|&x| Value::Float(x)).collect());
    let mut set = vec![
        ("network.demand_offset_s".to_string(), Value::Float(0.0)),
        (
            "network.base_demand_multiplier".to_string(),
            Value::Float(1.0),
        ),
        ("network.demand_scale".to_string(), Value::Float(1.0)),
        (
            "network.mainline_vph".to_string(),
            series(&est.mainline_vph),
        ),
    ];
    for (i, s) in est.on_ramp_vph.iter().enumerate() {
        set.push((format!("network.on_ramps[{i}].demand_vph"), series(s)));
    }
    for (j, s) in est.exit_fraction.iter().enumerate() {
        set.push((format!("network.off_ramps[{j}].exit_fraction"), series(s)));
    }
    Ok(Demand {
        set,
        starts,
        storage_vph,
        on_ids: corridor.on_ramps.iter().map(|r| r.0.clone()).collect(),
        off_ids: corridor.off_ramps.iter().map(|r| r.0.clone()).collect(),
        estimate: est,
    })
}

/// The mean density (veh/km, all lanes) of `station` over [t0, t1): the mean of q/v over its
/// data, if they cover the interval and every one has a speed > 0.
fn covering_density(field: &[Obs], station: &str, t0: u32, t1: u32) -> Option<f64> {
    let mut covered = 0u32;
    let mut sum = 0.0;
    for o in field.iter().filter(|o| o.station == station) {
        if o.start_s >= t0 && o.start_s + o.interval_s <= t1 {
            let v = o.speed_kmh.filter(|&v| v > 0.0)?;
            covered += o.interval_s;
            sum += o.flow_vph / v * f64::from(o.interval_s);
        }
    }
    (covered == t1 - t0 && covered > 0).then(|| sum / f64::from(covered))
}

/// The mean flow of a station's intervals inside [t0, t1), if they cover it exactly.
fn covering_mean(field: &[Obs], station: &str, t0: u32, t1: u32) -> Option<f64> {
    let mut covered = 0u32;
    let mut sum = 0.0;
    for o in field.iter().filter(|o| o.station == station) {
        if o.start_s >= t0 && o.start_s + o.interval_s <= t1 {
            covered += o.interval_s;
            sum += o.flow_vph * f64::from(o.interval_s);
        }
    }
    (covered == t1 - t0 && covered > 0).then(|| sum / f64::from(covered))
}

/// `demand.csv`: one row per interval (clock time), the entrance flow, each on-ramp's flow
/// and each off-ramp's exit flow and fraction, then the storage growth the estimate added.
pub fn csv(d: &Demand) -> Result<Vec<u8>, String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut header = vec!["time".to_string(), "mainline_vph".to_string()];
    header.extend(d.on_ids.iter().map(|i| format!("{i}_vph")));
    for i in &d.off_ids {
        header.push(format!("{i}_exit_vph"));
        header.push(format!("{i}_exit_fraction"));
    }
    header.push("storage_vph".to_string());
    w.write_record(&header).map_err(|e| e.to_string())?;
    for (k, &t) in d.starts.iter().enumerate() {
        let mut row = vec![
            platoonsim_scenario::clock::format_clock(t),
            format!("{}", d.estimate.mainline_vph[k]),
        ];
        row.extend(d.estimate.on_ramp_vph.iter().map(|s| format!("{}", s[k])));
        for j in 0..d.off_ids.len() {
            row.push(format!("{}", d.estimate.exit_vph[j][k]));
            row.push(format!("{}", d.estimate.exit_fraction[j][k]));
        }
        row.push(format!("{}", d.storage_vph[k]));
        w.write_record(&row).map_err(|e| e.to_string())?;
    }
    w.into_inner().map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn obs(t: u32, interval: u32, flow: f64) -> Obs {
        Obs {
            station: "S".into(),
            start_s: t,
            interval_s: interval,
            flow_vph: flow,
            speed_kmh: None,
            occupancy: None,
        }
    }

    #[test]
    fn a_count_covers_its_interval_or_is_missing() {
        let f = [
            obs(0, 300, 1000.0),
            obs(300, 300, 2000.0),
            obs(900, 300, 10.0),
        ];
        assert_eq!(covering_mean(&f, "S", 0, 600), Some(1500.0));
        // 600-900 is missing: never filled in.
        assert_eq!(covering_mean(&f, "S", 600, 1200), None);
        assert_eq!(covering_mean(&f, "T", 0, 600), None);
    }
}
