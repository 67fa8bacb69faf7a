//! Read-only views of the state between two steps, in columns: every vehicle on the road, the
//! latest closed detector interval, where the through lanes are. For bindings that exchange
//! whole arrays per step (the Python package, docs/python.md); they never change the
//! simulation.

use crate::detector::DetectorRecord;
use crate::vehicle::{ModeLabel, NEVER};
use crate::Simulation;
use platoonsim_model::cav::CavMode;

/// Every vehicle on the road, one entry per vehicle in each column, lane by lane (0 = the
/// rightmost) and front first within a lane.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VehicleColumns {
    pub id: Vec<u64>,
    /// 0 human, 1 CAV ([`crate::Kind`] as `u8`).
    pub kind: Vec<u8>,
    /// Lateral lane index, 0 = rightmost (the engine's numbering, as in `trajectories.csv`).
    pub lane: Vec<u32>,
    /// Front position in the output coordinate (m).
    pub x_m: Vec<f64>,
    pub v_mps: Vec<f64>,
    /// Acceleration applied in the last step (m/s²).
    pub a_mps2: Vec<f64>,
    /// Index into [`MODE_LABELS`].
    pub mode: Vec<u8>,
    /// Index into [`REGIME_LABELS`], or −1 while not automated (a human driver, a CAV driven
    /// manually).
    pub regime: Vec<i8>,
    /// Position in its CACC string as in `trajectories.csv`: 1 leads it (every human driver,
    /// every CAV outside a string), k the k-th vehicle of the string.
    pub platoon_pos: Vec<u32>,
    /// Id of the vehicle at position 1 of its string (its own id when it leads).
    pub platoon_id: Vec<u64>,
    /// Id of the vehicle directly ahead in the same lane, `None` for the first of a lane.
    pub leader_id: Vec<Option<u64>>,
    /// Body length (m): the gap to the vehicle behind is `x_m − length_m − x_m(behind)`.
    pub length_m: Vec<f64>,
}

/// The driving modes of [`VehicleColumns::mode`], by index ([`ModeLabel::as_str`]).
pub const MODE_LABELS: [&str; 6] = ["cf", "cf-auto", "blc", "blc-auto", "ycf", "ycf-auto"];

/// The CAV controller regimes of [`VehicleColumns::regime`], by index ([`CavMode::as_str`]).
pub const REGIME_LABELS: [&str; 4] = ["speed", "gap", "gap-closing", "collision-avoidance"];

fn mode_index(m: ModeLabel) -> u8 {
    match m {
        ModeLabel::Cf => 0,
        ModeLabel::CfAuto => 1,
        ModeLabel::Blc => 2,
        ModeLabel::BlcAuto => 3,
        ModeLabel::Ycf => 4,
        ModeLabel::YcfAuto => 5,
    }
}

fn regime_index(r: Option<CavMode>) -> i8 {
    match r {
        None => -1,
        Some(CavMode::SpeedRegulation) => 0,
        Some(CavMode::GapRegulation) => 1,
        Some(CavMode::GapClosing) => 2,
        Some(CavMode::CollisionAvoidance) => 3,
    }
}

impl VehicleColumns {
    /// Number of vehicles.
    pub fn len(&self) -> usize {
        self.id.len()
    }

    pub fn is_empty(&self) -> bool {
        self.id.is_empty()
    }

    fn clear(&mut self) {
        self.id.clear();
        self.kind.clear();
        self.lane.clear();
        self.x_m.clear();
        self.v_mps.clear();
        self.a_mps2.clear();
        self.mode.clear();
        self.regime.clear();
        self.platoon_pos.clear();
        self.platoon_id.clear();
        self.leader_id.clear();
        self.length_m.clear();
    }
}

