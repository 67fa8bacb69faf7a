//! What happens in a run, as typed events, and the observers that receive them.
//!
//! The engine buffers a step's events only while an observer is attached
//! ([`crate::Simulation::observe`]): without one, a run pays one branch per event site. Events
//! of a step come in the order of the step's phases (docs/library.md): emergency brakings and
//! lane-end collisions (integrate), lane changes, exits, entries, rear-end collisions, then the
//! driving-mode changes seen at the end of the step. All carry the simulated time at the end of
//! the step.
//!
//! An observer sees a [`StepView`] after each step (the time, the vehicles as
//! [`VehicleView`]s, the step's events) and a [`VehicleView`] of each vehicle that leaves: never
//! the engine itself, so this module and the observers depend on the vehicle record's public
//! face only.
//!
//! The built-in records are observers too: the paper's statistics ([`crate::metrics::Metrics`]),
//! the trip and trajectory records and the energy meter are called through [`Observer`]
//! (statically, without a virtual call).

use crate::vehicle::{Kind, ModeLabel, Vehicle};
use crate::view::{self, VehicleView};
use platoonsim_model::cav::CavMode;
use serde::Serialize;

/// Why a vehicle changed lanes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LaneChangeReason {
    /// A mandatory desire (a lane that ends, the way to its off-ramp, a lane its strategy
    /// closes to it), possibly with a discretionary part on the same side (spec 4.2).
    Mandatory,
    /// A discretionary desire: speed gain, on-ramp anticipation (spec 4.2).
    Discretionary,
    /// Platoon organization: the strategy's `Join` advice (spec 4.7).
    Organizing,
    /// A lane change commanded from outside ([`crate::Command::ChangeLane`]).
    Commanded,
}

impl LaneChangeReason {
    /// `mandatory`, `discretionary`, `organizing` or `commanded`.
    pub fn as_str(self) -> &'static str {
        match self {
            LaneChangeReason::Mandatory => "mandatory",
            LaneChangeReason::Discretionary => "discretionary",
            LaneChangeReason::Organizing => "organizing",
            LaneChangeReason::Commanded => "commanded",
        }
    }
}

/// How a vehicle left the road, or that it is still on it at the end of the run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Departure {
    /// By this off-ramp (index into the network's off-ramps).
    OffRamp(usize),
    /// At the end of the mainline (where it meant to, or after missing its off-ramp).
    RoadEnd,
    /// It ran past the end of its lane and was removed (a lane-end collision).
    Collided,
    /// Still on the road when the run ends (reported once, by [`Observer::on_exit`] at the end).
    OnRoad,
}

/// One event. Yielding in this model is done by slowing down, so it appears as a
/// [`Event::ModeChange`] to `ycf`, never as a lane change.
#[derive(Clone, Debug, PartialEq)]
pub enum Event {
    /// A vehicle was inserted at an entrance (0 the mainline, i + 1 on-ramp i).
    Entered {
        t_s: f64,
        id: u64,
        kind: Kind,
        entrance: u32,
        lane: u32,
        x_m: f64,
        v_mps: f64,
    },
    /// A vehicle left the road.
    Exited {
        t_s: f64,
        id: u64,
        kind: Kind,
        how: Departure,
        x_m: f64,
        v_mps: f64,
    },
    /// A lane change from lane `from` to `to` (engine indices, 0 = rightmost).
    LaneChange {
        t_s: f64,
        id: u64,
        kind: Kind,
        from: u32,
        to: u32,
        x_m: f64,
        reason: LaneChangeReason,
        /// A cooperative change, made under automation into a gap a CAV follower opened
        /// (spec 9.2).
        cooperative: bool,
    },
    /// The driving mode or the CAV controller's regime changed in this step.
    ModeChange {
        t_s: f64,
        id: u64,
        kind: Kind,
        from: ModeLabel,
        to: ModeLabel,
        regime_from: Option<CavMode>,
        regime_to: Option<CavMode>,
    },
    /// A hard-braking episode started: a deceleration beyond 4 m/s² (docs/safety.md, spec
    /// 9.4), `decel_mps2` that of its first step. Reported at all times (the summary counts
    /// those that start in the measurement window).
    HardBraking {
        t_s: f64,
        id: u64,
        kind: Kind,
        decel_mps2: f64,
    },
    /// A collision (the same record as `collisions.csv`).
    Collision(CollisionEvent),
}

impl Event {
    /// The simulated time of the event (s).
    pub fn t_s(&self) -> f64 {
        match self {
            Event::Entered { t_s, .. }
            | Event::Exited { t_s, .. }
            | Event::LaneChange { t_s, .. }
            | Event::ModeChange { t_s, .. }
            | Event::HardBraking { t_s, .. } => *t_s,
            Event::Collision(c) => c.t_s,
        }
    }
}

