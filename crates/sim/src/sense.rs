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

impl Simulation {
    /// Phase 1.
    pub(crate) fn sense(&mut self) {
        let n = self.vehicles.len();
        if self.nb.len() < n {
            self.nb.resize(n, Neighbours::default());
            self.platoon_pos.resize(n, 1);
            self.linked.resize(n, false);
            self.changed_this_step.resize(n, u64::MAX);
        }
        let n_lanes = self.lanes.len();
        for l in 0..n_lanes {
            let lane = &self.lanes[l];
            for (k, &s) in lane.iter().enumerate() {
                let nb = &mut self.nb[s as usize];
                nb.idx = k as u32;
                nb.leader = if k > 0 { lane[k - 1] } else { NONE };
                nb.follower = lane.get(k + 1).copied().unwrap_or(NONE);
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
                let mut j = 0usize;
                for &s in lane {
                    let x = self.vehicles[s as usize].x;
                    while j < olane.len() && self.vehicles[olane[j] as usize].x > x {
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
        self.platoons();
    }

    /// CACC links and platoon positions (spec 3.6), front to back in every lane, and the
    /// platoon statistics: each CAV's largest platoon (spec 5.1.6; a link counts only while the
    /// follower is not in speed regulation, spec 6.15).
    fn platoons(&mut self) {
        let max = self.cfg.cav.max_platoon.max(1);
        let range = self.cfg.cav.sensor_range_m;
        for l in 0..self.lanes.len() {
            let lane = &self.lanes[l];
            // Statistics run: members [run_start, k) of the current statistical platoon.
            let mut run_start = 0usize;
            for (k, &s) in lane.iter().enumerate() {
                let v = &self.vehicles[s as usize];
                let ld = if k > 0 { lane[k - 1] } else { NONE };
                let linked = v.automated()
                    && ld != NONE
                    && self.vehicles[ld as usize].is_cav()
                    && self.vehicles[ld as usize].rear() - v.x <= range;
                let pos = if linked {
                    let p = self.platoon_pos[ld as usize] + 1;
                    if p > max {
                        1
                    } else {
                        p
                    }
                } else {
                    1
                };
                self.linked[s as usize] = linked;
                self.platoon_pos[s as usize] = pos;
                let stat_link = linked && pos > 1 && v.family == platoonsim_model::cav::Family::Gap;
                if !stat_link {
                    close_run(&mut self.vehicles, &lane[run_start..k]);
                    run_start = k;
                }
            }
            close_run(&mut self.vehicles, &lane[run_start..]);
        }
    }
}

/// A statistical platoon ends: every CAV in it records its size.
fn close_run(vehicles: &mut [Vehicle], run: &[u32]) {
    let size = run.len() as u32;
    if size < 2 {
        return;
    }
    for &s in run {
        let v = &mut vehicles[s as usize];
        if v.max_platoon < size {
            v.max_platoon = size;
        }
    }
}
