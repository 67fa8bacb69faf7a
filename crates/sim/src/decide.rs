//! Phase 2 (decide): every vehicle decides from the step-start state (synchronous update,
//! spec 1): lane-change desire and gap acceptance (spec 4.2-4.3), BLC behaviour, cooperative
//! yielding (spec 4.5), and its acceleration: the human model (spec 2) for humans and CAVs
//! driving manually, CAV control (spec 3) for automated CAVs.

use crate::events::LaneChangeReason;

use crate::config::Config;
use crate::here::SideWalls;
use crate::insert::Entrance;
use crate::organize::Organizer;
use crate::state::Decision;
use crate::state::{Clock, Control, RoadState, Scratch, Traffic};
use crate::state::{Neighbours, Sensed, NONE};
use crate::vehicle::{AutoFlags, Mode, Relaxation, Vehicle};
use platoonsim_model::cav::{self, CaccLaw, Family};
use platoonsim_model::driver;
use platoonsim_model::human;
use platoonsim_model::lanechange::{self as lcm, Side};
use platoonsim_model::safegap;
use platoonsim_model::{Leader, Relax};

mod commands;
mod cooperate;
mod safe_gaps;
pub(crate) use safe_gaps::{automated_follower_after, follower_accel_after, safe_decel};

/// Gap acceptance toward the target lane (spec 4.3) and the anticipated acceleration behind
/// the target-lane leader.
#[derive(Clone, Copy, Debug)]
struct Gaps {
    lead_ok: bool,
    lag_ok: bool,
    a_ant: f64,
    /// The target-lane leader's rear is ahead of the own front (or there is none).
    target_ahead: bool,
}

/// A lane-change desire that passed the threshold.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Desire {
    pub side: Side,
    pub gamma: f64,
    pub mandatory: bool,
    /// The move toward the PD lane of platoon organization (spec 4.7).
    pub organize: bool,
}

/// One vehicle as the decide phase sees it: what the rules of its decision share, read or
/// computed once per vehicle ([`View::me`]) and passed by reference from rule to rule instead
/// of as the same five or six parameters of every method.
///
/// Its desired speed in its own lane is not a field: without lane caps it is one load, which
/// the rules repeat ([`View::own_v_des`]); held here, it stayed live across the inlined
/// automation and cost spills, +1.7 % instructions per update on the homogeneous road.
#[derive(Clone, Copy)]
pub(crate) struct Me<'a> {
    /// Its slot.
    pub s: u32,
    pub v: &'a Vehicle,
    /// What the sense phase found for it: its neighbours, its place on the road, its string.
    pub sensed: &'a Sensed,
    /// The nearer of its same-lane leader and the wall ending its lane segment
    /// ([`View::leader_or_wall`]).
    pub leader: Option<Leader>,
    /// `leader` is the wall.
    pub wall: bool,
}

impl Me<'_> {
    /// Its neighbours from the sense phase.
    #[inline]
    pub(crate) fn nb(&self) -> &Neighbours {
        &self.sensed.nb
    }
}

/// What the decide phase reads: the step-start state, part by part. Every rule of the phase
/// is a method of this view (here, in `desire.rs` and in `yielding.rs`), so none can write
/// the state: the phase's only output is the decision per vehicle.
pub(crate) struct View<'a> {
    pub cfg: &'a Config,
    pub clock: &'a Clock,
    pub traffic: &'a Traffic,
    pub road: &'a RoadState,
    /// What the sense phase found, per slot.
    pub sensed: &'a [Sensed],
    /// Per lane, (x, v) at the step start (sense phase).
    pub lane_xv: &'a [Vec<(f64, f64)>],
    /// Per on-ramp, the anticipation factors of this step ([`ramp_factors`]).
    pub ramp_factor: &'a [[f64; 2]],
    pub organizer: &'a dyn Organizer,
    /// Whether the organizer advises human drivers (index 0) and CAVs (1).
    pub advise: [bool; 2],
}

