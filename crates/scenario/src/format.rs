//! The way back: a resolved [`Config`] as a complete scenario file (every key written out),
//! which loads again to the same `Config`.

use crate::network::{detectors, split_name, stretches, RampStations, Spacing, END_DETECTOR};
use crate::raw::{
    RawBehaviour, RawDemand, RawDetector, RawLaneStretch, RawMeasurement, RawMeter, RawNetwork,
    RawNetworkDetectors, RawOffRamp, RawOnRamp, RawRoad, RawRun, RawScenario, RawStrategy, RawTime,
};
use platoonsim_sim::config::{DetectorKind, Meter, MeterLaw, Network};
use platoonsim_sim::{Config, LaneChoice, Strategy};
use toml::{Table, Value};

/// A [`RawScenario`] with every key set to the config's value. With a network, positions are
/// written in the corridor coordinate, the generated detectors are left to the generator (its
/// spacing is read back from their positions), and `demand_scale` is the total scale (with
/// `base_demand_multiplier = 1`).
pub fn to_raw(config: &Config, description: Option<String>) -> RawScenario {
    let origin = config.road.origin_m();
    let file = |x: f64| x + origin;
    let mut strategy = RawStrategy::default();
    let Strategy {
        kind,
        pd,
        thresholds,
    } = &config.strategy;
    strategy.kind = Some(kind.as_str().to_string());
    if let Some(pd) = pd {
        strategy.zone_start_m = Some(file(pd.zone_start_m));
        strategy.zone_end_m = Some(file(pd.zone_end_m));
        strategy.start_s = Some(pd.start_s);
        strategy.end_s = Some(pd.end_s);
        strategy.lane = match pd.lane {
            LaneChoice::Leftmost => None,
            LaneChoice::Rightmost => Some(Value::String("rightmost".into())),
            LaneChoice::Index(i) => Some(Value::Integer(i64::from(i) + 1)),
        };
    }
    if let Some(t) = thresholds {
        strategy.flow_threshold_vphpl = Some(t.flow_threshold_vphpl);
        strategy.speed_threshold_kmh = Some(t.speed_threshold_kmh);
        strategy.radius_m = Some(t.radius_m);
    }
    let (network, generated) = match &config.road.network {
        Some(n) => {
            let (raw, generated) = raw_network(n, config);
            (Some(raw), generated)
        }
        None => (None, Vec::new()),
    };
    let is_network = network.is_some();
    RawScenario {
        // Every behaviour key is written out, so the file needs no preset (`show` names the
        // one it ran under).
        model: Default::default(),
        name: Some(config.name.clone()),
        description,
        run: RawRun {
            seed: Some(config.seed),
            dt_s: Some(config.dt_s),
            duration_s: Some(config.duration_s),
            warmup_s: Some(config.warmup_s),
            penetration: Some(config.penetration),
            clock_start: config.clock_start_s.map(crate::clock::format_clock),
        },
        road: RawRoad {
            lanes: (!is_network).then_some(config.road.lanes),
            length_m: (!is_network).then_some(config.road.length_m),
            control_start_m: Some(file(config.road.control_start_m)),
            control_end_m: Some(file(config.road.control_end_m)),
        },
        network,
        demand: RawDemand {
            vph_per_lane: (!is_network).then_some(config.demand.vph_per_lane),
        },
        detectors: config
            .detectors
            .iter()
            .filter(|d| !generated.contains(&d.name))
            .map(|d| RawDetector {
                name: Some(d.name.clone()),
                position_m: Some(file(d.position_m)),
            })
            .collect(),
        measurement: RawMeasurement {
            detector: config
                .detectors
                .get(config.measurement_detector)
                .map(|d| d.name.clone()),
            aggregation_s: Some(config.aggregation_s),
            mechanism: config.mechanism.then_some(true),
        },
        strategy,
        human: config.human,
        cav: config.cav.clone(),
        lane_change: config.lane_change,
        safety: config.safety,
        energy: config.energy,
    }
}

