//! Level two: a [`RawScenario`] becomes a [`Config`], or a list of every [`Problem`] found.
//! Defaults for optional keys are applied here (and reported as `(default)` if they clash with
//! something the file gave).

use crate::error::{Problem, ScenarioError};
use crate::limits;
use crate::overrides::StrategyKind;
use crate::raw::{num, render, RawScenario};
use platoonsim_model::dist::Dist;
use platoonsim_sim::config::DetectorKind;
use platoonsim_sim::{Config, Demand, DetectorSpec, FlowAwareConfig, PdConfig, Road, Strategy};
use toml::Value;

#[path = "validate_models.rs"]
mod models;
use models::{all_finite, check_cav, check_human, check_lane_change};

#[path = "validate_network.rs"]
mod network;
pub use network::defaults as network_defaults;

/// Defaults of the optional keys.
pub mod defaults {
    pub const SEED: u64 = 1;
    pub const DT_S: f64 = 0.1;
    pub const DURATION_S: f64 = 3600.0;
    pub const WARMUP_S: f64 = 1200.0;
    pub const PENETRATION: f64 = 0.5;
    pub const AGGREGATION_S: f64 = 300.0;
    /// ρ_q (veh/h/lane).
    pub const FLOW_THRESHOLD_VPHPL: f64 = 1800.0;
    /// ρ_v (km/h).
    pub const SPEED_THRESHOLD_KMH: f64 = 90.0;
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
    let mut c = Checker {
        problems: Vec::new(),
    };

    // --- name
    let name = raw.name.clone().unwrap_or_else(|| default_name.to_string());
    if name.trim().is_empty() {
        c.push("name", quoted(&name), "must be a non-empty string");
    }

    // --- [run]
    let seed = raw.run.seed.unwrap_or(defaults::SEED);
    let dt = c.opt(raw.run.dt_s, defaults::DT_S);
    let dt_ok = c.check(
        "run.dt_s",
        dt,
        (limits::DT_MIN_S..=limits::DT_MAX_S).contains(&dt.v),
        format!(
            "must be in [{}, {}] s ({})",
            num(limits::DT_MIN_S),
            num(limits::DT_MAX_S),
            limits::DT_REASON
        ),
    );
    let duration = c.opt(raw.run.duration_s, defaults::DURATION_S);
    let duration_ok = c.check(
        "run.duration_s",
        duration,
        duration.v > 0.0 && duration.v <= limits::MAX_DURATION_S,
        format!(
            "must be in (0, {}] s (at most 7 simulated days)",
            num(limits::MAX_DURATION_S)
        ),
    );
    let warmup = c.opt(raw.run.warmup_s, defaults::WARMUP_S);
    if duration_ok {
        c.check(
            "run.warmup_s",
            warmup,
            warmup.v >= 0.0 && warmup.v < duration.v,
            format!("must be >= 0 and < run.duration_s = {}", duration.shown()),
        );
    } else {
        c.non_negative("run.warmup_s", warmup);
    }
    if dt_ok && duration_ok && duration.v < dt.v {
        c.push(
            "run.duration_s",
            duration.shown(),
            format!("must be at least one step (run.dt_s = {})", dt.shown()),
        );
    }
    let penetration = c.opt(raw.run.penetration, defaults::PENETRATION);
    c.unit("run.penetration", penetration);

