//! Validated simulation input. The engine only ever sees a [`Config`] that
//! `platoonsim-scenario` has validated (ranges, detector positions, …); [`Config::check`]
//! repeats the invariants the engine relies on so that a library user cannot bypass them.

use crate::error::SimError;
use crate::organize::{LaneChoice, StrategyKind};
use platoonsim_model::cav::CavParams;
use platoonsim_model::energy::EnergyParams;
use platoonsim_model::human::HumanDists;
use platoonsim_model::lanechange::LaneChangeDists;
use platoonsim_model::safety::SafetyParams;
use serde::Serialize;

mod meter;
pub use meter::{Meter, MeterLaw, MAX_METER_RATE_VPH};

/// A straight multi-lane road (the paper's homogeneous segment). Positions in metres from
/// the entrance; lanes numbered from the right, 0 = rightmost, `lanes - 1` = leftmost (the PD
/// lane).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Road {
    pub lanes: u32,
    pub length_m: f64,
    /// The control section, where platoon organization may act (paper: 5,000-6,000 m).
    pub control_start_m: f64,
    pub control_end_m: f64,
    /// A freeway network (issue 4): changing lane count, ramps, time-varying demand. `None`
    /// for the homogeneous road, where every lane is open over [0, length_m).
    pub network: Option<Network>,
}

impl Road {
    /// Output coordinate of engine x = 0: the network's `origin_m`, 0 on the plain road.
    #[inline]
    pub fn origin_m(&self) -> f64 {
        self.network.as_ref().map_or(0.0, |n| n.origin_m)
    }
}

/// A freeway corridor (issue 4). Engine coordinates: x = 0 at the mainline entrance, x =
/// `length_m` at the end; outputs report x + `origin_m` (e.g. metres downstream of a
/// reference ramp). Lateral lane indices run from the right: index 0 is the rightmost
/// position anywhere on the corridor, so that a lane added on the right has a lower index
/// than the lanes beside it, and an acceleration lane lies at (rightmost through lane − 1).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Network {
    /// Output coordinate of engine x = 0 (m).
    pub origin_m: f64,
    /// Where each through (mainline) lane is open. A lane may have several extents; one that
    /// ends before the road end is a lane drop (its vehicles must leave it).
    pub through_lanes: Vec<LaneExtent>,
    pub on_ramps: Vec<OnRamp>,
    pub off_ramps: Vec<OffRamp>,
    /// Length of one demand interval (s), e.g. 900 for 15 min. Interval k covers
    /// [k·interval_s, (k+1)·interval_s); past the last one the last value holds.
    pub interval_s: f64,
    /// Demand at the mainline entrance per interval (veh/h, all lanes), before scaling.
    pub mainline_vph: Vec<f64>,
    /// Multiplier on every entrance demand (paper: 100-127 %).
    pub demand_scale: f64,
    /// Speed limit of the ramps: vehicles enter the acceleration lane at most at this speed (km/h).
    pub ramp_speed_kmh: f64,
    /// Lane-based desired-speed caps (spec 2.7, km/h): every driver's desired speed in a lane is
    /// at most the cap of that lane, counted from the rightmost through lane at its position
    /// (the first entry; an acceleration lane takes it too); the last entry holds for every lane
    /// further left. Empty: no caps (the default).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub lane_speed_limits_kmh: Vec<f64>,
    /// Cross-lane friction c_fr ∈ (0, 1] (spec 2.7): a human driver (or a CAV's driver in
    /// manual mode) whose slower adjacent lane runs below its desired speed v_F drives toward
    /// v_adj + c_fr (v_F − v_adj) instead. `None` (the default) and 1 are off.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cross_lane_friction: Option<f64>,
    /// Section behaviour (docs/network-scenarios.md; `behaviour.rs`): stretches, in order and
    /// not overlapping, with factors on the human car-following buffer θ and on the desired
    /// speed. Empty: 1 everywhere (the default).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub behaviour: Vec<DriverStretch>,
}

