//! The public, read-only face of a vehicle: what observers ([`crate::Observer`]), organizers
//! ([`crate::Organizer`]), tests and bindings read, whatever the engine's record looks like.
//!
//! [`VehicleView`] borrows the engine's record (one pointer, `Copy`): handing it out costs
//! nothing per vehicle and step, and its accessors compile to plain loads. The record itself
//! (`vehicle.rs`) is laid out by cache line for the step and may change with it; this type's
//! methods are the stable names. Units are in the names where they are not the engine's
//! plain SI ones: positions in metres in the engine coordinate (0 = the mainline entry, as
//! [`crate::network::Geometry`] takes them; the output coordinate adds the network origin),
//! speeds in m/s, accelerations in m/s².

use crate::vehicle::{Kind, Mode, ModeLabel, Relaxation, Vehicle, NEVER, NO_EXIT};
use platoonsim_model::cav::CavMode;
use platoonsim_model::human::HumanParams;
use platoonsim_model::lanechange::LaneChangeParams;
use std::fmt;

/// One vehicle as it is now, read-only (see the module doc).
#[derive(Clone, Copy)]
pub struct VehicleView<'a>(&'a Vehicle);

impl<'a> VehicleView<'a> {
    #[inline]
    pub(crate) fn new(v: &'a Vehicle) -> Self {
        VehicleView(v)
    }

    /// The engine's record (for the engine's own observers).
    #[inline]
    pub(crate) fn record(self) -> &'a Vehicle {
        self.0
    }

    /// Unique, increasing in creation order.
    #[inline]
    pub fn id(self) -> u64 {
        self.0.id
    }

    /// Human-driven or CAV.
    #[inline]
    pub fn kind(self) -> Kind {
        self.0.kind
    }

    #[inline]
    pub fn is_cav(self) -> bool {
        self.0.is_cav()
    }

    /// Lane (0 = rightmost).
    #[inline]
    pub fn lane(self) -> u32 {
        self.0.lane
    }

    /// Front bumper position (m, engine coordinate).
    #[inline]
    pub fn x(self) -> f64 {
        self.0.x
    }

    /// Front bumper position before the last step (m, engine coordinate).
    #[inline]
    pub fn x_prev(self) -> f64 {
        self.0.x_prev
    }

    /// Rear bumper position (m, engine coordinate): `x() − length_m()`.
    #[inline]
    pub fn rear(self) -> f64 {
        self.0.rear()
    }

    /// Speed (m/s).
    #[inline]
    pub fn v(self) -> f64 {
        self.0.v
    }

    /// Acceleration applied in the last step (m/s²).
    #[inline]
    pub fn a(self) -> f64 {
        self.0.a
    }

    /// Body length (m).
    #[inline]
    pub fn length_m(self) -> f64 {
        self.0.driver.human.length_m
    }

    /// The driver's desired speed now (m/s; a command may have set it).
    #[inline]
    pub fn desired_speed_mps(self) -> f64 {
        self.0.driver.human.desired_speed
    }

    /// The driver's drawn car-following parameters (spec 2: desired speed, jam gap, reaction
    /// time, ...; the model crate's type).
    #[inline]
    pub fn driver_params(self) -> &'a HumanParams {
        &self.0.driver.human
    }

    /// The driver's drawn lane-change parameters (spec 4).
    #[inline]
    pub fn lane_change_params(self) -> &'a LaneChangeParams {
        &self.0.driver.lc
    }

    /// A relaxation (spec 4.6) is running: after its own lane change or after being cut in.
    #[inline]
    pub fn relaxing(self) -> bool {
        self.0.lcs.relax != Relaxation::NONE
    }

    /// The driving mode of the lane-change state machine (spec 4.1).
    #[inline]
    pub fn mode(self) -> Mode {
        self.0.mode
    }

    /// The driving mode as the records give it ([`ModeLabel`]).
    #[inline]
    pub fn mode_label(self) -> ModeLabel {
        self.0.mode_label()
    }

    /// A CAV whose automation is engaged (spec 3.1); never a human driver.
    #[inline]
    pub fn automated(self) -> bool {
        self.0.automated()
    }

    /// The CAV controller's regime in the last step while automated (spec 3.9); `None` for a
    /// human driver or a CAV driven manually.
    #[inline]
    pub fn regime(self) -> Option<CavMode> {
        self.0.cacc.regime
    }

    /// The CAV's effective target time gap (s; spec 3.5 transitions); 0 for a human driver.
    #[inline]
    pub fn time_gap_s(self) -> f64 {
        self.0.cacc.time_gap_s
    }

    /// The CACC time gap t_C drawn for this CAV (s; 0 for a human driver).
    #[inline]
    pub fn cacc_gap_s(self) -> f64 {
        self.0.cacc.gap_s
    }

    /// AEB braked this CAV in the last step (spec 9.3).
    #[inline]
    pub fn aeb(self) -> bool {
        self.0.cacc.auto.aeb()
    }

    /// This CAV's CACC fell back to ACC in the last step for want of V2V beacons (spec 9.3).
    #[inline]
    pub fn cacc_fallback(self) -> bool {
        self.0.cacc.auto.degraded()
    }

    /// The id of the vehicle whose CACC string this CAV has joined (`None`: it leads its own
    /// string, or is a human driver). Membership is sticky (`sense.rs`): it counts as a
    /// string position only while that vehicle is directly ahead.
    #[inline]
    pub fn joined(self) -> Option<u64> {
        (self.0.cacc.pred != NEVER).then_some(self.0.cacc.pred)
    }

    /// The largest platoon this CAV has been in (1: never in one).
    #[inline]
    pub fn max_platoon(self) -> u32 {
        self.0.cacc.max_platoon
    }

    /// Steps since the CAV last received a V2V beacon (spec 9.3; 0 without packet loss).
    #[inline]
    pub fn beacon_age(self) -> u32 {
        self.0.cacc.beacon_age
    }

    /// Lane changes made so far (of which [`VehicleView::cooperative_lane_changes`]).
    #[inline]
    pub fn lane_changes(self) -> u32 {
        self.0.lcs.count
    }

    /// Cooperative lane changes made so far (spec 9.2).
    #[inline]
    pub fn cooperative_lane_changes(self) -> u32 {
        u32::from(self.0.lcs.coop_count)
    }

    /// The off-ramp it leaves by (index into the network's off-ramps; `None`: the mainline
    /// end).
    #[inline]
    pub fn exit(self) -> Option<u32> {
        (self.0.route.exit != NO_EXIT).then_some(self.0.route.exit)
    }

    /// The entrance it came in by: 0 the mainline, i + 1 on-ramp i.
    #[inline]
    pub fn origin(self) -> u32 {
        self.0.route.origin
    }

    /// The step at which it entered the road.
    #[inline]
    pub fn entered_step(self) -> u64 {
        self.0.stats.entered_step
    }
}

impl fmt::Debug for VehicleView<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("VehicleView")
            .field("id", &self.id())
            .field("kind", &self.kind())
            .field("lane", &self.lane())
            .field("x", &self.x())
            .field("v", &self.v())
            .field("a", &self.a())
            .field("mode", &self.mode())
            .finish()
    }
}

/// The vehicles of one lane, front first, as views (an iterator over the lane's slots).
#[inline]
pub(crate) fn lane<'a>(
    slots: &'a [u32],
    vehicles: &'a [Vehicle],
) -> impl Iterator<Item = VehicleView<'a>> + 'a {
    slots
        .iter()
        .map(move |&s| VehicleView(&vehicles[s as usize]))
}
