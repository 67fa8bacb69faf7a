//! `road.json`: a sketch of the road as the engine built it (open lane stretches, acceleration
//! lanes, ramps, detectors, the control section and the organized lane in its zone), so that a
//! reader draws the road without re-deriving the engine's geometry from `scenario.json`.
//!
//! Written for every run by the one writer (`platoonsim_runs::run_dir`, from the engine's
//! `network::Geometry` and `organize::organized_lane_at`); read by the viewer
//! (`platoonsim view`). docs/outputs.md describes the fields.
//!
//! Conventions, as in `trajectories.csv` and `detectors.csv`: positions are output coordinates
//! (engine x plus the network's `origin_m`; on the homogeneous road the two agree) in m; lanes
//! are numbered from 1 = the rightmost lateral position (one more than the engine's index; on
//! a network position 1 is that of the acceleration lanes).

use crate::DetectorKind;
use serde::{Deserialize, Serialize};

/// The road of one run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RoadSketch {
    /// The scenario's name (`summary.json`'s `scenario`).
    pub name: String,
    /// The run's seed.
    pub seed: u64,
    /// The share of CAVs among arrivals, 0 to 1.
    pub penetration: f64,
    /// Output coordinate of engine x = 0 (m): the network's `origin_m`, 0 on the homogeneous
    /// road.
    pub origin_m: f64,
    /// Where the road starts (m): the mainline entrance, equal to `origin_m`.
    pub start_m: f64,
    /// Where the road ends (m): `origin_m` plus the road length.
    pub end_m: f64,
    /// Lateral positions: the highest lane number with an open stretch.
    pub lanes: u32,
    /// Every open stretch of every lane, by lane and then position.
    pub segments: Vec<Segment>,
    /// The on-ramps, in the scenario's order.
    pub on_ramps: Vec<Ramp>,
    /// The off-ramps, in the scenario's order (`end_m` = `x_m`, `adds_lane` false).
    pub off_ramps: Vec<Ramp>,
    /// The detectors, in the scenario's order (the names of `detectors.csv`).
    pub detectors: Vec<Detector>,
    /// The control section, [start, end] (m).
    pub control_m: [f64; 2],
    /// The strategy's name: `none`, `pd`, `flow-aware`, `dedicated`, ...
    pub strategy: String,
    /// The organizing strategy's zone, [start, end] (m), as the scenario gives it; `None` for
    /// a strategy that does not organize.
    pub pd_zone_m: Option<[f64; 2]>,
    /// The organizing strategy's time window, [start, end] (s); `None` as `pd_zone_m`.
    pub pd_window_s: Option<[f64; 2]>,
    /// The organized lane (PD or dedicated) inside the zone, cut to the road: one piece per
    /// stretch where it is the same lane (`strategy.pd.lane`: the leftmost or rightmost through
    /// lane at each position, or a lane held within the through lanes). Empty without a zone.
    pub organized: Vec<LanePiece>,
    /// The vehicle body length to draw (m): the mean of `human.length_m`, which every vehicle
    /// draws.
    pub vehicle_length_m: f64,
}

/// One open stretch [from_m, to_m) of a lane.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Segment {
    /// Lane number (1 = rightmost).
    pub lane: u32,
    /// Start (m); the road start where the lane is open from the entrance.
    pub from_m: f64,
    /// End (m); the road end where the lane runs to the end.
    pub to_m: f64,
    /// An acceleration lane: entered only from its on-ramp, never by a lane change.
    pub accel: bool,
    /// The stretch ends in a wall at `to_m` (a lane drop or the end of an acceleration lane):
    /// its vehicles must leave it before. False where it runs on to the road end or into a
    /// through lane.
    pub ends: bool,
}

/// An on-ramp's merge point or an off-ramp's diverge point.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Ramp {
    /// The ramp's id (`OR3` of `OR3: Laguna Blvd WB`), as in `trips.csv`.
    pub name: String,
    /// The merge or diverge point (m).
    pub x_m: f64,
    /// On-ramps: the lane its vehicles enter (the acceleration lane, or the added lane);
    /// off-ramps: the lane its vehicles leave from (the rightmost through lane there).
    pub lane: u32,
    /// On-ramps: where its acceleration lane ends (m; with a neighbour's merged in, the end of
    /// the joint lane), `x_m` for a lane add; off-ramps: `x_m`.
    pub end_m: f64,
    /// The ramp's vehicles enter a through lane that starts at its merge point (a lane add).
    pub adds_lane: bool,
}

/// A detector.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Detector {
    /// Its name in `detectors.csv`.
    pub name: String,
    /// Its position (m; `detectors.csv`'s `position_m`).
    pub x_m: f64,
    /// `mainline`, `on-ramp` or `off-ramp`, as in `detectors.csv`.
    pub kind: DetectorKind,
}

/// A stretch [from_m, to_m) of one lane.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LanePiece {
    /// Lane number (1 = rightmost).
    pub lane: u32,
    /// Start (m).
    pub from_m: f64,
    /// End (m).
    pub to_m: f64,
}

/// A sketch with every list filled (its fields are all seen in the JSON), for tests.
#[cfg(test)]
pub(crate) fn sample() -> RoadSketch {
    let ramp = |name: &str, x_m, lane, end_m, adds_lane| Ramp {
        name: name.into(),
        x_m,
        lane,
        end_m,
        adds_lane,
    };
    RoadSketch {
        name: "t".into(),
        seed: 3,
        penetration: 0.4,
        origin_m: -500.0,
        start_m: -500.0,
        end_m: 2500.0,
        lanes: 2,
        segments: vec![Segment {
            lane: 2,
            from_m: -500.0,
            to_m: 2500.0,
            accel: false,
            ends: false,
        }],
        on_ramps: vec![ramp("OR1", 500.0, 1, 750.0, false)],
        off_ramps: vec![ramp("FR1", 1000.0, 2, 1000.0, false)],
        detectors: vec![Detector {
            name: "FR1-off".into(),
            x_m: 1000.0,
            kind: DetectorKind::OffRamp,
        }],
        control_m: [-500.0, 2500.0],
        strategy: "pd".into(),
        pd_zone_m: Some([0.0, 1000.0]),
        pd_window_s: None,
        organized: vec![LanePiece {
            lane: 2,
            from_m: 0.0,
            to_m: 1000.0,
        }],
        vehicle_length_m: 4.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sketch_reads_back_as_written() {
        let sketch = sample();
        let text = serde_json::to_string(&sketch).unwrap();
        // The detector kind is the word of detectors.csv.
        assert!(text.contains(r#""kind":"off-ramp""#), "{text}");
        assert!(text.contains(r#""pd_window_s":null"#), "{text}");
        assert_eq!(serde_json::from_str::<RoadSketch>(&text).unwrap(), sketch);
    }
}
