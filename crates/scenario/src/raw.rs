//! Level one: the scenario file as written. Serde structs with `deny_unknown_fields`, every
//! number kept as written (`Option` where the file may leave it out); nothing is checked here
//! but the shape. [`crate::validate`] turns a [`RawScenario`] into a
//! [`platoonsim_sim::Config`].
//!
//! The model sections (`[human]`, `[cav]`, `[lane_change]`) are the model crate's own
//! parameter structs; keys left out take the model specification's defaults, including single
//! fields of a distribution (`human.desired_speed_kmh.mean = 100` keeps the default sd, min
//! and max).

use crate::error::{clip_lines, ScenarioError, MAX_ECHO_CHARS};
use platoonsim_model::cav::CavParams;
use platoonsim_model::energy::EnergyParams;
use platoonsim_model::human::HumanDists;
use platoonsim_model::lanechange::LaneChangeDists;
use platoonsim_model::safety::SafetyParams;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use toml::{Table, Value};

/// A whole scenario file.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawScenario {
    /// Scenario name (copied into the summary). Default: the file name without extension.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Free text, shown by `platoonsim scenarios`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// `[model]`: the preset the behaviour keys default to (`preset.rs`); written only when
    /// set.
    #[serde(skip_serializing_if = "RawModel::is_empty")]
    pub model: RawModel,
    pub run: RawRun,
    pub road: RawRoad,
    /// A freeway corridor with ramps (issue 4); without it the road is homogeneous.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub network: Option<RawNetwork>,
    #[serde(skip_serializing_if = "RawDemand::is_empty")]
    pub demand: RawDemand,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub detectors: Vec<RawDetector>,
    pub measurement: RawMeasurement,
    pub strategy: RawStrategy,
    pub human: HumanDists,
    pub cav: CavParams,
    pub lane_change: LaneChangeDists,
    pub safety: SafetyParams,
    /// Fuel and electricity per vehicle (docs/energy.md); written only when not the default.
    #[serde(skip_serializing_if = "EnergyParams::is_default")]
    pub energy: EnergyParams,
}

/// `[model]`: `preset = "paper" | "platform"` (`preset.rs`; applied to the document before
/// this level reads it).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawModel {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub preset: Option<crate::preset::Preset>,
}

impl RawModel {
    pub fn is_empty(&self) -> bool {
        self.preset.is_none()
    }
}

/// `[run]`: seed, step, duration, warm-up, CAV share. All optional.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawRun {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dt_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub duration_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub warmup_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub penetration: Option<f64>,
    /// Clock time of t = 0, "HH:MM" or "HH:MM:SS" (validated in `validate_run.rs`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub clock_start: Option<String>,
}

/// `[road]`: all keys required, except with a `[network]`, which gives the lanes and the length
/// (and where the control section defaults to the whole corridor).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawRoad {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lanes: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub length_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub control_start_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub control_end_m: Option<f64>,
}

/// `[demand]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawDemand {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vph_per_lane: Option<f64>,
}

impl RawDemand {
    pub fn is_empty(&self) -> bool {
        self.vph_per_lane.is_none()
    }
}

/// `[network]`: a freeway corridor. Every position is in the corridor's own coordinate (e.g.
/// metres downstream of a reference ramp); the mainline entrance is at `start_m`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawNetwork {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub start_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub end_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interval_s: Option<f64>,
    /// Demand time offset (s): the simulation clock t reads every demand and exit-fraction
    /// series at t + offset (default 0; see `docs/network-scenarios.md`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub demand_offset_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mainline_vph: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub base_demand_multiplier: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub demand_scale: Option<f64>,
    /// The table by penetration that `demand_scale` defaults to: a built-in table's name or a
    /// file path ([`crate::tables`]). Without it (and without `demand_scale`) the scale is 1.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub demand_scale_table: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ramp_speed_kmh: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lane_speed_limits_kmh: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cross_lane_friction: Option<f64>,
    #[serde(skip_serializing_if = "RawNetworkDetectors::is_empty")]
    pub detectors: RawNetworkDetectors,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub lanes: Vec<RawLaneStretch>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub on_ramps: Vec<RawOnRamp>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub off_ramps: Vec<RawOffRamp>,
    /// Section behaviour stretches (docs/network-scenarios.md).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub behaviour: Vec<RawBehaviour>,
}

