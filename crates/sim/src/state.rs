//! The simulation state, split by responsibility. [`crate::Simulation`] holds one of each;
//! ARCHITECTURE.md lists which phase reads and writes which part.

use crate::automation::Automation;
use crate::command::Active;
use crate::detector::Detector;
use crate::events::{Event, Observer};
use crate::here::HereTables;
use crate::metrics::Metrics;
use crate::network::{Geometry, NO_LANE};
use crate::organize::Organizer;
use crate::safety::Safety;
use crate::vehicle::Vehicle;
use platoonsim_model::bounded;
use platoonsim_model::lanechange::Side;

mod decision;
mod sensed;

pub(crate) use decision::Decision;
pub(crate) use sensed::{Neighbours, Sensed, NONE};

/// Simulated time, counted in steps.
#[derive(Clone, Debug)]
pub(crate) struct Clock {
    /// Step length Δt (s).
    pub dt: f64,
    /// Steps done so far; simulated time = step · dt.
    pub step: u64,
    pub total_steps: u64,
    /// First step of the measurement window.
    pub warmup_step: u64,
    /// Steps of a detector interval.
    pub agg_steps: u64,
}

/// The vehicles and their lanes.
#[derive(Clone, Debug, Default)]
pub(crate) struct Traffic {
    /// Dense vehicle storage; slots listed in `free` are dead.
    pub vehicles: Vec<Vehicle>,
    pub free: Vec<u32>,
    /// Per lane (0 = rightmost), vehicle slots sorted front first (descending x).
    pub lanes: Vec<Vec<u32>>,
    /// The id of the next vehicle to enter.
    pub next_id: u64,
    /// The automation's realism (spec 9.3): its constants and the V2V broadcast log by slot.
    pub auto: Automation,
}

impl Traffic {
    /// Slot of the vehicle with this id, if it is on the road.
    pub fn slot_of(&self, id: u64) -> Option<u32> {
        self.lanes
            .iter()
            .flatten()
            .copied()
            .find(|&s| self.vehicles[s as usize].id == id)
    }

    /// Allocate a slot for a new vehicle.
    pub fn alloc(&mut self, v: Vehicle) -> u32 {
        let speed = v.v;
        let s = if let Some(s) = self.free.pop() {
            self.vehicles[s as usize] = v;
            s
        } else {
            self.vehicles.push(v);
            (self.vehicles.len() - 1) as u32
        };
        if let Some(b) = &mut self.auto.beacons {
            b.fill(s, speed);
        }
        s
    }
}

/// The road: its geometry and the lookup tables built from it once.
#[derive(Clone, Debug)]
pub(crate) struct RoadState {
    pub geom: Geometry,
    /// `Here` along each lane as a step function (here.rs).
    pub here_tables: HereTables,
    /// Ramp speed limit (m/s); ∞ on a plain road.
    pub ramp_speed_mps: f64,
    /// Lane-based desired-speed caps (spec 2.7, m/s) by lane counted from the rightmost through
    /// lane, the last for every lane further left; empty: none.
    pub lane_caps_mps: Vec<f64>,
    /// Cross-lane friction c_fr (spec 2.7), `None` when off (not given, or 1).
    pub friction: Option<f64>,
    /// Section behaviour stretches (`behaviour.rs`), engine coordinates; empty: none.
    pub behaviour: Vec<crate::config::DriverStretch>,
}

impl RoadState {
    /// The desired speed of a driver whose own is `v_f` in `lane` (spec 2.7): capped by the
    /// lane's speed limit when the network has lane-based caps, counted from the rightmost
    /// through lane `right` at its position (`NO_LANE`: none there; the first cap). Without
    /// caps exactly `v_f`.
    #[inline]
    pub fn desired_speed_in(&self, v_f: f64, lane: usize, right: u8) -> f64 {
        if self.lane_caps_mps.is_empty() {
            return v_f;
        }
        self.lane_capped(v_f, lane, right)
    }

    /// For a vehicle not yet on the road (insertion): `v_f` times the section's speed factor
    /// at `x`; on the road [`crate::behaviour::Sections`] has set it already.
    pub fn section_speed(&self, v_f: f64, x: f64) -> f64 {
        if self.behaviour.is_empty() {
            return v_f;
        }
        v_f * crate::behaviour::factors_at(&self.behaviour, x).1
    }