    // --- [road] (with a [network], the lanes and the length follow from it)
    let net = raw
        .network
        .as_ref()
        .map(|n| network::check_network(&mut c, n, penetration.v));
    let (lanes, length) = match &net {
        Some(v) => {
            let given = [
                ("road.lanes", raw.road.lanes.map(|n| n.to_string())),
                ("road.length_m", raw.road.length_m.map(num)),
            ];
            for (field, value) in given {
                if let Some(value) = value {
                    c.push(
                        field,
                        value,
                        "must be left out with [network]: the lanes and the length follow from \
                         network.lanes, network.start_m and network.end_m",
                    );
                }
            }
            (v.lanes, v.length)
        }
        None => road_size(&mut c, raw),
    };
    let frame = match &net {
        Some(v) => Frame {
            network: true,
            origin: v.origin,
            hi: v.end,
        },
        None => Frame {
            network: false,
            origin: 0.0,
            hi: length,
        },
    };
    let (cstart, cend) = if frame.network {
        // Optional: the whole corridor by default.
        (
            Some(c.opt(raw.road.control_start_m, frame.origin)),
            Some(c.opt(raw.road.control_end_m, frame.hi.unwrap_or(f64::NAN))),
        )
    } else {
        (
            c.req(
                "road.control_start_m",
                raw.road.control_start_m,
                "start of the control section (m from the entrance)",
            ),
            c.req(
                "road.control_end_m",
                raw.road.control_end_m,
                "end of the control section (m from the entrance)",
            ),
        )
    };
    if let (Some(s), Some(e)) = (cstart, cend) {
        match frame.hi {
            _ if s.defaulted && e.defaulted => {}
            Some(hi) => {
                let s_ok = c.check(
                    "road.control_start_m",
                    s,
                    s.v >= frame.origin && s.v < hi,
                    format!(
                        "must lie in [{}, {}) (the control section must be on the road)",
                        frame.lo_text(),
                        frame.hi_text(hi)
                    ),
                );
                if s_ok {
                    c.check(
                        "road.control_end_m",
                        e,
                        e.v > s.v && e.v <= hi,
                        format!(
                            "must be > road.control_start_m = {} and <= {}",
                            s.shown(),
                            frame.hi_text(hi)
                        ),
                    );
                }
            }
            None if frame.network => {}
            None => {
                c.non_negative("road.control_start_m", s);
                c.non_negative("road.control_end_m", e);
            }
        }
    }

    // --- [demand] (with a [network]: its series instead)
    if frame.network {
        if let Some(q) = raw.demand.vph_per_lane {
            c.push(
                "demand.vph_per_lane",
                num(q),
                "must be left out with [network]: the demand is network.mainline_vph and \
                 network.on_ramps[].demand_vph (scale it with network.demand_scale or --demand-scale)",
            );
        }
    } else if let Some(q) = c.req(
        "demand.vph_per_lane",
        raw.demand.vph_per_lane,
        "arrival rate per lane (veh/h/lane)",
    ) {
        c.check(
            "demand.vph_per_lane",
            q,
            (0.0..=defaults::MAX_DEMAND_VPHPL).contains(&q.v),
            format!(
                "must be in [0, {}] veh/h/lane",
                num(defaults::MAX_DEMAND_VPHPL)
            ),
        );
    }

    // --- the vehicles the run would bring: each one waiting in an entry queue is held in
    // memory, so the total is bounded even when every rate and the duration are in range.
    if duration_ok && c.problems.is_empty() {
        let arrivals = match &net {
            Some(v) => expected_network_arrivals(&v.network, duration.v),
            None => raw.demand.vph_per_lane.unwrap_or(0.0) * f64::from(lanes) * duration.v / 3600.0,
        };
        if arrivals > limits::MAX_ARRIVALS {
            c.push(
                "run.duration_s",
                duration.shown(),
                format!(
                    "with this demand the run brings about {} vehicles; at most {} (a vehicle \
                     waiting at an entrance is held in memory): shorten the run or lower the demand",
                    num(arrivals.round()),
                    num(limits::MAX_ARRIVALS)
                ),
            );
        }
    }

