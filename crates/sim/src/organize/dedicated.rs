//! `dedicated`: a dedicated lane (CAVs only) inside the zone, the alternative to the PD lane
//! that the seed paper's Fig. 2 sets beside it. CAVs organize into the lane as under `pd`;
//! human drivers keep out of it: one in it has a mandatory desire to leave, as for a lane that
//! ends at the zone start (it rises as the driver approaches the zone and is 1 inside it), and
//! none changes into it while that desire would be positive. Outside the zone and the time
//! window the lane is open to all. The zone, window and lane are those of `pd`.
//!
//! Not modelled: a human driver whose only way on is through the lane (a left-hand on-ramp
//! or exit) still takes it.

use super::pd::PdLane;
use super::{organized_lane_at, Advice, Organizer, StrategyEntry};
use crate::config::{Config, PdConfig};
use crate::network::Geometry;
use crate::vehicle::Kind;
use crate::view::VehicleView;

pub(super) const ENTRY: StrategyEntry = StrategyEntry {
    name: "dedicated",
    about: "dedicated lane: CAVs organize into one lane inside the zone, humans keep out of it",
    organizes: true,
    needs_thresholds: false,
    build,
};

fn build(cfg: &Config) -> Box<dyn Organizer> {
    Box::new(DedicatedLane {
        pd: cfg.strategy.pd.clone().unwrap_or_default(),
    })
}

/// The dedicated lane.
#[derive(Debug)]
pub struct DedicatedLane {
    pub pd: PdConfig,
}

impl Organizer for DedicatedLane {
    fn name(&self) -> &str {
        ENTRY.name
    }

    fn advises_humans(&self) -> bool {
        true
    }

    fn advise(&self, v: VehicleView<'_>, t_s: f64, road: &Geometry) -> Advice {
        if v.kind() == Kind::Cav {
            return PdLane::join(&self.pd, v, t_s, road);
        }
        let pd = &self.pd;
        if v.x() >= pd.zone_end_m || t_s < pd.start_s || t_s >= pd.end_s {
            return Advice::Free;
        }
        // The lane as it will be at the zone start (a driver upstream keeps out of the lane
        // that the zone reserves), or here inside the zone.
        let at = v.x().max(pd.zone_start_m);
        match organized_lane_at(pd.lane, road, at, 0) {
            Some(lane) => Advice::Avoid {
                lane,
                from_m: pd.zone_start_m,
            },
            None => Advice::Free,
        }
    }
}
