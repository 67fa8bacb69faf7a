//! Level two: a [`RawScenario`] becomes a [`Config`], or a list of every [`Problem`] found.
//! Defaults for optional keys are applied here (and reported as `(default)` if they clash with
//! something the file gave).

use crate::error::{Problem, ScenarioError};
use crate::overrides::StrategyKind;
use crate::raw::{num, render, RawScenario};
use platoonsim_model::cav::CavParams;
use platoonsim_model::dist::Dist;
use platoonsim_model::human::HumanDists;
use platoonsim_model::lanechange::LaneChangeDists;
use platoonsim_sim::{Config, Demand, DetectorSpec, FlowAwareConfig, PdConfig, Road, Strategy};
use toml::Value;

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
    pub const MAX_DEMAND_VPHPL: f64 = 10_000.0;
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
        dt.v > 0.0 && dt.v <= 1.0,
        "must be in (0, 1] seconds",
    );
    let duration = c.opt(raw.run.duration_s, defaults::DURATION_S);
    let duration_ok = c.positive("run.duration_s", duration);
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

    // --- [road]
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
        .filter(|&l| c.positive("road.length_m", l))
        .map(|n| n.v);
    let cstart = c.req(
        "road.control_start_m",
        raw.road.control_start_m,
        "start of the control section (m from the entrance)",
    );
    let cend = c.req(
        "road.control_end_m",
        raw.road.control_end_m,
        "end of the control section (m from the entrance)",
    );
    if let (Some(s), Some(e)) = (cstart, cend) {
        match length {
            Some(l) => {
                let s_ok = c.check(
                    "road.control_start_m",
                    s,
                    s.v >= 0.0 && s.v < l,
                    format!("must lie in [0, road.length_m = {}) (the control section must be on the road)", num(l)),
                );
                if s_ok {
                    c.check(
                        "road.control_end_m",
                        e,
                        e.v > s.v && e.v <= l,
                        format!(
                            "must be > road.control_start_m = {} and <= road.length_m = {}",
                            num(s.v),
                            num(l)
                        ),
                    );
                }
            }
            None => {
                c.non_negative("road.control_start_m", s);
                c.non_negative("road.control_end_m", e);
            }
        }
    }

    // --- [demand]
    if let Some(q) = c.req(
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

    // --- [[detectors]]
    if raw.detectors.is_empty() {
        c.push(
            "detectors",
            "[]",
            "at least one [[detectors]] entry (name, position_m) is required",
        );
    }
    let mut detectors = Vec::with_capacity(raw.detectors.len());
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
                }
                n.clone()
            }
        };
        let field = format!("detectors[{i}].position_m");
        let pos = c.req(&field, d.position_m, "position in metres from the entrance");
        if let (Some(p), Some(l)) = (pos, length) {
            c.check(
                &field,
                p,
                p.v > 0.0 && p.v < l,
                format!("must lie inside the road (0, {})", num(l)),
            );
        }
        detectors.push(DetectorSpec {
            name,
            position_m: pos.map_or(f64::NAN, |p| p.v),
        });
    }

    // --- [measurement]
    let measurement_detector = match &raw.measurement.detector {
        None if raw.detectors.len() == 1 => 0,
        None => {
            c.missing(
                "measurement.detector",
                &format!("the name of one of the detectors ({})", detector_names(raw)),
            );
            0
        }
        Some(n) => match raw
            .detectors
            .iter()
            .position(|d| d.name.as_deref() == Some(n.as_str()))
        {
            Some(i) => i,
            None => {
                c.push(
                    "measurement.detector",
                    quoted(n),
                    format!("names no detector; defined: {}", detector_names(raw)),
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
    // Zone and window default to the control section and the measurement window, which are
    // checked above; only values the file gives are checked again.
    let zone_given = !(zs.defaulted && ze.defaulted);
    if let (Some(l), true) = (length, zone_given) {
        let ok = c.check(
            "strategy.zone_start_m",
            zs,
            zs.v >= 0.0 && zs.v < l,
            format!(
                "must lie in [0, road.length_m = {}) (the zone must be on the road)",
                num(l)
            ),
        );
        if ok {
            c.check(
                "strategy.zone_end_m",
                ze,
                ze.v > zs.v && ze.v <= l,
                format!(
                    "must be > strategy.zone_start_m = {} and <= road.length_m = {}",
                    zs.shown(),
                    num(l)
                ),
            );
        }
    }
    let ts = c.opt(s.start_s, warmup.v);
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
    c.positive("strategy.flow_threshold_vphpl", flow);
    let speed = c.opt(s.speed_threshold_kmh, speed_default);
    c.non_negative("strategy.speed_threshold_kmh", speed);
    let radius = c.opt(s.radius_m, defaults::RADIUS_M);
    c.positive("strategy.radius_m", radius);
    let pd = PdConfig {
        zone_start_m: zs.v,
        zone_end_m: ze.v,
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
            control_start_m: cstart.map_or(f64::NAN, |n| n.v),
            control_end_m: cend.map_or(f64::NAN, |n| n.v),
        },
        demand: Demand {
            vph_per_lane: raw.demand.vph_per_lane.unwrap_or(f64::NAN),
        },
        detectors,
        aggregation_s: aggregation.v,
        measurement_detector,
        strategy,
        human: raw.human,
        cav: raw.cav.clone(),
        lane_change: raw.lane_change,
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

fn detector_names(raw: &RawScenario) -> String {
    let names: Vec<String> = raw
        .detectors
        .iter()
        .filter_map(|d| d.name.as_deref().map(quoted))
        .collect();
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}

/// Report every non-finite number (TOML allows `nan` and `inf`) in a model section; true if
/// there is none.
fn all_finite<T: serde::Serialize>(c: &mut Checker, section: &str, params: &T) -> bool {
    fn walk(c: &mut Checker, path: &str, v: &Value, ok: &mut bool) {
        match v {
            Value::Float(f) if !f.is_finite() => {
                c.push(path, num(*f), "must be a finite number");
                *ok = false;
            }
            Value::Table(t) => {
                for (k, v) in t {
                    walk(c, &format!("{path}.{k}"), v, ok);
                }
            }
            Value::Array(items) => {
                for (i, v) in items.iter().enumerate() {
                    walk(c, &format!("{path}[{i}]"), v, ok);
                }
            }
            _ => {}
        }
    }
    let mut ok = true;
    match Value::try_from(params) {
        Ok(v) => walk(c, section, &v, &mut ok),
        Err(e) => {
            c.push(section, "-", format!("cannot be represented: {e}"));
            ok = false;
        }
    }
    ok
}

fn check_human(c: &mut Checker, h: &HumanDists) {
    c.dist(
        "human.length_m",
        &h.length_m,
        Some((h.length_m.min > 0.0, "min must be > 0 m")),
    );
    c.dist(
        "human.jam_gap_m",
        &h.jam_gap_m,
        Some((h.jam_gap_m.min >= 0.0, "min must be >= 0 m")),
    );
    c.dist(
        "human.headway_s",
        &h.headway_s,
        Some((h.headway_s.min > 0.0, "min must be > 0 s")),
    );
    c.dist(
        "human.reaction_s",
        &h.reaction_s,
        Some((h.reaction_s.min > 0.0, "min must be > 0 s")),
    );
    c.dist(
        "human.max_accel",
        &h.max_accel,
        Some((
            h.max_accel.min > 0.0,
            "min must be > 0 m/s² (an acceleration)",
        )),
    );
    c.dist(
        "human.max_decel",
        &h.max_decel,
        Some((
            h.max_decel.max < 0.0,
            "max must be < 0 m/s² (decelerations are negative)",
        )),
    );
    c.dist(
        "human.desired_speed_kmh",
        &h.desired_speed_kmh,
        Some((
            h.desired_speed_kmh.min > 0.0 && h.desired_speed_kmh.max <= 300.0,
            "must lie in (0, 300] km/h",
        )),
    );
    c.value(
        "human.buffer_s",
        h.buffer_s,
        h.buffer_s >= 0.0,
        "must be >= 0 s",
    );
    c.value(
        "human.leader_brake_factor",
        h.leader_brake_factor,
        h.leader_brake_factor > 0.0,
        "must be > 0",
    );
    c.value(
        "human.free_exponent",
        h.free_exponent,
        h.free_exponent > 0.0,
        "must be > 0",
    );
    c.value(
        "human.smoothing",
        h.smoothing,
        h.smoothing >= 1.0,
        "must be >= 1 (1 = no smoothing)",
    );
    c.value(
        "human.comfort_factor",
        h.comfort_factor,
        h.comfort_factor > 0.0 && h.comfort_factor <= 1.0,
        "must be in (0, 1] (a fraction of max_decel)",
    );
}

fn check_cav(c: &mut Checker, p: &CavParams) {
    let pos = |c: &mut Checker, f: &str, v: f64| c.value(f, v, v > 0.0, "must be > 0");
    let nonneg = |c: &mut Checker, f: &str, v: f64| c.value(f, v, v >= 0.0, "must be >= 0");
    pos(c, "cav.speed_gain", p.speed_gain);
    pos(c, "cav.acc_time_gap_s", p.acc_time_gap_s);
    for (f, g) in [
        ("cav.acc_reg_gains", p.acc_reg_gains),
        ("cav.acc_closing_gains", p.acc_closing_gains),
        ("cav.acc_avoid_gains", p.acc_avoid_gains),
        ("cav.cacc_reg_gains", p.cacc_reg_gains),
        ("cav.cacc_closing_gains", p.cacc_closing_gains),
        ("cav.cacc_avoid_gains", p.cacc_avoid_gains),
    ] {
        if !(g[0] >= 0.0 && g[1] >= 0.0) {
            c.push(f, pair(g), "both gains must be >= 0");
        }
    }
    for (f, b, unit) in [
        ("cav.acc_range_m", p.acc_range_m, "m"),
        ("cav.cacc_tg_band_s", p.cacc_tg_band_s, "s"),
    ] {
        if !(b[0] > 0.0 && b[0] <= b[1]) {
            c.push(
                f,
                pair(b),
                format!("must be [low, high] with 0 < low <= high ({unit})"),
            );
        }
    }
    nonneg(c, "cav.speed_control_min_gap_m", p.speed_control_min_gap_m);
    nonneg(c, "cav.reg_gap_band_m", p.reg_gap_band_m);
    nonneg(c, "cav.reg_speed_band_mps", p.reg_speed_band_mps);
    nonneg(c, "cav.standstill_gap_m", p.standstill_gap_m);
    nonneg(c, "cav.reaction_s", p.reaction_s);
    nonneg(c, "cav.time_gap_ramp_per_s", p.time_gap_ramp_per_s);
    c.value(
        "cav.max_accel",
        p.max_accel,
        p.max_accel > 0.0,
        "must be > 0 m/s²",
    );
    c.value(
        "cav.max_decel",
        p.max_decel,
        p.max_decel < 0.0,
        "must be < 0 m/s² (decelerations are negative)",
    );
    pos(c, "cav.inter_platoon_gap_s", p.inter_platoon_gap_s);
    if p.max_platoon < 1 {
        c.push(
            "cav.max_platoon",
            p.max_platoon.to_string(),
            "must be >= 1 vehicle",
        );
    }
    pos(c, "cav.sensor_range_m", p.sensor_range_m);

    let shares = &p.time_gap_shares;
    let text = || {
        let items: Vec<String> = shares
            .iter()
            .map(|&(g, s)| format!("[{}, {}]", num(g), num(s)))
            .collect();
        format!("[{}]", items.join(", "))
    };
    if shares.is_empty() {
        c.push(
            "cav.time_gap_shares",
            "[]",
            "at least one [time_gap_s, share] pair is required",
        );
    } else if let Some(i) = shares
        .iter()
        .position(|&(g, s)| !(g > 0.0 && (0.0..=1.0).contains(&s)))
    {
        c.push(
            format!("cav.time_gap_shares[{i}]"),
            format!("[{}, {}]", num(shares[i].0), num(shares[i].1)),
            "each pair is [time_gap_s > 0, share in [0, 1]]",
        );
    } else {
        let sum: f64 = shares.iter().map(|&(_, s)| s).sum();
        if (sum - 1.0).abs() > 1e-6 {
            c.push(
                "cav.time_gap_shares",
                text(),
                format!("the shares must sum to 1 (they sum to {})", num(sum)),
            );
        }
    }
}

fn pair(g: [f64; 2]) -> String {
    format!("[{}, {}]", num(g[0]), num(g[1]))
}

fn check_lane_change(c: &mut Checker, l: &LaneChangeDists, road_length: Option<f64>) {
    c.dist(
        "lane_change.mandatory_distance_m",
        &l.mandatory_distance_m,
        Some((
            l.mandatory_distance_m.min > l.mandatory_min_distance_m,
            "min must be > lane_change.mandatory_min_distance_m",
        )),
    );
    c.dist(
        "lane_change.mandatory_time_s",
        &l.mandatory_time_s,
        Some((
            l.mandatory_time_s.min > l.mandatory_min_time_s,
            "min must be > lane_change.mandatory_min_time_s",
        )),
    );
    c.dist(
        "lane_change.threshold",
        &l.threshold,
        Some((
            l.threshold.min >= 0.0 && l.threshold.max <= 1.0,
            "must lie in [0, 1]",
        )),
    );
    c.dist(
        "lane_change.cooperativeness",
        &l.cooperativeness,
        Some((
            l.cooperativeness.min >= 0.0 && l.cooperativeness.max <= 1.0,
            "must lie in [0, 1] (a probability)",
        )),
    );
    let nonneg = |c: &mut Checker, f: &str, v: f64| c.value(f, v, v >= 0.0, "must be >= 0");
    let unit = |c: &mut Checker, f: &str, v: f64| {
        c.value(f, v, (0.0..=1.0).contains(&v), "must be in [0, 1]")
    };
    let relax =
        |c: &mut Checker, f: &str, v: f64| c.value(f, v, v > 0.0 && v <= 1.0, "must be in (0, 1]");
    nonneg(
        c,
        "lane_change.mandatory_min_distance_m",
        l.mandatory_min_distance_m,
    );
    nonneg(
        c,
        "lane_change.mandatory_min_time_s",
        l.mandatory_min_time_s,
    );
    unit(c, "lane_change.right_discount", l.right_discount);
    unit(c, "lane_change.mandatory_weight", l.mandatory_weight);
    unit(
        c,
        "lane_change.discretionary_coop_factor",
        l.discretionary_coop_factor,
    );
    unit(c, "lane_change.slow_down_desire", l.slow_down_desire);
    unit(c, "lane_change.cav_weight_leader", l.cav_weight_leader);
    unit(c, "lane_change.cav_weight_follower", l.cav_weight_follower);
    c.value(
        "lane_change.sigma_forward",
        l.sigma_forward,
        l.sigma_forward > 0.0,
        "must be > 0",
    );
    c.value(
        "lane_change.sigma_backward",
        l.sigma_backward,
        l.sigma_backward > 0.0,
        "must be > 0",
    );
    relax(c, "lane_change.relax_headway", l.relax_headway);
    relax(c, "lane_change.relax_jam", l.relax_jam);
    relax(c, "lane_change.relax_reaction", l.relax_reaction);
    c.value(
        "lane_change.relax_time_s",
        l.relax_time_s,
        l.relax_time_s > 0.0,
        "must be > 0 s",
    );
    nonneg(c, "lane_change.scan_distance_m", l.scan_distance_m);
    if l.scan_vehicles < 1 {
        c.push(
            "lane_change.scan_vehicles",
            l.scan_vehicles.to_string(),
            "must be >= 1",
        );
    }
    nonneg(c, "lane_change.min_interval_s", l.min_interval_s);
    nonneg(c, "lane_change.return_factor", l.return_factor);
    nonneg(c, "lane_change.min_speed_gain_mps", l.min_speed_gain_mps);
    c.value(
        "lane_change.min_reference_speed_mps",
        l.min_reference_speed_mps,
        l.min_reference_speed_mps > 0.0,
        "must be > 0 m/s",
    );
    match road_length {
        Some(len) => c.value(
            "lane_change.forbid_zone_m",
            l.forbid_zone_m,
            l.forbid_zone_m >= 0.0 && l.forbid_zone_m < len,
            &format!("must be >= 0 and < road.length_m = {}", num(len)),
        ),
        None => nonneg(c, "lane_change.forbid_zone_m", l.forbid_zone_m),
    }
}