/// Something that watches a run: it reads, it never changes the simulation.
pub trait Observer: AsAny + Send {
    /// After each step: the state after the step and the step's events (in phase order).
    fn on_step(&mut self, _step: &StepView<'_>) {}
    /// A vehicle leaves the road (`how`), as it is when it leaves; at the end of the run,
    /// once for each vehicle still on the road ([`Departure::OnRoad`]). `t_s` is the time at
    /// the end of the step.
    fn on_exit(&mut self, _v: VehicleView<'_>, _how: Departure, _t_s: f64) {}
}

/// What an observer sees after a step: the time, the vehicles on the road (lane by lane, front
/// first, as [`VehicleView`]s) and the step's events. Borrowed from the engine: building it
/// copies nothing.
#[derive(Clone, Copy)]
pub struct StepView<'a> {
    step: u64,
    t_s: f64,
    origin_m: f64,
    lanes: &'a [Vec<u32>],
    vehicles: &'a [Vehicle],
    events: &'a [Event],
}

impl<'a> StepView<'a> {
    /// The view after step `step`, which ends at `t_s`; `lanes` lists each lane's slots into
    /// `vehicles` front first.
    #[inline]
    pub(crate) fn new(
        step: u64,
        t_s: f64,
        origin_m: f64,
        lanes: &'a [Vec<u32>],
        vehicles: &'a [Vehicle],
        events: &'a [Event],
    ) -> Self {
        StepView {
            step,
            t_s,
            origin_m,
            lanes,
            vehicles,
            events,
        }
    }

    /// Steps done (this step is the `step()`-th).
    pub fn step(&self) -> u64 {
        self.step
    }

    /// Simulated time at the end of the step (s), as [`crate::Simulation::time_s`] gives it.
    pub fn time_s(&self) -> f64 {
        self.t_s
    }

    /// Output coordinate of engine x = 0 (the network origin; 0 on a plain road): the
    /// records' and the events' positions are engine positions plus this.
    pub fn origin_m(&self) -> f64 {
        self.origin_m
    }

    /// The number of lanes.
    pub fn lanes(&self) -> usize {
        self.lanes.len()
    }

    /// The vehicles in `lane` (0 = rightmost), front first.
    pub fn lane_vehicles(&self, lane: usize) -> impl Iterator<Item = VehicleView<'a>> + 'a {
        view::lane(&self.lanes[lane], self.vehicles)
    }

    /// Every vehicle on the road, lane by lane (0 = rightmost), front first within a lane.
    pub fn vehicles(&self) -> impl Iterator<Item = VehicleView<'a>> + 'a {
        let vehicles = self.vehicles;
        self.lanes.iter().flat_map(move |l| view::lane(l, vehicles))
    }

    /// The number of vehicles on the road.
    pub fn vehicles_in_network(&self) -> usize {
        self.lanes.iter().map(Vec::len).sum()
    }

    /// The step's events, in the order of the step's phases (module doc).
    pub fn events(&self) -> &'a [Event] {
        self.events
    }

    /// The engine's lane lists and records (for the engine's own observers).
    #[inline]
    pub(crate) fn records(&self) -> (&'a [Vec<u32>], &'a [Vehicle]) {
        (self.lanes, self.vehicles)
    }
}

/// Lets [`crate::Simulation::observer`] hand back an observer as its own type.
pub trait AsAny {
    fn as_any(&self) -> &dyn std::any::Any;
}

impl<T: std::any::Any> AsAny for T {
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}

/// How a collision happened.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum CollisionKind {
    /// A follower's front passed its leader's rear in the same lane.
    RearEnd,
    /// A vehicle's front passed the end of its lane (an acceleration lane or a dropped lane).
    LaneEnd,
}

impl CollisionKind {
    pub fn as_str(self) -> &'static str {
        match self {
            CollisionKind::RearEnd => "rear-end",
            CollisionKind::LaneEnd => "lane-end",
        }
    }
}

/// One collision (`collisions.csv`): when and where it started, and who was involved.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CollisionEvent {
    /// Simulated time at the end of the step in which it happened (s).
    pub t_s: f64,
    pub kind: CollisionKind,
    /// Lane counted from the right, 1 = rightmost (the numbering of `detectors.csv`).
    pub lane: u32,
    /// Front position of the colliding vehicle (output coordinate, m).
    pub x_m: f64,
    /// The colliding (following) vehicle: id, "human" or "cav", speed (m/s).
    pub vehicle: u64,
    pub vehicle_kind: &'static str,
    pub v_mps: f64,
    /// The vehicle it ran into (none for a lane end).
    pub other: Option<u64>,
    pub other_kind: Option<&'static str>,
    pub other_v_mps: Option<f64>,
    /// How far the fronts/rear overlap (or the front is past the lane end), m.
    pub overlap_m: f64,
}
