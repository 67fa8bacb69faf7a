//! `flow-aware`: the Flow-Aware PD lane (seed Sec. 4.2). As `pd`, only while the detectors
//! within `radius_m` of the CAV broadcast, for their latest completed interval, a mean flow
//! below ρ_q and a mean speed above ρ_v. The condition is evaluated once per interval for road
//! cells of [`FA_CELL_M`] metres.
//!
//! | parameter (`[strategy]`) | unit | default | meaning |
//! |---|---|---|---|
//! | `flow_threshold_vphpl` | veh/h/lane | the scenario's (required) | ρ_q |
//! | `speed_threshold_kmh` | km/h | the scenario's (required) | ρ_v |
//! | `radius_m` | m | 1500 | detectors averaged around the CAV |
//! | zone, window, lane | | as `pd` | |

use super::pd::PdLane;
use super::{Advice, Organizer, StrategyEntry};
use crate::config::{Config, FlowAwareConfig, PdConfig};
use crate::detector::Broadcast;
use crate::network::Geometry;
use crate::view::VehicleView;

/// Cell length for the Flow-Aware condition cache (m).
pub const FA_CELL_M: f64 = 50.0;

pub(super) const ENTRY: StrategyEntry = StrategyEntry {
    name: "flow-aware",
    about: "PD lane only where nearby detectors report flow below ρ_q and speed above ρ_v",
    organizes: true,
    needs_thresholds: true,
    build,
};

fn build(cfg: &Config) -> Box<dyn Organizer> {
    Box::new(FlowAware {
        pd: cfg.strategy.pd.clone().unwrap_or_default(),
        thresholds: cfg
            .strategy
            .thresholds
            .clone()
            .expect("validated: flow-aware has thresholds"),
        road_length_m: cfg.road.length_m,
        cells: Vec::new(),
    })
}

/// The Flow-Aware PD lane and its condition per road cell.
#[derive(Debug)]
pub struct FlowAware {
    pd: PdConfig,
    thresholds: FlowAwareConfig,
    road_length_m: f64,
    /// Condition per cell of `FA_CELL_M` (from the latest broadcasts; empty before the first).
    cells: Vec<bool>,
}

impl Organizer for FlowAware {
    fn name(&self) -> &str {
        ENTRY.name
    }

    fn on_broadcasts(&mut self, _road: &Geometry, casts: &[(f64, Broadcast)]) {
        self.cells = cells(&self.thresholds, self.road_length_m, casts);
    }

    fn advise(&self, v: VehicleView<'_>, t_s: f64, road: &Geometry) -> Advice {
        let c = (v.x() / FA_CELL_M) as usize;
        if !self.cells.get(c).copied().unwrap_or(false) {
            return Advice::Free;
        }
        PdLane::join(&self.pd, v, t_s, road)
    }
}

/// The condition per cell: the mean flow of the detectors within the radius of the cell's
/// centre below ρ_q and their mean speed above ρ_v. No detector in range: no information, no
/// organization; no vehicle seen: a free road.
pub fn cells(t: &FlowAwareConfig, road_length_m: f64, casts: &[(f64, Broadcast)]) -> Vec<bool> {
    let n = (road_length_m / FA_CELL_M).ceil() as usize + 1;
    (0..n)
        .map(|c| {
            let x = (c as f64 + 0.5) * FA_CELL_M;
            let (mut q, mut nq, mut v, mut nv) = (0.0, 0usize, 0.0, 0usize);
            for (pos, b) in casts {
                if (pos - x).abs() <= t.radius_m {
                    q += b.flow_vphpl;
                    nq += 1;
                    if let Some(s) = b.speed_kmh {
                        v += s;
                        nv += 1;
                    }
                }
            }
            nq > 0
                && q / (nq as f64) < t.flow_threshold_vphpl
                && (nv == 0 || v / (nv as f64) > t.speed_threshold_kmh)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cast(flow: f64, speed: Option<f64>) -> Broadcast {
        Broadcast {
            flow_vphpl: flow,
            speed_kmh: speed,
        }
    }

    const T: FlowAwareConfig = FlowAwareConfig {
        flow_threshold_vphpl: 1000.0,
        speed_threshold_kmh: 80.0,
        radius_m: 100.0,
    };

    #[test]
    fn organizes_only_near_light_fast_detectors() {
        let c = cells(&T, 500.0, &[(125.0, cast(900.0, Some(90.0)))]);
        // Cells centred at 25, 75, ..., 525 m: those within 100 m of 125 m are 25..225.
        assert_eq!(
            c,
            [true, true, true, true, true, false, false, false, false, false, false]
        );
        assert!(
            !cells(&T, 100.0, &[(25.0, cast(1100.0, Some(90.0)))])[0],
            "too much flow"
        );
        assert!(
            !cells(&T, 100.0, &[(25.0, cast(900.0, Some(70.0)))])[0],
            "too slow"
        );
        assert!(
            cells(&T, 100.0, &[(25.0, cast(0.0, None))])[0],
            "an empty road is free"
        );
        assert!(!cells(&T, 100.0, &[])[0], "no detector, no information");
    }

    #[test]
    fn averages_the_detectors_in_range() {
        let casts = [
            (0.0, cast(1500.0, Some(90.0))),
            (50.0, cast(400.0, Some(90.0))),
        ];
        assert!(cells(&T, 50.0, &casts)[0], "mean 950 < 1000");
    }
}