    // --- [[detectors]] (with a [network], generated ones first; these are added)
    let generated = match &net {
        Some(v) => crate::network::detectors(
            &v.network,
            length.unwrap_or(f64::NAN),
            &v.on_ids,
            &v.off_ids,
            &v.spacing,
        ),
        None => Vec::new(),
    };
    if raw.detectors.is_empty() && !frame.network {
        c.push(
            "detectors",
            "[]",
            "at least one [[detectors]] entry (name, position_m) is required",
        );
    }
    if raw.detectors.len() > limits::MAX_DETECTORS {
        c.push(
            "detectors",
            format!("({} entries)", raw.detectors.len()),
            format!("at most {} [[detectors]] entries", limits::MAX_DETECTORS),
        );
    }
    let mut detectors = Vec::with_capacity(raw.detectors.len().min(limits::MAX_DETECTORS));
    for (i, d) in raw.detectors.iter().enumerate() {
        let field = format!("detectors[{i}].name");
        let name = match &d.name {
            None => {
                c.missing(&field, "a name, used in detectors.csv and [measurement]");
                String::new()
            }
            Some(n) if n.trim().is_empty() => {
                c.push(&field, quoted(n), "must be a non-empty string");
                n.clone()
            }
            Some(n) => {
                if let Some(j) = raw.detectors[..i]
                    .iter()
                    .position(|o| o.name.as_deref() == Some(n.as_str()))
                {
                    c.push(
                        &field,
                        quoted(n),
                        format!("duplicates detectors[{j}].name; names must be unique"),
                    );
                } else if generated.iter().any(|g| &g.name == n) {
                    c.push(
                        &field,
                        quoted(n),
                        "duplicates a detector generated for the network (\"end\", \
                         \"{id}-up\", \"{id}-down\", \"{id}-off\"); names must be unique",
                    );
                }
                n.clone()
            }
        };
        let field = format!("detectors[{i}].position_m");
        let what = if frame.network {
            "position in metres (corridor coordinate)"
        } else {
            "position in metres from the entrance"
        };
        let pos = c.req(&field, d.position_m, what);
        if let (Some(p), Some(hi)) = (pos, frame.hi) {
            c.check(
                &field,
                p,
                p.v > frame.origin && p.v < hi,
                format!("must lie inside {}", frame.inside_text(hi)),
            );
        }
        detectors.push(DetectorSpec::mainline(
            &name,
            pos.map_or(f64::NAN, |p| p.v - frame.origin),
        ));
    }
    if frame.network {
        // Mainline detectors by position (the generated ones first at a tie), then the
        // off-ramp detectors.
        let (mut all, off): (Vec<_>, Vec<_>) = generated
            .into_iter()
            .partition(|d| d.kind == DetectorKind::Mainline);
        all.append(&mut detectors);
        all.sort_by(|a, b| a.position_m.total_cmp(&b.position_m));
        all.extend(off);
        detectors = all;
    }

    // --- [measurement]
    let find = |n: &str| detectors.iter().position(|d| d.name == n);
    let measurement_detector = match (&raw.measurement.detector, frame.network) {
        (None, true) => find(crate::network::END_DETECTOR).unwrap_or(0),
        (None, false) if detectors.len() == 1 => 0,
        (None, false) => {
            c.missing(
                "measurement.detector",
                &format!(
                    "the name of one of the detectors ({})",
                    detector_names(&detectors)
                ),
            );
            0
        }
        (Some(n), _) => match find(n) {
            Some(i) => i,
            None => {
                c.push(
                    "measurement.detector",
                    quoted(n),
                    format!("names no detector; defined: {}", detector_names(&detectors)),
                );
                0
            }
        },
    };
    let aggregation = c.opt(raw.measurement.aggregation_s, defaults::AGGREGATION_S);
    if dt_ok {
        // The engine counts intervals in steps; an interval that is not a whole number of steps
        // would be reported with a length it does not have.
        let steps = aggregation.v / dt.v;
        let whole = (steps - steps.round()).abs() <= 1e-6 * steps.max(1.0);
        c.check(
            "measurement.aggregation_s",
            aggregation,
            aggregation.v >= dt.v && whole,
            format!(
                "must be a whole number of steps of run.dt_s = {}",
                dt.shown()
            ),
        );
    } else {
        c.positive("measurement.aggregation_s", aggregation);
    }
    // Every interval of every detector and lane is kept until the end of the run.
    if duration_ok && aggregation.v > 0.0 && aggregation.v.is_finite() {
        let records =
            (duration.v / aggregation.v).ceil() * detectors.len() as f64 * f64::from(lanes + 1);
        if records > limits::MAX_DETECTOR_RECORDS {
            c.push(
                "measurement.aggregation_s",
                aggregation.shown(),
                format!(
                    "gives {} detector records (run.duration_s / aggregation_s × {} detectors × \
                     (lanes + 1)); at most {}: use a longer interval or fewer detectors",
                    num(records),
                    detectors.len(),
                    num(limits::MAX_DETECTOR_RECORDS)
                ),
            );
        }
    }