/// The `[network]` section of a config, and the names of the detectors it generates.
fn raw_network(n: &Network, config: &Config) -> (RawNetwork, Vec<String>) {
    let o = n.origin_m;
    let length = config.road.length_m;
    let position = |name: &str| {
        config
            .detectors
            .iter()
            .find(|d| d.name == name && d.kind == DetectorKind::Mainline)
            .map(|d| d.position_m)
    };
    let on: Vec<(String, String)> = n.on_ramps.iter().map(|r| split_name(&r.name)).collect();
    let off: Vec<(String, String)> = n.off_ramps.iter().map(|r| split_name(&r.name)).collect();
    // The spacing of the generated detectors, from any of them that was kept.
    let mut spacing = Spacing::default();
    let ups = n
        .on_ramps
        .iter()
        .zip(&on)
        .map(|(r, (id, _))| (r.x_m, id))
        .chain(n.off_ramps.iter().zip(&off).map(|(r, (id, _))| (r.x_m, id)));
    if let Some(d) = ups
        .filter_map(|(x, id)| position(&format!("{id}-up")).map(|p| x - p))
        .next()
    {
        spacing.upstream_of_ramps_m = d;
    }
    if let Some(d) = n
        .on_ramps
        .iter()
        .zip(&on)
        .find_map(|(r, (id, _))| position(&format!("{id}-down")).map(|p| p - r.x_m))
    {
        spacing.downstream_of_onramps_m = d;
    }
    if let Some(p) = position(END_DETECTOR) {
        spacing.before_end_m = length - p;
    }
    let on_ids: Vec<String> = on.iter().map(|(id, _)| id.clone()).collect();
    let off_ids: Vec<String> = off.iter().map(|(id, _)| id.clone()).collect();
    // A ramp's station is the name of its counter (an off-ramp's, unless it is `{id}-off`).
    let counter = |kind: DetectorKind| {
        config
            .detectors
            .iter()
            .find(|d| d.kind == kind)
            .map(|d| d.name.clone())
    };
    let stations = RampStations {
        on: (0..n.on_ramps.len())
            .map(|i| counter(DetectorKind::OnRamp { ramp: i }))
            .collect(),
        off: (0..n.off_ramps.len())
            .map(|i| counter(DetectorKind::OffRamp { ramp: i }))
            .zip(&off_ids)
            .map(|(name, id)| name.filter(|s| *s != format!("{id}-off")))
            .collect(),
    };
    let generated = detectors(n, length, &on_ids, &off_ids, &stations, &spacing)
        .into_iter()
        .map(|d| d.name)
        .collect();
    let named = |id: &str, name: &str| (name != id).then(|| name.to_string());
    let raw = RawNetwork {
        start_m: Some(o),
        end_m: Some(o + length),
        interval_s: Some(n.interval_s),
        // The series below are already read at the offset (validation shifts them).
        demand_offset_s: None,
        mainline_vph: Some(n.mainline_vph.clone()),
        base_demand_multiplier: Some(1.0),
        demand_scale: Some(n.demand_scale),
        // The scale is resolved: the file names no table.
        demand_scale_table: None,
        ramp_speed_kmh: Some(n.ramp_speed_kmh),
        // Off (empty) stays unwritten, as in the files before the key existed.
        lane_speed_limits_kmh: (!n.lane_speed_limits_kmh.is_empty())
            .then(|| n.lane_speed_limits_kmh.clone()),
        cross_lane_friction: n.cross_lane_friction,
        detectors: RawNetworkDetectors {
            upstream_of_ramps_m: Some(spacing.upstream_of_ramps_m),
            downstream_of_onramps_m: Some(spacing.downstream_of_onramps_m),
            before_end_m: Some(spacing.before_end_m),
        },
        lanes: stretches(&n.through_lanes)
            .into_iter()
            .map(|s| RawLaneStretch {
                from_m: Some(s.from_m + o),
                to_m: Some(s.to_m + o),
                count: Some(s.count),
            })
            .collect(),
        on_ramps: n
            .on_ramps
            .iter()
            .zip(&on)
            .enumerate()
            .map(|(i, (r, (id, name)))| RawOnRamp {
                id: Some(id.clone()),
                name: named(id, name),
                x_m: Some(r.x_m + o),
                accel_lane_m: Some(r.accel_lane_m),
                ramp_length_m: Some(r.ramp_length_m),
                demand_vph: Some(r.demand_vph.clone()),
                station: stations.on[i].clone(),
                meter: r.meter.as_ref().map(raw_meter),
                penetration: r.penetration,
            })
            .collect(),
        off_ramps: n
            .off_ramps
            .iter()
            .zip(&off)
            .enumerate()
            .map(|(i, (r, (id, name)))| RawOffRamp {
                id: Some(id.clone()),
                name: named(id, name),
                x_m: Some(r.x_m + o),
                exit_fraction: Some(r.exit_fraction.clone()),
                station: stations.off[i].clone(),
            })
            .collect(),
        behaviour: n
            .behaviour
            .iter()
            .map(|b| RawBehaviour {
                from_m: Some(b.from_m + o),
                to_m: Some(b.to_m + o),
                buffer_factor: Some(b.buffer_factor),
                speed_factor: Some(b.speed_factor),
            })
            .collect(),
    };
    (raw, generated)
}