/// A stretch [from_m, to_m) (engine coordinates) of section behaviour (`behaviour.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DriverStretch {
    pub from_m: f64,
    pub to_m: f64,
    /// f_θ: factor on the Gipps buffer θ of the human car-following model.
    pub buffer_factor: f64,
    /// f_v: factor on the desired speed v_F.
    pub speed_factor: f64,
}

/// A through lane open on [from_m, to_m) (engine coordinates).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LaneExtent {
    pub lane: u32,
    pub from_m: f64,
    pub to_m: f64,
}

/// An on-ramp. Its vehicles enter at the merge point `x_m`: into the through lane that starts
/// there if there is one (a lane add), otherwise into an acceleration lane of length
/// `accel_lane_m` just right of the rightmost through lane, which they must leave by its end
/// (mandatory change, spec 4.2); at the end they stop and wait.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OnRamp {
    pub name: String,
    pub x_m: f64,
    pub accel_lane_m: f64,
    /// Ramp roadway length upstream of the merge point (m): the ramp density of the
    /// anticipation rule (spec 4.2) counts its queue over this length plus the acceleration lane.
    pub ramp_length_m: f64,
    /// Demand per interval (veh/h), before scaling.
    pub demand_vph: Vec<f64>,
    /// A ramp meter (docs/network-scenarios.md); `None`, the default, releases the queue as
    /// the insertion rule admits, and is not written (configurations without meters keep
    /// their identity).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub meter: Option<Meter>,
    /// The share of CAVs among this ramp's arrivals, in [0, 1]; `None`, the default, is the
    /// run's `penetration` (and is not written, so configurations without it keep their
    /// identity).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub penetration: Option<f64>,
}

/// An off-ramp (diverge at `x_m`). A vehicle decides on entry, for each off-ramp downstream in
/// turn, with the current interval's exit fraction (a Bernoulli trial), and then makes the
/// mandatory changes to the rightmost through lane at `x_m` (spec 4.2).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OffRamp {
    pub name: String,
    pub x_m: f64,
    /// Share of the arriving mainline vehicles that take this exit, per interval, in [0, 1].
    pub exit_fraction: Vec<f64>,
}