/// One `[[network.behaviour]]` stretch: factors on the drivers' headway and desired speed on
/// `[from_m, to_m)` (corridor coordinates).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawBehaviour {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub from_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub to_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub buffer_factor: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub speed_factor: Option<f64>,
}

/// One `[[network.lanes]]` stretch: `count` through lanes on `[from_m, to_m)`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawLaneStretch {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub from_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub to_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub count: Option<u32>,
}

/// A station id as a string or a whole number (PeMS station IDs are numbers:
/// `station = 314107` and `station = "314107"` are the same station).
fn station_id<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<String>, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Id {
        Text(String),
        Number(u64),
    }
    Ok(Some(
        match Id::deserialize(d).map_err(|_| {
            serde::de::Error::custom("expected a station id: a string or a whole number")
        })? {
            Id::Text(s) => s,
            Id::Number(n) => n.to_string(),
        },
    ))
}

/// One `[[network.on_ramps]]` entry.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawOnRamp {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub x_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub accel_lane_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ramp_length_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub demand_vph: Option<Vec<f64>>,
    /// A field station at this ramp (e.g. a PeMS station ID): the ramp gets a counter of
    /// that name (docs/network-scenarios.md).
    #[serde(
        skip_serializing_if = "Option::is_none",
        deserialize_with = "station_id"
    )]
    pub station: Option<String>,
    /// A ramp meter: `{ kind = "fixed", rate_vph = 900 }` or `{ kind = "alinea", ... }`
    /// (docs/network-scenarios.md, "Ramp meters").
    #[serde(skip_serializing_if = "Option::is_none")]
    pub meter: Option<RawMeter>,
    /// The share of CAVs among this ramp's arrivals (default: `run.penetration`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub penetration: Option<f64>,
}

/// The `meter` of an on-ramp, as written; `validate_meters.rs` checks it against its `kind`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawMeter {
    /// `"fixed"` or `"alinea"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kind: Option<String>,
    /// Fixed: the rate (veh/h), one vehicle per green.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rate_vph: Option<f64>,
    /// ALINEA: o* (%), K_R (veh/h per %), r_min and r_max (veh/h), T (s), and where its
    /// detector is (m downstream of the merge point).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub occupancy_target_pct: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gain_vph: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub min_rate_vph: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_rate_vph: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub period_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detector_m: Option<f64>,
    /// Queue override: the most vehicles that may wait on the ramp.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub queue_max_veh: Option<i64>,
    /// When the meter runs: a clock time ("06:30", with `run.clock_start`) or simulated
    /// seconds.
    #[serde(
        skip_serializing_if = "Option::is_none",
        deserialize_with = "meter_time"
    )]
    pub from: Option<RawTime>,
    #[serde(
        skip_serializing_if = "Option::is_none",
        deserialize_with = "meter_time"
    )]
    pub to: Option<RawTime>,
}

/// A time of a meter's hours: a clock time or simulated seconds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum RawTime {
    Clock(String),
    Seconds(f64),
}

/// A [`RawTime`] with a message that says what is expected.
fn meter_time<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Option<RawTime>, D::Error> {
    RawTime::deserialize(d).map(Some).map_err(|_| {
        serde::de::Error::custom(
            "expected a clock time \"HH:MM\" or \"HH:MM:SS\", or simulated seconds (a number)",
        )
    })
}

/// One `[[network.off_ramps]]` entry.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawOffRamp {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub x_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exit_fraction: Option<Vec<f64>>,
    /// A field station at this ramp: the off-ramp's counter takes its name.
    #[serde(
        skip_serializing_if = "Option::is_none",
        deserialize_with = "station_id"
    )]
    pub station: Option<String>,
}

/// `[network.detectors]`: where the generated detectors go.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawNetworkDetectors {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub upstream_of_ramps_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub downstream_of_onramps_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub before_end_m: Option<f64>,
}

impl RawNetworkDetectors {
    pub fn is_empty(&self) -> bool {
        *self == RawNetworkDetectors::default()
    }
}

/// One `[[detectors]]` entry.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawDetector {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub position_m: Option<f64>,
}

/// `[measurement]`: which detector measures the discharge, and the aggregation interval.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawMeasurement {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub detector: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aggregation_s: Option<f64>,
    /// Measure where an organizing strategy's discharge change comes from (docs/outputs.md,
    /// "The mechanism measures"); default false.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mechanism: Option<bool>,
}

