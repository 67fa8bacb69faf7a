//! The run file `<experiment>/runs/<key>.json`: the run's summary and the hash of the
//! configuration it ran, written once the run has finished (atomically), read back instead
//! of rerunning.
//!
//! ```json
//! { "config_hash": "…16 hex…", "seed": 3, "version": "0.1.0", "engine": "…16 hex…",
//!   "detectors": { "scope": "all", "rows": 11089, "hash": "…16 hex…" },
//!   "summary": { …Summary… } }
//! ```
//!
//! `detectors` is present only for runs that keep their detector records
//! (`<key>.detectors.csv`, see [`crate::detectors`]): which records, how many, and the hash
//! of the file's bytes, written before the run file.
//!
//! `engine` identifies the program that computed the run (see [`engine_id`]): a file made
//! by another build is not reused, so a rebuilt engine never reports stale results.

use crate::detectors::DetectorsRef;
use crate::metric::Metric;
use platoonsim_sim::Summary;
use serde::de::{Deserializer, MapAccess, Visitor};
use serde::{Deserialize, Serialize};
use std::fmt;

/// Summary fields that echo the configuration (they are cell labels or the seed) or that
/// differ between identical runs (`wall_seconds`): kept in the run file, not counted as
/// metrics.
pub const NOT_METRICS: [&str; 10] = [
    "scenario",
    "strategy",
    "penetration",
    "demand_vphpl",
    "demand_scale",
    "seed",
    "dt_s",
    "duration_s",
    "warmup_s",
    "wall_seconds",
];

/// Derived columns that count things (written without a decimal point in `runs.csv`, as
/// the counting [`Metric`]s are, see [`is_count`]).
pub const DERIVED_COUNTS: [&str; 2] = ["runs_with_collisions", "seed"];

pub use crate::metric::HISTOGRAM;

/// Is the column `name` a count: a [`Metric`] that counts things, one of [`DERIVED_COUNTS`],
/// or a column derived from a bin of the [`HISTOGRAM`] (a sweep's `_diff` and `_pct` of it;
/// `runs.csv` has always written those as counts).
pub fn is_count(name: &str) -> bool {
    match Metric::parse(name) {
        Some(m) => m.is_count(),
        None => DERIVED_COUNTS.contains(&name) || name.starts_with(HISTOGRAM),
    }
}

/// Named numbers in a fixed order: a run's metrics (the summary's numeric fields that are
/// [`Metric`]s, in the summary's order, then any derived ones, named by the experiment or
/// sweep that adds them). A JSON `null` (a NaN when written) reads as NaN.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Fields(pub Vec<(String, f64)>);

impl Fields {
    /// The value of a metric of the summary.
    pub fn metric(&self, m: Metric) -> Option<f64> {
        self.get(&m.name())
    }

    /// The value of a column by name (a metric's or a derived one's).
    pub fn get(&self, name: &str) -> Option<f64> {
        self.0.iter().find(|(k, _)| k == name).map(|(_, v)| *v)
    }

    /// Set a field, replacing one of the same name or appending.
    pub fn set(&mut self, name: &str, v: f64) {
        match self.0.iter_mut().find(|(k, _)| k == name) {
            Some(slot) => slot.1 = v,
            None => self.0.push((name.to_string(), v)),
        }
    }

    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.0.iter().map(|(k, _)| k.as_str())
    }
}

#[derive(Serialize)]
struct RunFileOut<'a> {
    config_hash: &'a str,
    seed: u64,
    version: &'a str,
    engine: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    detectors: Option<&'a DetectorsRef>,
    summary: &'a Summary,
}

#[derive(Deserialize)]
struct RunFileIn {
    config_hash: String,
    seed: u64,
    #[serde(default)]
    engine: String,
    #[serde(default)]
    detectors: Option<DetectorsRef>,
    summary: OrderedObject,
}

/// The identity of the running program: FNV-1a 64 of its executable file (computed once),
/// or "unknown" if it cannot be read. Two builds that differ in any way get different ids.
pub fn engine_id() -> &'static str {
    static ID: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    ID.get_or_init(|| {
        std::env::current_exe()
            .and_then(std::fs::read)
            .map(|bytes| format!("{:016x}", crate::hash::fnv1a64(&bytes)))
            .unwrap_or_else(|_| "unknown".into())
    })
}

/// A JSON object read with its keys in file order.
struct OrderedObject(Vec<(String, serde_json::Value)>);

