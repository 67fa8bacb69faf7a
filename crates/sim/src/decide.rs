//! Phase 2 (decide): every vehicle decides from the step-start state (synchronous update,
//! spec 1): lane-change desire and gap acceptance (spec 4.2-4.3), BLC behaviour, cooperative
//! yielding (spec 4.5), and its acceleration: the human model (spec 2) for humans and CAVs
//! driving manually, CAV control (spec 3) for automated CAVs.

use crate::events::LaneChangeReason;
use crate::network::NO_LANE;
use crate::organize::Advice;
use crate::sense::{Neighbours, NONE};
use crate::sim::{Decision, Simulation};
use crate::vehicle::{Kind, Mode, Relaxation, Vehicle, NEVER, NO_EXIT};
use platoonsim_model::cav::{self, Family};
use platoonsim_model::driver;
use platoonsim_model::human;
use platoonsim_model::lanechange::{self as lcm, Side};
use platoonsim_model::{bounded, Leader, Relax};

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
struct Desire {
    side: Side,
    gamma: f64,
    mandatory: bool,
    /// The move toward the PD lane of platoon organization (spec 4.7).
    organize: bool,
}

impl Simulation {
    /// Phase 2.
    pub(crate) fn decide(&mut self) {
        let n = self.traffic.vehicles.len();
        if self.scratch.decisions.len() < n {
            self.scratch.decisions.resize(
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
                },
            );
        }
        self.update_ramp_density();
        // Taken out for the loop, so that the lanes are walked by iterator (no bounds checks
        // on the lane lists) while the decisions are written.
        let mut decisions = std::mem::take(&mut self.scratch.decisions);
        for lane in &self.traffic.lanes {
            for &s in lane {
                decisions[s as usize] = self.decide_one(s);
            }
        }
        if !self.control.commands.is_empty() {
            self.apply_commands(&mut decisions);
        }
        self.scratch.decisions = decisions;
    }

    /// The decision of a vehicle that must change toward `side` (a commanded change): a
    /// mandatory desire of 1 with the model's gap acceptance and BLC behaviour (spec 4.3).
    pub(crate) fn forced_change(&self, s: u32, v: &Vehicle, side: Side) -> Decision {
        let nb = &self.scratch.sensed[s as usize].nb;
        let (leader, _) = self.leader_or_wall(s, v, nb.leader);
        let d = Desire {
            side,
            gamma: 1.0,
            mandatory: true,
            organize: false,
        };
        self.before_lane_change(s, v, nb, leader, d).0
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
        match self.scratch.sensed[s as usize].here.wall {
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

    /// Density on each on-ramp (its queue plus its acceleration lane) (veh/km), for the
    /// anticipation rule (spec 4.2), and from it the rule's factor for j = 1, 2.
    fn update_ramp_density(&mut self) {
        for (i, r) in self.road.geom.on_ramps.iter().enumerate() {
            let queued = self.entrances[i + 1].waiting();
            let lane = &self.traffic.lanes[r.lane as usize];
            let on_accel = if r.adds_lane {
                0
            } else {
                let hi =
                    lane.partition_point(|&o| self.traffic.vehicles[o as usize].x >= r.accel_end);
                let lo = lane.partition_point(|&o| self.traffic.vehicles[o as usize].x >= r.x);
                lo.saturating_sub(hi)
            };
            let density = (queued + on_accel) as f64 / (r.density_length_m / 1000.0);
            let c = self.cfg.lane_change.anticipation_strength;
            // The same expression as per vehicle before, so the same bits.
            self.scratch.ramp_factor[i] =
                [1, 2].map(|j: u32| 1.0 + c * (density / RHO_JAM_PER_KM) / f64::from(j));
        }
    }

    /// Current relaxation factors of a vehicle (spec 4.6).
    #[inline]
    fn relax_now(&self, v: &Vehicle) -> Relax {
        match v.relax {
            Relaxation::None => Relax::NONE,
            Relaxation::Since(since) => {
                lcm::relax_at(&v.lc, (self.clock.step - since) as f64 * self.clock.dt)
            }
        }
    }

    fn decide_one(&self, s: u32) -> Decision {
        let v = &self.traffic.vehicles[s as usize];
        let nb = &self.scratch.sensed[s as usize].nb;
        let v_des = self.v_des_in(s, v, v.lane as usize);
        let (leader, wall) = self.leader_or_wall(s, v, nb.leader);

        // 1. Lane-change desire (takes priority over yielding).
        if let Some(d) = self.desire(s, v, nb) {
            // With `cav.organize_while_automated` [D] a CAV's automation stays engaged while
            // its driver waits for a gap toward the PD lane: the driver takes over only once
            // both gaps are acceptable (a leader then changes at once, a follower splits first,
            // spec 3.6.4). Meanwhile the request stays visible to neighbours (BLC, spec 4.5)
            // and, while the lag gap is acceptable, the automation holds back as the driver's
            // discretionary synchronization would (no acceleration beyond what the target-lane
            // leader allows; it never brakes for it). A driver who took over and lost the gap
            // hands back once the relaxation has ended.
            if d.organize && self.cfg.cav.organize_while_automated && v.relax == Relaxation::None {
                let (blc, g) = self.before_lane_change(s, v, nb, leader, d);
                if g.lead_ok && g.lag_ok {
                    return blc;
                }
                let mut a = self.automated_decision(s, v, nb, leader, wall);
                a.accel = driver::held_back(a.accel, g.lag_ok, g.a_ant);
                if a.mode == Mode::Cf {
                    a.mode = Mode::Blc {
                        side: d.side,
                        mandatory: false,
                        auto: true,
                    };
                }
                return a;
            }
            return self.before_lane_change(s, v, nb, leader, d).0;
        }

        // 2. Automated CAV: ACC / CACC / speed regulation (spec 3).
        if v.automated() {
            return self.automated_decision(s, v, nb, leader, wall);
        }
        let yield_to = self.agreed_request(v, nb, false);

        // 3. Human model (humans and CAVs driving manually), possibly yielding.
        let v_des = self.manual_v_des(s, v, v_des);
        let relax = self.relax_now(v);
        let mut target = human::target_accel(&v.human, v.v, v_des, leader, relax);
        let mut mode = Mode::Cf;
        if let Some(req) = yield_to {
            let r = &self.traffic.vehicles[req as usize];
            target = lcm::yield_accel(&v.human, &v.lc, v.v, v_des, target, self.yield_gap(v, r));
            mode = Mode::Ycf {
                to: r.id,
                auto: false,
            };
        }
        Decision {
            accel: human::smooth_accel(v.a, target, v.human.smoothing),
            mode,
            family: v.family,
            regime: None,
            time_gap: v.time_gap_s,
            change: None,
            why: LaneChangeReason::Discretionary,
            takeover: false,
        }
    }

    /// An automated CAV's decision: ACC / CACC / speed regulation (spec 3). With the spec 6.5
    /// flag the automation also answers a mandatory yield request it agrees to: it follows the
    /// requester as a virtual leader as a yielding driver would (spec 4.5), without leaving
    /// automation [D].
    fn automated_decision(
        &self,
        s: u32,
        v: &Vehicle,
        nb: &Neighbours,
        leader: Option<Leader>,
        wall: bool,
    ) -> Decision {
        let mut d = self.cav_control(s, v, leader, wall);
        if self.cfg.cav.yield_while_automated {
            if let Some(req) = self.agreed_request(v, nb, true) {
                let r = &self.traffic.vehicles[req as usize];
                d.accel = lcm::yield_accel(
                    &v.human,
                    &v.lc,
                    v.v,
                    self.v_des_in(s, v, v.lane as usize),
                    d.accel,
                    self.yield_gap(v, r),
                );
                d.mode = Mode::Ycf {
                    to: r.id,
                    auto: true,
                };
            }
        }
        d
    }

    /// Automated CAV control (spec 3.9).
    fn cav_control(&self, s: u32, v: &Vehicle, leader: Option<Leader>, wall: bool) -> Decision {
        let p = &self.cfg.cav;
        let v_des = self.v_des_in(s, v, v.lane as usize);
        let ld = self.scratch.sensed[s as usize].nb.leader;
        let leader = leader.filter(|l| l.gap_m <= p.sensor_range_m);
        let mut time_gap = v.time_gap_s;
        let cmd = match leader {
            None => cav::Command {
                accel: cav::speed_regulation(p, v.v, v_des),
                mode: cav::CavMode::SpeedRegulation,
                family: Family::Speed,
            },
            Some(l) if !wall && self.is_cav(ld) => {
                let target = if !self.scratch.sensed[s as usize].linked {
                    p.inter_platoon_gap_s
                } else {
                    v.cacc_gap_s
                };
                time_gap = cav::ramp_time_gap(p, time_gap, target, self.clock.dt);
                cav::cacc(p, v.v, v.a, v_des, l, time_gap, v.family)
            }
            Some(l) => {
                time_gap = cav::ramp_time_gap(p, time_gap, p.acc_time_gap_s, self.clock.dt);
                cav::acc(p, v.v, v_des, Some(l), time_gap, v.family)
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
        }
    }

    /// Spec 4.2: the lane-change desire, if it exceeds the driver's threshold.
    fn desire(&self, s: u32, v: &Vehicle, nb: &Neighbours) -> Option<Desire> {
        let lcd = &self.cfg.lane_change;
        if v.x < lcd.forbid_zone_m {
            return None;
        }
        // Anti-oscillation (spec 4.2), first part: no desire at all so soon after a change
        // (checked before the scans below; `desire` has no side effects).
        let since = if v.last_lc_step != NEVER {
            let since = (self.clock.step - v.last_lc_step) as f64 * self.clock.dt;
            if driver::too_soon_after_change(&v.lc, since) {
                return None;
            }
            Some(since)
        } else {
            None
        };
        // A vehicle its strategy advises (`organize`) takes the longer way; the others (every
        // vehicle without a strategy) pay nothing for strategies.
        let advised = match v.kind {
            Kind::Human => self.control.advise[0],
            Kind::Cav => self.control.advise[1],
        };
        if advised {
            return self.advised_desire(s, v, nb, since);
        }
        let mandatory = if self.road.geom.plain {
            None
        } else {
            self.mandatory(s, v, None)
        };
        let [left, right] = self.discretionary(s, v, nb, self.is_follower(s, v));
        let (side, gamma) = driver::combine(mandatory, left, right, v.lc.mandatory_weight)?;
        settle(v, since, side, gamma, mandatory.is_some(), false)
    }

    /// [`Self::desire`] of a vehicle its strategy advises: `Join` replaces the discretionary
    /// desire when there is no mandatory need and the exit is not near [D] (spec 4.7);
    /// `Avoid` adds a mandatory desire to leave the lane and closes it to discretionary
    /// changes while that desire would be positive (the lane-drop rule).
    #[inline(never)]
    fn advised_desire(
        &self,
        s: u32,
        v: &Vehicle,
        nb: &Neighbours,
        since: Option<f64>,
    ) -> Option<Desire> {
        let advice = self.control.organizer.advise(
            v,
            self.clock.step as f64 * self.clock.dt,
            &self.road.geom,
        );
        let avoid = match advice {
            Advice::Avoid { lane, from_m } => Some((lane, from_m)),
            _ => None,
        };
        let mandatory = if self.road.geom.plain && avoid.is_none() {
            None
        } else {
            self.mandatory(s, v, avoid)
        };
        let join = match advice {
            Advice::Join { lane, strength } if mandatory.is_none() && !self.exit_near(v) => {
                Some((lane, strength))
            }
            _ => None,
        };
        let (side, gamma) = if let Some((lane, strength)) = join {
            // γ_d = 0 in the organized lane (spec 4.7).
            (driver::toward(v.lane, lane)?, strength)
        } else {
            let [mut left, mut right] = self.discretionary(s, v, nb, self.is_follower(s, v));
            if let Some((lane, from_m)) = avoid {
                let closed = |target: u32| {
                    target == lane && lcm::mandatory_desire(&v.lc, from_m - v.x, v.v, 1) > 0.0
                };
                if closed(v.lane + 1) {
                    left = None;
                }
                if v.lane > 0 && closed(v.lane - 1) {
                    right = None;
                }
            }
            driver::combine(mandatory, left, right, v.lc.mandatory_weight)?
        };
        settle(v, since, side, gamma, mandatory.is_some(), join.is_some())
    }

    /// A CAV that follows a CAV within sensor range is (or is about to be, "a CAV directly
    /// behind another CAV automatically starts to form a platoon" [S]) a platoon follower: no
    /// discretionary desire (w_CAV follower, spec 4.7).
    #[inline]
    fn is_follower(&self, s: u32, v: &Vehicle) -> bool {
        self.scratch.sensed[s as usize].linked
            || (v.is_cav() && self.scratch.sensed[s as usize].cav_ahead)
    }

    /// The side toward which vehicle `v` organizes now (its strategy's `Join` advice, no
    /// mandatory need aside: it is not near its exit), if it is not in the organized lane.
    /// Used for yielding to organizing vehicles.
    pub(crate) fn organizing_side(&self, v: &Vehicle) -> Option<Side> {
        if !self.control.advise[v.kind as usize] || self.exit_near(v) {
            return None;
        }
        match self.control.organizer.advise(
            v,
            self.clock.step as f64 * self.clock.dt,
            &self.road.geom,
        ) {
            Advice::Join { lane, .. } => driver::toward(v.lane, lane),
            _ => None,
        }
    }

    /// Is the vehicle's off-ramp within the anticipation range (no organizing there)?
    #[inline]
    fn exit_near(&self, v: &Vehicle) -> bool {
        self.exit_within(v, self.cfg.lane_change.anticipation_distance_m)
    }

    /// Is the vehicle's off-ramp within `range` ahead?
    fn exit_within(&self, v: &Vehicle, range: f64) -> bool {
        v.exit != NO_EXIT && self.road.geom.off_ramps[v.exit as usize].x - v.x < range
    }

    /// Mandatory desire (spec 4.2), if any is positive: leaving a lane that ends (an
    /// acceleration lane or a dropped lane; one change toward the side where a lane goes on),
    /// or reaching the rightmost through lane at the driver's off-ramp (N = lanes to cross).
    /// The larger one wins.
    #[inline(always)]
    fn mandatory(&self, s: u32, v: &Vehicle, avoid: Option<(u32, f64)>) -> Option<(Side, f64)> {
        let mut best: Option<(Side, f64)> = None;
        // A lane the strategy closes to this vehicle (`Advice::Avoid`): leave it as a lane
        // that ends at `from_m`, toward the right unless it is the rightmost lane.
        if let Some((lane, from_m)) = avoid {
            if v.lane == lane {
                let g = lcm::mandatory_desire(&v.lc, from_m - v.x, v.v, 1);
                if g > 0.0 {
                    let side = if lane == 0 { Side::Left } else { Side::Right };
                    best = Some((side, g));
                }
            }
        }
        if self.road.geom.plain {
            return best;
        }
        if let Some(w) = self.scratch.sensed[s as usize].here.wall {
            let probe = (w - 1.0).max(v.x);
            let side = if self.road.geom.through(v.lane + 1, probe) || v.lane == 0 {
                Side::Left
            } else {
                Side::Right
            };
            let g = lcm::mandatory_desire(&v.lc, w - v.x, v.v, 1);
            if g > 0.0 && best.is_none_or(|(_, b)| g > b) {
                best = Some((side, g));
            }
        }
        if v.exit != NO_EXIT {
            let r = &self.road.geom.off_ramps[v.exit as usize];
            if v.x < r.x && v.lane > r.lane {
                let g = lcm::mandatory_desire(&v.lc, r.x - v.x, v.v, v.lane - r.lane);
                if g > 0.0 && best.is_none_or(|(_, b)| g > b) {
                    best = Some((Side::Right, g));
                }
            }
        }
        best
    }

    /// Discretionary desires [left, right] (spec 4.2), `None` for a side that cannot be taken
    /// (no lane, an acceleration lane) or when there is nothing to gain. Includes w_CAV (spec
    /// 4.7), the exit constraint η_e and the on-ramp anticipation.
    #[inline(always)]
    fn discretionary(
        &self,
        s: u32,
        v: &Vehicle,
        nb: &Neighbours,
        follower: bool,
    ) -> [Option<f64>; 2] {
        let lcd = &self.cfg.lane_change;
        // A platoon follower has no speed-gain motivation (w_CAV follower), but ahead of a busy
        // on-ramp (spec 4.2 "Anticipatory") it still makes room, moving left with the leader's
        // weight [D]: otherwise, at high penetration, the strings stay in the merge lane while
        // the lanes beside them run empty. (Only to the left: the anticipation factor lowers the
        // current lane's speed, so it would also make the lane nearer the ramp look better.)
        let mut anticipation = None;
        let (w_left, w_right) = if !v.is_cav() {
            (1.0, 1.0)
        } else if follower {
            let w = lcd.cav_weight_follower;
            if lcd.follower_anticipates && !self.road.geom.plain {
                let f = self.anticipation_factor(s, v);
                anticipation = Some(f);
                if f > 1.0 {
                    (lcd.cav_weight_leader, w)
                } else {
                    (w, w)
                }
            } else {
                (w, w)
            }
        } else {
            (lcd.cav_weight_leader, lcd.cav_weight_leader)
        };
        if w_left <= 0.0 && w_right <= 0.0 {
            return [None, None];
        }
        // η_e: no discretionary change within E_exit of the exit; a penalty on moving away from
        // the exit lane within the anticipation range (spec 4.2, 4.9).
        let mut eta_left = 1.0;
        if v.exit != NO_EXIT {
            let d = self.road.geom.off_ramps[v.exit as usize].x - v.x;
            if d < lcd.exit_no_change_m {
                return [None, None];
            }
            if d < lcd.anticipation_distance_m {
                eta_left = lcd.exit_lane_penalty;
            }
        }
        // Speeds are what the driver could achieve: capped at its desired speed (in that lane,
        // spec 2.7).
        let v_des = self.v_des_in(s, v, v.lane as usize);
        let mut v_cur = bounded::min(
            self.avg_speed_ahead(v.lane as usize, nb.idx as usize, v.x, v_des),
            v_des,
        );
        if !self.road.geom.plain {
            // Mostly 1 (no on-ramp ahead): dividing by 1 changes nothing.
            let f = anticipation.unwrap_or_else(|| self.anticipation_factor(s, v));
            if f != 1.0 {
                v_cur /= f;
            }
        }
        // v_ant ≤ the driver's desired speed in the target lane ≤ its own desired speed, so no
        // side can beat the absolute gain gate: nothing to scan.
        if v_des_of(v) - v_cur < v.lc.min_speed_gain_mps {
            return [None, None];
        }
        let here = &self.scratch.sensed[s as usize].here;
        let mut out = [None, None];
        let lane = v.lane as usize;
        for (i, side, target, j, w, eta, open) in [
            (
                0,
                Side::Left,
                lane + 1,
                nb.left_j,
                w_left,
                eta_left,
                here.enter_left,
            ),
            (
                1,
                Side::Right,
                lane.wrapping_sub(1),
                nb.right_j,
                w_right,
                1.0,
                here.enter_right,
            ),
        ] {
            // `Geometry::can_enter` of the lane on that side (none right of lane 0); not into a
            // lane that ends where the driver would already have to leave it (a lane drop
            // ahead: its mandatory desire there is positive), issue 18.
            if !open || w <= 0.0 || (!self.road.geom.plain && self.ends_too_soon(v, target)) {
                continue;
            }

            let v_ant = self.anticipated_speed(s, v, target, j as usize, v_cur);
            out[i] = Some(w * eta * lcm::discretionary_desire(&v.lc, v_ant, v_cur, side));
        }
        out
    }

    /// Does lane `target` end so soon ahead of `v` that a driver who moved into it would at
    /// once want to leave it again (mandatory desire γ_m > 0 for its wall, one change)? A
    /// discretionary change into such a lane ends at the wall (issue 18: 3 → 2 lane drops).
    #[inline(never)]
    fn ends_too_soon(&self, v: &Vehicle, target: usize) -> bool {
        self.road
            .geom
            .wall_ahead(target as u32, v.x)
            .is_some_and(|w| lcm::mandatory_desire(&v.lc, w - v.x, v.v, 1) > 0.0)
    }

    /// Spec 4.2 "Anticipatory": in the two rightmost through lanes within the anticipation
    /// range of an on-ramp, the current-lane speed is divided by 1 + c_inc (ρ_ramp/ρ_jam)/j.
    #[inline]
    fn anticipation_factor(&self, s: u32, v: &Vehicle) -> f64 {
        let lcd = &self.cfg.lane_change;
        let here = &self.scratch.sensed[s as usize].here;
        let k = here.ramps_upto as usize;
        let Some((ramp, _)) =
            self.road
                .geom
                .next_on_ramp_after(k, v.x, lcd.anticipation_distance_m)
        else {
            return 1.0;
        };
        // `Geometry::rightmost_through(v.x)`, looked up in the sense phase.
        if here.right == NO_LANE {
            return 1.0;
        }
        let right = u32::from(here.right);
        if v.lane < right {
            return 1.0;
        }
        let j = v.lane - right + 1;
        if j > 2 {
            return 1.0;
        }
        // 1 + c_inc (ρ_ramp/ρ_jam)/j, computed once per step (`update_ramp_density`).
        self.scratch.ramp_factor[ramp][(j - 1) as usize]
    }

    /// Average speed of the next `n_scan` vehicles within `d_scan` ahead of `x` in `lane`,
    /// starting at list index `from` (front-first list: indices below `from` are ahead);
    /// `v_empty` if none (spec 2.7 "speeds ahead").
    fn avg_speed_ahead(&self, lane: usize, from: usize, x: f64, v_empty: f64) -> f64 {
        let lcd = &self.cfg.lane_change;
        // The vehicles ahead, nearest first (one bounds check for the scan).
        let ahead = &self.scratch.lane_xv[lane][..from];
        let mut sum = 0.0;
        let mut n = 0u32;
        for &(ox, ov) in ahead.iter().rev().take(lcd.scan_vehicles as usize) {
            if ox - x > lcd.scan_distance_m {
                break;
            }
            sum += ov;
            n += 1;
        }
        if n == 0 {
            v_empty
        } else {
            sum / n as f64
        }
    }

    /// v_ant = min(v̄_target, v_target-leader) (spec 4.2), scanning from the target leader, in
    /// lane `target` whose merge-sweep cursor for this vehicle is `j` (the target leader is at
    /// index j − 1, read from `lane_xv`: the same step-start x and v as its record).
    ///
    /// When even min(v_target-leader, v_des), an upper bound of v_ant, gains less than the
    /// minimum speed gain over `v_cur`, the bound is returned without the scan: the
    /// discretionary desire is then 0 for the bound as for v_ant (`discretionary_desire`'s first
    /// test; v_ant ≤ bound and subtracting `v_cur` is monotonic, so v_ant − v_cur < the gain
    /// too). In queues beside a queue this skips most scans.
    #[inline]
    fn anticipated_speed(&self, s: u32, v: &Vehicle, target: usize, j: usize, v_cur: f64) -> f64 {
        let v_des = self.v_des_in(s, v, target);
        if j == 0 {
            return v_des; // no target leader
        }
        let (tl_x, tl_v) = self.scratch.lane_xv[target][j - 1];
        if tl_x - v.x > self.cfg.lane_change.scan_distance_m {
            return v_des;
        }
        let bound = bounded::min(tl_v, v_des);
        if bound - v_cur < v.lc.min_speed_gain_mps {
            return bound;
        }
        let avg = self.avg_speed_ahead(target, j, v.x, v_des);
        bounded::min(avg.min(tl_v), v_des)
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
    fn before_lane_change(
        &self,
        s: u32,
        v: &Vehicle,
        nb: &Neighbours,
        leader: Option<Leader>,
        d: Desire,
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
        let h = &v.human;
        // An automated CAV hands over to its driver now ("manual mode from a lane-change desire
        // on", spec 3.1). At a CACC gap of 0.6 s the human model alone would brake hard; the
        // driver takes over with relaxed car following that recovers over t_s, as after a cut-in
        // (spec 4.6) [D].
        let takeover = v.automated();
        let relax = if takeover {
            lcm::gap_relax(&v.lc)
        } else {
            self.relax_now(v)
        };
        let a_cur = human::target_accel(h, v.v, v_des, leader, relax);
        let lead_view = self.view(v, tl);
        let a_ant = human::target_accel(h, v.v, v_des_target, lead_view, lcm::gap_relax(&v.lc));
        let lead_ok = match lead_view {
            None => true,
            Some(l) => {
                // Discretionary changes must not have to brake behind the new leader (spec
                // 4.3); a mandatory change, and a move toward the PD lane "regardless of the
                // speed difference" (`cav.organize_regardless_of_speed` [D] 6.22), need not.
                driver::lead_acceptable(
                    lcm::accept_lead_gap(h, &v.lc, l.gap_m, v.v, l.v_mps),
                    d.mandatory,
                    d.organize && self.cfg.cav.organize_regardless_of_speed,
                    a_ant,
                )
            }
        };
        let lag_ok = if tf == NONE {
            true
        } else {
            let f = &self.traffic.vehicles[tf as usize];
            lcm::accept_lag_gap(h, &v.lc, v.rear() - f.x, v.v, f.v, a_ant)
        };
        // Only a platoon leader changes lanes: a follower splits first (spec 3.6.4).
        let must_split = self.scratch.sensed[s as usize].linked;
        let change = driver::change_now(lead_ok, lag_ok, must_split);
        // BLC-Slow only for a mandatory change with the lag gap closed (evaluated lazily:
        // `keeps_pace` reads the follower).
        let slow =
            d.mandatory && !lag_ok && d.gamma > v.lc.slow_down_desire && !self.keeps_pace(s, v, tf);
        let target = driver::blc_target(
            a_cur,
            a_ant,
            h.comfort_decel,
            change,
            d.mandatory,
            lead_ok,
            lag_ok,
            slow,
        );
        (
            Decision {
                accel: human::smooth_accel(v.a, target, h.smoothing),
                mode: Mode::Blc {
                    side: d.side,
                    mandatory: d.mandatory,
                    auto: false,
                },
                family: Family::Speed,
                regime: None,
                time_gap: v.time_gap_s,
                change: change.then_some(d.side),
                why: if d.mandatory {
                    LaneChangeReason::Mandatory
                } else if d.organize {
                    LaneChangeReason::Organizing
                } else {
                    LaneChangeReason::Discretionary
                },
                takeover,
            },
            Gaps {
                lead_ok,
                lag_ok,
                a_ant,
            },
        )
    }

    /// Exceptions to BLC-Slow [D]: the target-lane follower is yielding to this vehicle (it is
    /// dropping back to make room; slowing down as well would leave both waiting for the other,
    /// a deadlock seen at standstill), or the follower is faster (it passes by itself) and
    /// either this vehicle is in an acceleration lane (slowing would only widen the speed
    /// difference the next gap must absorb) or it is already below the creep speed (spec 4.3's
    /// 5 mph): beside a slow gapless string, BLC-Slow would stop it in an open lane and stop
    /// the whole lane behind it.
    fn keeps_pace(&self, s: u32, v: &Vehicle, tf: u32) -> bool {
        if tf == NONE {
            return false;
        }
        let f = &self.traffic.vehicles[tf as usize];
        driver::keeps_pace(
            matches!(f.mode, Mode::Ycf { to, .. } if to == v.id),
            f.v,
            v.v,
            !self.road.geom.plain && self.scratch.sensed[s as usize].here.accel,
        )
    }
}

/// ρ_jam of the anticipation rule (spec 4.2): 1000/6 veh/km.
const RHO_JAM_PER_KM: f64 = 1000.0 / 6.0;

/// The driver's own desired speed v_F, in no particular lane.
#[inline]
fn v_des_of(v: &Vehicle) -> f64 {
    v.human.desired_speed
}

impl Simulation {
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
        let nb = &self.scratch.sensed[s as usize].nb;
        let lane = v.lane as usize;
        let mut v_adj = v_des;
        if lane + 1 < self.scratch.lane_xv.len() {
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
        self.road.lane_capped(
            v_des_of(v),
            lane,
            self.scratch.sensed[s as usize].here.right,
        )
    }
}

/// The desire if it passes the driver's threshold, after the second part of the
/// anti-oscillation rule (spec 4.2; `since`: seconds since the last change).
#[inline]
fn settle(
    v: &Vehicle,
    since: Option<f64>,
    side: Side,
    gamma: f64,
    mandatory: bool,
    organize: bool,
) -> Option<Desire> {
    if let Some(since) = since {
        if driver::quick_return(&v.lc, since, gamma, side, v.last_lc_side) {
            return None;
        }
    }
    driver::wants_change(&v.lc, gamma).then_some(Desire {
        side,
        gamma,
        mandatory,
        organize,
    })
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