/// `[strategy]`: platoon organization. Only `kind` decides whether it acts; the other keys
/// are checked whatever the kind so that `--strategy` can switch it on.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RawStrategy {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kind: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub zone_start_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub zone_end_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub start_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub end_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flow_threshold_vphpl: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub speed_threshold_kmh: Option<f64>,
    /// The table by penetration that the two thresholds default to: a built-in table's name or
    /// a file path ([`crate::tables`]). Without it (and without the thresholds) Flow-Aware
    /// cannot be chosen.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thresholds_table: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub radius_m: Option<f64>,
    /// `"leftmost"`, `"rightmost"` or a lane number (1 = rightmost).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lane: Option<toml::Value>,
}

/// Parse TOML text into a document (a table). Syntax errors carry toml's line and column.
pub fn parse_document(text: &str, origin: &str) -> Result<Table, ScenarioError> {
    text.parse::<Table>().map_err(|e| ScenarioError::Syntax {
        origin: origin.to_string(),
        message: clip_lines(e.to_string().trim_end(), MAX_ECHO_CHARS),
    })
}

/// Turn a document (after overrides) into a [`RawScenario`]. On failure the error names the
/// offending key path (`road.foo`, `detectors[1].position_m`, `human.headway_s`).
pub fn from_document(doc: &Table, origin: &str) -> Result<RawScenario, ScenarioError> {
    let mut doc = doc.clone();
    fill_model_defaults(&mut doc);
    RawScenario::deserialize(Value::Table(doc.clone())).map_err(|_| {
        let (path, message) = diagnose(&doc);
        ScenarioError::Structure {
            origin: origin.to_string(),
            path,
            message,
        }
    })
}

/// The model sections accept partial tables, down to single fields of a distribution: merge
/// what the file gives onto the defaults.
fn fill_model_defaults(doc: &mut Table) {
    let defaults = [
        ("human", Value::try_from(HumanDists::default())),
        ("cav", Value::try_from(CavParams::default())),
        ("lane_change", Value::try_from(LaneChangeDists::default())),
    ];
    for (key, default) in defaults {
        let Some(user) = doc.get(key) else { continue };
        if !user.is_table() {
            continue; // left for the type error
        }
        let Ok(mut merged) = default else { continue };
        merge(&mut merged, user);
        doc.insert(key.to_string(), merged);
    }
}

/// Deep merge: tables merge key by key, anything else replaces.
fn merge(base: &mut Value, over: &Value) {
    match (base, over) {
        (Value::Table(b), Value::Table(o)) => {
            for (k, v) in o {
                match b.get_mut(k) {
                    Some(bv) => merge(bv, v),
                    None => {
                        b.insert(k.clone(), v.clone());
                    }
                }
            }
        }
        (b, o) => *b = o.clone(),
    }
}

/// Find the first key whose value alone fails to deserialize, two levels deep, and say why.
fn diagnose(doc: &Table) -> (String, String) {
    for (key, value) in doc {
        if try_single::<RawScenario>(key, value).is_ok() {
            continue;
        }
        return match key.as_str() {
            "run" => narrow::<RawRun>("run", value),
            "road" => narrow::<RawRoad>("road", value),
            "demand" => narrow::<RawDemand>("demand", value),
            "measurement" => narrow::<RawMeasurement>("measurement", value),
            "strategy" => narrow::<RawStrategy>("strategy", value),
            "network" => narrow_network(value),
            "human" => narrow::<HumanDists>("human", value),
            "cav" => narrow::<CavParams>("cav", value),
            "lane_change" => narrow::<LaneChangeDists>("lane_change", value),
            "safety" => narrow::<SafetyParams>("safety", value),
            "energy" => narrow::<EnergyParams>("energy", value),
            "detectors" => narrow_array::<RawDetector>("detectors", value)
                .unwrap_or_else(|| ("detectors".into(), single_message(key, value))),
            _ => (key.clone(), rewrite(&single_message(key, value), None)),
        };
    }
    // Not expected: every key passes alone but the whole fails.
    let message = match RawScenario::deserialize(Value::Table(doc.clone())) {
        Err(e) => e.message().to_string(),
        Ok(_) => "cannot be read".to_string(),
    };
    ("(document)".into(), message)
}

/// The failing entry of an array of tables `path` whose entries should read as `T`; `None` if
/// every entry reads.
fn narrow_array<T: DeserializeOwned>(path: &str, value: &Value) -> Option<(String, String)> {
    match value {
        Value::Array(items) => items
            .iter()
            .enumerate()
            .find(|(_, item)| T::deserialize((*item).clone()).is_err())
            .map(|(i, item)| narrow::<T>(&format!("{path}[{i}]"), item)),
        _ => Some((
            path.into(),
            format!(
                "must be an array of tables ([[{path}]] entries), found {}",
                value.type_str()
            ),
        )),
    }
}