impl Network {
    /// The invariants the engine relies on (the scenario crate checks the same with file
    /// context).
    pub fn check(&self, lanes: u32, length_m: f64) -> Result<(), SimError> {
        let series = |name: &str, v: &[f64], hi: f64| -> Result<(), SimError> {
            if v.is_empty() {
                return Err(SimError::Config(format!(
                    "{name}: must have at least one interval"
                )));
            }
            match v
                .iter()
                .position(|x| !(x.is_finite() && *x >= 0.0 && *x <= hi))
            {
                Some(k) => Err(SimError::Config(format!(
                    "{name}[{k}] = {}: must be a finite number in [0, {hi}]",
                    v[k]
                ))),
                None => Ok(()),
            }
        };
        if !(self.interval_s.is_finite() && self.interval_s > 0.0) {
            return Err(SimError::Config(format!(
                "network.interval_s = {}: must be a finite number > 0",
                self.interval_s
            )));
        }
        if !(self.demand_scale.is_finite() && self.demand_scale >= 0.0) {
            return Err(SimError::Config(format!(
                "network.demand_scale = {}: must be a finite number >= 0",
                self.demand_scale
            )));
        }
        if !(self.ramp_speed_kmh.is_finite() && self.ramp_speed_kmh > 0.0) {
            return Err(SimError::Config(format!(
                "network.ramp_speed_kmh = {}: must be a finite number > 0",
                self.ramp_speed_kmh
            )));
        }
        for (i, c) in self.lane_speed_limits_kmh.iter().enumerate() {
            if !(c.is_finite() && *c > 0.0) {
                return Err(SimError::Config(format!(
                    "network.lane_speed_limits_kmh[{i}] = {c}: must be a finite number > 0"
                )));
            }
        }
        for (i, r) in self.on_ramps.iter().enumerate() {
            if let Some(p) = r.penetration {
                if !(0.0..=1.0).contains(&p) {
                    return Err(SimError::Config(format!(
                        "network.on_ramps[{i}].penetration = {p}: must be in [0, 1]"
                    )));
                }
            }
        }
        if let Some(c) = self.cross_lane_friction {
            if !(c > 0.0 && c <= 1.0) {
                return Err(SimError::Config(format!(
                    "network.cross_lane_friction = {c}: must be in (0, 1] (1 = off)"
                )));
            }
        }
        for (i, b) in self.behaviour.iter().enumerate() {
            let after = i.checked_sub(1).map_or(0.0, |k| self.behaviour[k].to_m);
            if !(b.from_m >= after && b.to_m > b.from_m && b.to_m <= length_m) {
                return Err(SimError::Config(format!(
                    "network.behaviour[{i}] on [{}, {}): stretches must lie in [0, {length_m}], \
                     in order, each after the previous one's end ({after})",
                    b.from_m, b.to_m
                )));
            }
            if !((0.0..=5.0).contains(&b.buffer_factor) && (0.5..=1.5).contains(&b.speed_factor)) {
                return Err(SimError::Config(format!(
                    "network.behaviour[{i}]: buffer_factor = {} must be in [0, 5] and \
                     speed_factor = {} in [0.5, 1.5]",
                    b.buffer_factor, b.speed_factor
                )));
            }
        }
        series("network.mainline_vph", &self.mainline_vph, f64::MAX)?;
        for (i, e) in self.through_lanes.iter().enumerate() {
            if e.lane >= lanes || !(e.from_m >= 0.0 && e.to_m > e.from_m && e.to_m <= length_m) {
                return Err(SimError::Config(format!(
                    "network.through_lanes[{i}] = lane {} on [{}, {}): the lane must be < {lanes} and the extent inside [0, {length_m}]",
                    e.lane, e.from_m, e.to_m
                )));
            }
        }
        if !self.through_lanes.iter().any(|e| e.from_m == 0.0) {
            return Err(SimError::Config(
                "network.through_lanes: no lane is open at the entrance (x = 0)".into(),
            ));
        }
        for (i, r) in self.on_ramps.iter().enumerate() {
            if !(r.x_m > 0.0 && r.x_m < length_m) {
                return Err(SimError::Config(format!(
                    "network.on_ramps[{i}].x_m = {}: must lie inside the road (0, {length_m})",
                    r.x_m
                )));
            }
            let ok = |v: f64| v.is_finite() && v >= 0.0;
            if !(ok(r.accel_lane_m) && ok(r.ramp_length_m)) {
                return Err(SimError::Config(format!(
                    "network.on_ramps[{i}]: accel_lane_m = {} and ramp_length_m = {} must be finite and >= 0",
                    r.accel_lane_m, r.ramp_length_m
                )));
            }
            series(
                &format!("network.on_ramps[{i}].demand_vph"),
                &r.demand_vph,
                f64::MAX,
            )?;
            if let Some(m) = &r.meter {
                m.check(i, r.x_m, length_m)?;
            }
        }
        for (i, r) in self.off_ramps.iter().enumerate() {
            if i > 0 && r.x_m < self.off_ramps[i - 1].x_m {
                return Err(SimError::Config(format!(
                    "network.off_ramps[{i}].x_m = {}: off-ramps must be listed in downstream order (off_ramps[{}].x_m = {})",
                    r.x_m,
                    i - 1,
                    self.off_ramps[i - 1].x_m
                )));
            }
            if !(r.x_m > 0.0 && r.x_m < length_m) {
                return Err(SimError::Config(format!(
                    "network.off_ramps[{i}].x_m = {}: must lie inside the road (0, {length_m})",
                    r.x_m
                )));
            }
            series(
                &format!("network.off_ramps[{i}].exit_fraction"),
                &r.exit_fraction,
                1.0,
            )?;
        }
        Ok(())
    }

    /// Value of a per-interval series at time `t_s` (the last value past the end; 0 if empty).
    pub fn at(&self, series: &[f64], t_s: f64) -> f64 {
        if series.is_empty() {
            return 0.0;
        }
        let k = if self.interval_s > 0.0 {
            (t_s / self.interval_s).floor().max(0.0) as usize
        } else {
            0
        };
        series[k.min(series.len() - 1)]
    }
}

