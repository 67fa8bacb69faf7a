//! Platoon organization (spec 4.7, seed Sec. 2.2 and 4.2): where and when a CAV organizes.
//!
//! * PD lane: inside the zone and the time window, a CAV outside the PD lane (the leftmost
//!   lane) has γ_PO = 1 toward it; in the PD lane it has no discretionary desire. The gap rules
//!   are the discretionary ones (decide.rs).
//! * Flow-Aware: the same, only while the detectors within `radius_m` of the CAV broadcast (for
//!   their latest completed interval) a mean flow below ρ_q and a mean speed above ρ_v. The
//!   condition is evaluated once per interval for road cells of `FA_CELL_M` metres.

use crate::config::{PdConfig, Strategy};
use crate::sim::Simulation;
use crate::vehicle::Vehicle;

/// Cell length for the Flow-Aware condition cache (m).
pub const FA_CELL_M: f64 = 50.0;

impl Simulation {
    /// Does platoon organization apply to this CAV now?
    pub(crate) fn organization_active(&self, v: &Vehicle) -> bool {
        let t = self.step as f64 * self.dt;
        match &self.cfg.strategy {
            Strategy::None => false,
            Strategy::Pd { pd } => in_zone(pd, v.x, t),
            Strategy::FlowAware { pd, .. } => {
                in_zone(pd, v.x, t) && {
                    let c = (v.x / FA_CELL_M) as usize;
                    self.fa_cells.get(c).copied().unwrap_or(false)
                }
            }
        }
    }

    /// Recompute the Flow-Aware cells from the detectors' latest broadcasts.
    pub(crate) fn update_flow_aware(&mut self) {
        let Strategy::FlowAware { thresholds, .. } = &self.cfg.strategy else {
            return;
        };
        let n = (self.cfg.road.length_m / FA_CELL_M).ceil() as usize + 1;
        self.fa_cells.clear();
        let interval = self.cfg.aggregation_s;
        let casts: Vec<_> = self
            .detectors
            .iter()
            .filter_map(|d| d.broadcast(interval).map(|b| (d.position_m, b)))
            .collect();
        for c in 0..n {
            let x = (c as f64 + 0.5) * FA_CELL_M;
            let (mut q, mut nq, mut v, mut nv) = (0.0, 0usize, 0.0, 0usize);
            for (pos, b) in &casts {
                if (pos - x).abs() <= thresholds.radius_m {
                    q += b.flow_vphpl;
                    nq += 1;
                    if let Some(s) = b.speed_kmh {
                        v += s;
                        nv += 1;
                    }
                }
            }
            // No detector in range: no information, no organization. No vehicle seen: free road.
            let ok = nq > 0
                && q / (nq as f64) < thresholds.flow_threshold_vphpl
                && (nv == 0 || v / (nv as f64) > thresholds.speed_threshold_kmh);
            self.fa_cells.push(ok);
        }
    }
}

fn in_zone(pd: &PdConfig, x: f64, t: f64) -> bool {
    x >= pd.zone_start_m && x < pd.zone_end_m && t >= pd.start_s && t < pd.end_s
}