impl Simulation {
    /// Every vehicle on the road now, into `out` (cleared first; its buffers are reused).
    /// String positions come from the sticky memberships as in the trajectory records: a CAV
    /// is a member when the predecessor it joined is the vehicle directly ahead of it now.
    pub fn vehicle_columns(&self, out: &mut VehicleColumns) {
        out.clear();
        let origin = self.origin_m();
        for l in 0..self.traffic.lanes.len() {
            let (mut ahead, mut ahead_pos, mut head) = (NEVER, 0u32, NEVER);
            for v in self.lane_vehicles(l).map(crate::view::VehicleView::record) {
                let member = v.cacc.pred != NEVER && v.cacc.pred == ahead;
                let pos = if member { ahead_pos + 1 } else { 1 };
                if !member {
                    head = v.id;
                }
                out.id.push(v.id);
                out.kind.push(v.kind as u8);
                out.lane.push(v.lane);
                out.x_m.push(v.x + origin);
                out.v_mps.push(v.v);
                out.a_mps2.push(v.a);
                out.mode.push(mode_index(v.mode_label()));
                out.regime.push(regime_index(v.cacc.regime));
                out.platoon_pos.push(pos);
                out.platoon_id.push(head);
                out.leader_id.push((ahead != NEVER).then_some(ahead));
                out.length_m.push(v.driver.human.length_m);
                (ahead, ahead_pos) = (v.id, pos);
            }
        }
    }

    /// The latest closed aggregation interval of every detector, as the rows it has in
    /// `detectors.csv` (per lane, then "all"); empty before the first interval closes.
    pub fn latest_detector_records(&self) -> Vec<DetectorRecord> {
        let interval = self.cfg.aggregation_s;
        let mut out = Vec::new();
        let mut all = Vec::new();
        for d in &self.detectors.list {
            let Some(last) = d.intervals().checked_sub(1) else {
                continue;
            };
            all.clear();
            d.records(interval, &mut all);
            let start = last as f64 * interval;
            out.extend(all.drain(..).filter(|r| r.interval_start_s == start));
        }
        out
    }

    /// The leftmost through lane at output coordinate `x_m` (the PD lane there), if any lane
    /// is open there.
    pub fn leftmost_through_at(&self, x_m: f64) -> Option<u32> {
        self.road.geom.leftmost_through(x_m - self.origin_m())
    }

    /// The rightmost through lane at output coordinate `x_m`, if any lane is open there.
    pub fn rightmost_through_at(&self, x_m: f64) -> Option<u32> {
        self.road.geom.rightmost_through(x_m - self.origin_m())
    }

    /// The number of completed steps.
    pub fn steps_done(&self) -> u64 {
        self.clock.step
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Config;

    #[test]
    fn columns_list_every_vehicle_with_its_leader_and_string() {
        let cfg = Config::homogeneous(0.5, 2500.0, 120.0, 0.0, 7);
        let mut sim = Simulation::new(cfg).unwrap();
        for _ in 0..1200 {
            sim.step().unwrap();
        }
        let mut c = VehicleColumns::default();
        sim.vehicle_columns(&mut c);
        assert_eq!(c.len(), sim.vehicles_in_network());
        assert!(c.len() > 100, "{} vehicles after 2 min", c.len());
        let mut members = 0;
        for i in 0..c.len() {
            match c.leader_id[i] {
                // The leader is the entry before, in the same lane and further on.
                Some(l) => {
                    assert_eq!(c.id[i - 1], l);
                    assert_eq!(c.lane[i - 1], c.lane[i]);
                    assert!(c.x_m[i - 1] - c.length_m[i - 1] > c.x_m[i], "overlap");
                }
                None => assert!(i == 0 || c.lane[i - 1] != c.lane[i]),
            }
            if c.platoon_pos[i] > 1 {
                members += 1;
                assert_eq!(c.kind[i], 1, "only CAVs follow in a string");
                assert_eq!(c.platoon_pos[i], c.platoon_pos[i - 1] + 1);
                assert_eq!(c.platoon_id[i], c.platoon_id[i - 1]);
            } else {
                assert_eq!(c.platoon_id[i], c.id[i]);
            }
            assert!(c.regime[i] < REGIME_LABELS.len() as i8);
        }
        assert!(members > 10, "{members} string members at 50 % CAVs");
        // Two intervals of 300 s have not closed yet; the detectors report nothing.
        assert!(sim.latest_detector_records().is_empty());
        assert_eq!(sim.leftmost_through_at(5500.0), Some(2));
    }
}