/// Traffic demand at the entrance: Poisson arrivals, Bernoulli vehicle type.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Demand {
    /// Arrival rate per lane of the entrance (veh/h/lane).
    pub vph_per_lane: f64,
}

/// A loop detector across all through lanes at a position, or the counter of an off-ramp.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DetectorSpec {
    pub name: String,
    /// Engine coordinate (m).
    pub position_m: f64,
    pub kind: DetectorKind,
    /// Counts toward the network discharge (off-ramps and the mainline end).
    pub exit: bool,
}

/// What a detector covers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Default)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum DetectorKind {
    /// The through lanes open at its position (acceleration lanes excluded).
    #[default]
    Mainline,
    /// The vehicles leaving by off-ramp `ramp` (index into `Network::off_ramps`).
    OffRamp { ramp: usize },
    /// The vehicles entering from on-ramp `ramp` (index into `Network::on_ramps`), counted
    /// where they are placed on the acceleration lane: a PeMS on-ramp station's count.
    OnRamp { ramp: usize },
}

impl DetectorSpec {
    /// A mainline detector that is not an exit.
    pub fn mainline(name: &str, position_m: f64) -> DetectorSpec {
        DetectorSpec {
            name: name.to_string(),
            position_m,
            kind: DetectorKind::Mainline,
            exit: false,
        }
    }
}

/// Platoon organization strategy (`[strategy]`): which registered organizer
/// ([`crate::organize::STRATEGIES`]) and its settings. Serialized as before the organizer
/// table: `{"kind": "none"}`, with `pd` for an organizing strategy and `thresholds` for
/// Flow-Aware.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Strategy {
    pub kind: StrategyKind,
    /// Zone, time window and lane; `None` for a strategy that does not organize.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pd: Option<PdConfig>,
    /// Flow-Aware thresholds; `None` unless the strategy needs them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thresholds: Option<FlowAwareConfig>,
}

impl Default for Strategy {
    fn default() -> Self {
        Strategy::none()
    }
}

impl Strategy {
    /// No organization (the baseline).
    pub fn none() -> Strategy {
        Strategy {
            kind: StrategyKind::NONE,
            pd: None,
            thresholds: None,
        }
    }

    /// The PD lane with these settings.
    pub fn pd(pd: PdConfig) -> Strategy {
        Strategy {
            kind: StrategyKind::PD,
            pd: Some(pd),
            thresholds: None,
        }
    }
}

/// Where, when and which lane an organizing strategy applies.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct PdConfig {
    pub zone_start_m: f64,
    pub zone_end_m: f64,
    pub start_s: f64,
    pub end_s: f64,
    /// The organized lane (default the leftmost through lane).
    #[serde(skip_serializing_if = "LaneChoice::is_leftmost")]
    pub lane: LaneChoice,
}

/// Flow-Aware thresholds.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FlowAwareConfig {
    /// ρ_q (veh/h/lane): organize only below this mean flow.
    pub flow_threshold_vphpl: f64,
    /// ρ_v (km/h): organize only above this mean speed.
    pub speed_threshold_kmh: f64,
    /// Detectors within this distance of the CAV are averaged (m).
    pub radius_m: f64,
}

