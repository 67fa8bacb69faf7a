//! Run outputs: the summary and the detector records (plain data; the CLI writes files).

use crate::record::{TrajectoryPoint, Trip};
// Defined where they are made (the detectors, the collision events); listed here too as what
// a run produces.
pub use crate::detector::DetectorRecord;
pub use crate::events::{CollisionEvent, CollisionKind};
use serde::Serialize;

/// One run's summary (`summary.json`). Rates per lane use the road's lane count.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    pub scenario: String,
    pub penetration: f64,
    /// Demand of a plain road (veh/h/lane); `None` (null) on a network, whose entrances have
    /// their own demand series.
    pub demand_vphpl: Option<f64>,
    /// Network scenarios: the multiplier applied to every entrance demand series of the
    /// scenario file (`network.base_demand_multiplier` × `network.demand_scale`, the latter
    /// from the scenario's table at the run's penetration). `None` (null) on a plain road.
    pub demand_scale: Option<f64>,
    pub strategy: String,
    pub seed: u64,
    pub dt_s: f64,
    pub duration_s: f64,
    pub warmup_s: f64,
    pub vehicles_entered: u64,
    pub vehicles_exited: u64,
    pub vehicles_in_network: u64,
    /// Vehicles still in the virtual entry queue at the end.
    pub vehicles_waiting: u64,
    /// Lane changes of vehicles that entered in the window / those vehicles. A statistic
    /// that does not apply (no vehicle of its kind counted, e.g. the CAV and platoon fields
    /// at 0 % CAV) is `None`, written as `null`, never 0: a 0 would pull averages down.
    pub lane_changes_per_vehicle: Option<f64>,
    /// The same per CAV and per human-driven vehicle.
    pub lane_changes_per_cav: Option<f64>,
    pub lane_changes_per_human: Option<f64>,
    /// Cooperative lane changes (spec 9.2: made under automation into a gap a CAV follower
    /// opened) of the vehicles counted in the lane-change statistic; 0 without
    /// `cav.cooperative_lane_change`.
    pub cooperative_lane_changes: u64,
    /// L̄: mean over CAVs (entered in the window) of the largest platoon each was in.
    pub avg_platoon_length: Option<f64>,
    /// P_P: share of those CAVs ever in a platoon of 2 or more.
    pub platooning_probability: Option<f64>,
    /// L̄ and P_P counting a link only while the follower is not in speed regulation (time gap
    /// ≤ 2 s, spec 6.15); the two fields above use the paper's definition (a CAV directly
    /// behind a CAV under CACC, within sensor range).
    pub avg_platoon_length_tg2: Option<f64>,
    pub platooning_probability_tg2: Option<f64>,
    /// CAVs counted in the platoon statistics.
    pub cavs_counted: u64,
    /// Vehicles counted in the lane-change statistic.
    pub vehicles_counted: u64,
    /// Flow at the measurement detector over the measurement window (veh/h/lane).
    pub discharge_flow_vphpl: f64,
    /// Highest aggregation-interval flow at the measurement detector in the window (veh/h/lane).
    pub max_sustained_flow_vphpl: f64,
    /// Network scenarios: vehicles leaving by the exit detectors (off-ramps and the mainline
    /// end) per hour, mean over the measurement window (veh/h). Absent for a plain road.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub network_discharge_vph: Option<f64>,
    /// Aggregation intervals of the measurement window in which a mainline detector counted
    /// no vehicle in any of its lanes, summed over the mainline detectors: a stopped section
    /// (a deadlock or a queue standing still for a whole interval) while demand is present.
    pub zero_flow_intervals: u64,
    /// Vehicles that could not reach the lane of their off-ramp in time and drove on to the end.
    pub missed_exits: u64,
    /// Collision events over the whole run: a vehicle pair that starts to overlap, or a vehicle
    /// that reaches the end of its lane ([`CollisionEvent`]). A run with any is a failed run.
    pub collisions: u64,
    /// Largest deceleration applied by any vehicle over the whole run (m/s², positive; 0 if
    /// none braked). Never above the vehicle's emergency limit.
    pub max_deceleration_mps2: f64,
    /// Vehicle-km driven in the measurement window (all vehicles, CAVs, human-driven
    /// vehicles): the denominators of the `_per_100vkm` rates.
    pub vehicle_km: f64,
    pub vehicle_km_cav: f64,
    pub vehicle_km_human: f64,
    /// The measures counted in episodes over the measurement window (docs/safety.md, spec
    /// 9.4): hard, severe and at-limit brakings, rear-end and lane-change conflicts, each as
    /// `<name>`, `<name>_cav`, `<name>_human` (counts) and `<name>_per_100vkm`,
    /// `<name>_per_100vkm_cav`, `<name>_per_100vkm_human` (per 100 veh-km of the same
    /// vehicles; null without any).
    #[serde(flatten)]
    pub counted: CountedMeasures,
    /// The hard-braking episodes of the window by peak deceleration and kind.
    pub braking_peaks: BrakingPeaks,
    /// Time-exposed TTC (vehicle-seconds with TTC below the threshold).
    pub tet_s: f64,
    pub tet_s_cav: f64,
    pub tet_s_human: f64,
    /// Time-integrated TTC: Σ (TTC* − TTC) Δt below the threshold (s²).
    pub tit_s2: f64,
    pub tit_s2_cav: f64,
    pub tit_s2_human: f64,
    /// Smallest TTC seen in the window (s); `None` (null) if no follower ever closed in on its
    /// leader.
    pub min_ttc_s: Option<f64>,
    /// CACC fallbacks to ACC (spec 9.3) in the measurement window: episodes in which a CAV
    /// behind a CAV received no V2V beacon within `cav.beacon_timeout_s`.
    pub cacc_fallbacks: u64,
    /// Fuel and electricity (docs/energy.md), with `energy.enabled` only.
    #[serde(flatten)]
    pub energy: Option<crate::energy::EnergySummary>,
    /// Where an organizing strategy's discharge change comes from (`mechanism.rs`,
    /// docs/outputs.md), with `measurement.mechanism` only.
    #[serde(flatten)]
    pub mechanism: Option<crate::mechanism::MechanismSummary>,
    /// The ramp meters' accounts over the whole run, in ramp order; empty (and not written)
    /// without meters.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub meters: Vec<MeterSummary>,
    pub vehicle_updates: u64,
    pub steps: u64,
    pub wall_seconds: f64,
}

