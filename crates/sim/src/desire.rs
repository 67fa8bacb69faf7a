//! Phase 2, the lane-change desire (spec 4.2, 4.7): mandatory and discretionary desires, the
//! strategy's advice, the anticipation of on-ramps and the speeds ahead. The rules themselves
//! are pure functions in `platoonsim_model::driver`; this module gathers their inputs.

use crate::decide::{v_des_of, Desire};
use crate::decide::{Me, View};
use crate::here::SideWalls;
use crate::network::NO_LANE;
use crate::organize::Advice;
use crate::vehicle::{Kind, Vehicle, NEVER, NO_EXIT};
use crate::view::VehicleView;
use platoonsim_model::bounded;
use platoonsim_model::driver;
use platoonsim_model::lanechange::{self as lcm, Side};

impl View<'_> {
    /// Spec 4.2: the lane-change desire, if it exceeds the driver's threshold.
    #[inline]
    pub(crate) fn desire(&self, me: &Me, walls: &mut SideWalls) -> Option<Desire> {
        let lcd = &self.cfg.lane_change;
        let v = me.v;
        if v.x < lcd.forbid_zone_m {
            return None;
        }
        // Anti-oscillation (spec 4.2), first part: no desire at all so soon after a change
        // (checked before the scans below; `desire` has no side effects).
        let since = if v.lcs.last_step != NEVER {
            let since = (self.clock.step - v.lcs.last_step) as f64 * self.clock.dt;
            if driver::too_soon_after_change(&v.driver.lc, since) {
                return None;
            }
            Some(since)
        } else {
            None
        };
        // A vehicle its strategy advises (`organize`) takes the longer way; the others (every
        // vehicle without a strategy) pay nothing for strategies.
        let advised = match v.kind {
            Kind::Human => self.advise[0],
            Kind::Cav => self.advise[1],
        };
        if advised {
            return self.advised_desire(me, since, walls);
        }
        let mandatory = if self.road.geom.plain {
            None
        } else {
            self.mandatory(me, None)
        };
        let [left, right] = self.discretionary(me, self.is_follower(me), walls);
        let (side, gamma) = driver::combine(mandatory, left, right, v.driver.lc.mandatory_weight)?;
        settle(v, since, side, gamma, mandatory.is_some(), false)
    }

    /// [`Self::desire`] of a vehicle its strategy advises: `Join` replaces the discretionary
    /// desire when there is no mandatory need and the exit is not near [D] (spec 4.7);
    /// `Avoid` adds a mandatory desire to leave the lane and closes it to discretionary
    /// changes while that desire would be positive (the lane-drop rule).
    #[inline(never)]
    fn advised_desire(&self, me: &Me, since: Option<f64>, walls: &mut SideWalls) -> Option<Desire> {
        let v = me.v;
        let advice = self.organizer.advise(
            VehicleView::new(v),
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
            self.mandatory(me, avoid)
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
            let [mut left, mut right] = self.discretionary(me, self.is_follower(me), walls);
            if let Some((lane, from_m)) = avoid {
                let closed = |target: u32| {
                    target == lane
                        && lcm::mandatory_desire(&v.driver.lc, from_m - v.x, v.v, 1) > 0.0
                };
                if closed(v.lane + 1) {
                    left = None;
                }
                if v.lane > 0 && closed(v.lane - 1) {
                    right = None;
                }
            }
            driver::combine(mandatory, left, right, v.driver.lc.mandatory_weight)?
        };
        settle(v, since, side, gamma, mandatory.is_some(), join.is_some())
    }

    /// A CAV that follows a CAV within sensor range is (or is about to be, "a CAV directly
    /// behind another CAV automatically starts to form a platoon" [S]) a platoon follower: no
    /// discretionary desire (w_CAV follower, spec 4.7).
    #[inline]
    pub(crate) fn is_follower(&self, me: &Me) -> bool {
        me.sensed.linked || (me.v.is_cav() && me.sensed.cav_ahead)
    }

    /// The side toward which vehicle `v` organizes now (its strategy's `Join` advice, no
    /// mandatory need aside: it is not near its exit), if it is not in the organized lane.
    /// Used for yielding to organizing vehicles.
    pub(crate) fn organizing_side(&self, v: &Vehicle) -> Option<Side> {
        if !self.advise[v.kind as usize] || self.exit_near(v) {
            return None;
        }
        match self.organizer.advise(
            VehicleView::new(v),
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
    pub(crate) fn exit_within(&self, v: &Vehicle, range: f64) -> bool {
        v.route.exit != NO_EXIT && self.road.geom.off_ramps[v.route.exit as usize].x - v.x < range
    }

    /// Mandatory desire (spec 4.2), if any is positive: leaving a lane that ends (an
    /// acceleration lane or a dropped lane; one change toward the side where a lane goes on),
    /// or reaching the rightmost through lane at the driver's off-ramp (N = lanes to cross).
    /// The larger one wins.
    #[inline(always)]
    fn mandatory(&self, me: &Me, avoid: Option<(u32, f64)>) -> Option<(Side, f64)> {
        let v = me.v;
        let mut best: Option<(Side, f64)> = None;
        // A lane the strategy closes to this vehicle (`Advice::Avoid`): leave it as a lane
        // that ends at `from_m`, toward the right unless it is the rightmost lane.
        if let Some((lane, from_m)) = avoid {
            if v.lane == lane {
                let g = lcm::mandatory_desire(&v.driver.lc, from_m - v.x, v.v, 1);
                if g > 0.0 {
                    let side = if lane == 0 { Side::Left } else { Side::Right };
                    best = Some((side, g));
                }
            }
        }
        if self.road.geom.plain {
            return best;
        }
        // A lane that ends beyond the driver's exit, where it is already in the exit lane,
        // is no reason to leave it: it leaves by the off-ramp first (an exit lane followed by
        // a lane drop, as SUMO networks have them; without this the exiting driver stopped
        // at the exit, waiting to move away from it) [D] (docs/model-choices.md 6.23).
        let wall = me.sensed.here.wall.filter(|&w| {
            v.route.exit == NO_EXIT || {
                let r = &self.road.geom.off_ramps[v.route.exit as usize];
                !(v.lane == r.lane && v.x < r.x && r.x <= w)
            }
        });
        if let Some(w) = wall {
            let probe = (w - 1.0).max(v.x);
            let side = if self.road.geom.through(v.lane + 1, probe) || v.lane == 0 {
                Side::Left
            } else {
                Side::Right
            };
            let g = lcm::mandatory_desire(&v.driver.lc, w - v.x, v.v, 1);
            if g > 0.0 && best.is_none_or(|(_, b)| g > b) {
                best = Some((side, g));
            }
        }
        if v.route.exit != NO_EXIT {
            let r = &self.road.geom.off_ramps[v.route.exit as usize];
            if v.x < r.x && v.lane > r.lane {
                let g = lcm::mandatory_desire(&v.driver.lc, r.x - v.x, v.v, v.lane - r.lane);
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
    fn discretionary(&self, me: &Me, follower: bool, walls: &mut SideWalls) -> [Option<f64>; 2] {
        let lcd = &self.cfg.lane_change;
        let (v, nb) = (me.v, me.nb());
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
                let f = self.anticipation_factor(me);
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
        if v.route.exit != NO_EXIT {
            let d = self.road.geom.off_ramps[v.route.exit as usize].x - v.x;
            if d < lcd.exit_no_change_m {
                return [None, None];
            }
            if d < lcd.anticipation_distance_m {
                eta_left = lcd.exit_lane_penalty;
            }
        }
        // Speeds are what the driver could achieve: capped at its desired speed (in that lane,
        // spec 2.7).
        let v_des = self.own_v_des(me);
        let mut v_cur = bounded::min(
            self.avg_speed_ahead(v.lane as usize, nb.idx as usize, v.x, v_des),
            v_des,
        );
        if !self.road.geom.plain {
            // Mostly 1 (no on-ramp ahead): dividing by 1 changes nothing.
            let f = anticipation.unwrap_or_else(|| self.anticipation_factor(me));
            if f != 1.0 {
                v_cur /= f;
            }
        }
        // v_ant ≤ the driver's desired speed in the target lane ≤ its own desired speed, so no
        // side can beat the absolute gain gate: nothing to scan.
        if v_des_of(v) - v_cur < v.driver.lc.min_speed_gain_mps {
            return [None, None];
        }
        let here = &me.sensed.here;
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
            // ahead: its mandatory desire there is positive), issue 18. The target lane's wall
            // comes from the walk along this lane list (`SideWalls`; `v.x` is finite, phase 7).
            if !open
                || w <= 0.0
                || (!self.road.geom.plain
                    && self.ends_too_soon(v, walls.wall_ahead(&self.road.geom, target, v.x)))
            {
                continue;
            }

            let v_ant = self.anticipated_speed(me, target, j as usize, v_cur);
            out[i] = Some(w * eta * lcm::discretionary_desire(&v.driver.lc, v_ant, v_cur, side));
        }
        out
    }

    /// Does lane `target` end so soon ahead of `v` that a driver who moved into it would at
    /// once want to leave it again (mandatory desire γ_m > 0 for its wall, one change)? A
    /// discretionary change into such a lane ends at the wall (issue 18: 3 → 2 lane drops).
    /// `wall`: `Geometry::wall_ahead` of that lane at `v.x`.
    #[inline]
    fn ends_too_soon(&self, v: &Vehicle, wall: Option<f64>) -> bool {
        wall.is_some_and(|w| lcm::mandatory_desire(&v.driver.lc, w - v.x, v.v, 1) > 0.0)
    }

    /// Spec 4.2 "Anticipatory": in the two rightmost through lanes within the anticipation
    /// range of an on-ramp, the current-lane speed is divided by 1 + c_inc (ρ_ramp/ρ_jam)/j.
    #[inline]
    fn anticipation_factor(&self, me: &Me) -> f64 {
        let lcd = &self.cfg.lane_change;
        let (v, here) = (me.v, &me.sensed.here);
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
        self.ramp_factor[ramp][(j - 1) as usize]
    }

    /// Average speed of the next `n_scan` vehicles within `d_scan` ahead of `x` in `lane`,
    /// starting at list index `from` (front-first list: indices below `from` are ahead);
    /// `v_empty` if none (spec 2.7 "speeds ahead").
    pub(crate) fn avg_speed_ahead(&self, lane: usize, from: usize, x: f64, v_empty: f64) -> f64 {
        let lcd = &self.cfg.lane_change;
        // The vehicles ahead, nearest first (one bounds check for the scan).
        let ahead = &self.lane_xv[lane][..from];
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
    fn anticipated_speed(&self, me: &Me, target: usize, j: usize, v_cur: f64) -> f64 {
        let v = me.v;
        let v_des = self.v_des_in(me.s, v, target);
        if j == 0 {
            return v_des; // no target leader
        }
        let (tl_x, tl_v) = self.lane_xv[target][j - 1];
        if tl_x - v.x > self.cfg.lane_change.scan_distance_m {
            return v_des;
        }
        let bound = bounded::min(tl_v, v_des);
        if bound - v_cur < v.driver.lc.min_speed_gain_mps {
            return bound;
        }
        let avg = self.avg_speed_ahead(target, j, v.x, v_des);
        bounded::min(avg.min(tl_v), v_des)
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
        if driver::quick_return(&v.driver.lc, since, gamma, side, v.lcs.last_side) {
            return None;
        }
    }
    driver::wants_change(&v.driver.lc, gamma).then_some(Desire {
        side,
        gamma,
        mandatory,
        organize,
    })
}

#[cfg(test)]
mod tests {
    use super::settle;
    use crate::insert::place_for_test;
    use crate::vehicle::Kind;
    use crate::{Config, Simulation};
    use platoonsim_model::lanechange::Side;

    /// A driver with the mean lane-change parameters (threshold 0.25, minimum interval 5 s,
    /// return factor 3) whose last change was to `last`.
    fn driver(last: Option<Side>) -> crate::vehicle::Vehicle {
        let mut sim = Simulation::new(Config::homogeneous(0.0, 0.0, 60.0, 0.0, 1)).unwrap();
        let id = place_for_test(&mut sim, Kind::Human, 1, 1000.0, 25.0);
        let s = sim.traffic.slot_of(id).unwrap();
        let mut v = sim.traffic.vehicles[s as usize].clone();
        v.lcs.last_side = last;
        v
    }

    #[test]
    fn a_desire_leads_to_an_attempt_only_above_the_drivers_threshold() {
        let v = driver(None);
        assert_eq!(v.driver.lc.threshold, 0.25);
        assert!(settle(&v, None, Side::Left, 0.25, false, false).is_none());
        let d = settle(&v, None, Side::Left, 0.26, true, false).expect("above the threshold");
        assert_eq!(
            (d.side, d.gamma, d.mandatory, d.organize),
            (Side::Left, 0.26, true, false)
        );
    }

    #[test]
    fn a_desire_back_toward_the_lane_just_left_waits_three_minimum_intervals() {
        // Last change to the left; a desire below 1 back to the right is dropped for
        // 3 × 5 s = 15 s, a desire of 1 (mandatory in full) and one further left are not.
        let v = driver(Some(Side::Left));
        assert!(settle(&v, Some(14.9), Side::Right, 0.9, false, false).is_none());
        assert!(settle(&v, Some(15.0), Side::Right, 0.9, false, false).is_some());
        assert!(settle(&v, Some(1.0), Side::Right, 1.0, true, false).is_some());
        assert!(settle(&v, Some(1.0), Side::Left, 0.9, false, false).is_some());
    }
}
