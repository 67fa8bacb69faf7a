//! Phase 1 (sense): neighbours, CACC links, platoon positions and platoon statistics.

use crate::sim::Simulation;
use crate::vehicle::Vehicle;

/// "No vehicle" slot marker.
pub const NONE: u32 = u32::MAX;

/// A vehicle's neighbourhood at the start of the step (slots; `NONE` if absent).
#[derive(Clone, Copy, Debug)]
pub struct Neighbours {
    /// Same-lane leader.
    pub leader: u32,
    /// Same-lane follower.
    pub follower: u32,
    /// Index of the vehicle in its lane list (front first).
    pub idx: u32,
    /// Leader and follower in the lane to the left (lane + 1) and to the right (lane − 1).
    pub left_leader: u32,
    pub left_follower: u32,
    pub right_leader: u32,
    pub right_follower: u32,
}

impl Default for Neighbours {
    fn default() -> Self {
        Neighbours {
            leader: NONE,
            follower: NONE,
            idx: 0,
            left_leader: NONE,
            left_follower: NONE,
            right_leader: NONE,
            right_follower: NONE,
        }
    }
}

/// Where a vehicle is at the start of the step, by the geometry (network.rs): looked up once
/// per step by walking each lane's segments along the sorted lane lists.
#[derive(Clone, Copy, Debug, Default)]
pub struct Here {
    /// The wall ending its lane segment, if it ends in one (`Geometry::wall_ahead`).
    pub wall: Option<f64>,
    /// It is in an acceleration segment.
    pub accel: bool,
    /// May change into the lane to the left / to the right here (`Geometry::can_enter`).
    pub enter_left: bool,
    pub enter_right: bool,
    /// On-ramps with their merge point at or before it (`Geometry::ramps_upto`).
    pub ramps_upto: u32,
}

impl Simulation {
    /// Phase 1.
    pub(crate) fn sense(&mut self) {
        let n = self.vehicles.len();
        if self.nb.len() < n {
            self.nb.resize(n, Neighbours::default());
            self.platoon_pos.resize(n, 1);
            self.linked.resize(n, false);
            self.cav_ahead.resize(n, false);
            self.sub_size.resize(n, 1);
            self.string_pred_next.resize(n, crate::vehicle::NEVER);
            self.changed_this_step.resize(n, u64::MAX);
            self.here.resize(n, Here::default());
        }
        let n_lanes = self.lanes.len();
        self.lane_xv.resize(n_lanes, Vec::new());
        for (xv, lane) in self.lane_xv.iter_mut().zip(&self.lanes) {
            xv.clear();
            xv.extend(lane.iter().map(|&s| {
                let v = &self.vehicles[s as usize];
                (v.x, v.v)
            }));
        }
        let range = self.cfg.cav.sensor_range_m;
        for l in 0..n_lanes {
            let lane = &self.lanes[l];
            for (k, &s) in lane.iter().enumerate() {
                let nb = &mut self.nb[s as usize];
                nb.idx = k as u32;
                nb.leader = if k > 0 { lane[k - 1] } else { NONE };
                nb.follower = lane.get(k + 1).copied().unwrap_or(NONE);
                self.cav_ahead[s as usize] = k > 0 && {
                    let lv = &self.vehicles[lane[k - 1] as usize];
                    lv.is_cav() && lv.rear() - self.vehicles[s as usize].x <= range
                };
            }
            // Adjacent lanes by a merge sweep: the cursor j points at the first vehicle of the
            // other lane that is not strictly ahead.
            for (other, is_left) in [(l + 1, true), (l.wrapping_sub(1), false)] {
                if other >= n_lanes {
                    for &s in lane {
                        let nb = &mut self.nb[s as usize];
                        if is_left {
                            nb.left_leader = NONE;
                            nb.left_follower = NONE;
                        } else {
                            nb.right_leader = NONE;
                            nb.right_follower = NONE;
                        }
                    }
                    continue;
                }
                let olane = &self.lanes[other];
                let ox = &self.lane_xv[other];
                let mut j = 0usize;
                for (&s, &(x, _)) in lane.iter().zip(&self.lane_xv[l]) {
                    while j < olane.len() && ox[j].0 > x {
                        j += 1;
                    }
                    let ld = if j > 0 { olane[j - 1] } else { NONE };
                    let fo = olane.get(j).copied().unwrap_or(NONE);
                    let nb = &mut self.nb[s as usize];
                    if is_left {
                        nb.left_leader = ld;
                        nb.left_follower = fo;
                    } else {
                        nb.right_leader = ld;
                        nb.right_follower = fo;
                    }
                }
            }
        }
        self.locate();
        self.platoons();
    }

    /// Fill `here` for every vehicle on the road.
    fn locate(&mut self) {
        let n_lanes = self.lanes.len();
        for (l, lane) in self.lanes.iter().enumerate() {
            if self.geom.plain {
                for &s in lane {
                    self.here[s as usize] = Here {
                        wall: None,
                        accel: false,
                        enter_left: l + 1 < n_lanes,
                        enter_right: l > 0,
                        ramps_upto: 0,
                    };
                }
                continue;
            }
            let mut own = self.geom.walk(l);
            let mut left = self.geom.walk(l + 1);
            let mut right = self.geom.walk(l.wrapping_sub(1));
            let mut ramps = self.geom.ramps_by_x.len();
            for (&s, &(x, _)) in lane.iter().zip(&self.lane_xv[l]) {
                let seg = own.at(x);
                ramps = self.geom.ramps_upto_from(ramps, x);
                self.here[s as usize] = Here {
                    wall: seg.filter(|g| g.wall).map(|g| g.to),
                    accel: seg.is_some_and(|g| g.accel),
                    enter_left: left.at(x).is_some_and(|g| !g.accel),
                    enter_right: l > 0 && right.at(x).is_some_and(|g| !g.accel),
                    ramps_upto: ramps as u32,
                };
            }
        }
    }