/// A meter with every key written out (its hours in simulated seconds).
fn raw_meter(m: &Meter) -> RawMeter {
    let mut raw = RawMeter {
        kind: Some(m.law.name().to_string()),
        queue_max_veh: m.queue_max_veh.map(i64::from),
        from: Some(RawTime::Seconds(m.from_s)),
        to: m.to_s.map(RawTime::Seconds),
        ..RawMeter::default()
    };
    match &m.law {
        MeterLaw::Fixed { rate_vph } => raw.rate_vph = Some(*rate_vph),
        MeterLaw::Alinea { law, detector_m } => {
            raw.occupancy_target_pct = Some(law.occupancy_target_pct);
            raw.gain_vph = Some(law.gain_vph);
            raw.min_rate_vph = Some(law.min_rate_vph);
            raw.max_rate_vph = Some(law.max_rate_vph);
            raw.period_s = Some(law.period_s);
            raw.detector_m = Some(*detector_m);
        }
    }
    raw
}

/// A resolved scenario as TOML text: one `[section]` per table, distributions as inline tables.
pub fn to_toml(config: &Config, description: Option<String>) -> String {
    let raw = to_raw(config, description);
    match Value::try_from(&raw) {
        Ok(Value::Table(t)) => pretty(&t),
        // A Config always serializes; keep the library panic-free regardless.
        Ok(_) | Err(_) => format!("# cannot render scenario '{}' as TOML\n", config.name),
    }
}

/// Lay out a document: top-level plain values, then each table as a section with inline
/// values (followed by its own arrays of tables as `[[section.name]]` blocks), then arrays of
/// tables as `[[name]]` blocks, in the document's key order.
pub fn pretty(doc: &Table) -> String {
    let mut out = String::new();
    let is_table_array =
        |v: &Value| matches!(v, Value::Array(a) if !a.is_empty() && a.iter().all(Value::is_table));
    for (k, v) in doc {
        if !v.is_table() && !is_table_array(v) {
            out.push_str(&format!("{k} = {v}\n"));
        }
    }
    for (k, v) in doc {
        match v {
            Value::Table(t) => {
                out.push_str(&format!("\n[{k}]\n"));
                for (kk, vv) in t {
                    if !is_table_array(vv) {
                        out.push_str(&format!("{kk} = {vv}\n"));
                    }
                }
                // Arrays of tables inside a section ([[network.on_ramps]]) as blocks.
                for (kk, vv) in t {
                    if let Value::Array(items) = vv {
                        if is_table_array(vv) {
                            for item in items {
                                out.push_str(&format!("\n[[{k}.{kk}]]\n"));
                                if let Value::Table(it) = item {
                                    for (x, y) in it {
                                        out.push_str(&format!("{x} = {y}\n"));
                                    }
                                }
                            }
                        }
                    }
                }
            }
            Value::Array(items) if is_table_array(v) => {
                for item in items {
                    out.push_str(&format!("\n[[{k}]]\n"));
                    if let Value::Table(t) = item {
                        for (kk, vv) in t {
                            out.push_str(&format!("{kk} = {vv}\n"));
                        }
                    }
                }
            }
            _ => {}
        }
    }
    out
}