/// Phase 2: every vehicle's decision from the step-start state, into `scratch.decisions`;
/// then the commands in force override the decisions of their vehicles (`command.rs`).
pub(crate) fn decide(
    cfg: &Config,
    clock: &Clock,
    traffic: &Traffic,
    road: &RoadState,
    entrances: &[Entrance],
    control: &mut Control,
    scratch: &mut Scratch,
) {
    let n = traffic.vehicles.len();
    if scratch.decisions.len() < n {
        scratch.decisions.resize(
            n,
            Decision {
                accel: 0.0,
                mode: Mode::Cf,
                family: Family::Speed,
                regime: None,
                time_gap: 0.0,
                change: None,
                why: LaneChangeReason::Discretionary,
                takeover: false,
                coop: false,
                auto: AutoFlags::NONE,
                urgent: false,
            },
        );
    }
    ramp_factors(cfg, traffic, road, entrances, &mut scratch.ramp_factor);
    let view = View {
        cfg,
        clock,
        traffic,
        road,
        sensed: &scratch.sensed,
        lane_xv: &scratch.lane_xv,
        ramp_factor: &scratch.ramp_factor,
        organizer: control.organizer.as_ref(),
        advise: control.advise,
    };
    // The lanes are walked by iterator (no bounds checks on the lane lists); the walls of
    // the lanes beside each list are walked along with it (`SideWalls`).
    let decisions = &mut scratch.decisions;
    let n_lanes = traffic.lanes.len();
    for (l, lane) in traffic.lanes.iter().enumerate() {
        let mut walls = SideWalls::new(&road.here_tables, l, n_lanes);
        for &s in lane {
            decisions[s as usize] = view.decide_one(s, &mut walls);
        }
    }
    if !control.commands.is_empty() {
        commands::apply_commands(&view, &mut control.commands, decisions);
    }
}

/// Density on each on-ramp (its queue plus its acceleration lane) (veh/km), for the
/// anticipation rule (spec 4.2), and from it the rule's factor for j = 1, 2.
fn ramp_factors(
    cfg: &Config,
    traffic: &Traffic,
    road: &RoadState,
    entrances: &[Entrance],
    factors: &mut [[f64; 2]],
) {
    for (i, r) in road.geom.on_ramps.iter().enumerate() {
        let queued = entrances[i + 1].waiting();
        let lane = &traffic.lanes[r.lane as usize];
        let on_accel = if r.adds_lane {
            0
        } else {
            let hi = lane.partition_point(|&o| traffic.vehicles[o as usize].x >= r.accel_end);
            let lo = lane.partition_point(|&o| traffic.vehicles[o as usize].x >= r.x);
            lo.saturating_sub(hi)
        };
        let density = (queued + on_accel) as f64 / (r.density_length_m / 1000.0);
        let c = cfg.lane_change.anticipation_strength;
        // The same expression as per vehicle before, so the same bits.
        factors[i] = [1, 2].map(|j: u32| 1.0 + c * (density / RHO_JAM_PER_KM) / f64::from(j));
    }
}