/// Everything one run needs.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Config {
    /// Scenario name, copied to the summary.
    pub name: String,
    pub seed: u64,
    /// Step length Δt (s); default 0.1.
    pub dt_s: f64,
    /// Simulated time (s).
    pub duration_s: f64,
    /// Start of the measurement window (s); the window is [warmup_s, duration_s].
    pub warmup_s: f64,
    /// Share of CAVs among arrivals, in [0, 1].
    pub penetration: f64,
    pub road: Road,
    pub demand: Demand,
    pub detectors: Vec<DetectorSpec>,
    /// Detector aggregation interval (s); paper: 300.
    pub aggregation_s: f64,
    /// Index into `detectors` of the discharge (measurement) detector.
    pub measurement_detector: usize,
    pub strategy: Strategy,
    pub human: HumanDists,
    pub cav: CavParams,
    pub lane_change: LaneChangeDists,
    /// Surrogate safety measures' settings (`[safety]`, docs/safety.md).
    pub safety: SafetyParams,
    /// Energy per vehicle (`[energy]`, docs/energy.md); off by default, and then not written,
    /// so that configurations without it keep their identity.
    #[serde(skip_serializing_if = "EnergyParams::is_default")]
    pub energy: EnergyParams,
    /// The mechanism measures (`measurement.mechanism`, `mechanism.rs`); off by default, and
    /// then not written, so that configurations without them keep their identity.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub mechanism: bool,
    /// Clock time of t = 0 (s after midnight, `run.clock_start`), when the scenario names one:
    /// outputs then carry clock time next to simulated time. A label of the outputs only: the
    /// engine never reads it, so it is not serialized and no run's identity depends on it.
    #[serde(skip)]
    pub clock_start_s: Option<u32>,
}

/// Input limits shared by the engine's [`Config::check`] and the scenario crate's validation
/// (the one place they are defined; docs/robustness.md lists them with the reasons).
pub mod limits {
    /// Smallest step Δt (s). The laws are tuned per 0.1 s step and the built-in scenarios
    /// stay collision-free and within the braking limits on [`DT_MIN_S`, `DT_MAX_S`]
    /// (docs/safety.md).
    pub const DT_MIN_S: f64 = 0.05;
    /// Largest step Δt (s): the CACC law is tuned per 0.1 s step; the built-in scenarios were
    /// measured collision-free up to 0.25 s and collide at 0.5 s (docs/safety.md).
    pub const DT_MAX_S: f64 = 0.2;
    /// Why Δt is limited, for error messages.
    pub const DT_REASON: &str = "the CACC law is tuned per 0.1 s step; at 0.5 s the \
        built-in scenarios collide, docs/safety.md";
    /// Longest run (s): 7 simulated days, far beyond any experiment (the paper's longest is
    /// 4 h), and a bound on the time and memory a run can take.
    pub const MAX_DURATION_S: f64 = 7.0 * 86_400.0;
    /// Highest entrance demand per lane (veh/h/lane): five times a lane's capacity; above it
    /// the entry queue would only grow (and hold every waiting vehicle in memory).
    pub const MAX_DEMAND_VPHPL: f64 = 10_000.0;
    /// Longest road or corridor (m).
    pub const MAX_LENGTH_M: f64 = 200_000.0;
}

