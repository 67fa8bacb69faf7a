//! `pd`: the pseudo-dedicated lane (spec 4.7, seed Sec. 2.2). Inside the zone and the time
//! window, a CAV outside the PD lane organizes toward it with desire 1; in it, it has no
//! discretionary desire. Human drivers may use the lane.
//!
//! | parameter (`[strategy]`) | unit | default | meaning |
//! |---|---|---|---|
//! | `zone_start_m`, `zone_end_m` | m | the control section | where the lane applies |
//! | `start_s`, `end_s` | s | the measurement window (whole run on a network) | when |
//! | `lane` | – | `"leftmost"` | `"leftmost"`, `"rightmost"` or a lane number (1 = rightmost) |

use super::{in_zone, Advice, Organizer, StrategyEntry};
use crate::config::{Config, PdConfig};
use crate::network::Geometry;
use crate::view::VehicleView;
use serde::Serialize;

pub(super) const ENTRY: StrategyEntry = StrategyEntry {
    name: "pd",
    about: "pseudo-dedicated lane: CAVs organize into one lane inside the zone",
    organizes: true,
    needs_thresholds: false,
    build,
};

fn build(cfg: &Config) -> Box<dyn Organizer> {
    Box::new(PdLane {
        pd: cfg.strategy.pd.clone().unwrap_or_default(),
    })
}

/// Which lane a strategy organizes into.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum LaneChoice {
    /// The leftmost through lane at each position (the paper's PD lane).
    #[default]
    Leftmost,
    /// The rightmost through lane at each position.
    Rightmost,
    /// This lateral lane (engine index, 0 = rightmost), held within the through lanes at each
    /// position.
    Index(u32),
}

impl LaneChoice {
    /// The default (serde's `skip_serializing_if`: configs from before the choice existed
    /// serialize as they did).
    pub fn is_leftmost(&self) -> bool {
        *self == LaneChoice::Leftmost
    }
}

/// The organized lane at `x` for a vehicle in `lane`, or `None` where no lane is open. With
/// `Leftmost`, a vehicle left of the leftmost through lane (a lane that is not a through
/// lane) is where it should be: the answer is its own lane.
#[inline]
pub fn organized_lane_at(choice: LaneChoice, road: &Geometry, x: f64, lane: u32) -> Option<u32> {
    match choice {
        LaneChoice::Leftmost => road.leftmost_through(x).map(|l| l.max(lane)),
        LaneChoice::Rightmost => road.rightmost_through(x),
        LaneChoice::Index(i) => {
            let (lo, hi) = (road.rightmost_through(x)?, road.leftmost_through(x)?);
            Some(i.clamp(lo, hi))
        }
    }
}

/// The PD lane.
#[derive(Debug)]
pub struct PdLane {
    pub pd: PdConfig,
}

impl PdLane {
    /// Join advice inside the zone and the window (also `dedicated`'s advice to CAVs).
    #[inline]
    pub(super) fn join(pd: &PdConfig, v: VehicleView<'_>, t_s: f64, road: &Geometry) -> Advice {
        if !in_zone(pd, v.x(), t_s) {
            return Advice::Free;
        }
        // Where no lane is open the vehicle stays where it is (no desire).
        let lane = organized_lane_at(pd.lane, road, v.x(), v.lane()).unwrap_or(v.lane());
        Advice::Join {
            lane,
            strength: 1.0,
        }
    }
}

impl Organizer for PdLane {
    fn name(&self) -> &str {
        ENTRY.name
    }
    fn advise(&self, v: VehicleView<'_>, t_s: f64, road: &Geometry) -> Advice {
        PdLane::join(&self.pd, v, t_s, road)
    }
}