impl View<'_> {
    /// Is the vehicle in slot `s` a CAV?
    #[inline]
    pub(crate) fn is_cav(&self, s: u32) -> bool {
        s != NONE && self.traffic.vehicles[s as usize].is_cav()
    }

    /// The decision of the vehicle in slot `s` that must change toward `side` (a commanded
    /// change): a mandatory desire of 1 with the model's gap acceptance and BLC behaviour
    /// (spec 4.3).
    pub(crate) fn forced_change(&self, s: u32, side: Side) -> Decision {
        let d = Desire {
            side,
            gamma: 1.0,
            mandatory: true,
            organize: false,
        };
        self.before_lane_change(&self.me(s), d, true).0
    }

    /// The vehicle in slot `s` as its decision reads it ([`Me`]).
    #[inline]
    fn me(&self, s: u32) -> Me<'_> {
        let v = &self.traffic.vehicles[s as usize];
        let sensed = &self.sensed[s as usize];
        let (leader, wall) = self.leader_or_wall(v, sensed);
        Me {
            s,
            v,
            sensed,
            leader,
            wall,
        }
    }

    /// The desired speed of `me` in its own lane ([`Self::v_des_in`]); recomputed where used
    /// rather than kept in [`Me`] (see there).
    #[inline]
    pub(crate) fn own_v_des(&self, me: &Me) -> f64 {
        self.v_des_in(me.s, me.v, me.v.lane as usize)
    }

    /// The leader view (net gap, speed) of slot `ld` for vehicle `v`.
    #[inline]
    fn view(&self, v: &Vehicle, ld: u32) -> Option<Leader> {
        (ld != NONE).then(|| {
            let l = &self.traffic.vehicles[ld as usize];
            Leader {
                gap_m: l.rear() - v.x,
                v_mps: l.v,
            }
        })
    }

    /// The nearer of the same-lane leader of `v` (`sensed`: its record from the sense phase)
    /// and the wall ending its lane segment (a standing obstacle, issue 4: vehicles wait at the
    /// end of an acceleration lane or a dropped lane). The flag is true if the wall is the
    /// nearer one.
    #[inline]
    fn leader_or_wall(&self, v: &Vehicle, sensed: &Sensed) -> (Option<Leader>, bool) {
        let leader = self.view(v, sensed.nb.leader);
        if self.road.geom.plain {
            return (leader, false);
        }
        match sensed.here.wall {
            Some(w) if leader.is_none_or(|l| w - v.x < l.gap_m) => (
                Some(Leader {
                    gap_m: w - v.x,
                    v_mps: 0.0,
                }),
                true,
            ),
            _ => (leader, false),
        }
    }

    /// Current relaxation factors of a vehicle (spec 4.6).
    #[inline]
    fn relax_now(&self, v: &Vehicle) -> Relax {
        match v.lcs.relax.started() {
            None => Relax::NONE,
            Some(since) => lcm::relax_at(
                &v.driver.lc,
                (self.clock.step - since) as f64 * self.clock.dt,
            ),
        }
    }

    fn decide_one(&self, s: u32, walls: &mut SideWalls) -> Decision {
        let me = &self.me(s);
        let v = me.v;
        let v_des = self.own_v_des(me);

        // 1. Lane-change desire (takes priority over yielding).
        if let Some(d) = self.desire(me, walls) {
            // Cooperative lane changes (spec 9.2): an automated CAV with a mandatory or
            // organizing desire asks its target-lane CAV follower; without one, or while the
            // request rests, the published behaviour below (the request counter rides along
            // in the BLC mode).
            if self.cfg.cav.cooperative_lane_change && (d.mandatory || d.organize) && v.automated()
            {
                return self.cooperative_or_published(me, d);
            }
            return self.published_change(me, d);
        }

        // 2. Automated CAV: ACC / CACC / speed regulation (spec 3); with cooperative lane
        // changes (spec 9.2) it first answers a CAV that asks it for a gap.
        if v.automated() {
            if self.cfg.cav.cooperative_lane_change {
                if let Some(d) = self.open_gap(me) {
                    return d;
                }
            }
            let d = self.automated_decision(me, None);
            // Under the field law the automation engages (after a manual spell: no regime in
            // the last step) only where its demand lies within the ISO 15622 envelope; else
            // the driver keeps driving this step (docs/cacc-field.md, engagement).
            if !(v.cacc.regime.is_none()
                && self.cfg.cav.cacc_law == CaccLaw::Field
                && (d.auto.aeb() || d.auto.takeover()))
            {
                return d;
            }
        }
        let yield_to = self.agreed_request(me, false);

        // 3. Human model (humans and CAVs driving manually), possibly yielding.
        let v_des = self.manual_v_des(me, v_des);
        let relax = self.relax_now(v);
        let mut target = human::target_accel(&v.driver.human, v.v, v_des, me.leader, relax);
        let mut mode = Mode::Cf;
        if let Some(req) = yield_to {
            let r = &self.traffic.vehicles[req as usize];
            target = lcm::yield_accel(
                &v.driver.human,
                &v.driver.lc,
                v.v,
                v_des,
                target,
                self.yield_gap(v, r),
            );
            mode = Mode::Ycf {
                to: r.id,
                auto: false,
                coop: false,
            };
        }
        Decision {
            accel: human::smooth_accel(v.a, target, v.driver.human.smoothing),
            mode,
            family: v.cacc.family,
            regime: None,
            time_gap: v.cacc.time_gap_s,
            change: None,
            why: LaneChangeReason::Discretionary,
            takeover: false,
            coop: false,
            auto: AutoFlags::NONE,
            urgent: false,
        }
    }

    /// The published lane-change behaviour of a vehicle with a desire (spec 4.3; docs/model-choices.md 6.20).
    fn published_change(&self, me: &Me, d: Desire) -> Decision {
        let v = me.v;
        // With `cav.organize_while_automated` [D] a CAV's automation stays engaged while
        // its driver waits for a gap toward the PD lane: the driver takes over only once
        // both gaps are acceptable (a leader then changes at once, a follower splits first,
        // spec 3.6.4). Meanwhile the request stays visible to neighbours (BLC, spec 4.5)
        // and, while the lag gap is acceptable, the automation holds back as the driver's
        // discretionary synchronization would (no acceleration beyond what the target-lane
        // leader allows; it never brakes for it). A driver who took over and lost the gap
        // hands back once the relaxation has ended.
        if d.organize && self.cfg.cav.organize_while_automated && v.lcs.relax == Relaxation::NONE {
            let (blc, g) = self.before_lane_change(me, d, false);
            if g.lead_ok && g.lag_ok {
                return blc;
            }
            let held = driver::HoldView {
                lag_ok: g.lag_ok,
                a_ant: g.a_ant,
                leader_ahead: g.target_ahead,
                v: v.v,
                waited_slow_s: f64::from(v.hold_wait) * self.clock.dt,
            };
            let mut a = self.automated_decision(me, Some(held));
            // The wait goes on; below the creep speed it counts toward the hold's timeout.
            a.auto = a
                .auto
                .union(AutoFlags::waiting(v.v < driver::CREEP_SPEED_MPS));
            if a.mode == Mode::Cf {
                a.mode = Mode::Blc {
                    side: d.side,
                    mandatory: false,
                    auto: true,
                    ask: 0,
                };
            }
            return a;
        }
        self.before_lane_change(me, d, false).0
    }

    /// An automated CAV's decision: ACC / CACC / speed regulation (spec 3). With the spec 6.5
    /// flag the automation also answers a mandatory yield request it agrees to: it follows the
    /// requester as a virtual leader as a yielding driver would (spec 4.5), without leaving
    /// automation [D]. `held`: what a CAV waiting for a PD-lane gap sees of its wait
    /// (`driver::held_back`, `cav.organize_hold`). Then the demand goes through the actuators
    /// (spec 9.3).
    // Inlined, with `cav_control`, into the decide loop: as two calls, the leader view, the
    // 40-byte `Decision` and what `decide_one` had loaded already (the sensed record, the
    // desired speed) crossed two call boundaries, about 105 instructions per automated CAV
    // and step (docs/performance.md).
    #[inline(always)]
    fn automated_decision(&self, me: &Me, held: Option<driver::HoldView>) -> Decision {
        let v = me.v;
        let mut d = self.cav_control(me);
        if self.cfg.cav.yield_while_automated {
            if let Some(req) = self.agreed_request(me, true) {
                let r = &self.traffic.vehicles[req as usize];
                d.accel = lcm::yield_accel(
                    &v.driver.human,
                    &v.driver.lc,
                    v.v,
                    self.own_v_des(me),
                    d.accel,
                    self.yield_gap(v, r),
                );
                d.mode = Mode::Ycf {
                    to: r.id,
                    auto: true,
                    coop: false,
                };
            }
        }
        if let Some(w) = held {
            let p = &self.cfg.cav;
            d.accel = driver::held_back(d.accel, p.organize_hold, &w, p.organize_hold_timeout_s);
        }
        self.actuate(v, &mut d);
        d
    }

    /// The automation's demand `d.accel` through its actuators (spec 9.3): bounded by
    /// `cav.max_automated_decel_mps2` (beyond it AEB applies the demand and the decision says
    /// so) and lagged by `cav.actuator_lag_s` from the acceleration realized in the last step.
    /// Both off (no lag, demand within the bound): `d` unchanged.
    /// Under the field law (`cav.cacc_law`) the demand first goes through the ISO 15622
    /// envelope (deceleration and jerk bounds by speed); a demand beyond its deceleration is a
    /// take-over request, flagged (`cav::actuate_field`).
    #[inline]
    fn actuate(&self, v: &Vehicle, d: &mut Decision) {
        let auto = &self.traffic.auto;
        let p = &self.cfg.cav;
        let (a, aeb, tor) = match p.cacc_law {
            CaccLaw::Spec => {
                let (a, aeb) = cav::actuate(v.a, d.accel, auto.lag_gain, auto.bound);
                (a, aeb, false)
            }
            CaccLaw::Field => cav::actuate_field(
                v.a,
                d.accel,
                auto.lag_gain,
                auto.bound,
                cav::envelope(p, v.v),
                self.clock.dt,
            ),
        };
        d.accel = a;
        if aeb {
            d.auto = d.auto.union(AutoFlags::new(true, false));
        }
        if tor {
            d.auto = d.auto.union(AutoFlags::TAKEOVER);
        }
    }

    /// Automated CAV control (spec 3.9).
    // Inlined: see `automated_decision`.
    #[inline(always)]
    fn cav_control(&self, me: &Me) -> Decision {
        let p = &self.cfg.cav;
        let (v, wall) = (me.v, me.wall);
        let v_des = self.own_v_des(me);
        let ld = me.sensed.nb.leader;
        let leader = me.leader.filter(|l| l.gap_m <= p.sensor_range_m);
        let mut time_gap = v.cacc.time_gap_s;
        // CACC behind a CAV, on the leader's speed as the law knows it: from the V2V beacons
        // (spec 9.3; `None` when they timed out: ACC on the radar alone, a fallback), without
        // delay and loss the leader's current speed.
        let cav_ahead = !wall && self.is_cav(ld);
        // The field law also reads the leader's acceleration from the same beacon (its
        // realized acceleration of the last step, or the speed change between two broadcasts).
        let field = p.cacc_law == CaccLaw::Field;
        let mut a_pred = 0.0;
        let known = match (leader, &self.traffic.auto.beacons) {
            (Some(l), None) if cav_ahead => {
                if field {
                    a_pred = self.traffic.vehicles[ld as usize].a;
                }
                Some(l)
            }
            (Some(l), Some(b)) if cav_ahead => b
                .received_speed(v.cacc.beacon_age, ld, self.clock.step)
                .map(|v_mps| {
                    if field {
                        a_pred =
                            b.received_accel(v.cacc.beacon_age, ld, self.clock.step, self.clock.dt);
                    }
                    Leader { v_mps, ..l }
                }),
            _ => None,
        };
        let fallback = cav_ahead && leader.is_some() && known.is_none();
        let cmd = match (leader, known) {
            (None, _) => cav::Command {
                accel: cav::speed_regulation(p, v.v, v_des),
                mode: cav::CavMode::SpeedRegulation,
                family: Family::Speed,
            },
            (Some(_), Some(known)) => {
                let target = if !me.sensed.linked {
                    p.inter_platoon_gap_s
                } else {
                    v.cacc.gap_s
                };
                time_gap = cav::ramp_time_gap(p, time_gap, target, self.clock.dt);
                cav::cacc_by_law(p, v.v, v.a, a_pred, v_des, known, time_gap, v.cacc.family)
            }
            (Some(l), None) => {
                time_gap = cav::ramp_time_gap(p, time_gap, p.acc_time_gap_s, self.clock.dt);
                // The field law's approach reads the leader's acceleration as the radar
                // estimates it: its realized acceleration of the last step (a wall: 0).
                let a_radar = if field && !wall && ld != NONE {
                    self.traffic.vehicles[ld as usize].a
                } else {
                    0.0
                };
                cav::acc_by_law(p, v.v, v_des, Some(l), a_radar, time_gap, v.cacc.family)
            }
        };
        Decision {
            accel: cav::finalize(p, v.v, cmd.accel, v_des, leader, self.clock.dt),
            mode: Mode::Cf,
            family: cmd.family,
            regime: Some(cmd.mode),
            time_gap,
            change: None,
            why: LaneChangeReason::Discretionary,
            takeover: false,
            coop: false,
            auto: AutoFlags::new(false, fallback),
            urgent: false,
        }
    }

    /// The follower (slot) in the lane on `side`, from the merge-sweep cursor (`NONE` if there
    /// is none, or no lane).
    fn side_follower(&self, me: &Me, side: Side) -> u32 {
        let (v, nb) = (me.v, me.nb());
        let (lane, j) = match side {
            Side::Left => (v.lane as usize + 1, nb.left_j),
            Side::Right => ((v.lane as usize).wrapping_sub(1), nb.right_j),
        };
        self.traffic
            .lanes
            .get(lane)
            .and_then(|l| l.get(j as usize))
            .copied()
            .unwrap_or(NONE)
    }

    /// BLC (spec 4.3): gap acceptance and the before-change behaviour; also whether both gaps
    /// are acceptable now (a follower that must split first does not change yet).
    /// `commanded`: a change commanded from outside (command.rs).
    fn before_lane_change(&self, me: &Me, d: Desire, commanded: bool) -> (Decision, Gaps) {
        let (v, nb) = (me.v, me.nb());
        let tl = match d.side {
            Side::Left => nb.left_leader,
            Side::Right => nb.right_leader,
        };
        let tf = self.side_follower(me, d.side);
        let v_des = self.manual_v_des(me, self.own_v_des(me));
        let target = match d.side {
            Side::Left => v.lane as usize + 1,
            Side::Right => (v.lane as usize).saturating_sub(1),
        };
        let v_des_target = self.v_des_in(me.s, v, target);
        // An automated CAV hands over to its driver now ("manual mode from a lane-change desire
        // on", spec 3.1). At a CACC gap of 0.6 s the human model alone would brake hard; the
        // driver takes over with relaxed car following that recovers over t_s, as after a cut-in
        // (spec 4.6) [D].
        let takeover = v.automated();
        let relax = if takeover {
            lcm::gap_relax(&v.driver.lc)
        } else {
            self.relax_now(v)
        };
        let safe = safe_decel(self.cfg);
        let target_follower = (tf != NONE).then(|| {
            let f = &self.traffic.vehicles[tf as usize];
            let changer = Leader {
                gap_m: v.rear() - f.x,
                v_mps: v.v,
            };
            driver::TargetFollower {
                gap_m: changer.gap_m,
                v_mps: f.v,
                yields: matches!(f.mode, Mode::Ycf { to, .. } if to == v.id),
                // spec 9.1: the follower's own law, evaluated only under the safe rule.
                a_after: if safe.is_some() {
                    follower_accel_after(
                        self.cfg,
                        self.road,
                        self.sensed,
                        self.clock.dt,
                        f,
                        tf,
                        v,
                        changer,
                    )
                } else {
                    0.0
                },
            }
        });
        let view = driver::BlcView {
            v: v.v,
            a: v.a,
            v_des,
            v_des_target,
            leader: me.leader,
            relax,
            target_leader: self.view(v, tl),
            target_follower,
            mandatory: d.mandatory,
            gamma: d.gamma,
            // A move toward the PD lane accepts the lead gap "regardless of the speed
            // difference" (`cav.organize_regardless_of_speed` [D] 6.22).
            organize_regardless: d.organize && self.cfg.cav.organize_regardless_of_speed,
            must_split: me.sensed.linked,
            in_accel_lane: !self.road.geom.plain && me.sensed.here.accel,
            commanded,
            safe,
        };
        let blc = driver::before_lane_change(&v.driver.human, &v.driver.lc, &view);
        (
            Decision {
                accel: blc.accel,
                mode: Mode::Blc {
                    side: d.side,
                    mandatory: d.mandatory,
                    auto: false,
                    ask: 0,
                },
                family: Family::Speed,
                regime: None,
                time_gap: v.cacc.time_gap_s,
                change: blc.change.then_some(d.side),
                why: if d.mandatory {
                    LaneChangeReason::Mandatory
                } else if d.organize {
                    LaneChangeReason::Organizing
                } else {
                    LaneChangeReason::Discretionary
                },
                takeover,
                coop: false,
                auto: AutoFlags::NONE,
                urgent: safegap::urgent(d.mandatory, d.gamma),
            },
            Gaps {
                lead_ok: blc.lead_ok,
                lag_ok: blc.lag_ok,
                a_ant: blc.a_ant,
                target_ahead: blc.target_ahead,
            },
        )
    }
}