impl<'de> Deserialize<'de> for OrderedObject {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = OrderedObject;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a JSON object")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<OrderedObject, A::Error> {
                let mut out = Vec::new();
                while let Some((k, v)) = map.next_entry::<String, serde_json::Value>()? {
                    out.push((k, v));
                }
                Ok(OrderedObject(out))
            }
        }
        d.deserialize_map(V)
    }
}

/// The bytes of a run file (pretty JSON, final newline).
pub fn encode(key: &str, seed: u64, engine: &str, summary: &Summary) -> Vec<u8> {
    encode_with(key, seed, engine, summary, None)
}

/// [`encode`] naming the run's detector file.
pub fn encode_with(
    key: &str,
    seed: u64,
    engine: &str,
    summary: &Summary,
    detectors: Option<&DetectorsRef>,
) -> Vec<u8> {
    let out = RunFileOut {
        config_hash: key,
        seed,
        version: env!("CARGO_PKG_VERSION"),
        engine,
        detectors,
        summary,
    };
    let mut bytes = serde_json::to_vec_pretty(&out).expect("a Summary always serializes");
    bytes.push(b'\n');
    bytes
}

/// Why a run file cannot be reused: the run is then computed again.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum StaleRunFile {
    #[error("it is not a run file ({0})")]
    Unreadable(String),
    #[error("it was computed by another build ({found}, this is {this})")]
    OtherBuild { found: String, this: String },
    #[error("it holds the run of configuration {found} (expected {expected})")]
    OtherConfig { found: String, expected: String },
    #[error("it holds seed {found} (expected {expected})")]
    OtherSeed { found: u64, expected: u64 },
    #[error("its summary has no discharge_flow_vphpl")]
    NoSummary,
}

/// Read a run file's metrics. `Err` says why the file cannot be used (unreadable JSON,
/// another configuration's hash or seed, another engine when `engine` is given, a missing
/// summary): the run is then computed again.
pub fn decode(
    bytes: &[u8],
    key: &str,
    seed: u64,
    engine: Option<&str>,
) -> Result<Fields, StaleRunFile> {
    decode_with(bytes, key, seed, engine).map(|(fields, _)| fields)
}

/// [`decode`], with what the run file says about its detector file.
pub fn decode_with(
    bytes: &[u8],
    key: &str,
    seed: u64,
    engine: Option<&str>,
) -> Result<(Fields, Option<DetectorsRef>), StaleRunFile> {
    let f: RunFileIn =
        serde_json::from_slice(bytes).map_err(|e| StaleRunFile::Unreadable(e.to_string()))?;
    if let Some(e) = engine {
        if f.engine != e {
            return Err(StaleRunFile::OtherBuild {
                found: f.engine,
                this: e.to_string(),
            });
        }
    }
    if f.config_hash != key {
        return Err(StaleRunFile::OtherConfig {
            found: f.config_hash,
            expected: key.to_string(),
        });
    }
    if f.seed != seed {
        return Err(StaleRunFile::OtherSeed {
            found: f.seed,
            expected: seed,
        });
    }
    let mut fields = Fields::default();
    for (k, v) in f.summary.0 {
        // Only the summary's metrics: no configuration echo of NOT_METRICS parses as one, and
        // a histogram's bins are checked one by one.
        if k != HISTOGRAM && Metric::parse(&k).is_none() {
            continue;
        }
        match v {
            serde_json::Value::Number(n) => fields.0.push((k, n.as_f64().unwrap_or(f64::NAN))),
            serde_json::Value::Null => fields.0.push((k, f64::NAN)),
            // The histogram: one metric per kind and bin (its integer arrays).
            serde_json::Value::Object(o) if k == HISTOGRAM => {
                for (kind, bins) in o {
                    let Some(bins) = bins.as_array() else {
                        continue;
                    };
                    if !bins.iter().all(|b| b.is_u64()) {
                        continue;
                    }
                    for (i, b) in bins.iter().enumerate() {
                        let name = format!("{k}_{kind}_{i}");
                        if Metric::parse(&name).is_some() {
                            fields.0.push((name, b.as_f64().unwrap_or(f64::NAN)));
                        }
                    }
                }
            }
            _ => {}
        }
    }
    if fields.metric(Metric::DISCHARGE_FLOW).is_none() {
        return Err(StaleRunFile::NoSummary);
    }
    Ok((fields, f.detectors))
}

#[cfg(test)]
mod tests {
    use super::*;
    use platoonsim_sim::Config;

