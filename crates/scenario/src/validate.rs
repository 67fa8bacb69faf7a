//! Level two: a [`RawScenario`] becomes a [`Config`], or a list of every [`Problem`] found.
//! Defaults for optional keys are applied here (and reported as `(default)` if they clash with
//! something the file gave).

use crate::error::{Problem, ScenarioError};
use crate::raw::{num, render, RawScenario};
use platoonsim_model::dist::Dist;
use platoonsim_sim::{Config, Demand, Road};
use std::path::Path;
use toml::Value;

// One file per part of the scenario (split by responsibility); `validate` below calls them in
// the order of the problems in an error.
#[path = "validate_run.rs"]
mod run;

#[path = "validate_network.rs"]
mod network;
pub use network::defaults as network_defaults;

#[path = "validate_road.rs"]
mod road;

#[path = "validate_detectors.rs"]
mod detectors;

#[path = "validate_stations.rs"]
mod stations;

#[path = "validate_strategy.rs"]
mod strategy;

#[path = "validate_models.rs"]
mod models;

#[path = "validate_room.rs"]
mod room;
use models::{all_finite, check_cav, check_human, check_lane_change, check_safety};
pub use room::{warnings, LANE_DROP_WARN_M, SHORT_ACCEL_LANE_M};

/// Defaults of the optional keys.
pub mod defaults {
    pub const SEED: u64 = 1;
    pub const DT_S: f64 = 0.1;
    pub const DURATION_S: f64 = 3600.0;
    pub const WARMUP_S: f64 = 1200.0;
    pub const PENETRATION: f64 = 0.5;
    pub const AGGREGATION_S: f64 = 300.0;
    pub const RADIUS_M: f64 = 1500.0;
    /// Highest demand accepted (veh/h/lane); above it the entry queue would only grow.
    pub const MAX_DEMAND_VPHPL: f64 = crate::limits::MAX_DEMAND_VPHPL;
    /// Lanes the engine supports.
    pub const MAX_LANES: u32 = 8;
}

/// Collects problems while values are read.
struct Checker {
    problems: Vec<Problem>,
}

/// A number together with whether it came from a default (for messages).
#[derive(Clone, Copy)]
struct Num {
    v: f64,
    defaulted: bool,
}

impl Num {
    fn shown(self) -> String {
        if self.defaulted {
            format!("{} (default)", num(self.v))
        } else {
            num(self.v)
        }
    }
}

impl Checker {
    fn push(
        &mut self,
        field: impl Into<String>,
        value: impl Into<String>,
        allowed: impl Into<String>,
    ) {
        self.problems.push(Problem {
            field: field.into(),
            value: value.into(),
            allowed: allowed.into(),
        });
    }

    fn missing(&mut self, field: &str, what: &str) {
        self.push(field, "(missing)", format!("required: {what}"));
    }

    /// An optional number with a default.
    fn opt(&mut self, v: Option<f64>, default: f64) -> Num {
        match v {
            Some(v) => Num {
                v,
                defaulted: false,
            },
            None => Num {
                v: default,
                defaulted: true,
            },
        }
    }

    /// A required number; `None` (after reporting) if missing.
    fn req(&mut self, field: &str, v: Option<f64>, what: &str) -> Option<Num> {
        match v {
            Some(v) => Some(Num {
                v,
                defaulted: false,
            }),
            None => {
                self.missing(field, what);
                None
            }
        }
    }

    /// Report unless `ok(v)` (and v is finite); returns whether it passed.
    fn check(&mut self, field: &str, n: Num, ok: bool, allowed: impl Into<String>) -> bool {
        let pass = ok && n.v.is_finite();
        if !pass {
            self.push(field, n.shown(), allowed);
        }
        pass
    }

    fn positive(&mut self, field: &str, n: Num) -> bool {
        self.check(field, n, n.v > 0.0, "must be a finite number > 0")
    }

    fn non_negative(&mut self, field: &str, n: Num) -> bool {
        self.check(field, n, n.v >= 0.0, "must be a finite number >= 0")
    }

    fn unit(&mut self, field: &str, n: Num) -> bool {
        self.check(field, n, (0.0..=1.0).contains(&n.v), "must be in [0, 1]")
    }

    fn value(&mut self, field: &str, v: f64, ok: bool, allowed: &str) {
        self.check(
            field,
            Num {
                v,
                defaulted: false,
            },
            ok,
            allowed,
        );
    }

    fn dist(&mut self, field: &str, d: &Dist, extra: Option<(bool, &str)>) {
        if let Some(p) = d.problem() {
            self.push(field, dist_text(d), p);
        } else if let Some((ok, allowed)) = extra {
            if !ok {
                self.push(field, dist_text(d), allowed);
            }
        }
    }
}

fn dist_text(d: &Dist) -> String {
    format!(
        "{{ mean = {}, sd = {}, min = {}, max = {} }}",
        num(d.mean),
        num(d.sd),
        num(d.min),
        num(d.max)
    )
}

fn quoted(s: &str) -> String {
    render(&Value::String(s.to_string()))
}

