//! Optional per-vehicle records (the kind of SUMO's tripinfo and FCD outputs): one [`Trip`] per
//! vehicle that entered the road, and [`TrajectoryPoint`] samples at a fixed period.
//!
//! Off by default. A [`Recording`] is not part of the [`crate::Config`]: it does not change the
//! simulation (the records are read from the state, never fed back), nor the configuration's
//! JSON, so neither `scenario.json` nor the experiment runner's run keys depend on it. When it is
//! off, the cost is one branch per vehicle that leaves and one per step.

use crate::config::Config;
use crate::error::SimError;
use crate::events::{Departure, Observer, StepView};
use crate::vehicle::{Kind, ModeLabel, Vehicle, NEVER, NO_EXIT};
use crate::view::VehicleView;
use platoonsim_model::cav::CavMode;

/// What to record besides the summary and the detectors.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Recording {
    /// One [`Trip`] per vehicle that entered the road.
    pub trips: bool,
    /// Trajectory samples.
    pub trajectories: Option<TrajectorySpec>,
}

/// When and where to sample trajectories.
#[derive(Clone, Debug, PartialEq)]
pub struct TrajectorySpec {
    /// Sampling period (s): a positive multiple of the step `dt_s`. Samples are taken at the
    /// multiples of the period (t = period, 2·period, …), after the step that ends there.
    pub period_s: f64,
    /// Only samples with t0 ≤ t ≤ t1 (s of simulated time); `None`: the whole run.
    pub window_s: Option<(f64, f64)>,
    /// Only vehicles whose front is at x0 ≤ x ≤ x1, in the output coordinate of the detectors
    /// (engine x + the network origin; m); `None`: the whole road.
    pub x_m: Option<(f64, f64)>,
}

impl Recording {
    /// Whether anything is recorded.
    pub fn any(&self) -> bool {
        self.trips || self.trajectories.is_some()
    }

    /// The invariants the recorder relies on; `Err` names the field, the value and what is
    /// allowed.
    pub fn check(&self, cfg: &Config) -> Result<(), SimError> {
        let Some(t) = &self.trajectories else {
            return Ok(());
        };
        if period_steps(t.period_s, cfg.dt_s).is_none() {
            return Err(SimError::Recording(format!(
                "trajectories.period_s = {}: must be a positive multiple of the time step dt_s = {}",
                t.period_s, cfg.dt_s
            )));
        }
        if let Some((t0, t1)) = t.window_s {
            if !(t0.is_finite() && t1.is_finite() && t0 >= 0.0 && t0 < t1) {
                return Err(SimError::Recording(format!(
                    "trajectories.window_s = ({t0}, {t1}): must be finite with 0 <= t0 < t1"
                )));
            }
        }
        if let Some((x0, x1)) = t.x_m {
            if !(x0.is_finite() && x1.is_finite() && x0 < x1) {
                return Err(SimError::Recording(format!(
                    "trajectories.x_m = ({x0}, {x1}): must be finite with x0 < x1"
                )));
            }
        }
        let (rows, vehicles, samples) = trajectory_rows_bound(t, cfg);
        let bytes = rows * std::mem::size_of::<TrajectoryPoint>() as f64;
        if bytes > MAX_TRAJECTORY_BYTES {
            const GIB: f64 = (1u64 << 30) as f64;
            return Err(SimError::Recording(format!(
                "--trajectories {} s: the recording could hold up to {rows:.3e} rows ({vehicles:.0} \
                 vehicles on the road × {samples:.0} samples), {:.1} GiB of memory at {} bytes \
                 each; at most {:.0} GiB: narrow it with --trajectory-window T0,T1, \
                 --trajectory-x X0,X1 or a longer period",
                t.period_s,
                bytes / GIB,
                std::mem::size_of::<TrajectoryPoint>(),
                MAX_TRAJECTORY_BYTES / GIB
            )));
        }
        Ok(())
    }
}

/// Most memory a trajectory recording may take (bytes): it is held until the end of the run.
pub const MAX_TRAJECTORY_BYTES: f64 = 4.0 * (1u64 << 30) as f64;

/// Upper bound of the trajectory rows of a run: (rows, vehicles, samples). The vehicles are at
/// most the sampled length × the lateral lanes / the jam spacing (the shortest vehicle plus
/// the smallest jam gap, at least 1 m: vehicles do not overlap); the samples are the multiples
/// of the period inside the window and the run.
pub fn trajectory_rows_bound(t: &TrajectorySpec, cfg: &Config) -> (f64, f64, f64) {
    let origin = cfg.road.origin_m();
    let (lo, hi) = (origin, origin + cfg.road.length_m);
    let (x0, x1) = t.x_m.map_or((lo, hi), |(a, b)| (a.max(lo), b.min(hi)));
    let spacing = (cfg.human.length_m.min + cfg.human.jam_gap_m.min).max(1.0);
    let vehicles = ((x1 - x0).max(0.0) / spacing).ceil() * f64::from(cfg.road.lanes);
    let (t0, t1) = t
        .window_s
        .map_or((0.0, cfg.duration_s), |(a, b)| (a, b.min(cfg.duration_s)));
    let samples = ((t1 / t.period_s).floor() - (t0 / t.period_s).ceil().max(1.0) + 1.0).max(0.0);
    (vehicles * samples, vehicles, samples)
}