/// One ramp meter over the whole run (`summary.json`'s `meters`; docs/outputs.md). "Active":
/// inside the meter's hours; "metering": active and not in queue override.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MeterSummary {
    /// The on-ramp, named as in the configuration (`"OR7: Calvine Rd WB"`).
    pub ramp: String,
    /// `fixed` or `alinea`.
    pub kind: &'static str,
    /// Time the meter was active (s).
    pub active_s: f64,
    /// Vehicles it released while active (at a green, or freely in a fixed meter's override).
    pub released: u64,
    /// Time mean of the rate it ran while metering (veh/h); `None` if it never metered.
    pub mean_rate_vph: Option<f64>,
    /// The lowest rate it ran while metering (veh/h).
    pub min_rate_vph: Option<f64>,
    /// Time in queue override (s).
    pub override_s: f64,
    /// Time mean of the vehicles waiting on the ramp while active; `None` if never active.
    pub queue_mean_veh: Option<f64>,
    /// The most vehicles waiting on the ramp while active.
    pub queue_max_veh: u64,
}

/// One measure counted in episodes, by kind (the braking vehicle's, or the conflict's
/// follower's), with its rates per 100 veh-km.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CountedMeasure {
    /// Its name in the outputs, e.g. `hard_brakings`.
    pub name: &'static str,
    pub cav: u64,
    pub human: u64,
    /// Per 100 veh-km of all vehicles, of CAVs, of human-driven vehicles (`None` when no such
    /// vehicle drove in the window).
    pub per_100vkm: Option<f64>,
    pub per_100vkm_cav: Option<f64>,
    pub per_100vkm_human: Option<f64>,
}

impl CountedMeasure {
    pub fn total(&self) -> u64 {
        self.cav + self.human
    }
}

/// The counted measures, written into the summary as six fields each (see
/// [`Summary::counted`]), in this order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CountedMeasures(pub Vec<CountedMeasure>);

impl CountedMeasures {
    /// The measure named `name` (e.g. `severe_brakings`).
    pub fn get(&self, name: &str) -> Option<&CountedMeasure> {
        self.0.iter().find(|m| m.name == name)
    }

    /// The names of the fields a measure `name` gives, in output order.
    pub fn field_names(name: &str) -> [String; 6] {
        [
            name.to_string(),
            format!("{name}_cav"),
            format!("{name}_human"),
            format!("{name}_per_100vkm"),
            format!("{name}_per_100vkm_cav"),
            format!("{name}_per_100vkm_human"),
        ]
    }
}

impl Serialize for CountedMeasures {
    fn serialize<S: serde::Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = ser.serialize_map(Some(self.0.len() * 6))?;
        for m in &self.0 {
            let [n, n_cav, n_human, r, r_cav, r_human] = CountedMeasures::field_names(m.name);
            map.serialize_entry(&n, &m.total())?;
            map.serialize_entry(&n_cav, &m.cav)?;
            map.serialize_entry(&n_human, &m.human)?;
            map.serialize_entry(&r, &m.per_100vkm)?;
            map.serialize_entry(&r_cav, &m.per_100vkm_cav)?;
            map.serialize_entry(&r_human, &m.per_100vkm_human)?;
        }
        map.end()
    }
}

/// A histogram of the hard-braking episodes' peak decelerations by kind: bin i holds the
/// peaks from `lower_edges_mps2[i]` up to the next edge (the last bin is open).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct BrakingPeaks {
    pub lower_edges_mps2: Vec<f64>,
    pub cav: Vec<u64>,
    pub human: Vec<u64>,
}

/// Everything a run produces.
#[derive(Clone, Debug, PartialEq)]
pub struct Output {
    pub summary: Summary,
    pub detectors: Vec<DetectorRecord>,
    /// Every collision, in time order (empty in a correct run).
    pub collision_events: Vec<CollisionEvent>,
    /// With [`crate::Recording::trips`]: one trip per vehicle that entered the road, in the
    /// order they left, then those still on the road by id.
    pub trips: Option<Vec<Trip>>,
    /// With [`crate::Recording::trips`]: the vehicles still waiting in an entrance queue at the
    /// end of the run, by id (as many as `Simulation::vehicles_waiting` then).
    pub queued: Option<Vec<crate::record::Queued>>,
    /// With [`crate::Recording::trajectories`]: the samples in time order, each sample by id.
    pub trajectories: Option<Vec<TrajectoryPoint>>,
}