/// The coordinate of the file's positions: the road's own (0 at the entrance, up to
/// `road.length_m`) or, with a `[network]`, the corridor's (from `network.start_m` to
/// `network.end_m`). Engine position = file position − `origin`.
struct Frame {
    network: bool,
    origin: f64,
    /// File coordinate of the road end, if known.
    hi: Option<f64>,
}

impl Frame {
    fn lo_text(&self) -> String {
        if self.network {
            format!("network.start_m = {}", num(self.origin))
        } else {
            "0".into()
        }
    }

    fn hi_text(&self, hi: f64) -> String {
        if self.network {
            format!("network.end_m = {}", num(hi))
        } else {
            format!("road.length_m = {}", num(hi))
        }
    }

    fn inside_text(&self, hi: f64) -> String {
        if self.network {
            format!("the corridor ({}, {})", num(self.origin), num(hi))
        } else {
            format!("the road (0, {})", num(hi))
        }
    }
}

/// Validate a raw scenario into a [`Config`]. `default_name` is used when the file has no
/// `name` (the file stem); `origin` names the source in the error.
pub fn validate(
    raw: &RawScenario,
    default_name: &str,
    origin: &str,
) -> Result<Config, ScenarioError> {
    validate_in(raw, default_name, origin, None)
}

/// [`validate`] for a scenario whose relative table paths (`network.demand_scale_table`,
/// `strategy.thresholds_table`) are read from `base_dir` (the scenario file's directory).
pub fn validate_in(
    raw: &RawScenario,
    default_name: &str,
    origin: &str,
    base_dir: Option<&Path>,
) -> Result<Config, ScenarioError> {
    let mut c = Checker {
        problems: Vec::new(),
    };

    // --- name
    let name = raw.name.clone().unwrap_or_else(|| default_name.to_string());
    if name.trim().is_empty() {
        c.push("name", quoted(&name), "must be a non-empty string");
    }

    // --- [run]
    let run = run::check_run(&mut c, &raw.run);

    // --- [road] (with a [network], the lanes and the length follow from it)
    let net = raw
        .network
        .as_ref()
        .map(|n| network::check_network(&mut c, n, &run, base_dir));
    let road = road::check_road(&mut c, &raw.road, net.as_ref());
    let frame = &road.frame;

    // --- [demand] (with a [network]: its series instead)
    road::check_demand(&mut c, &raw.demand, frame);

    // --- the vehicles the run would bring
    run::check_arrivals(
        &mut c,
        &run,
        net.as_ref().map(|v| &v.network),
        raw.demand.vph_per_lane,
        road.lanes,
    );

    // --- [[detectors]] (with a [network], generated ones first; these are added)
    let detectors = detectors::check_detectors(&mut c, raw, net.as_ref(), road.length, frame);

    // --- [measurement]
    let measurement = detectors::check_measurement(
        &mut c,
        &raw.measurement,
        &detectors,
        frame,
        &run,
        road.lanes,
    );

    // --- [strategy]
    let strategy = strategy::check_strategy(
        &mut c,
        &raw.strategy,
        frame,
        (road.control_start, road.control_end),
        &run,
        road.lanes,
        base_dir,
    );

    // --- model sections
    if all_finite(&mut c, "human", &raw.human) {
        check_human(&mut c, &raw.human);
    }
    if all_finite(&mut c, "cav", &raw.cav) {
        check_cav(&mut c, &raw.cav);
    }
    if all_finite(&mut c, "lane_change", &raw.lane_change) {
        check_lane_change(&mut c, &raw.lane_change, road.length);
    }
    if all_finite(&mut c, "safety", &raw.safety) {
        check_safety(&mut c, &raw.safety);
    }

    let config = Config {
        name,
        seed: run.seed,
        dt_s: run.dt.v,
        duration_s: run.duration.v,
        warmup_s: run.warmup.v,
        penetration: run.penetration.v,
        road: Road {
            lanes: road.lanes,
            length_m: road.length.unwrap_or(f64::NAN),
            control_start_m: road.control_start.map_or(f64::NAN, |n| n.v - frame.origin),
            control_end_m: road.control_end.map_or(f64::NAN, |n| n.v - frame.origin),
            network: net.map(|v| v.network),
        },
        demand: Demand {
            // Unused on a network (its demand is in the series).
            vph_per_lane: if frame.network {
                0.0
            } else {
                raw.demand.vph_per_lane.unwrap_or(f64::NAN)
            },
        },
        detectors,
        aggregation_s: measurement.aggregation.v,
        measurement_detector: measurement.detector,
        strategy,
        human: raw.human,
        cav: raw.cav.clone(),
        lane_change: raw.lane_change,
        safety: raw.safety,
        energy: raw.energy,
        mechanism: raw.measurement.mechanism.unwrap_or(false),
        clock_start_s: run.clock_start_s,
    };
    if c.problems.is_empty() {
        // The engine's own invariants; the checks above are stricter, so this is a safety net.
        if let Err(message) = config.check() {
            c.push("(engine check)", "-", message.to_string());
        }
    }
    if c.problems.is_empty() {
        // Room for a vehicle at merge points and lane ends, on the engine's geometry.
        room::check_room(&mut c, &config);
    }
    if c.problems.is_empty() {
        Ok(config)
    } else {
        Err(ScenarioError::Invalid {
            origin: origin.to_string(),
            problems: c.problems,
        })
    }
}