    /// CACC strings (spec 3.6) and platoon statistics (spec 5.1.6, 6.15).
    ///
    /// A *candidate link* exists when an automated CAV follows a CAV within sensor range and is
    /// not in speed regulation (time gap ≤ 2 s, spec 6.15). Membership is sticky [D]: a CAV
    /// stays in the string of the predecessor it joined while the candidate link to that same
    /// vehicle lasts; a new link is a *join*, allowed only if the predecessor's position plus
    /// the size of the joining sub-string is at most `max_platoon`. Otherwise the CAV leads its
    /// own string and keeps the inter-platoon gap. (Re-splitting merged strings at 10 by
    /// recounting positions every step, spec 3.6.6, moved every follower behind a merge or a
    /// broken link to a new gap at once; the resulting braking waves halved 100 % CAV
    /// capacity.) A member's position is its predecessor's + 1; a string is a platoon.
    fn platoons(&mut self) {
        let p = &self.cfg.cav;
        let max = p.max_platoon.max(1);
        let t_far = p.cacc_tg_band_s[1];
        let slack = p.standstill_gap_m + p.speed_control_min_gap_m;
        let vehicles = &self.vehicles;
        let cav_ahead = &self.cav_ahead;
        // `ld` is always `f`'s same-lane leader.
        let candidate = |f: u32, ld: u32| -> bool {
            let fv = &vehicles[f as usize];
            cav_ahead[f as usize]
                && fv.automated()
                && vehicles[ld as usize].rear() - fv.x <= t_far * fv.v + slack
        };
        for l in 0..self.lanes.len() {
            let lane = &self.lanes[l];
            let n = lane.len();
            // Back to front: size of the sub-string each vehicle leads (previous memberships).
            for k in (0..n).rev() {
                let s = lane[k] as usize;
                let mut size = 1;
                if k + 1 < n {
                    let f = lane[k + 1];
                    if vehicles[f as usize].string_pred == vehicles[s].id && candidate(f, lane[k]) {
                        size += self.sub_size[f as usize];
                    }
                }
                self.sub_size[s] = size;
            }
            // Front to back: memberships and positions.
            for k in 0..n {
                let s = lane[k];
                let ld = if k > 0 { lane[k - 1] } else { NONE };
                let mut pred_id = crate::vehicle::NEVER;
                let mut pos = 1;
                if candidate(s, ld) {
                    let lpos = self.platoon_pos[ld as usize];
                    let lid = vehicles[ld as usize].id;
                    let member = vehicles[s as usize].string_pred == lid;
                    if (member && lpos < max)
                        || (!member && lpos + self.sub_size[s as usize] <= max)
                    {
                        pred_id = lid;
                        pos = lpos + 1;
                    }
                }
                self.string_pred_next[s as usize] = pred_id;
                self.platoon_pos[s as usize] = pos;
                self.linked[s as usize] = pred_id != crate::vehicle::NEVER;
            }
        }
        // Statistics (spec 5.1.6). Paper definition [S]: "when a CAV immediately follows
        // another CAV, it automatically starts to form a platoon", and P_P ≈ 1 − (1 − p)² "given
        // the subject vehicle is a CAV, its leader and/or follower is a CAV": a link is an
        // automated CAV directly behind a CAV within sensor range. Strict variant (spec 6.15):
        // only string members (not in speed regulation). Runs longer than `max` count as
        // platoons of at most `max`.
        for l in 0..self.lanes.len() {
            let lane = &self.lanes[l];
            let (mut adj_start, mut tg2_start) = (0usize, 0usize);
            for (k, &s) in lane.iter().enumerate() {
                self.vehicles[s as usize].string_pred = self.string_pred_next[s as usize];
                let adjacent = self.cav_ahead[s as usize] && self.vehicles[s as usize].automated();
                if !adjacent || k - adj_start >= max as usize {
                    close_run(&mut self.vehicles, &lane[adj_start..k], false);
                    adj_start = k;
                }
                if !self.linked[s as usize] {
                    close_run(&mut self.vehicles, &lane[tg2_start..k], true);
                    tg2_start = k;
                }
            }
            close_run(&mut self.vehicles, &lane[adj_start..], false);
            close_run(&mut self.vehicles, &lane[tg2_start..], true);
        }
    }
}

/// A statistical platoon ends: every CAV in it records its size.
fn close_run(vehicles: &mut [Vehicle], run: &[u32], strict: bool) {
    let size = run.len() as u32;
    if size < 2 {
        return;
    }
    for &s in run {
        let v = &mut vehicles[s as usize];
        let m = if strict {
            &mut v.max_platoon_tg2
        } else {
            &mut v.max_platoon
        };
        if *m < size {
            *m = size;
        }
    }
}
