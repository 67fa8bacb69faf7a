//! Validated simulation input. The engine only ever sees a [`Config`] that
//! `platoonsim-scenario` has validated (ranges, detector positions, …); [`Config::check`]
//! repeats the invariants the engine relies on so that a library user cannot bypass them.

use platoonsim_model::cav::CavParams;
use platoonsim_model::human::HumanDists;
use platoonsim_model::lanechange::LaneChangeDists;
use serde::Serialize;

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
}

/// Traffic demand at the entrance: Poisson arrivals, Bernoulli vehicle type.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Demand {
    /// Arrival rate per lane of the entrance (veh/h/lane).
    pub vph_per_lane: f64,
}

/// A loop detector across all lanes at a position.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DetectorSpec {
    pub name: String,
    pub position_m: f64,
}

/// Platoon organization strategy (issue 3). `None` = no organization (baseline).
#[derive(Clone, Debug, PartialEq, Serialize, Default)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Strategy {
    #[default]
    None,
    /// Pseudo-dedicated lane (spec 4.7): the leftmost lane, inside the zone and time window.
    Pd { pd: PdConfig },
    /// Flow-Aware PD lane: PD only while nearby detectors report flow < ρ_q and speed > ρ_v.
    FlowAware {
        pd: PdConfig,
        thresholds: FlowAwareConfig,
    },
}

/// Where and when the PD lane applies.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PdConfig {
    pub zone_start_m: f64,
    pub zone_end_m: f64,
    pub start_s: f64,
    pub end_s: f64,
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
}

impl Config {
    /// The invariants the engine relies on; `Err` names the field, the value and what is
    /// allowed. (The scenario crate checks the same and more, with file context.)
    pub fn check(&self) -> Result<(), String> {
        let pos = |name: &str, v: f64| -> Result<(), String> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(format!("{name} = {v}: must be a finite number > 0"))
            }
        };
        pos("run.dt_s", self.dt_s)?;
        pos("run.duration_s", self.duration_s)?;
        pos("road.length_m", self.road.length_m)?;
        pos("measurement.aggregation_s", self.aggregation_s)?;
        if !(self.warmup_s.is_finite() && self.warmup_s >= 0.0 && self.warmup_s < self.duration_s) {
            return Err(format!(
                "run.warmup_s = {}: must be >= 0 and < run.duration_s = {}",
                self.warmup_s, self.duration_s
            ));
        }
        if !(0.0..=1.0).contains(&self.penetration) {
            return Err(format!(
                "run.penetration = {}: must be in [0, 1]",
                self.penetration
            ));
        }
        if !(1..=8).contains(&self.road.lanes) {
            return Err(format!("road.lanes = {}: must be 1 to 8", self.road.lanes));
        }
        if !(self.demand.vph_per_lane.is_finite() && self.demand.vph_per_lane >= 0.0) {
            return Err(format!(
                "demand.vph_per_lane = {}: must be a finite number >= 0",
                self.demand.vph_per_lane
            ));
        }
        for (i, d) in self.detectors.iter().enumerate() {
            if !(d.position_m.is_finite()
                && d.position_m > 0.0
                && d.position_m < self.road.length_m)
            {
                return Err(format!(
                    "detectors[{i}].position_m = {}: must lie inside the road (0, {})",
                    d.position_m, self.road.length_m
                ));
            }
        }
        if self.measurement_detector >= self.detectors.len() {
            return Err(format!(
                "measurement.detector index {} names no detector ({} defined)",
                self.measurement_detector,
                self.detectors.len()
            ));
        }
        Ok(())
    }
}

impl Config {
    /// The paper's homogeneous road with the spec defaults (the same values as the built-in
    /// `homogeneous` scenario file; handy for tests and benchmarks of the engine alone).
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
            },
            demand: Demand {
                vph_per_lane: demand_vphpl,
            },
            detectors: vec![
                DetectorSpec {
                    name: "upstream".into(),
                    position_m: 4900.0,
                },
                DetectorSpec {
                    name: "control_mid".into(),
                    position_m: 5500.0,
                },
                DetectorSpec {
                    name: "discharge".into(),
                    position_m: 6100.0,
                },
            ],
            aggregation_s: 300.0,
            measurement_detector: 2,
            strategy: Strategy::None,
            human: HumanDists::default(),
            cav: CavParams::default(),
            lane_change: LaneChangeDists::default(),
        }
    }
}
