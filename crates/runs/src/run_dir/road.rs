//! `road.json`'s sketch ([`RoadSketch`]) from the engine's own rules: the lanes, acceleration
//! lanes and ramps of `platoonsim_sim::network::Geometry`, the organized lane of
//! `platoonsim_sim::organize::organized_lane_at`. The viewer draws this instead of deriving
//! the road from `scenario.json` itself, so what it draws is what the engine simulated.

use crate::Error;
use platoonsim_rundir::road::{Detector, LanePiece, Ramp, RoadSketch, Segment};
use platoonsim_rundir::DetectorKind;
use platoonsim_sim::config::DetectorKind as SimDetectorKind;
use platoonsim_sim::network::Geometry;
use platoonsim_sim::organize::organized_lane_at;
use platoonsim_sim::{Config, LaneChoice};

/// The sketch of `config`'s road (output coordinates, lanes from 1 = rightmost).
pub fn road_sketch(config: &Config) -> Result<RoadSketch, Error> {
    let geometry =
        Geometry::new(config).map_err(|e| Error::Other(format!("cannot sketch the road: {e}")))?;
    let road = &config.road;
    let origin = road.origin_m();
    let length = road.length_m;
    // The engine's segments that run from the entrance or to the end are open-ended (±∞); the
    // sketch ends them at the road's ends.
    let out = |x: f64| {
        if x.is_infinite() {
            x.clamp(0.0, length) + origin
        } else {
            x + origin
        }
    };
    let segments: Vec<Segment> = geometry
        .lanes
        .iter()
        .zip(1u32..)
        .flat_map(|(segs, lane)| {
            segs.iter().map(move |s| Segment {
                lane,
                from_m: out(s.from),
                to_m: out(s.to),
                accel: s.accel,
                ends: s.wall,
            })
        })
        .collect();
    let lanes = segments.iter().map(|s| s.lane).max().unwrap_or(road.lanes);
    let network = road.network.as_ref();
    let id = |name: &str| platoonsim_scenario::network::split_name(name).0;
    let on_ramps = network
        .map(|n| &n.on_ramps[..])
        .unwrap_or_default()
        .iter()
        .zip(&geometry.on_ramps)
        .map(|(r, g)| Ramp {
            name: id(&r.name),
            x_m: g.x + origin,
            lane: g.lane + 1,
            end_m: if g.adds_lane { g.x } else { g.accel_end } + origin,
            adds_lane: g.adds_lane,
        })
        .collect();
    let off_ramps = network
        .map(|n| &n.off_ramps[..])
        .unwrap_or_default()
        .iter()
        .zip(&geometry.off_ramps)
        .map(|(r, g)| Ramp {
            name: id(&r.name),
            x_m: g.x + origin,
            lane: g.lane + 1,
            end_m: g.x + origin,
            adds_lane: false,
        })
        .collect();
    let detectors = config
        .detectors
        .iter()
        .map(|d| Detector {
            name: d.name.clone(),
            x_m: d.position_m + origin,
            kind: match d.kind {
                SimDetectorKind::Mainline => DetectorKind::Mainline,
                SimDetectorKind::OnRamp { .. } => DetectorKind::OnRamp,
                SimDetectorKind::OffRamp { .. } => DetectorKind::OffRamp,
            },
        })
        .collect();
    let pd = config.strategy.pd.as_ref();
    let organized = pd.map_or_else(Vec::new, |p| {
        // Past the road's ends no lane is open (the engine's open-ended segments would say
        // otherwise).
        let (a, b) = (p.zone_start_m.max(0.0), p.zone_end_m.min(length));
        organized_pieces(&geometry, p.lane, a, b)
            .into_iter()
            .map(|p| LanePiece {
                lane: p.lane,
                from_m: p.from_m + origin,
                to_m: p.to_m + origin,
            })
            .collect()
    });
    Ok(RoadSketch {
        name: config.name.clone(),
        seed: config.seed,
        penetration: config.penetration,
        origin_m: origin,
        start_m: origin,
        end_m: origin + length,
        lanes,
        segments,
        on_ramps,
        off_ramps,
        detectors,
        control_m: [road.control_start_m + origin, road.control_end_m + origin],
        strategy: config.strategy.kind.as_str().to_string(),
        pd_zone_m: pd.map(|p| [p.zone_start_m + origin, p.zone_end_m + origin]),
        pd_window_s: pd.map(|p| [p.start_s, p.end_s]),
        organized,
        vehicle_length_m: config.human.length_m.mean,
    })
}

/// The organized lane over [a, b) (engine coordinates; lanes numbered from 1): the zone cut at
/// every segment boundary, where the open lanes (and so the engine's answer) change, the
/// engine's lane on each piece, equal neighbours merged; no piece where no lane is open.
fn organized_pieces(geometry: &Geometry, choice: LaneChoice, a: f64, b: f64) -> Vec<LanePiece> {
    if a >= b {
        return Vec::new();
    }
    let mut cuts: Vec<f64> = vec![a, b];
    for s in geometry.lanes.iter().flatten() {
        cuts.extend([s.from, s.to].into_iter().filter(|&x| x > a && x < b));
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let mut out: Vec<LanePiece> = Vec::new();
    for w in cuts.windows(2) {
        // Segments are [from, to): the answer at a piece's start holds on the whole piece. The
        // vehicle's own lane only matters (with `Leftmost`) to a vehicle left of the leftmost
        // through lane, which keeps its lane; the sketch draws the lane for every other
        // vehicle, so it asks for lane 0, as the `dedicated` organizer does.
        let Some(lane) = organized_lane_at(choice, geometry, w[0], 0) else {
            continue;
        };
        match out.last_mut() {
            Some(p) if p.lane == lane + 1 && p.to_m == w[0] => p.to_m = w[1],
            _ => out.push(LanePiece {
                lane: lane + 1,
                from_m: w[0],
                to_m: w[1],
            }),
        }
    }
    out
}

#[cfg(test)]
mod tests;