    // --- [strategy]
    let s = &raw.strategy;
    let kind = match s.kind.as_deref() {
        None => StrategyKind::None,
        Some(k) => k.parse().unwrap_or_else(|_| {
            c.push(
                "strategy.kind",
                quoted(k),
                "must be one of \"none\", \"pd\", \"flow-aware\"",
            );
            StrategyKind::None
        }),
    };
    let zs = c.opt(s.zone_start_m, cstart.map_or(0.0, |n| n.v));
    let ze = c.opt(s.zone_end_m, cend.map_or(0.0, |n| n.v));
    // (Both in the file's coordinate.)
    // Zone and window default to the control section and the measurement window, which are
    // checked above; only values the file gives are checked again.
    let zone_given = !(zs.defaulted && ze.defaulted);
    if let (Some(hi), true) = (frame.hi, zone_given) {
        let ok = c.check(
            "strategy.zone_start_m",
            zs,
            zs.v >= frame.origin && zs.v < hi,
            format!(
                "must lie in [{}, {}) (the zone must be on the road)",
                frame.lo_text(),
                frame.hi_text(hi)
            ),
        );
        if ok {
            c.check(
                "strategy.zone_end_m",
                ze,
                ze.v > zs.v && ze.v <= hi,
                format!(
                    "must be > strategy.zone_start_m = {} and <= {}",
                    zs.shown(),
                    frame.hi_text(hi)
                ),
            );
        }
    }
    // The PD window defaults to the measurement window on the homogeneous road and to the
    // whole run on a network.
    let ts = c.opt(s.start_s, if frame.network { 0.0 } else { warmup.v });
    let te = c.opt(s.end_s, duration.v);
    let window_given = !(ts.defaulted && te.defaulted);
    if window_given && c.non_negative("strategy.start_s", ts) {
        c.check(
            "strategy.end_s",
            te,
            te.v > ts.v,
            format!("must be > strategy.start_s = {}", ts.shown()),
        );
    }
    // Unset thresholds come from the calibrated table at this penetration (issue 3 item 4).
    let (flow_default, speed_default) = crate::thresholds::default_at(
        penetration.v,
        (
            defaults::FLOW_THRESHOLD_VPHPL,
            defaults::SPEED_THRESHOLD_KMH,
        ),
    );
    let flow = c.opt(s.flow_threshold_vphpl, flow_default);
    c.check(
        "strategy.flow_threshold_vphpl",
        flow,
        flow.v > 0.0 && flow.v <= limits::MAX_FLOW_THRESHOLD_VPHPL,
        format!(
            "must be in (0, {}] veh/h/lane",
            num(limits::MAX_FLOW_THRESHOLD_VPHPL)
        ),
    );
    let speed = c.opt(s.speed_threshold_kmh, speed_default);
    c.check(
        "strategy.speed_threshold_kmh",
        speed,
        (0.0..=limits::MAX_SPEED_THRESHOLD_KMH).contains(&speed.v),
        format!(
            "must be in [0, {}] km/h",
            num(limits::MAX_SPEED_THRESHOLD_KMH)
        ),
    );
    let radius = c.opt(s.radius_m, defaults::RADIUS_M);
    c.check(
        "strategy.radius_m",
        radius,
        radius.v > 0.0 && radius.v <= limits::MAX_LENGTH_M,
        format!("must be in (0, {}] m", num(limits::MAX_LENGTH_M)),
    );
    let pd = PdConfig {
        zone_start_m: zs.v - frame.origin,
        zone_end_m: ze.v - frame.origin,
        start_s: ts.v,
        end_s: te.v,
    };
    let strategy = match kind {
        StrategyKind::None => Strategy::None,
        StrategyKind::Pd => Strategy::Pd { pd },
        StrategyKind::FlowAware => Strategy::FlowAware {
            pd,
            thresholds: FlowAwareConfig {
                flow_threshold_vphpl: flow.v,
                speed_threshold_kmh: speed.v,
                radius_m: radius.v,
            },
        },
    };

    // --- model sections
    if all_finite(&mut c, "human", &raw.human) {
        check_human(&mut c, &raw.human);
    }
    if all_finite(&mut c, "cav", &raw.cav) {
        check_cav(&mut c, &raw.cav);
    }
    if all_finite(&mut c, "lane_change", &raw.lane_change) {
        check_lane_change(&mut c, &raw.lane_change, length);
    }
    all_finite(&mut c, "safety", &raw.safety);