impl Config {
    /// The invariants the engine relies on; `Err` names the field, the value and what is
    /// allowed. (The scenario crate checks the same and more, with file context.)
    pub fn check(&self) -> Result<(), SimError> {
        use limits::*;
        let pos = |name: &str, v: f64| -> Result<(), SimError> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(SimError::Config(format!(
                    "{name} = {v}: must be a finite number > 0"
                )))
            }
        };
        // A range check, with the allowed interval and why in the message.
        let within = |name: &str, v: f64, lo: f64, hi: f64, why: &str| -> Result<(), SimError> {
            if (lo..=hi).contains(&v) {
                Ok(())
            } else {
                Err(SimError::Config(format!(
                    "{name} = {v}: must be in [{lo}, {hi}]{why}"
                )))
            }
        };
        within(
            "run.dt_s",
            self.dt_s,
            DT_MIN_S,
            DT_MAX_S,
            &format!(" s ({DT_REASON})"),
        )?;
        pos("run.duration_s", self.duration_s)?;
        within(
            "run.duration_s",
            self.duration_s,
            0.0,
            MAX_DURATION_S,
            " s (at most 7 simulated days)",
        )?;
        pos("road.length_m", self.road.length_m)?;
        within("road.length_m", self.road.length_m, 0.0, MAX_LENGTH_M, " m")?;
        pos("measurement.aggregation_s", self.aggregation_s)?;
        // Detector intervals are counted in whole steps.
        let steps = self.aggregation_s / self.dt_s;
        if !(steps >= 1.0 && (steps - steps.round()).abs() <= 1e-6 * steps) {
            return Err(SimError::Config(format!(
                "measurement.aggregation_s = {}: must be a whole number of steps of run.dt_s = {}",
                self.aggregation_s, self.dt_s
            )));
        }
        if !(self.warmup_s.is_finite() && self.warmup_s >= 0.0 && self.warmup_s < self.duration_s) {
            return Err(SimError::Config(format!(
                "run.warmup_s = {}: must be >= 0 and < run.duration_s = {}",
                self.warmup_s, self.duration_s
            )));
        }
        if !(0.0..=1.0).contains(&self.penetration) {
            return Err(SimError::Config(format!(
                "run.penetration = {}: must be in [0, 1]",
                self.penetration
            )));
        }
        if !(1..=8).contains(&self.road.lanes) {
            return Err(SimError::Config(format!(
                "road.lanes = {}: must be 1 to 8",
                self.road.lanes
            )));
        }
        within(
            "demand.vph_per_lane",
            self.demand.vph_per_lane,
            0.0,
            MAX_DEMAND_VPHPL,
            " veh/h/lane",
        )?;
        // Braking limits: b_e positive, harder than the normal limit (docs/safety.md).
        use platoonsim_model::safety::{MAX_EMERGENCY_DECEL_MPS2, MAX_TTC_THRESHOLD_S};
        for (name, b_e, normal) in [
            (
                "human.emergency_decel_mps2",
                self.human.emergency_decel_mps2,
                -self.human.max_decel.min,
            ),
            (
                "cav.emergency_decel_mps2",
                self.cav.emergency_decel_mps2,
                -self.cav.max_decel,
            ),
        ] {
            pos(name, b_e)?;
            let lo = normal.max(0.0);
            if !(b_e > lo && b_e <= MAX_EMERGENCY_DECEL_MPS2) {
                return Err(SimError::Config(format!(
                    "{name} = {b_e}: must be in ({lo}, {MAX_EMERGENCY_DECEL_MPS2}] m/s² (harder \
                     than the normal braking limit)"
                )));
            }
        }
        pos("safety.ttc_threshold_s", self.safety.ttc_threshold_s)?;
        within(
            "safety.ttc_threshold_s",
            self.safety.ttc_threshold_s,
            0.0,
            MAX_TTC_THRESHOLD_S,
            " s",
        )?;
        let entry = self.strategy.kind.entry();
        if entry.organizes && self.strategy.pd.is_none() {
            return Err(SimError::Config(format!(
                "strategy.kind = \"{}\": needs its zone and time window (strategy.zone_start_m, \
                 strategy.zone_end_m, strategy.start_s, strategy.end_s)",
                entry.name
            )));
        }
        if entry.needs_thresholds && self.strategy.thresholds.is_none() {
            return Err(SimError::Config(format!(
                "strategy.kind = \"{}\": needs strategy.flow_threshold_vphpl, \
                 strategy.speed_threshold_kmh and strategy.radius_m",
                entry.name
            )));
        }
        if let Some(LaneChoice::Index(i)) = self.strategy.pd.as_ref().map(|p| p.lane) {
            if i >= self.road.lanes {
                return Err(SimError::Config(format!(
                    "strategy.lane = {}: must be 1 to road.lanes = {} (or \"leftmost\", \
                     \"rightmost\")",
                    i + 1,
                    self.road.lanes
                )));
            }
        }
        for (i, d) in self.detectors.iter().enumerate() {
            if !(d.position_m.is_finite()
                && d.position_m > 0.0
                && d.position_m < self.road.length_m)
            {
                return Err(SimError::Config(format!(
                    "detectors[{i}].position_m = {}: must lie inside the road (0, {})",
                    d.position_m, self.road.length_m
                )));
            }
        }
        if let Some(net) = &self.road.network {
            net.check(self.road.lanes, self.road.length_m)?;
            // Scaled entrance demand: the mainline per lane open at the entrance, a ramp as
            // one lane.
            let entry_lanes = net.through_lanes.iter().filter(|e| e.from_m == 0.0).count();
            let cap = |lanes: usize| MAX_DEMAND_VPHPL * lanes.max(1) as f64;
            let entrances = std::iter::once((
                "network.mainline_vph".to_string(),
                &net.mainline_vph,
                cap(entry_lanes),
            ))
            .chain(net.on_ramps.iter().enumerate().map(|(i, r)| {
                (
                    format!("network.on_ramps[{i}].demand_vph"),
                    &r.demand_vph,
                    cap(1),
                )
            }));
            for (name, series, hi) in entrances {
                if let Some(k) = series
                    .iter()
                    .position(|q| !(0.0..=hi).contains(&(q * net.demand_scale)))
                {
                    return Err(SimError::Config(format!(
                        "{name}[{k}] = {} (x demand scale {}): must be at most {hi} veh/h \
                         ({MAX_DEMAND_VPHPL} veh/h per entrance lane)",
                        series[k], net.demand_scale
                    )));
                }
            }
        }
        for (i, d) in self.detectors.iter().enumerate() {
            let net = self.road.network.as_ref();
            let (ramp, n, what) = match d.kind {
                DetectorKind::Mainline => continue,
                DetectorKind::OffRamp { ramp } => {
                    (ramp, net.map_or(0, |n| n.off_ramps.len()), "off-ramp")
                }
                DetectorKind::OnRamp { ramp } => {
                    (ramp, net.map_or(0, |n| n.on_ramps.len()), "on-ramp")
                }
            };
            if ramp >= n {
                return Err(SimError::Config(format!(
                    "detectors[{i}] counts {what} {ramp}, but only {n} {what}s exist"
                )));
            }
        }
        if self.measurement_detector >= self.detectors.len() {
            return Err(SimError::Config(format!(
                "measurement.detector index {} names no detector ({} defined)",
                self.measurement_detector,
                self.detectors.len()
            )));
        }
        Ok(())
    }
}

