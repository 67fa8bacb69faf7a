//! The paper's statistics (seed Sec. 4.1, spec 5.1.6), accumulated as vehicles leave (or at the
//! end for those still on the road). Only vehicles that entered in the measurement window count.

use crate::events::{Departure, Observer};
use crate::vehicle::Vehicle;
use crate::view::VehicleView;

#[derive(Clone, Debug, Default)]
pub struct Metrics {
    pub entered: u64,
    pub exited: u64,
    /// Vehicles counted (entered in the window).
    pub vehicles_counted: u64,
    pub lane_changes: u64,
    pub lane_changes_cav: u64,
    /// Cooperative lane changes (spec 9.2) of the vehicles counted.
    pub cooperative_lane_changes: u64,
    pub cavs_counted: u64,
    pub platoon_length_sum: u64,
    pub cavs_platooned: u64,
    pub platoon_length_sum_tg2: u64,
    pub cavs_platooned_tg2: u64,
}

impl Metrics {
    fn count(&mut self, v: &Vehicle) {
        if !v.stats.measured {
            return;
        }
        self.vehicles_counted += 1;
        self.lane_changes += v.lcs.count as u64;
        if v.is_cav() {
            self.lane_changes_cav += v.lcs.count as u64;
            self.cooperative_lane_changes += v.lcs.coop_count as u64;
            self.cavs_counted += 1;
            self.platoon_length_sum += v.cacc.max_platoon as u64;
            if v.cacc.max_platoon > 1 {
                self.cavs_platooned += 1;
            }
            self.platoon_length_sum_tg2 += v.cacc.max_platoon_tg2 as u64;
            if v.cacc.max_platoon_tg2 > 1 {
                self.cavs_platooned_tg2 += 1;
            }
        }
    }

    /// A vehicle that left the road.
    pub(crate) fn exited(&mut self, v: &Vehicle) {
        self.exited += 1;
        self.count(v);
    }

    /// A vehicle that did not leave by an exit (collided, or on the road at the end).
    pub(crate) fn stayed(&mut self, v: &Vehicle) {
        self.count(v);
    }

    /// All lane changes / all vehicles (seed Sec. 4.1).
    pub fn lane_changes_per_vehicle(&self) -> Option<f64> {
        ratio(self.lane_changes as f64, self.vehicles_counted)
    }

    /// Lane changes per CAV and per human-driven vehicle (the paper's Table 3 note: both rise).
    pub fn lane_changes_by_type(&self) -> (Option<f64>, Option<f64>) {
        let humans = self.vehicles_counted - self.cavs_counted;
        (
            ratio(self.lane_changes_cav as f64, self.cavs_counted),
            ratio((self.lane_changes - self.lane_changes_cav) as f64, humans),
        )
    }

    /// L̄ (seed eq. 1); `None` if no CAV was counted.
    pub fn avg_platoon_length(&self) -> Option<f64> {
        ratio(self.platoon_length_sum as f64, self.cavs_counted)
    }

    /// L̄ and P_P with the strict link criterion of spec 6.15 (tg ≤ 2 s).
    pub fn platoon_stats_tg2(&self) -> (Option<f64>, Option<f64>) {
        (
            ratio(self.platoon_length_sum_tg2 as f64, self.cavs_counted),
            ratio(self.cavs_platooned_tg2 as f64, self.cavs_counted),
        )
    }

    /// P_P (seed eq. 2); `None` if no CAV was counted.
    pub fn platooning_probability(&self) -> Option<f64> {
        ratio(self.cavs_platooned as f64, self.cavs_counted)
    }
}

/// The statistics observe the vehicles as they leave: those that left the road count as
/// exited; a lane-end collision and the vehicles still on the road at the end count in the
/// statistics only.
impl Observer for Metrics {
    fn on_exit(&mut self, v: VehicleView<'_>, how: Departure, _t_s: f64) {
        let v = v.record();
        match how {
            Departure::OffRamp(_) | Departure::RoadEnd => self.exited(v),
            Departure::Collided | Departure::OnRoad => self.stayed(v),
        }
    }
}

/// a / n; `None` when nothing was counted (the statistic does not apply).
fn ratio(a: f64, n: u64) -> Option<f64> {
    (n > 0).then(|| a / n as f64)
}
