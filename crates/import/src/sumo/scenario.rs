//! The imported corridor as a scenario file: a header saying where it came from and what was
//! kept, reduced and dropped, then `[run]`, `[network]` (lanes, ramps, demand series),
//! `[[detectors]]` and the `[human]` keys the vehicle types give. Positions and the series are
//! rounded to 0.001 (mm, and 0.001 veh/h or 1e-6 of a fraction): the file is meant to be read.

use super::additional::OnCorridor;
use super::corridor::Corridor;
use super::demand::Series;
use crate::Notes;
use toml::{Table, Value};

fn r3(v: f64) -> Value {
    Value::Float((v * 1e3).round() / 1e3)
}
fn r6(v: f64) -> Value {
    Value::Float((v * 1e6).round() / 1e6)
}
fn list(v: &[f64], f: fn(f64) -> Value) -> Value {
    Value::Array(v.iter().map(|&x| f(x)).collect())
}
fn s(v: &str) -> Value {
    Value::String(v.to_string())
}

pub struct Parts<'a> {
    pub name: &'a str,
    pub description: String,
    pub corridor: &'a Corridor,
    pub series: &'a Series,
    pub duration_s: f64,
    pub detectors: &'a OnCorridor,
    /// Extra `[[detectors]]` (name, x): `--edge-detectors`.
    pub edge_detectors: &'a [(String, f64)],
    pub ramp_speed_kmh: Option<f64>,
    pub lane_speed_limit_kmh: Option<f64>,
    pub human: Table,
}

pub fn table(p: &Parts) -> Table {
    let c = p.corridor;
    let mut doc = Table::new();
    doc.insert("name".into(), s(p.name));
    doc.insert("description".into(), s(&p.description));
    let mut run = Table::new();
    run.insert("duration_s".into(), r3(p.duration_s));
    run.insert("warmup_s".into(), Value::Float(0.0));
    run.insert("penetration".into(), Value::Float(0.0));
    doc.insert("run".into(), Value::Table(run));

    let mut net = Table::new();
    net.insert("start_m".into(), Value::Float(0.0));
    net.insert("end_m".into(), r3(c.length));
    net.insert("interval_s".into(), r3(p.series.interval_s));
    net.insert("mainline_vph".into(), list(&p.series.mainline_vph, r3));
    if let Some(v) = p.ramp_speed_kmh {
        net.insert("ramp_speed_kmh".into(), r3(v));
    }
    if let Some(v) = p.lane_speed_limit_kmh {
        net.insert("lane_speed_limits_kmh".into(), Value::Array(vec![r3(v)]));
    }
    let lanes = c
        .stretches
        .iter()
        .map(|&(from, to, count)| {
            let mut t = Table::new();
            t.insert("from_m".into(), r3(from));
            t.insert("to_m".into(), r3(to));
            t.insert("count".into(), Value::Integer(count as i64));
            Value::Table(t)
        })
        .collect();
    net.insert("lanes".into(), Value::Array(lanes));
    let on = c
        .on_ramps
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let mut t = Table::new();
            t.insert("id".into(), s(&r.id));
            t.insert("name".into(), s(&r.name));
            t.insert("x_m".into(), r3(r.x));
            if let Some(a) = r.accel_lane_m {
                t.insert("accel_lane_m".into(), r3(a));
            }
            t.insert("ramp_length_m".into(), r3(r.ramp_length_m));
            t.insert("demand_vph".into(), list(&p.series.on_ramp_vph[i], r3));
            if let Some(st) = p.detectors.on_station.get(&i) {
                t.insert("station".into(), s(st));
            }
            Value::Table(t)
        })
        .collect::<Vec<_>>();
    if !on.is_empty() {
        net.insert("on_ramps".into(), Value::Array(on));
    }
    let off = c
        .off_ramps
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let mut t = Table::new();
            t.insert("id".into(), s(&r.id));
            t.insert("name".into(), s(&r.name));
            t.insert("x_m".into(), r3(r.x));
            t.insert("exit_fraction".into(), list(&p.series.exit_fraction[i], r6));
            if let Some(st) = p.detectors.off_station.get(&i) {
                t.insert("station".into(), s(st));
            }
            Value::Table(t)
        })
        .collect::<Vec<_>>();
    if !off.is_empty() {
        net.insert("off_ramps".into(), Value::Array(off));
    }
    doc.insert("network".into(), Value::Table(net));

    let dets: Vec<Value> = p
        .detectors
        .mainline
        .iter()
        .map(|d| (d.name.as_str(), d.x))
        .chain(p.edge_detectors.iter().map(|(n, x)| (n.as_str(), *x)))
        .map(|(name, x)| {
            let mut t = Table::new();
            t.insert("name".into(), s(name));
            t.insert("position_m".into(), r3(x));
            Value::Table(t)
        })
        .collect();
    if !dets.is_empty() {
        doc.insert("detectors".into(), Value::Array(dets));
    }
    if !p.human.is_empty() {
        doc.insert("human".into(), Value::Table(p.human.clone()));
    }
    doc
}

/// The file's header: provenance, then the notes, as comments.
pub fn header(sources: &[String], notes: &Notes, speed_data: &[String]) -> String {
    let mut h = String::from("# Imported by `platoonsim import sumo` (docs/import.md) from:\n");
    for s in sources {
        h.push_str(&format!("#   {}\n", printable(s)));
    }
    h.push_str("#\n# What the import did:\n");
    for line in notes.to_string().lines() {
        h.push_str(&format!("#   {}\n", printable(line)));
    }
    if !speed_data.is_empty() {
        h.push_str("#\n# Speed limits of the mainline (km/h) from each edge where they change, kept as data:\n");
        for line in speed_data {
            h.push_str(&format!("#   {}\n", printable(line)));
        }
    }
    h.push('\n');
    h
}

/// A comment line may not hold control characters (ids and names come from the files).
fn printable(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_control() { '?' } else { c })
        .collect()
}