/// ρ_jam of the anticipation rule (spec 4.2): 1000/6 veh/km.
const RHO_JAM_PER_KM: f64 = 1000.0 / 6.0;

/// The driver's own desired speed v_F, in no particular lane.
#[inline]
pub(crate) fn v_des_of(v: &Vehicle) -> f64 {
    v.driver.human.desired_speed
}

impl View<'_> {
    /// The desired speed of a driver in manual control (a human, or a CAV's driver) in its own
    /// lane, from `v_des`, that lane's `v_des_in`: with cross-lane friction on (spec 2.7), the
    /// pull of the slower adjacent lane. The automation keeps its set speed: friction is a
    /// driver's behaviour [D].
    #[inline]
    fn manual_v_des(&self, me: &Me, v_des: f64) -> f64 {
        match self.road.friction {
            None => v_des,
            Some(c) => self.with_friction(me, v_des, c),
        }
    }

    /// Cross-lane friction (spec 2.7): v_adj is the slower of the average speeds ahead in the
    /// adjacent lanes (the same scan, n_scan vehicles within d_scan, as the lane-change
    /// motivation; a lane with no vehicle in range counts as `v_des`, so it adds nothing).
    fn with_friction(&self, me: &Me, v_des: f64, c_fr: f64) -> f64 {
        let (v, nb) = (me.v, me.nb());
        let lane = v.lane as usize;
        let mut v_adj = v_des;
        if lane + 1 < self.lane_xv.len() {
            v_adj = v_adj.min(self.avg_speed_ahead(lane + 1, nb.left_j as usize, v.x, v_des));
        }
        if lane > 0 {
            v_adj = v_adj.min(self.avg_speed_ahead(lane - 1, nb.right_j as usize, v.x, v_des));
        }
        human::friction_desired_speed(v_des, v_adj, c_fr)
    }

    /// The desired speed of vehicle `s` in `lane` (spec 2.7): v_F, capped by the lane's speed
    /// limit when the network has lane-based caps (counted from the rightmost through lane at
    /// the vehicle's position; an acceleration lane, right of it, takes the first cap). Without
    /// caps exactly v_F.
    #[inline]
    pub(crate) fn v_des_in(&self, s: u32, v: &Vehicle, lane: usize) -> f64 {
        if self.road.lane_caps_mps.is_empty() {
            return v_des_of(v); // no lookup of the vehicle's geometry on the hot path
        }
        self.road
            .lane_capped(v_des_of(v), lane, self.sensed[s as usize].here.right)
    }
}

