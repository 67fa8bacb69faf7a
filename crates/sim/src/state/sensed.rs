//! What the sense phase finds for each vehicle (phase 1), read by the later phases: step
//! state, so it lives with the state and the phases depend on it, not on each other.

use crate::here::Here;

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
    /// Leader in the lane to the left (lane + 1) and to the right (lane − 1).
    pub left_leader: u32,
    pub right_leader: u32,
    /// Merge-sweep cursors: the index, in the list of the lane to the left / right, of the
    /// first vehicle that is not strictly ahead (the follower there, if any; the leader there is
    /// at the index before). With `Simulation::lane_xv` they give the leader's (x, v) and the
    /// start of its lane-speed scan without reading its records.
    pub left_j: u32,
    pub right_j: u32,
}

impl Default for Neighbours {
    fn default() -> Self {
        Neighbours {
            leader: NONE,
            follower: NONE,
            idx: 0,
            left_leader: NONE,
            right_leader: NONE,
            left_j: 0,
            right_j: 0,
        }
    }
}

/// What the sense phase finds for one vehicle (indexed by slot; 64 bytes, one cache line).
#[derive(Clone, Copy, Debug)]
#[repr(align(64))]
pub struct Sensed {
    pub nb: Neighbours,
    pub here: Here,
    /// Position in its CACC string (1: leads it).
    pub platoon_pos: u32,
    /// Size of the sub-string it leads under the previous memberships (pass A).
    pub sub_size: u32,
    /// Member of its predecessor's CACC string (spec 3.6); the candidate link between the
    /// two passes.
    pub linked: bool,
    /// The same-lane leader is a CAV within sensor range.
    pub cav_ahead: bool,
}

impl Default for Sensed {
    fn default() -> Self {
        Sensed {
            nb: Neighbours::default(),
            here: Here::default(),
            platoon_pos: 1,
            sub_size: 1,
            linked: false,
            cav_ahead: false,
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn sensed_fills_one_cache_line() {
        assert_eq!(std::mem::size_of::<super::Sensed>(), 64);
    }
}