/// The number of steps in `period_s` if it is a positive multiple of `dt_s` (within a relative
/// 1e-6, so that 0.3 s is three steps of 0.1 s), otherwise `None`.
pub fn period_steps(period_s: f64, dt_s: f64) -> Option<u64> {
    if !(period_s.is_finite() && period_s > 0.0 && dt_s.is_finite() && dt_s > 0.0) {
        return None;
    }
    let r = period_s / dt_s;
    let k = r.round();
    ((1.0..1e15).contains(&k) && (r - k).abs() <= 1e-6 * k).then_some(k as u64)
}

/// How a trip ended (or did not, by the end of the run).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TripStatus {
    /// Left the road where it meant to: by off-ramp `off_ramp` (index into the network's
    /// off-ramps), or at the mainline end (`None`).
    Exited { off_ramp: Option<usize> },
    /// Chose off-ramp `missed` on entry, was not in its lane there, and drove on to the end.
    MissedExitThenEnd { missed: usize },
    /// Still on the road at the end of the run.
    InNetwork,
    /// Ran past the end of its lane and was removed (a collision, `collisions.csv`).
    Collided,
}

/// One vehicle that entered the road.
#[derive(Clone, Debug, PartialEq)]
pub struct Trip {
    pub id: u64,
    pub kind: Kind,
    /// Entrance: 0 the mainline, i + 1 on-ramp i of the network.
    pub origin: usize,
    pub status: TripStatus,
    /// Time at which it arrived at its entrance (s): `entered_s − depart_delay_s`.
    pub arrived_s: f64,
    /// Time at which it entered the road (s).
    pub entered_s: f64,
    /// Time it waited in its entrance's queue: from its arrival at the entrance to its
    /// insertion on the road (s; SUMO's `departDelay`). Never negative.
    pub depart_delay_s: f64,
    /// Time at which it left (s); `None` if still on the road.
    pub left_s: Option<f64>,
    /// left − entered, from the step counts (s); `None` if still on the road.
    pub travel_time_s: Option<f64>,
    /// Front position at entry and when it left (or at the end), output coordinate (m).
    pub entry_x_m: f64,
    pub last_x_m: f64,
    /// The per-vehicle counters of the summary's statistics (`metrics.rs`).
    pub lane_changes: u32,
    pub max_platoon: u32,
    pub max_platoon_tg2: u32,
    /// Entered in the measurement window: counts in the summary's statistics.
    pub measured: bool,
    /// Fuel or electricity and the drag saving (with `energy.enabled`; docs/energy.md).
    pub energy: Option<crate::energy::TripEnergy>,
}

/// A vehicle still waiting in its entrance's queue when the run ended: it never entered the
/// road, so it has no entry time, travel time or positions.
#[derive(Clone, Debug, PartialEq)]
pub struct Queued {
    pub id: u64,
    pub kind: Kind,
    /// Entrance: 0 the mainline, i + 1 on-ramp i of the network.
    pub origin: usize,
    /// Time at which it arrived at its entrance (s).
    pub arrived_s: f64,
    /// Time it has waited so far: from its arrival to the end of the run (s).
    pub depart_delay_s: f64,
}

/// The vehicles in `queue`s (in any order) at the end of the run, `end_s`, by id; `arrived_s`
/// holds the arrival times by id (the recorder's).
pub(crate) fn queued_of<'a>(
    queues: impl Iterator<Item = &'a Vehicle>,
    arrived_s: &[f64],
    end_s: f64,
) -> Vec<Queued> {
    let mut out: Vec<Queued> = queues
        .map(|v| {
            let a = arrived_s.get(v.id as usize).copied().unwrap_or(end_s);
            Queued {
                id: v.id,
                kind: v.kind,
                origin: v.route.origin as usize,
                arrived_s: a,
                depart_delay_s: (end_s - a).max(0.0),
            }
        })
        .collect();
    out.sort_unstable_by_key(|q| q.id);
    out
}