    fn summary() -> Summary {
        let cfg = Config::homogeneous(0.5, 600.0, 120.0, 30.0, 4);
        platoonsim_sim::run(&cfg, None).unwrap().summary
    }

    #[test]
    fn round_trip_keeps_the_metrics_in_summary_order() {
        let s = summary();
        let bytes = encode("00000000000000ab", 4, "e1", &s);
        let f = decode(&bytes, "00000000000000ab", 4, Some("e1")).unwrap();
        let names: Vec<&str> = f.names().collect();
        assert_eq!(names[0], "vehicles_entered");
        assert!(names.contains(&"lane_changes_per_cav"));
        for skipped in NOT_METRICS {
            assert!(!names.contains(&skipped), "{skipped}");
        }
        assert_eq!(f.get("discharge_flow_vphpl"), Some(s.discharge_flow_vphpl));
        assert_eq!(f.get("vehicles_entered"), Some(s.vehicles_entered as f64));
        let i = names
            .iter()
            .position(|n| *n == "discharge_flow_vphpl")
            .unwrap();
        let j = names
            .iter()
            .position(|n| *n == "max_sustained_flow_vphpl")
            .unwrap();
        assert!(i < j);
    }

    #[test]
    fn unusable_files_are_rejected() {
        let s = summary();
        let bytes = encode("00000000000000ab", 4, "e1", &s);
        assert!(decode(&bytes, "00000000000000ac", 4, None).is_err());
        assert!(decode(&bytes, "00000000000000ab", 4, Some("e2")).is_err());
        assert!(decode(&bytes, "00000000000000ab", 4, None).is_ok());
        assert!(decode(&bytes, "00000000000000ab", 5, None).is_err());
        assert!(decode(&bytes[..bytes.len() / 2], "00000000000000ab", 4, None).is_err());
        assert!(decode(b"", "00000000000000ab", 4, None).is_err());
        assert!(decode(
            br#"{"config_hash":"00000000000000ab","seed":4,"summary":{}}"#,
            "00000000000000ab",
            4,
            None
        )
        .is_err());
    }

    #[test]
    fn the_detector_reference_round_trips() {
        let s = summary();
        let r = DetectorsRef::of(crate::detectors::Scope::All, 2, b"x");
        let bytes = encode_with("k", 4, "e", &s, Some(&r));
        assert!(String::from_utf8_lossy(&bytes).contains("\"scope\": \"all\""));
        let (_, got) = decode_with(&bytes, "k", 4, Some("e")).unwrap();
        assert_eq!(got, Some(r));
        let (_, none) = decode_with(&encode("k", 4, "e", &s), "k", 4, None).unwrap();
        assert_eq!(none, None);
    }

    #[test]
    fn the_counts_are_the_integer_fields_of_the_summary() {
        let json = serde_json::to_value(summary()).unwrap();
        for (k, v) in json.as_object().unwrap() {
            if NOT_METRICS.contains(&k.as_str()) || !v.is_number() {
                continue;
            }
            assert_eq!(is_count(k), v.is_u64(), "{k}");
        }
        for rate in [
            "hard_brakings_per_100vkm",
            "severe_brakings_per_100vkm_cav",
            "tet_s",
            "discharge_change_pct",
        ] {
            assert!(!is_count(rate), "{rate}");
        }
        for count in ["braking_peaks_human_2", "seed", "runs_with_collisions"] {
            assert!(is_count(count), "{count}");
        }
    }

    #[test]
    fn the_histogram_becomes_one_count_per_kind_and_bin() {
        let mut s = summary();
        s.braking_peaks.human = vec![3, 1, 0, 0, 0, 2];
        s.braking_peaks.cav = vec![1, 0, 0, 0, 0, 0];
        let f = decode(&encode("k", 4, "e", &s), "k", 4, None).unwrap();
        assert_eq!(f.get("braking_peaks_human_0"), Some(3.0));
        assert_eq!(f.get("braking_peaks_human_5"), Some(2.0));
        assert_eq!(f.get("braking_peaks_cav_0"), Some(1.0));
        assert_eq!(f.get("braking_peaks_cav_6"), None);
        assert!(f.names().all(|n| !n.contains("lower_edges")));
    }

    #[test]
    fn nan_reads_back_as_nan() {
        let mut s = summary();
        s.avg_platoon_length = None;
        let f = decode(&encode("k", 4, engine_id(), &s), "k", 4, Some(engine_id())).unwrap();
        assert!(f.get("avg_platoon_length").unwrap().is_nan());
    }
}
