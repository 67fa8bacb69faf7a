//! The way back: a resolved [`Config`] as a complete scenario file (every key written out),
//! which loads again to the same `Config`.

use crate::raw::{
    RawDemand, RawDetector, RawMeasurement, RawRoad, RawRun, RawScenario, RawStrategy,
};
use platoonsim_sim::{Config, Strategy};
use toml::{Table, Value};

/// A [`RawScenario`] with every key set to the config's value.
pub fn to_raw(config: &Config, description: Option<String>) -> RawScenario {
    let mut strategy = RawStrategy::default();
    let (kind, pd, thresholds) = match &config.strategy {
        Strategy::None => ("none", None, None),
        Strategy::Pd { pd } => ("pd", Some(pd), None),
        Strategy::FlowAware { pd, thresholds } => ("flow-aware", Some(pd), Some(thresholds)),
    };
    strategy.kind = Some(kind.to_string());
    if let Some(pd) = pd {
        strategy.zone_start_m = Some(pd.zone_start_m);
        strategy.zone_end_m = Some(pd.zone_end_m);
        strategy.start_s = Some(pd.start_s);
        strategy.end_s = Some(pd.end_s);
    }
    if let Some(t) = thresholds {
        strategy.flow_threshold_vphpl = Some(t.flow_threshold_vphpl);
        strategy.speed_threshold_kmh = Some(t.speed_threshold_kmh);
        strategy.radius_m = Some(t.radius_m);
    }
    RawScenario {
        name: Some(config.name.clone()),
        description,
        run: RawRun {
            seed: Some(config.seed),
            dt_s: Some(config.dt_s),
            duration_s: Some(config.duration_s),
            warmup_s: Some(config.warmup_s),
            penetration: Some(config.penetration),
        },
        road: RawRoad {
            lanes: Some(config.road.lanes),
            length_m: Some(config.road.length_m),
            control_start_m: Some(config.road.control_start_m),
            control_end_m: Some(config.road.control_end_m),
        },
        demand: RawDemand {
            vph_per_lane: Some(config.demand.vph_per_lane),
        },
        detectors: config
            .detectors
            .iter()
            .map(|d| RawDetector {
                name: Some(d.name.clone()),
                position_m: Some(d.position_m),
            })
            .collect(),
        measurement: RawMeasurement {
            detector: config
                .detectors
                .get(config.measurement_detector)
                .map(|d| d.name.clone()),
            aggregation_s: Some(config.aggregation_s),
        },
        strategy,
        human: config.human,
        cav: config.cav.clone(),
        lane_change: config.lane_change,
    }
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
/// values, then arrays of tables as `[[name]]` blocks, in the document's key order.
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
                    out.push_str(&format!("{kk} = {vv}\n"));
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