impl Config {
    /// The paper's homogeneous road with the spec defaults, for the engine's own tests and
    /// benchmarks, which cannot read scenario files. A mirror, not a definition: the road is
    /// defined by the built-in scenario file `crates/scenario/scenarios/homogeneous.toml`, and
    /// the scenario crate's test `homogeneous_config_mirrors_the_scenario_file` requires this
    /// config to equal the file loaded with the same five values (and [`Config::with_pd`] to
    /// equal it with `strategy.kind = "pd"`). Code outside tests loads the file.
    pub fn homogeneous(
        penetration: f64,
        demand_vphpl: f64,
        duration_s: f64,
        warmup_s: f64,
        seed: u64,
    ) -> Config {
        Config {
            name: "homogeneous".into(),
            seed,
            dt_s: 0.1,
            duration_s,
            warmup_s,
            penetration,
            road: Road {
                lanes: 3,
                length_m: 6500.0,
                control_start_m: 5000.0,
                control_end_m: 6000.0,
                network: None,
            },
            demand: Demand {
                vph_per_lane: demand_vphpl,
            },
            detectors: vec![
                DetectorSpec::mainline("upstream", 4900.0),
                DetectorSpec::mainline("control_mid", 5500.0),
                DetectorSpec::mainline("discharge", 6100.0),
            ],
            aggregation_s: 300.0,
            measurement_detector: 2,
            strategy: Strategy::none(),
            human: HumanDists::default(),
            cav: CavParams::default(),
            lane_change: LaneChangeDists::default(),
            safety: SafetyParams::default(),
            energy: EnergyParams::default(),
            mechanism: false,
            clock_start_s: None,
        }
    }

    /// The same run with the paper's PD set-up: the PD lane in the road's control section from
    /// the end of the warm-up to the end of the run.
    pub fn with_pd(mut self) -> Config {
        self.strategy = Strategy::pd(PdConfig {
            zone_start_m: self.road.control_start_m,
            zone_end_m: self.road.control_end_m,
            start_s: self.warmup_s,
            end_s: self.duration_s,
            lane: LaneChoice::Leftmost,
        });
        self
    }
}
