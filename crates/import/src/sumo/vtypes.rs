//! Vehicle types onto the model's `[human]` parameters.
//!
//! | SUMO `vType` | model key | how |
//! |---|---|---|
//! | `length` (m) | `human.length_m` | mean, sd, min, max over the demand's types |
//! | `accel` (m/s²) | `human.max_accel` | as above |
//! | `decel` (m/s²) | `human.max_decel` | negated |
//! | `maxSpeed` (m/s) | `human.desired_speed_kmh` | caps the distribution when every type sets a cap below its maximum |
//!
//! A key is written only when some type used by the demand sets the attribute; a type that
//! does not takes SUMO's default for its `vClass` (table below). Several types become one
//! truncated normal: the demand-weighted mean and standard deviation, bounded by the types'
//! smallest and largest values (a reduction, noted). Every other attribute is listed as
//! ignored.

use super::routes::Routes;
use crate::Notes;
use std::collections::BTreeMap;
use toml::{Table, Value};

/// SUMO's defaults by vehicle class (SUMO's vehicle type documentation): length (m), accel,
/// decel (m/s²), maxSpeed (m/s).
fn sumo_default(vclass: &str, attr: &str) -> f64 {
    let (len, acc, dec, vmax) = match vclass {
        "truck" => (7.1, 1.3, 4.0, 36.11),
        "trailer" => (16.5, 1.1, 4.0, 36.11),
        "bus" => (12.0, 1.2, 4.0, 27.78),
        "delivery" => (6.5, 2.6, 4.5, 55.56),
        "motorcycle" => (2.2, 6.0, 10.0, 55.56),
        _ => (5.0, 2.6, 4.5, 55.56), // passenger and every other class
    };
    match attr {
        "length" => len,
        "accel" => acc,
        "decel" => dec,
        _ => vmax,
    }
}

const MAPPED: [&str; 4] = ["length", "accel", "decel", "maxSpeed"];
/// Attributes that only name or draw a type: neither mapped nor worth a note.
const QUIET: [&str; 5] = ["id", "probability", "color", "guiShape", "vClass"];

/// Demand shares per concrete type, distributions resolved.
fn shares(routes: &Routes, by_type: &BTreeMap<String, f64>) -> BTreeMap<String, f64> {
    let mut out = BTreeMap::new();
    for (t, veh) in by_type {
        match routes.vtype_dists.get(t) {
            Some(members) => {
                for (m, p) in members {
                    *out.entry(m.clone()).or_insert(0.0) += veh * p;
                }
            }
            None => *out.entry(t.clone()).or_insert(0.0) += *veh,
        }
    }
    out
}

fn dist(mean: f64, sd: f64, min: f64, max: f64) -> Value {
    let mut t = Table::new();
    t.insert("mean".into(), Value::Float(round(mean)));
    t.insert("sd".into(), Value::Float(round(sd)));
    t.insert("min".into(), Value::Float(round(min)));
    t.insert("max".into(), Value::Float(round(max)));
    Value::Table(t)
}

fn round(v: f64) -> f64 {
    (v * 1e6).round() / 1e6
}

/// The `[human]` keys the demand's vehicle types give, with notes. `desired` is the model's
/// desired-speed distribution (km/h: mean, sd, min, max) that `maxSpeed` may cap.
pub fn human(
    routes: &Routes,
    by_type: &BTreeMap<String, f64>,
    desired: (f64, f64, f64, f64),
    notes: &mut Notes,
) -> Table {
    let shares = shares(routes, by_type);
    let total: f64 = shares.values().sum();
    let mut out = Table::new();
    if total <= 0.0 {
        return out;
    }
    let used: Vec<(&String, f64)> = shares.iter().map(|(t, v)| (t, v / total)).collect();
    let attr = |t: &str, a: &str| -> Option<f64> {
        routes
            .vtypes
            .get(t)?
            .attrs
            .get(a)?
            .trim()
            .parse::<f64>()
            .ok()
    };
    let vclass = |t: &str| -> String {
        routes
            .vtypes
            .get(t)
            .and_then(|v| v.attrs.get("vClass").cloned())
            .unwrap_or_else(|| "passenger".into())
    };
    let mut ignored: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (t, _) in &used {
        if let Some(v) = routes.vtypes.get(*t) {
            for k in v.attrs.keys() {
                if !MAPPED.contains(&k.as_str()) && !QUIET.contains(&k.as_str()) {
                    ignored.entry(k.clone()).or_default().push((*t).clone());
                }
            }
        }
    }
    for a in MAPPED {
        if !used.iter().any(|(t, _)| attr(t, a).is_some()) {
            continue;
        }
        let vals: Vec<(f64, f64)> = used
            .iter()
            .map(|(t, w)| {
                (
                    attr(t, a).unwrap_or_else(|| sumo_default(&vclass(t), a)),
                    *w,
                )
            })
            .filter(|(v, _)| v.is_finite() && *v > 0.0)
            .collect();
        if vals.is_empty() {
            continue;
        }
        let mean: f64 = vals.iter().map(|(v, w)| v * w).sum();
        let var: f64 = vals.iter().map(|(v, w)| w * (v - mean).powi(2)).sum();
        let min = vals.iter().map(|v| v.0).fold(f64::INFINITY, f64::min);
        let max = vals.iter().map(|v| v.0).fold(0.0, f64::max);
        if min < max {
            notes.reduce(format!(
                "vType {a} of {} types as one distribution: mean {mean:.2}, sd {:.2}, [{min}, {max}]",
                vals.len(),
                var.sqrt()
            ));
        }
        match a {
            "length" => {
                out.insert("length_m".into(), dist(mean, var.sqrt(), min, max));
            }
            "accel" => {
                out.insert("max_accel".into(), dist(mean, var.sqrt(), min, max));
            }
            "decel" => {
                out.insert("max_decel".into(), dist(-mean, var.sqrt(), -max, -min));
            }
            _ => {
                // maxSpeed: a cap on the desired speed, if every type caps below the model's max.
                let cap = max * 3.6;
                let (d_mean, d_sd, d_min, d_max) = desired;
                if cap < d_max {
                    out.insert(
                        "desired_speed_kmh".into(),
                        dist(d_mean.min(cap), d_sd, d_min.min(cap), cap),
                    );
                    notes.keep(format!(
                        "vType maxSpeed {:.1} km/h caps the desired speed (model's {d_min}-{d_max} km/h)",
                        cap
                    ));
                } else if min * 3.6 < d_max {
                    notes.reduce(format!(
                        "vType maxSpeed below the model's desired speeds for some types ({:.1} km/h \
                         and up): one desired-speed distribution for all drivers, not capped",
                        min * 3.6
                    ));
                }
                continue;
            }
        }
        notes.keep(format!(
            "vType {a} -> human.{}",
            match a {
                "length" => "length_m",
                "accel" => "max_accel",
                _ => "max_decel",
            }
        ));
    }
    for (k, types) in ignored {
        notes.drop(format!(
            "vType attribute {k} (types {}): no model parameter",
            types.join(", ")
        ));
    }
    out
}
