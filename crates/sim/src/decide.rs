//! Phase 2 (decide): every vehicle decides from the step-start state (synchronous update,
//! spec 1): lane-change desire and gap acceptance (spec 4.2-4.3), BLC behaviour, cooperative
//! yielding (spec 4.5), and its acceleration: the human model (spec 2) for humans and CAVs
//! driving manually, CAV control (spec 3) for automated CAVs.

use crate::events::LaneChangeReason;

use crate::config::Config;
use crate::insert::Entrance;
use crate::organize::Organizer;
use crate::sense::{Neighbours, Sensed, NONE};
use crate::sim::Decision;
use crate::state::{Clock, Control, RoadState, Scratch, Traffic};
use crate::vehicle::{AutoFlags, Mode, Relaxation, Vehicle};
use platoonsim_model::cav::{self, Family};
use platoonsim_model::cooperative as coop;
use platoonsim_model::driver;
use platoonsim_model::human;
use platoonsim_model::lanechange::{self as lcm, Side};
use platoonsim_model::safegap::{self, AutomatedFollower, GapRule, SafeDecel};
use platoonsim_model::{Leader, Relax};

/// Gap acceptance toward the target lane (spec 4.3) and the anticipated acceleration behind
/// the target-lane leader.
#[derive(Clone, Copy, Debug)]
struct Gaps {
    lead_ok: bool,
    lag_ok: bool,
    a_ant: f64,
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
    // The lanes are walked by iterator (no bounds checks on the lane lists).
    let decisions = &mut scratch.decisions;
    for lane in &traffic.lanes {
        for &s in lane {
            decisions[s as usize] = view.decide_one(s);
        }
    }
    if !control.commands.is_empty() {
        crate::command::apply_commands(&view, &mut control.commands, decisions);
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

    /// The decision of a vehicle that must change toward `side` (a commanded change): a
    /// mandatory desire of 1 with the model's gap acceptance and BLC behaviour (spec 4.3).
    pub(crate) fn forced_change(&self, s: u32, v: &Vehicle, side: Side) -> Decision {
        let nb = &self.sensed[s as usize].nb;
        let (leader, _) = self.leader_or_wall(s, v, nb.leader);
        let d = Desire {
            side,
            gamma: 1.0,
            mandatory: true,
            organize: false,
        };
        self.before_lane_change(s, v, nb, leader, d, true).0
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

    /// The nearer of the same-lane leader `ld` and the wall ending the vehicle's lane segment
    /// (a standing obstacle, issue 4: vehicles wait at the end of an acceleration lane or a
    /// dropped lane). The flag is true if the wall is the nearer one.
    #[inline]
    fn leader_or_wall(&self, s: u32, v: &Vehicle, ld: u32) -> (Option<Leader>, bool) {
        let leader = self.view(v, ld);
        if self.road.geom.plain {
            return (leader, false);
        }
        match self.sensed[s as usize].here.wall {
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

    fn decide_one(&self, s: u32) -> Decision {
        let v = &self.traffic.vehicles[s as usize];
        let nb = &self.sensed[s as usize].nb;
        let v_des = self.v_des_in(s, v, v.lane as usize);
        let (leader, wall) = self.leader_or_wall(s, v, nb.leader);

        // 1. Lane-change desire (takes priority over yielding).
        if let Some(d) = self.desire(s, v, nb) {
            // Cooperative lane changes (spec 9.2): an automated CAV with a mandatory or
            // organizing desire asks its target-lane CAV follower; without one, or while the
            // request rests, the published behaviour below (the request counter rides along
            // in the BLC mode).
            if self.cfg.cav.cooperative_lane_change && (d.mandatory || d.organize) && v.automated()
            {
                return self.cooperative_or_published(s, v, nb, leader, wall, d);
            }
            return self.published_change(s, v, nb, leader, wall, d);
        }

        // 2. Automated CAV: ACC / CACC / speed regulation (spec 3); with cooperative lane
        // changes (spec 9.2) it first answers a CAV that asks it for a gap.
        if v.automated() {
            if self.cfg.cav.cooperative_lane_change {
                if let Some(d) = self.open_gap(s, v, nb, leader, wall) {
                    return d;
                }
            }
            return self.automated_decision(s, v, nb, leader, wall, None);
        }
        let yield_to = self.agreed_request(v, nb, false);

        // 3. Human model (humans and CAVs driving manually), possibly yielding.
        let v_des = self.manual_v_des(s, v, v_des);
        let relax = self.relax_now(v);
        let mut target = human::target_accel(&v.driver.human, v.v, v_des, leader, relax);
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
    fn published_change(
        &self,
        s: u32,
        v: &Vehicle,
        nb: &Neighbours,
        leader: Option<Leader>,
        wall: bool,
        d: Desire,
    ) -> Decision {
        {
            // With `cav.organize_while_automated` [D] a CAV's automation stays engaged while
            // its driver waits for a gap toward the PD lane: the driver takes over only once
            // both gaps are acceptable (a leader then changes at once, a follower splits first,
            // spec 3.6.4). Meanwhile the request stays visible to neighbours (BLC, spec 4.5)
            // and, while the lag gap is acceptable, the automation holds back as the driver's
            // discretionary synchronization would (no acceleration beyond what the target-lane
            // leader allows; it never brakes for it). A driver who took over and lost the gap
            // hands back once the relaxation has ended.
            if d.organize
                && self.cfg.cav.organize_while_automated
                && v.lcs.relax == Relaxation::NONE
            {
                let (blc, g) = self.before_lane_change(s, v, nb, leader, d, false);
                if g.lead_ok && g.lag_ok {
                    return blc;
                }
                let held = Some((g.lag_ok, g.a_ant));
                let mut a = self.automated_decision(s, v, nb, leader, wall, held);
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
            self.before_lane_change(s, v, nb, leader, d, false).0
        }
    }

    /// An automated CAV's decision: ACC / CACC / speed regulation (spec 3). With the spec 6.5
    /// flag the automation also answers a mandatory yield request it agrees to: it follows the
    /// requester as a virtual leader as a yielding driver would (spec 4.5), without leaving
    /// automation [D]. `held`: (lag gap acceptable, a_ant) of a CAV waiting for a PD-lane gap
    /// (`driver::held_back`). Then the demand goes through the actuators (spec 9.3).
    fn automated_decision(
        &self,
        s: u32,
        v: &Vehicle,
        nb: &Neighbours,
        leader: Option<Leader>,
        wall: bool,
        held: Option<(bool, f64)>,
    ) -> Decision {
        let mut d = self.cav_control(s, v, leader, wall);
        if self.cfg.cav.yield_while_automated {
            if let Some(req) = self.agreed_request(v, nb, true) {
                let r = &self.traffic.vehicles[req as usize];
                d.accel = lcm::yield_accel(
                    &v.driver.human,
                    &v.driver.lc,
                    v.v,
                    self.v_des_in(s, v, v.lane as usize),
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
        if let Some((lag_ok, a_ant)) = held {
            d.accel = driver::held_back(d.accel, lag_ok, a_ant);
        }
        self.actuate(v, &mut d);
        d
    }

    /// The automation's demand `d.accel` through its actuators (spec 9.3): bounded by
    /// `cav.max_automated_decel_mps2` (beyond it AEB applies the demand and the decision says
    /// so) and lagged by `cav.actuator_lag_s` from the acceleration realized in the last step.
    /// Both off (no lag, demand within the bound): `d` unchanged.
    #[inline]
    fn actuate(&self, v: &Vehicle, d: &mut Decision) {
        let auto = &self.traffic.auto;
        let (a, aeb) = cav::actuate(v.a, d.accel, auto.lag_gain, auto.bound);
        d.accel = a;
        if aeb {
            d.auto = d.auto.union(AutoFlags::new(true, false));
        }
    }

    /// Automated CAV control (spec 3.9).
    fn cav_control(&self, s: u32, v: &Vehicle, leader: Option<Leader>, wall: bool) -> Decision {
        let p = &self.cfg.cav;
        let v_des = self.v_des_in(s, v, v.lane as usize);
        let ld = self.sensed[s as usize].nb.leader;
        let leader = leader.filter(|l| l.gap_m <= p.sensor_range_m);
        let mut time_gap = v.cacc.time_gap_s;
        // CACC behind a CAV, on the leader's speed as the law knows it: from the V2V beacons
        // (spec 9.3; `None` when they timed out: ACC on the radar alone, a fallback), without
        // delay and loss the leader's current speed.
        let cav_ahead = !wall && self.is_cav(ld);
        let known = match (leader, &self.traffic.auto.beacons) {
            (Some(l), None) if cav_ahead => Some(l),
            (Some(l), Some(b)) if cav_ahead => b
                .received_speed(v.cacc.beacon_age, ld, self.clock.step)
                .map(|v_mps| Leader { v_mps, ..l }),
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
                let target = if !self.sensed[s as usize].linked {
                    p.inter_platoon_gap_s
                } else {
                    v.cacc.gap_s
                };
                time_gap = cav::ramp_time_gap(p, time_gap, target, self.clock.dt);
                cav::cacc(p, v.v, v.a, v_des, known, time_gap, v.cacc.family)
            }
            (Some(l), None) => {
                time_gap = cav::ramp_time_gap(p, time_gap, p.acc_time_gap_s, self.clock.dt);
                cav::acc(p, v.v, v_des, Some(l), time_gap, v.cacc.family)
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
    fn side_follower(&self, v: &Vehicle, nb: &Neighbours, side: Side) -> u32 {
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
    fn before_lane_change(
        &self,
        s: u32,
        v: &Vehicle,
        nb: &Neighbours,
        leader: Option<Leader>,
        d: Desire,
        commanded: bool,
    ) -> (Decision, Gaps) {
        let tl = match d.side {
            Side::Left => nb.left_leader,
            Side::Right => nb.right_leader,
        };
        let tf = self.side_follower(v, nb, d.side);
        let v_des = self.manual_v_des(s, v, self.v_des_in(s, v, v.lane as usize));
        let target = match d.side {
            Side::Left => v.lane as usize + 1,
            Side::Right => (v.lane as usize).saturating_sub(1),
        };
        let v_des_target = self.v_des_in(s, v, target);
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
            leader,
            relax,
            target_leader: self.view(v, tl),
            target_follower,
            mandatory: d.mandatory,
            gamma: d.gamma,
            // A move toward the PD lane accepts the lead gap "regardless of the speed
            // difference" (`cav.organize_regardless_of_speed` [D] 6.22).
            organize_regardless: d.organize && self.cfg.cav.organize_regardless_of_speed,
            must_split: self.sensed[s as usize].linked,
            in_accel_lane: !self.road.geom.plain && self.sensed[s as usize].here.accel,
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
            },
        )
    }
}

/// The safe rule's decelerations (spec 9.1), `None` under the published rule.
#[inline]
pub(crate) fn safe_decel(cfg: &Config) -> Option<SafeDecel> {
    let l = &cfg.lane_change;
    (l.gap_rule == GapRule::Safe).then_some(SafeDecel {
        normal_mps2: l.safe_follower_decel_mps2,
        mandatory_mps2: l.mandatory_safe_decel_mps2,
    })
}

/// The acceleration the new follower `f` (slot `fs`, in the target lane) would ask for by its
/// own law with the changer `c` cut in ahead of it at `changer` (net gap, speed), spec 9.1:
/// a human driver (or a CAV driven by hand) by the human model relaxed as after a cut-in (the
/// engine relaxes it, `execute.rs`); an automated CAV by its ACC or CACC controller with its
/// limits, not relaxed (spec 4.6). Shared by the decide phase and the re-check at execution.
#[allow(clippy::too_many_arguments)]
pub(crate) fn follower_accel_after(
    cfg: &Config,
    road: &RoadState,
    sensed: &[Sensed],
    dt: f64,
    f: &Vehicle,
    fs: u32,
    c: &Vehicle,
    changer: Leader,
) -> f64 {
    let v_des = road.desired_speed_in(v_des_of(f), f.lane as usize, sensed[fs as usize].here.right);
    if !f.automated() {
        return safegap::human_follower_accel(&f.driver.human, &f.driver.lc, f.v, v_des, changer);
    }
    let p = &cfg.cav;
    let changer_is_cav = c.is_cav();
    // The sense phase's link test (sense.rs): a CAV within the 2 s band joins the changer's
    // string with its own t_C, otherwise it keeps the inter-platoon gap (spec 3.6).
    let joins = changer_is_cav
        && changer.gap_m
            <= p.cacc_tg_band_s[1] * f.v + p.standstill_gap_m + p.speed_control_min_gap_m;
    let target_gap_s = if !changer_is_cav {
        p.acc_time_gap_s
    } else if joins {
        f.cacc.gap_s
    } else {
        p.inter_platoon_gap_s
    };
    safegap::automated_follower_accel(
        p,
        &AutomatedFollower {
            v: f.v,
            a: f.a,
            v_des,
            time_gap_s: f.cacc.time_gap_s,
            target_gap_s,
            family: f.cacc.family,
            changer_is_cav,
        },
        changer,
        dt,
    )
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
    fn manual_v_des(&self, s: u32, v: &Vehicle, v_des: f64) -> f64 {
        match self.road.friction {
            None => v_des,
            Some(c) => self.with_friction(s, v, v_des, c),
        }
    }

    /// Cross-lane friction (spec 2.7): v_adj is the slower of the average speeds ahead in the
    /// adjacent lanes (the same scan, n_scan vehicles within d_scan, as the lane-change
    /// motivation; a lane with no vehicle in range counts as `v_des`, so it adds nothing).
    fn with_friction(&self, s: u32, v: &Vehicle, v_des: f64, c_fr: f64) -> f64 {
        let nb = &self.sensed[s as usize].nb;
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

/// Adjacent-lane vehicles a CAV looks through for a cooperative request (spec 9.2): requests
/// come from between it and its own leader, so a few suffice [D].
const COOP_SCAN: usize = 4;

/// Cooperative lane changes (spec 9.2; `platoonsim_model::cooperative`).
impl View<'_> {
    /// The request timeout in steps (at least 1).
    #[inline]
    fn coop_timeout_steps(&self) -> u16 {
        (self.cfg.cav.cooperative_timeout_s / self.clock.dt)
            .round()
            .clamp(1.0, f64::from(u16::MAX / 2)) as u16
    }

    /// The effective time gap of an automated CAV's controller (its drawn t_C before the first
    /// setting).
    #[inline]
    fn effective_gap(v: &Vehicle) -> f64 {
        if v.cacc.time_gap_s > 0.0 {
            v.cacc.time_gap_s
        } else {
            v.cacc.gap_s
        }
    }

    /// An automated CAV `v` with a mandatory or organizing desire `d`: the cooperative change
    /// if its target-lane follower is an automated CAV within V2V (sensor) range and the
    /// request lives; otherwise the published behaviour, with the request counter carried in
    /// the BLC mode (0 without a CAV follower: a new request starts once there is one).
    #[inline(never)]
    fn cooperative_or_published(
        &self,
        s: u32,
        v: &Vehicle,
        nb: &Neighbours,
        leader: Option<Leader>,
        wall: bool,
        d: Desire,
    ) -> Decision {
        let p = &self.cfg.cav;
        let tf = self.side_follower(v, nb, d.side);
        let partner = tf != NONE && {
            let f = &self.traffic.vehicles[tf as usize];
            f.automated() && v.rear() - f.x <= p.sensor_range_m
        };
        let prev = match v.mode {
            Mode::Blc { side, ask, .. } if side == d.side => ask,
            _ => 0,
        };
        let timeout = self.coop_timeout_steps();
        let ask = if partner {
            coop::next_ask(prev, timeout)
        } else {
            0
        };
        if coop::asking(ask, timeout) {
            return self.cooperative_change(s, v, nb, leader, wall, d, tf, ask);
        }
        let mut dec = self.published_change(s, v, nb, leader, wall, d);
        if let Mode::Blc { ask: a, .. } = &mut dec.mode {
            *a = ask;
        }
        dec
    }

    /// The requester's step (spec 9.2): its automation keeps control; once the follower `tf`
    /// answers, it matches the target lane's leader (never braking harder than b_co), and it
    /// changes when both gaps pass the gap acceptance of spec 4.3 and the change is safe for
    /// both new pairs under their own automated laws (`cooperative::join_safe`).
    #[allow(clippy::too_many_arguments)]
    fn cooperative_change(
        &self,
        s: u32,
        v: &Vehicle,
        nb: &Neighbours,
        leader: Option<Leader>,
        wall: bool,
        d: Desire,
        tf: u32,
        ask: u16,
    ) -> Decision {
        let p = &self.cfg.cav;
        let b_co = p.cooperative_gap_decel_mps2;
        let f = &self.traffic.vehicles[tf as usize];
        let answered = matches!(f.mode, Mode::Ycf { to, coop: true, .. } if to == v.id);
        let tl = match d.side {
            Side::Left => nb.left_leader,
            Side::Right => nb.right_leader,
        };
        let target = match d.side {
            Side::Left => v.lane as usize + 1,
            Side::Right => (v.lane as usize).saturating_sub(1),
        };
        let v_des_target = self.v_des_in(s, v, target);
        let mut dec = self.cav_control(s, v, leader, wall);
        let t_own = Self::effective_gap(v);
        // The target lane's leader within sensor range, as the automation sees it.
        let lead = self
            .view(v, tl)
            .filter(|l| l.gap_m <= p.sensor_range_m)
            .map(|l| (l, self.is_cav(tl)));
        if let Some((l, cav_l)) = lead {
            let a_match = coop::open_gap_accel(
                p,
                v.v,
                v.a,
                v_des_target,
                l,
                cav_l,
                coop::opening_time_gap(p, t_own),
                b_co,
            );
            // Before the answer, no acceleration beyond what the target lane allows (never
            // braking for it, as 6.20); after it, the speed match.
            dec.accel = if answered {
                dec.accel.min(a_match)
            } else {
                dec.accel.min(a_match.max(0.0))
            };
        }
        let mut change = false;
        if answered {
            let (_, g) = self.before_lane_change(s, v, nb, leader, d, false);
            let lag = Leader {
                gap_m: v.rear() - f.x,
                v_mps: v.v,
            };
            let f_des = self.v_des_in(tf, f, f.lane as usize);
            let dt = self.clock.dt;
            change = g.lead_ok
                && g.lag_ok
                && coop::join_safe(
                    p,
                    f.v,
                    f.a,
                    f_des,
                    lag,
                    true,
                    Self::effective_gap(f),
                    b_co,
                    dt,
                )
                && lead.is_none_or(|(l, cav_l)| {
                    coop::join_safe(p, v.v, v.a, v_des_target, l, cav_l, t_own, b_co, dt)
                });
        }
        // The demand goes through the actuators (spec 9.3), as every automated one.
        self.actuate(v, &mut dec);
        dec.mode = Mode::Blc {
            side: d.side,
            mandatory: d.mandatory,
            auto: true,
            ask,
        };
        dec.change = change.then_some(d.side);
        dec.coop = change;
        dec.why = if d.mandatory {
            LaneChangeReason::Mandatory
        } else {
            LaneChangeReason::Organizing
        };
        dec
    }

    /// The opener's step (spec 9.2): an automated CAV without a desire of its own answers the
    /// nearest live request addressed to it (an automated CAV ahead of it in an adjacent lane,
    /// behind its own leader, asking toward its lane) by following the requester as a virtual
    /// leader at the opening gap, never braking harder than b_co.
    #[inline(never)]
    fn open_gap(
        &self,
        s: u32,
        v: &Vehicle,
        nb: &Neighbours,
        leader: Option<Leader>,
        wall: bool,
    ) -> Option<Decision> {
        let r = self.cooperative_request(v, nb)?;
        let p = &self.cfg.cav;
        let rv = &self.traffic.vehicles[r as usize];
        let mut dec = self.cav_control(s, v, leader, wall);
        let vl = Leader {
            gap_m: rv.rear() - v.x,
            v_mps: rv.v,
        };
        let t_open = coop::opening_time_gap(p, self.join_time_gap(s, v));
        let v_des = self.v_des_in(s, v, v.lane as usize);
        dec.accel = dec.accel.min(coop::open_gap_accel(
            p,
            v.v,
            v.a,
            v_des,
            vl,
            true,
            t_open,
            p.cooperative_gap_decel_mps2,
        ));
        self.actuate(v, &mut dec);
        dec.mode = Mode::Ycf {
            to: rv.id,
            auto: true,
            coop: true,
        };
        Some(dec)
    }

    /// The time gap a CAV `v` in slot `s` will keep behind a joiner that enters between it and
    /// its leader: its own t_C if the joined string stays within `max_platoon` (the joiner
    /// takes the leader's position + 1 when the leader is a CAV in range with room, spec 3.6;
    /// the opener brings its own sub-string), else the inter-platoon gap.
    fn join_time_gap(&self, s: u32, v: &Vehicle) -> f64 {
        let p = &self.cfg.cav;
        let sensed = &self.sensed[s as usize];
        let ld = sensed.nb.leader;
        let pos_ld = if sensed.cav_ahead {
            self.sensed[ld as usize].platoon_pos
        } else {
            0
        };
        let pos_joiner = if pos_ld >= 1 && pos_ld < p.max_platoon {
            pos_ld + 1
        } else {
            1
        };
        if pos_joiner + sensed.sub_size <= p.max_platoon {
            v.cacc.gap_s
        } else {
            p.inter_platoon_gap_s
        }
    }

    /// The nearest live cooperative request addressed to `v` (slot), if any: in each adjacent
    /// lane, from the vehicle alongside forward, the first automated CAV asking toward `v`'s
    /// lane whose target-lane follower is `v` (ahead of `v`, behind `v`'s leader), within
    /// sensor range; the nearer of the two sides, the left one on a tie. Deterministic, and a
    /// vehicle with a desire of its own never gets here (so two requesters never wait for each
    /// other).
    fn cooperative_request(&self, v: &Vehicle, nb: &Neighbours) -> Option<u32> {
        let p = &self.cfg.cav;
        let timeout = self.coop_timeout_steps();
        let x_limit = if nb.leader != NONE {
            self.traffic.vehicles[nb.leader as usize].x
        } else {
            f64::INFINITY
        };
        let lanes = &self.traffic.lanes;
        let mut best: Option<(u32, f64)> = None;
        for (lane, j, toward) in [
            (v.lane as usize + 1, nb.left_j as usize, Side::Right),
            (
                (v.lane as usize).wrapping_sub(1),
                nb.right_j as usize,
                Side::Left,
            ),
        ] {
            let Some(list) = lanes.get(lane) else {
                continue;
            };
            for &o in list[..j.min(list.len())].iter().rev().take(COOP_SCAN) {
                let r = &self.traffic.vehicles[o as usize];
                if r.x >= x_limit || r.rear() - v.x > p.sensor_range_m {
                    break;
                }
                let asks = matches!(r.mode, Mode::Blc { side, auto: true, ask, .. }
                    if side == toward && coop::asking(ask, timeout));
                if asks && r.automated() {
                    let dist = r.x - v.x;
                    if best.is_none_or(|(_, b)| dist < b) {
                        best = Some((o, dist));
                    }
                    break;
                }
            }
        }
        best.map(|(o, _)| o)
    }
}

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
