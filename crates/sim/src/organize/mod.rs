//! Platoon organization as a seam: an [`Organizer`] advises vehicles which lane to be in, and
//! the driver model (decide.rs) turns the advice into lane-change desires (spec 4.7).
//!
//! A strategy is one file that implements [`Organizer`] and two lines here: its `mod`
//! declaration and its entry in [`STRATEGIES`], the name table that the scenario files, the
//! command line and the experiments share. A library user can also hand an organizer of their
//! own to [`crate::Simulation::set_organizer`] (docs/organizers.md has a worked example).
//!
//! | strategy | advice |
//! |---|---|
//! | `none` | none (the baseline) |
//! | `pd` | CAVs: join the PD lane inside the zone and the time window |
//! | `flow-aware` | as `pd`, only where nearby detectors broadcast light, fast traffic |
//! | `dedicated` | as `pd` for CAVs; human drivers keep out of the lane inside the zone |

mod dedicated;
mod flow_aware;
mod none;
mod pd;

use crate::config::{Config, PdConfig};
use crate::detector::Broadcast;
use crate::network::Geometry;
use crate::view::VehicleView;
use std::fmt;
use std::str::FromStr;

pub use dedicated::DedicatedLane;
pub use flow_aware::{FlowAware, FA_CELL_M};
pub use none::NoOrganizer;
pub use pd::{organized_lane_at, LaneChoice, PdLane};

/// What a strategy asks of one vehicle now.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Advice {
    /// Nothing: the driver's own lane-change model decides.
    Free,
    /// Organize toward `lane` (engine index, 0 = rightmost): without a mandatory need, a
    /// desire of `strength` toward it replaces the discretionary desire, and none once in it
    /// (spec 4.7; the PD lane has strength 1). The driver does not organize within the
    /// anticipation range of its own exit.
    Join { lane: u32, strength: f64 },
    /// Keep out of `lane` from `from_m` (engine coordinate) on: in it, a mandatory desire to
    /// leave as for a lane that ends at `from_m`; elsewhere, no discretionary change into it
    /// while that desire would be positive (the rule of a lane drop).
    Avoid { lane: u32, from_m: f64 },
}

/// A platoon-organization strategy: lane advice per vehicle, from what the vehicle may know
/// (its own state, the road's geometry, the detectors' broadcasts).
///
/// The engine asks once per vehicle and step, in the decide phase, from the step-start state;
/// advice must be a pure function of its arguments and of the broadcasts received so far, so
/// that runs stay deterministic.
pub trait Organizer: Send + fmt::Debug {
    /// The name in the summary (`strategy`).
    fn name(&self) -> &str;
    /// Does this strategy advise CAVs? When false, CAVs are never asked (no cost per CAV).
    fn advises_cavs(&self) -> bool {
        true
    }
    /// Does this strategy advise human drivers? When false (the default), humans are never
    /// asked.
    fn advises_humans(&self) -> bool {
        false
    }
    /// At the end of each aggregation interval: every detector's position (engine
    /// coordinate, m) and broadcast of the interval that just ended, in the order of the
    /// scenario's detectors.
    fn on_broadcasts(&mut self, _road: &Geometry, _broadcasts: &[(f64, Broadcast)]) {}
    /// The advice for vehicle `v` at simulated time `t_s` (the step start).
    fn advise(&self, v: VehicleView<'_>, t_s: f64, road: &Geometry) -> Advice;
}

/// One registered strategy.
pub struct StrategyEntry {
    /// The name in scenario files (`strategy.kind`), on the command line and in summaries.
    pub name: &'static str,
    /// One line for `--help` and the docs.
    pub about: &'static str,
    /// Uses the zone, the time window and the lane of `[strategy]`.
    pub organizes: bool,
    /// Needs the Flow-Aware thresholds (`strategy.flow_threshold_vphpl`, ...).
    pub needs_thresholds: bool,
    /// The organizer of a validated config.
    pub build: fn(&Config) -> Box<dyn Organizer>,
}

/// The strategies, by name. A new strategy is one file and one line here.
pub static STRATEGIES: &[StrategyEntry] =
    &[none::ENTRY, pd::ENTRY, flow_aware::ENTRY, dedicated::ENTRY];

/// A registered strategy, by its name in [`STRATEGIES`].
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct StrategyKind(&'static str);

impl StrategyKind {
    /// No organization (the baseline).
    pub const NONE: StrategyKind = StrategyKind(none::ENTRY.name);
    /// Pseudo-dedicated lane.
    pub const PD: StrategyKind = StrategyKind(pd::ENTRY.name);
    /// Flow-Aware pseudo-dedicated lane.
    pub const FLOW_AWARE: StrategyKind = StrategyKind(flow_aware::ENTRY.name);
    /// Dedicated lane (CAVs only inside the zone).
    pub const DEDICATED: StrategyKind = StrategyKind(dedicated::ENTRY.name);

    /// Every registered strategy, in table order.
    pub fn all() -> impl Iterator<Item = StrategyKind> {
        STRATEGIES.iter().map(|e| StrategyKind(e.name))
    }

    /// The name used in files, on the command line and in summaries.
    pub fn as_str(self) -> &'static str {
        self.0
    }

    /// Its entry in [`STRATEGIES`].
    pub fn entry(self) -> &'static StrategyEntry {
        STRATEGIES
            .iter()
            .find(|e| e.name == self.0)
            .expect("a StrategyKind is made only from a registered name")
    }