/// One vehicle at one sample time (48 bytes: a long recording is held in memory until the end
/// of the run).
#[derive(Clone, Debug, PartialEq)]
pub struct TrajectoryPoint {
    /// Simulated time (s).
    pub t_s: f64,
    pub id: u64,
    /// Front position, output coordinate (m).
    pub x_m: f64,
    pub v_mps: f64,
    /// The acceleration applied in the last step (m/s²).
    pub a_mps2: f64,
    /// Lateral lane index, 0 = rightmost position of the road (the engine's numbering).
    pub lane: u32,
    pub kind: Kind,
    pub mode: ModeLabel,
    /// An automated CAV's control regime in the last step (`None`: a human, or manual).
    pub regime: Option<CavMode>,
    /// Position in its CACC string after the step: 1 leads a string or drives alone (every
    /// human), k the k-th vehicle of a string (at most 100, the limit of `cav.max_platoon`).
    pub platoon_pos: u8,
}

/// Simulated time of step `step`: `step / n` when a second is a whole number n of steps (so
/// that times print as short decimals, 12.3 rather than 12.300000000000001), else `step · dt`.
pub fn step_time(step: u64, dt: f64) -> f64 {
    let n = (1.0 / dt).round();
    if n >= 1.0 && (n * dt - 1.0).abs() < 1e-12 {
        step as f64 / n
    } else {
        step as f64 * dt
    }
}

/// The recorders of a running simulation: an [`Observer`] of exits (trips) and steps
/// (trajectory samples).
#[derive(Debug, Default)]
pub(crate) struct Recorder {
    pub trips: Option<Vec<Trip>>,
    pub trajectories: Option<TrajectoryRecorder>,
    /// Entry position (engine) per entrance: 0 the mainline, i + 1 on-ramp i.
    pub entry_x: Vec<f64>,
    /// With trips: each vehicle's arrival time at its entrance (s), by id (ids are dense).
    pub arrived_s: Vec<f64>,
    pub origin_m: f64,
    pub dt: f64,
}

impl Recorder {
    /// Vehicle `id` arrived at its entrance at `t_s` (it may wait in the queue before it
    /// enters the road).
    pub fn arrived(&mut self, id: u64, t_s: f64) {
        let i = id as usize;
        if self.arrived_s.len() <= i {
            self.arrived_s.resize(i + 1, f64::NAN);
        }
        self.arrived_s[i] = t_s;
    }
}

impl Observer for Recorder {
    fn on_step(&mut self, step: &StepView<'_>) {
        if let Some(t) = self.trajectories.as_mut() {
            if t.due(step.step()) {
                let (lanes, vehicles) = step.records();
                t.sample(step.step(), vehicles, lanes);
            }
        }
    }

    fn on_exit(&mut self, v: VehicleView<'_>, how: Departure, t_s: f64) {
        let v = v.record();
        let Some(trips) = self.trips.as_mut() else {
            return;
        };
        // The step that ends at t_s (`step_time` inverted: exact for any run length).
        let left_step = (how != Departure::OnRoad).then(|| (t_s / self.dt).round() as u64);
        let entry_x = self.entry_x[v.route.origin as usize];
        let mut trip = trip_of(v, how, left_step, entry_x, self.origin_m, self.dt);
        if let Some(&a) = self.arrived_s.get(v.id as usize) {
            trip.arrived_s = a.min(trip.entered_s);
            trip.depart_delay_s = (trip.entered_s - a).max(0.0);
        }
        trips.push(trip);
    }
}

#[derive(Debug)]
pub(crate) struct TrajectoryRecorder {
    /// Steps between samples.
    every: u64,
    /// First and last step sampled (inclusive).
    first: u64,
    last: u64,
    /// Engine coordinates, inclusive.
    x_lo: f64,
    x_hi: f64,
    /// Added to engine x in the records.
    origin_m: f64,
    dt: f64,
    pub rows: Vec<TrajectoryPoint>,
}

impl TrajectoryRecorder {
    pub fn new(spec: &TrajectorySpec, cfg: &Config, origin_m: f64) -> TrajectoryRecorder {
        let dt = cfg.dt_s;
        let every = period_steps(spec.period_s, dt).unwrap_or(1).max(1);
        // Steps of the window's ends, with a little slack for times that are not exact
        // multiples of dt in binary.
        let (first, last) = match spec.window_s {
            Some((t0, t1)) => (
                ((t0 / dt - 1e-6).ceil().max(0.0)) as u64,
                ((t1 / dt + 1e-6).floor().max(0.0)) as u64,
            ),
            None => (0, u64::MAX),
        };
        let first = first.max(1).div_ceil(every) * every;
        let (x_lo, x_hi) = spec
            .x_m
            .map_or((f64::NEG_INFINITY, f64::INFINITY), |(a, b)| {
                (a - origin_m, b - origin_m)
            });
        TrajectoryRecorder {
            every,
            first,
            last,
            x_lo,
            x_hi,
            origin_m,
            dt,
            rows: Vec::new(),
        }
    }