/// The failing key of `[network]`, down into its arrays of tables and `[network.detectors]`.
fn narrow_network(value: &Value) -> (String, String) {
    if let Value::Table(t) = value {
        let nested = [
            (
                "lanes",
                narrow_array::<RawLaneStretch> as fn(&str, &Value) -> _,
            ),
            ("on_ramps", narrow_array::<RawOnRamp>),
            ("off_ramps", narrow_array::<RawOffRamp>),
        ];
        for (key, f) in nested {
            if let Some(v) = t.get(key) {
                if let Some(found) = f(&format!("network.{key}"), v) {
                    return found;
                }
            }
        }
        if let Some(v) = t.get("detectors") {
            if RawNetworkDetectors::deserialize(v.clone()).is_err() {
                return narrow::<RawNetworkDetectors>("network.detectors", v);
            }
        }
    }
    narrow::<RawNetwork>("network", value)
}

fn try_single<T: DeserializeOwned>(key: &str, value: &Value) -> Result<T, toml::de::Error> {
    let mut t = Table::new();
    t.insert(key.to_string(), value.clone());
    T::deserialize(Value::Table(t))
}

fn single_message(key: &str, value: &Value) -> String {
    match try_single::<RawScenario>(key, value) {
        Err(e) => e.message().to_string(),
        Ok(_) => String::new(),
    }
}

/// Within section `path` (expected to deserialize as `T`), find the failing key.
fn narrow<T: DeserializeOwned>(path: &str, value: &Value) -> (String, String) {
    let Value::Table(table) = value else {
        return (
            path.to_string(),
            format!("must be a table ([{path}]), found {}", value.type_str()),
        );
    };
    for (key, v) in table {
        if let Err(e) = try_single::<T>(key, v) {
            // An unknown field one level further down (a distribution's `{ mean, sd, ... }`).
            if let (Some(inner), Value::Table(_)) = (unknown_field_name(e.message()), v) {
                if inner != key {
                    let section = format!("{path}.{key}");
                    return (
                        format!("{section}.{inner}"),
                        rewrite(e.message(), Some(&section)),
                    );
                }
            }
            let message = rewrite(e.message(), Some(path));
            let self_describing = ["unknown", "invalid type", "invalid value"]
                .iter()
                .any(|p| message.starts_with(p));
            if self_describing {
                return (format!("{path}.{key}"), message);
            }
            return (
                format!("{path}.{key}"),
                format!("{message} (found {})", render(v)),
            );
        }
    }
    let message = match T::deserialize(value.clone()) {
        Err(e) => e.message().to_string(),
        Ok(_) => "cannot be read".to_string(),
    };
    (path.to_string(), message)
}

fn unknown_field_name(message: &str) -> Option<&str> {
    message
        .strip_prefix("unknown field `")?
        .split_once('`')
        .map(|(name, _)| name)
}

/// Serde says "unknown field `foo`, expected one of `a`, `b`"; say it the scenario way.
fn rewrite(message: &str, section: Option<&str>) -> String {
    let Some(rest) = message.strip_prefix("unknown field `") else {
        return message.to_string();
    };
    let Some((name, tail)) = rest.split_once('`') else {
        return message.to_string();
    };
    let tail = tail.trim_start_matches(", ");
    let allowed = if let Some(list) = tail.strip_prefix("expected one of ") {
        list.replace('`', "")
    } else if let Some(list) = tail.strip_prefix("expected ") {
        list.replace('`', "").replace(" or ", ", ")
    } else {
        "(none)".to_string()
    };
    match section {
        Some(s) => format!("unknown field '{name}' in [{s}]; allowed keys: {allowed}"),
        None => format!("unknown key '{name}' at the top level; allowed keys: {allowed}"),
    }
}

/// A value as TOML text (strings quoted, tables inline).
pub fn render(v: &Value) -> String {
    v.to_string()
}

/// A float the way a user writes it: `7000`, `1.5`, `nan`, `inf`; with an exponent (`1e-300`,
/// `4.3e18`) when the decimal form would be long, so that a message stays readable.
pub fn num(v: f64) -> String {
    if v.is_nan() {
        "nan".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.into()
    } else if v != 0.0 && !(1e-6..1e16).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}