    let config = Config {
        name,
        seed,
        dt_s: dt.v,
        duration_s: duration.v,
        warmup_s: warmup.v,
        penetration: penetration.v,
        road: Road {
            lanes,
            length_m: length.unwrap_or(f64::NAN),
            control_start_m: cstart.map_or(f64::NAN, |n| n.v - frame.origin),
            control_end_m: cend.map_or(f64::NAN, |n| n.v - frame.origin),
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
        aggregation_s: aggregation.v,
        measurement_detector,
        strategy,
        human: raw.human,
        cav: raw.cav.clone(),
        lane_change: raw.lane_change,
        safety: raw.safety,
    };
    if c.problems.is_empty() {
        // The engine's own invariants; the checks above are stricter, so this is a safety net.
        if let Err(message) = config.check() {
            c.push("(engine check)", "-", message);
        }
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

/// The detector names for a message (the first 12 if there are more).
fn detector_names(detectors: &[DetectorSpec]) -> String {
    const SHOWN: usize = 12;
    let names: Vec<String> = detectors
        .iter()
        .filter(|d| !d.name.is_empty())
        .map(|d| quoted(&d.name))
        .collect();
    match names.len() {
        0 => "none".into(),
        n if n > SHOWN => format!(
            "{}, … ({n} in all; `platoonsim show` lists them)",
            names[..SHOWN].join(", ")
        ),
        _ => names.join(", "),
    }
}

/// `road.lanes` and `road.length_m` of a road without a network (both required).
fn road_size(c: &mut Checker, raw: &RawScenario) -> (u32, Option<f64>) {
    let lanes = match raw.road.lanes {
        None => {
            c.missing(
                "road.lanes",
                &format!("an integer from 1 to {}", defaults::MAX_LANES),
            );
            0
        }
        Some(n) => {
            if !(1..=defaults::MAX_LANES).contains(&n) {
                c.push(
                    "road.lanes",
                    n.to_string(),
                    format!("must be an integer from 1 to {}", defaults::MAX_LANES),
                );
            }
            n
        }
    };
    let length = c.req(
        "road.length_m",
        raw.road.length_m,
        "the road length in metres, > 0",
    );
    let length = length
        .filter(|&l| {
            c.check(
                "road.length_m",
                l,
                l.v > 0.0 && l.v <= limits::MAX_LENGTH_M,
                format!("must be in (0, {}] m", num(limits::MAX_LENGTH_M)),
            )
        })
        .map(|n| n.v);
    (lanes, length)
}

/// The expected number of arrivals at every entrance of a network over `duration_s` (the last
/// interval's demand holds past the end of the series, as in the engine).
fn expected_network_arrivals(n: &platoonsim_sim::config::Network, duration_s: f64) -> f64 {
    let over = |series: &[f64]| -> f64 {
        let mut total = 0.0;
        let mut t = 0.0;
        for (k, q) in series.iter().enumerate() {
            if t >= duration_s {
                break;
            }
            let end = if k + 1 == series.len() {
                duration_s
            } else {
                (t + n.interval_s).min(duration_s)
            };
            total += q * (end - t) / 3600.0;
            t = end;
        }
        total
    };
    let ramps: f64 = n.on_ramps.iter().map(|r| over(&r.demand_vph)).sum();
    (over(&n.mainline_vph) + ramps) * n.demand_scale
}

#[cfg(test)]
mod tests {
    use super::expected_network_arrivals;

    #[test]
    fn network_arrivals_integrate_the_series_and_hold_the_last_value() {
        let c = crate::load("sr99").unwrap();
        let n = c.road.network.unwrap();
        let per_interval = |k: usize| {
            let ramps: f64 = n.on_ramps.iter().map(|r| r.demand_vph[k]).sum();
            (n.mainline_vph[k] + ramps) * n.demand_scale * n.interval_s / 3600.0
        };
        let len = n.mainline_vph.len();
        let series: f64 = (0..len).map(per_interval).sum();
        let span = len as f64 * n.interval_s;
        assert!((expected_network_arrivals(&n, span) - series).abs() < 1e-6 * series);
        // Half the first interval; then one more interval at the last value.
        let half = expected_network_arrivals(&n, n.interval_s / 2.0);
        assert!((half - per_interval(0) / 2.0).abs() < 1e-6 * half);
        let more = expected_network_arrivals(&n, span + n.interval_s);
        assert!((more - series - per_interval(len - 1)).abs() < 1e-6 * more);
    }
}