    /// For a vehicle not yet on the road: its driver parameters with the section's buffer
    /// factor at `x`; `None` without one there (use its own).
    pub fn section_human(
        &self,
        p: &platoonsim_model::human::HumanParams,
        x: f64,
    ) -> Option<platoonsim_model::human::HumanParams> {
        if self.behaviour.is_empty() {
            return None;
        }
        crate::behaviour::params_at(&self.behaviour, p, x)
    }

    /// `v_f` capped by the desired-speed cap of `lane`. Requires caps.
    #[inline]
    pub fn lane_capped(&self, v_f: f64, lane: usize, right: u8) -> f64 {
        let caps = &self.lane_caps_mps;
        let rank = if right == NO_LANE {
            0
        } else {
            lane.saturating_sub(right as usize)
        };
        bounded::min(v_f, caps[rank.min(caps.len() - 1)])
    }
}

/// Per-step scratch, rebuilt every step (no allocation once warmed up).
#[derive(Clone, Debug, Default)]
pub(crate) struct Scratch {
    /// Indexed by slot: what the sense phase found for each vehicle (one cache line each).
    pub sensed: Vec<Sensed>,
    /// Per lane, parallel to the lane lists: (x, v) of each vehicle at the step start (sense
    /// phase), then sentinels (−∞, 0) (`sense::SENTINELS`).
    pub lane_xv: Vec<Vec<(f64, f64)>>,
    /// Indexed by slot: the decide phase's result.
    pub decisions: Vec<Decision>,
    /// Indexed by slot: the step of the vehicle's last lane change.
    pub changed_this_step: Vec<u64>,
    pub change_list: Vec<(u32, Side)>,
    /// A vehicle reached its off-ramp's position in this step's integrate phase.
    pub exit_due: bool,
    /// No lane was unsorted by this step's integrate phase.
    pub lanes_sorted: bool,
    /// Vehicles past the end of their lane in this step's integrate phase: (slot, lane, wall).
    pub crashed: Vec<(u32, u32, f64)>,
    /// Per on-ramp, the anticipation factor 1 + c_inc (ρ_ramp/ρ_jam)/j for j = 1, 2 (spec 4.2)
    /// from its density at the step start: computed once per step instead of per vehicle.
    pub ramp_factor: Vec<[f64; 2]>,
}

/// The loop detectors.
#[derive(Clone, Debug, Default)]
pub(crate) struct Detectors {
    pub list: Vec<Detector>,
    /// Per detector and lane: where the detector's last lane search ended.
    pub hint: Vec<u32>,
    /// Per off-ramp, the detector that counts it.
    pub exit_of_ramp: Vec<Option<usize>>,
    /// Per on-ramp, the detector that counts it.
    pub entry_of_ramp: Vec<Option<usize>>,
}

/// What the run measures as it goes: the paper's statistics, the safety measures, counters.
#[derive(Debug)]
pub(crate) struct Measures {
    pub metrics: Metrics,
    /// Braking limit, collisions and surrogate safety measures (`safety.rs`).
    pub safety: Safety,
    pub vehicle_updates: u64,
    pub missed_exits: u64,
    /// CACC fallbacks to ACC for want of V2V beacons in the measurement window (spec 9.3).
    pub cacc_fallbacks: u64,
}

/// What steers the vehicles besides their models: the platoon-organization strategy and the
/// commands from outside.
#[derive(Debug)]
pub(crate) struct Control {
    /// The strategy (`organize`).
    pub organizer: Box<dyn Organizer>,
    /// Whether it advises human drivers (index 0) and CAVs (1): asked once, so that a
    /// strategy that advises nobody costs nothing per vehicle.
    pub advise: [bool; 2],
    /// Commands in force (`command.rs`), applied in the decide phase.
    pub commands: Vec<Active>,
}

/// The library user's observers and the current step's events (buffered only while there
/// is one).
#[derive(Default)]
pub(crate) struct Watch {
    pub observers: Vec<Box<dyn Observer>>,
    pub events: Vec<Event>,
    pub observing: bool,
    /// Collision events already passed to the observers.
    pub collisions_reported: usize,
}