    /// The names, quoted and comma-separated, for error messages.
    pub fn names() -> String {
        STRATEGIES
            .iter()
            .map(|e| format!("\"{}\"", e.name))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

impl fmt::Display for StrategyKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.0)
    }
}

impl fmt::Debug for StrategyKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "StrategyKind({})", self.0)
    }
}

/// A name that no registered strategy has.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("must be one of {names} (found \"{0}\")", names = StrategyKind::names())]
pub struct UnknownStrategy(pub String);

impl FromStr for StrategyKind {
    type Err = UnknownStrategy;
    fn from_str(s: &str) -> Result<Self, UnknownStrategy> {
        STRATEGIES
            .iter()
            .find(|e| e.name == s)
            .map(|e| StrategyKind(e.name))
            .ok_or_else(|| UnknownStrategy(s.to_string()))
    }
}

impl serde::Serialize for StrategyKind {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.0)
    }
}

/// Is (x, t) inside the zone and the time window of `pd`?
#[inline]
pub fn in_zone(pd: &PdConfig, x: f64, t: f64) -> bool {
    x >= pd.zone_start_m && x < pd.zone_end_m && t >= pd.start_s && t < pd.end_s
}

/// The organizer of a validated config (its `strategy.kind`).
pub fn build(cfg: &Config) -> Box<dyn Organizer> {
    (cfg.strategy.kind.entry().build)(cfg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_through_the_table() {
        for k in StrategyKind::all() {
            assert_eq!(k.as_str().parse::<StrategyKind>(), Ok(k));
            assert_eq!(k.entry().name, k.as_str());
        }
        let names: Vec<_> = StrategyKind::all().map(StrategyKind::as_str).collect();
        assert_eq!(names, ["none", "pd", "flow-aware", "dedicated"]);
        let err = "platoon".parse::<StrategyKind>().unwrap_err().to_string();
        assert_eq!(
            err,
            "must be one of \"none\", \"pd\", \"flow-aware\", \"dedicated\" (found \"platoon\")"
        );
    }

    #[test]
    fn the_zone_is_half_open_in_space_and_time() {
        let pd = PdConfig {
            zone_start_m: 100.0,
            zone_end_m: 200.0,
            start_s: 10.0,
            end_s: 20.0,
            lane: LaneChoice::Leftmost,
        };
        assert!(in_zone(&pd, 100.0, 10.0));
        assert!(!in_zone(&pd, 200.0, 10.0));
        assert!(!in_zone(&pd, 150.0, 20.0));
        assert!(!in_zone(&pd, 99.9, 15.0));
    }
}