    /// Whether the state after step `step` is sampled.
    #[inline]
    pub fn due(&self, step: u64) -> bool {
        step >= self.first && step <= self.last && step.is_multiple_of(self.every)
    }

    /// Sample the vehicles on the road (lists of slots per lane) after step `step`, ordered by
    /// id.
    pub fn sample(&mut self, step: u64, vehicles: &[Vehicle], lanes: &[Vec<u32>]) {
        let t = step_time(step, self.dt);
        let start = self.rows.len();
        for lane in lanes {
            // String positions from the sticky memberships: a vehicle is a member when the
            // predecessor it joined is the one directly ahead of it now (a lane change in this
            // step left its string).
            let (mut ahead_id, mut ahead_pos) = (NEVER, 0u8);
            for &s in lane {
                let v = &vehicles[s as usize];
                let pos = if v.cacc.pred != NEVER && v.cacc.pred == ahead_id {
                    ahead_pos.saturating_add(1)
                } else {
                    1
                };
                (ahead_id, ahead_pos) = (v.id, pos);
                if v.x >= self.x_lo && v.x <= self.x_hi {
                    self.rows.push(TrajectoryPoint {
                        t_s: t,
                        id: v.id,
                        kind: v.kind,
                        lane: v.lane,
                        x_m: v.x + self.origin_m,
                        v_mps: v.v,
                        a_mps2: v.a,
                        mode: v.mode_label(),
                        regime: v.cacc.regime,
                        platoon_pos: pos,
                    });
                }
            }
        }
        self.rows[start..].sort_unstable_by_key(|p| p.id);
    }
}

/// How a trip ended, as the engine knows it when it records the trip.
pub(crate) use crate::events::Departure as TripEnd;

/// The trip of `v`, which ended as `end` in the step that ends at step `left_step` (`None`:
/// still on the road); `entry_x` is its entry position (engine).
pub(crate) fn trip_of(
    v: &Vehicle,
    end: TripEnd,
    left_step: Option<u64>,
    entry_x: f64,
    origin_m: f64,
    dt: f64,
) -> Trip {
    let status = match end {
        TripEnd::OnRoad => TripStatus::InNetwork,
        TripEnd::Collided => TripStatus::Collided,
        TripEnd::OffRamp(r) => TripStatus::Exited { off_ramp: Some(r) },
        TripEnd::RoadEnd if v.route.planned_exit != NO_EXIT => TripStatus::MissedExitThenEnd {
            missed: v.route.planned_exit as usize,
        },
        TripEnd::RoadEnd => TripStatus::Exited { off_ramp: None },
    };
    Trip {
        id: v.id,
        kind: v.kind,
        origin: v.route.origin as usize,
        status,
        entered_s: step_time(v.stats.entered_step, dt),
        // Both set by the recorder, which knows the arrival time (no wait without it).
        arrived_s: step_time(v.stats.entered_step, dt),
        depart_delay_s: 0.0,
        left_s: left_step.map(|s| step_time(s, dt)),
        travel_time_s: left_step.map(|s| step_time(s - v.stats.entered_step, dt)),
        entry_x_m: entry_x + origin_m,
        last_x_m: v.x + origin_m,
        lane_changes: v.lcs.count,
        max_platoon: v.cacc.max_platoon,
        max_platoon_tg2: v.cacc.max_platoon_tg2,
        measured: v.stats.measured,
        energy: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn periods_are_whole_multiples_of_the_step() {
        assert_eq!(period_steps(0.1, 0.1), Some(1));
        assert_eq!(period_steps(0.3, 0.1), Some(3));
        assert_eq!(period_steps(1.0, 0.1), Some(10));
        assert_eq!(period_steps(60.0, 0.1), Some(600));
        assert_eq!(period_steps(0.15, 0.1), None);
        assert_eq!(period_steps(0.05, 0.1), None);
        assert_eq!(period_steps(0.0, 0.1), None);
        assert_eq!(period_steps(-1.0, 0.1), None);
        assert_eq!(period_steps(f64::NAN, 0.1), None);
        assert_eq!(period_steps(f64::INFINITY, 0.1), None);
        assert_eq!(period_steps(0.25, 0.05), Some(5));
    }

    #[test]
    fn a_trajectory_point_is_small() {
        assert_eq!(std::mem::size_of::<TrajectoryPoint>(), 48);
    }

    #[test]
    fn step_times_are_short_decimals() {
        assert_eq!(step_time(123, 0.1).to_string(), "12.3");
        assert_eq!(step_time(3, 0.1).to_string(), "0.3");
        assert_eq!(step_time(36000, 0.1), 3600.0);
        assert_eq!(step_time(7, 0.05).to_string(), "0.35");
        // dt whose inverse is not whole: plain product.
        assert_eq!(step_time(2, 0.3), 2.0 * 0.3);
    }
}