pub(crate) use platoonsim_model::driver::opposite;

/// A uniform draw in [0, 1) for the pair (driver, requester): "a fresh U(0,1) at each new
/// request" (spec 4.5), reproducible without storing anything.
pub(crate) fn pair_uniform(seed: u64, a: u64, b: u64) -> f64 {
    let mut z = seed
        ^ a.wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ b.rotate_left(32).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

#[cfg(test)]
mod tests {
    use super::pair_uniform;

    #[test]
    fn a_pairs_uniform_is_in_the_unit_interval_and_fixed_by_seed_and_order() {
        let draws: Vec<f64> = (0..20_000u64).map(|k| pair_uniform(7, k, k + 1)).collect();
        assert!(draws.iter().all(|u| (0.0..1.0).contains(u)));
        let mean = draws.iter().sum::<f64>() / draws.len() as f64;
        assert!((mean - 0.5).abs() < 0.01, "mean {mean}");
        let below = draws.iter().filter(|&&u| u < 0.25).count() as f64 / draws.len() as f64;
        assert!((below - 0.25).abs() < 0.01, "share below 0.25: {below}");
        // The same pair and seed: the same draw (a yield decision is the pair's, step after
        // step); the other order or another seed: another draw.
        assert_eq!(pair_uniform(7, 3, 4), pair_uniform(7, 3, 4));
        assert_ne!(pair_uniform(7, 3, 4), pair_uniform(7, 4, 3));
        assert_ne!(pair_uniform(7, 3, 4), pair_uniform(8, 3, 4));
    }
}
