//! The road as drawn, from the run's `scenario.json` (the resolved configuration). Positions
//! are converted to the output coordinate of `trajectories.csv` and `detectors.csv` (engine x
//! plus the network's `origin_m`); lanes are numbered like `trajectories.csv` (1 = the
//! rightmost lateral position, one more than the engine's index).

use anyhow::{anyhow, bail, Result};
use serde::Serialize;
use serde_json::Value;

/// One open stretch of a lane.
#[derive(Debug, Serialize, PartialEq)]
pub struct Segment {
    pub lane: u32,
    pub from_m: f64,
    pub to_m: f64,
    /// An acceleration lane (its vehicles must leave it by its end).
    pub accel: bool,
    /// The stretch ends before the road end (a lane drop or the end of an acceleration lane).
    pub ends: bool,
}

#[derive(Debug, Serialize)]
pub struct Ramp {
    pub name: String,
    pub x_m: f64,
    /// The lane the ramp joins or leaves (output numbering).
    pub lane: u32,
    /// On-ramps: where its acceleration lane ends (= x_m for a lane add).
    pub end_m: f64,
    pub adds_lane: bool,
}

/// A stretch of one lane (output numbering and coordinates).
#[derive(Debug, Serialize, PartialEq)]
pub struct LanePiece {
    pub lane: u32,
    pub from_m: f64,
    pub to_m: f64,
}

/// `strategy.pd.lane` as written to scenario.json: absent or `"leftmost"`, `"rightmost"`, or
/// `{"index": i}` (engine index); a bare number is read as the scenario file's lane number
/// (1 = rightmost).
#[derive(Clone, Copy, Debug, PartialEq)]
enum LaneChoice {
    Leftmost,
    Rightmost,
    Index(u32),
}

fn lane_choice(v: Option<&Value>) -> Result<LaneChoice> {
    let Some(v) = v.filter(|v| !v.is_null()) else {
        return Ok(LaneChoice::Leftmost);
    };
    let index = |i: Option<u64>| i.and_then(|i| u32::try_from(i).ok());
    match v {
        Value::String(s) if s == "leftmost" => Ok(LaneChoice::Leftmost),
        Value::String(s) if s == "rightmost" => Ok(LaneChoice::Rightmost),
        Value::Number(n) => match index(n.as_u64()) {
            Some(l) if l >= 1 => Ok(LaneChoice::Index(l - 1)),
            _ => bail!("key strategy.pd.lane = {v}: expected a lane number from 1"),
        },
        Value::Object(o) => match index(o.get("index").and_then(Value::as_u64)) {
            Some(i) => Ok(LaneChoice::Index(i)),
            None => bail!("key strategy.pd.lane = {v}: expected {{\"index\": N}}"),
        },
        _ => bail!("key strategy.pd.lane = {v}: expected \"leftmost\", \"rightmost\" or a lane"),
    }
}

/// The organized lane's pieces over the zone [a, b) (engine coordinates), from the through
/// lanes `(engine lane, from, to)`.
fn organized_pieces(
    through: &[(u32, f64, f64)],
    choice: LaneChoice,
    a: f64,
    b: f64,
    origin: f64,
) -> Vec<LanePiece> {
    let mut cuts: Vec<f64> = vec![a, b];
    for t in through {
        cuts.extend([t.1, t.2].into_iter().filter(|&x| x > a && x < b));
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let mut out: Vec<LanePiece> = Vec::new();
    for w in cuts.windows(2) {
        let mid = 0.5 * (w[0] + w[1]);
        let open = || {
            through
                .iter()
                .filter(|t| t.1 <= mid && mid < t.2)
                .map(|t| t.0)
        };
        let (Some(lo), Some(hi)) = (open().min(), open().max()) else {
            continue;
        };
        let lane = match choice {
            LaneChoice::Leftmost => hi,
            LaneChoice::Rightmost => lo,
            LaneChoice::Index(i) => i.clamp(lo, hi),
        } + 1;
        match out.last_mut() {
            Some(p) if p.lane == lane && p.to_m == w[0] + origin => p.to_m = w[1] + origin,
            _ => out.push(LanePiece {
                lane,
                from_m: w[0] + origin,
                to_m: w[1] + origin,
            }),
        }
    }
    out
}

#[derive(Debug, Serialize)]
pub struct Detector {
    pub name: String,
    pub x_m: f64,
    /// `mainline` or `off-ramp`.
    pub kind: String,
}

#[derive(Debug, Serialize)]
pub struct Road {
    pub name: String,
    pub seed: Option<u64>,
    pub penetration: Option<f64>,
    pub origin_m: f64,
    pub start_m: f64,
    pub end_m: f64,
    /// Lateral positions (the highest lane number).
    pub lanes: u32,
    pub segments: Vec<Segment>,
    pub on_ramps: Vec<Ramp>,
    pub off_ramps: Vec<Ramp>,
    pub detectors: Vec<Detector>,
    /// The control section (output coordinates).
    pub control_m: [f64; 2],
    /// `none`, `pd` or `flow-aware`.
    pub strategy: String,
    /// The PD zone and window, for `pd` and `flow-aware`.
    pub pd_zone_m: Option<[f64; 2]>,
    pub pd_window_s: Option<[f64; 2]>,
    /// The organized lane (PD or dedicated) inside the zone: one piece per stretch where it is
    /// the same lane (`strategy.pd.lane`: the leftmost or rightmost through lane at each
    /// position, or a lane held within the through lanes).
    pub organized: Vec<LanePiece>,
    /// Vehicle body length drawn (m): the mean of `human.length_m`, which every vehicle draws.
    pub vehicle_length_m: f64,
}

fn num(v: &Value, path: &str) -> Result<f64> {
    let mut cur = v;
    for key in path.split('.') {
        cur = cur
            .get(key)
            .ok_or_else(|| anyhow!("key {path} is missing"))?;
    }
    cur.as_f64()
        .filter(|x| x.is_finite())
        .ok_or_else(|| anyhow!("key {path} = {cur}: expected a finite number"))
}

fn text(v: &Value, key: &str) -> String {
    v.get(key).and_then(Value::as_str).unwrap_or("").to_string()
}

/// The id part of a ramp name such as `OR3: Laguna Blvd WB`.
fn short(name: &str) -> String {
    name.split(':').next().unwrap_or(name).trim().to_string()
}

impl Road {
    pub fn from_scenario(s: &Value) -> Result<Road> {
        let road = s
            .get("road")
            .ok_or_else(|| anyhow!("key road is missing"))?;
        let lanes = num(road, "lanes")?;
        if !(1.0..=250.0).contains(&lanes) || lanes.fract() != 0.0 {
            bail!("key road.lanes = {lanes}: expected a whole number from 1 to 250");
        }
        let lanes = lanes as u32;
        let length = num(road, "length_m")?;
        if length <= 0.0 {
            bail!("key road.length_m = {length}: expected a positive length");
        }
        let network = road.get("network").filter(|n| !n.is_null());
        let origin = match network {
            Some(n) => num(n, "origin_m")?,
            None => 0.0,
        };
        let mut segments = Vec::new();
        let mut on_ramps = Vec::new();
        let mut off_ramps = Vec::new();
        let mut top = lanes;
        let mut through: Vec<(u32, f64, f64)> = (0..lanes).map(|l| (l, 0.0, length)).collect();
        match network {
            None => {
                for l in 1..=lanes {
                    segments.push(Segment {
                        lane: l,
                        from_m: origin,
                        to_m: origin + length,
                        accel: false,
                        ends: false,
                    });
                }
            }
            Some(n) => {
                let extents = n
                    .get("through_lanes")
                    .and_then(Value::as_array)
                    .ok_or_else(|| anyhow!("key road.network.through_lanes is missing"))?;
                through.clear();
                for (i, e) in extents.iter().enumerate() {
                    let lane = num(e, "lane")
                        .map_err(|err| anyhow!("road.network.through_lanes[{i}]: {err}"))?;
                    let from = num(e, "from_m")?;
                    let to = num(e, "to_m")?;
                    through.push((lane as u32, from, to));
                }
                top = through.iter().map(|t| t.0 + 1).max().unwrap_or(lanes);
                // The rightmost through lane open at x (engine index), as the engine finds it.
                let rightmost = |x: f64| {
                    through
                        .iter()
                        .filter(|t| t.1 <= x && x < t.2)
                        .map(|t| t.0)
                        .min()
                };
                for &(lane, from, to) in &through {
                    segments.push(Segment {
                        lane: lane + 1,
                        from_m: from + origin,
                        to_m: to + origin,
                        accel: false,
                        ends: to < length,
                    });
                }
                for r in n
                    .get("on_ramps")
                    .and_then(Value::as_array)
                    .into_iter()
                    .flatten()
                {
                    let x = num(r, "x_m")?;
                    let accel = num(r, "accel_lane_m").unwrap_or(0.0).max(1.0);
                    let Some(right) = rightmost(x) else { continue };
                    let adds = through
                        .iter()
                        .any(|t| t.0 == right && (t.1 - x).abs() <= 1.0);
                    let (lane, end) = if adds || right == 0 {
                        (right, x)
                    } else {
                        // An acceleration lane right of the through lanes, running on into a
                        // through stretch of the same index that starts before its end.
                        let a = right - 1;
                        let end = through
                            .iter()
                            .filter(|t| t.0 == a && t.1 > x && t.1 <= x + accel)
                            .map(|t| t.1)
                            .fold(x + accel, f64::min);
                        segments.push(Segment {
                            lane: a + 1,
                            from_m: x + origin,
                            to_m: end + origin,
                            accel: true,
                            ends: end >= x + accel,
                        });
                        (a, end)
                    };
                    on_ramps.push(Ramp {
                        name: short(&text(r, "name")),
                        x_m: x + origin,
                        lane: lane + 1,
                        end_m: end + origin,
                        adds_lane: adds,
                    });
                }
                for r in n
                    .get("off_ramps")
                    .and_then(Value::as_array)
                    .into_iter()
                    .flatten()
                {
                    let x = num(r, "x_m")?;
                    let lane = rightmost(x).unwrap_or(0);
                    off_ramps.push(Ramp {
                        name: short(&text(r, "name")),
                        x_m: x + origin,
                        lane: lane + 1,
                        end_m: x + origin,
                        adds_lane: false,
                    });
                }
            }
        }
        let mut detectors = Vec::new();
        for d in s
            .get("detectors")
            .and_then(Value::as_array)
            .into_iter()
            .flatten()
        {
            let kind = d
                .get("kind")
                .and_then(|k| k.get("kind"))
                .and_then(Value::as_str)
                .unwrap_or("mainline")
                .to_string();
            detectors.push(Detector {
                name: text(d, "name"),
                x_m: num(d, "position_m")? + origin,
                kind,
            });
        }
        let strategy = s.get("strategy");
        let kind = strategy
            .map(|st| text(st, "kind"))
            .filter(|k| !k.is_empty())
            .unwrap_or_else(|| "none".to_string());
        let pd = strategy
            .and_then(|st| st.get("pd"))
            .filter(|p| !p.is_null());
        let (pd_zone_m, pd_window_s, organized) = match pd {
            Some(p) => {
                let (a, b) = (num(p, "zone_start_m")?, num(p, "zone_end_m")?);
                let choice = lane_choice(p.get("lane"))?;
                (
                    Some([a + origin, b + origin]),
                    Some([num(p, "start_s")?, num(p, "end_s")?]),
                    organized_pieces(&through, choice, a, b, origin),
                )
            }
            None => (None, None, vec![]),
        };
        let vehicle_length_m = num(s, "human.length_m.mean").unwrap_or(4.0);
        if !(vehicle_length_m > 0.0 && vehicle_length_m < 100.0) {
            bail!("key human.length_m.mean = {vehicle_length_m}: expected a length in (0, 100) m");
        }
        Ok(Road {
            name: text(s, "name"),
            seed: s.get("seed").and_then(Value::as_u64),
            penetration: s.get("penetration").and_then(Value::as_f64),
            origin_m: origin,
            start_m: origin,
            end_m: origin + length,
            lanes: top,
            segments,
            on_ramps,
            off_ramps,
            detectors,
            control_m: [
                num(road, "control_start_m").unwrap_or(0.0) + origin,
                num(road, "control_end_m").unwrap_or(length) + origin,
            ],
            strategy: kind,
            pd_zone_m,
            pd_window_s,
            organized,
            vehicle_length_m,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn network_lanes_ramps_and_coordinates() {
        let s = json!({
            "name": "t", "seed": 3, "penetration": 0.4,
            "road": {"lanes": 4, "length_m": 3000.0, "control_start_m": 0.0, "control_end_m": 3000.0,
              "network": {"origin_m": -500.0,
                "through_lanes": [
                  {"lane": 1, "from_m": 0.0, "to_m": 3000.0},
                  {"lane": 2, "from_m": 0.0, "to_m": 3000.0},
                  {"lane": 3, "from_m": 0.0, "to_m": 2000.0},
                  {"lane": 0, "from_m": 2500.0, "to_m": 3000.0}],
                "on_ramps": [{"name": "OR1: A St", "x_m": 1000.0, "accel_lane_m": 250.0},
                             {"name": "OR2: B St", "x_m": 2500.0, "accel_lane_m": 250.0}],
                "off_ramps": [{"name": "FR1: C St", "x_m": 1500.0}]}},
            "detectors": [{"name": "d", "position_m": 100.0, "kind": {"kind": "mainline"}}],
            "strategy": {"kind": "pd", "pd": {"zone_start_m": 0.0, "zone_end_m": 3000.0, "start_s": 0.0, "end_s": 60.0}},
            "human": {"length_m": {"mean": 4.5}}
        });
        let r = Road::from_scenario(&s).unwrap();
        assert_eq!(r.lanes, 4);
        // The leftmost through lane: output lane 4 until its drop at engine 2000 m, then 3.
        let piece = |lane, from_m, to_m| LanePiece { lane, from_m, to_m };
        assert_eq!(
            r.organized,
            vec![piece(4, -500.0, 1500.0), piece(3, 1500.0, 2500.0)]
        );
        assert_eq!((r.start_m, r.end_m), (-500.0, 2500.0));
        // The lane drop of engine lane 3 (output 4) at 2000 m.
        assert!(r.segments.contains(&Segment {
            lane: 4,
            from_m: -500.0,
            to_m: 1500.0,
            accel: false,
            ends: true
        }));
        // OR1: an acceleration lane at engine index 0 (output lane 1), 250 m long.
        assert!(r.segments.contains(&Segment {
            lane: 1,
            from_m: 500.0,
            to_m: 750.0,
            accel: true,
            ends: true
        }));
        assert_eq!(r.on_ramps[0].name, "OR1");
        // OR2 adds the lane that starts at its merge point.
        assert!(r.on_ramps[1].adds_lane);
        assert_eq!((r.on_ramps[1].lane, r.on_ramps[1].end_m), (1, 2000.0));
        assert_eq!(
            (r.off_ramps[0].name.as_str(), r.off_ramps[0].lane),
            ("FR1", 2)
        );
        assert_eq!(r.detectors[0].x_m, -400.0);
        assert_eq!(r.pd_zone_m, Some([-500.0, 2500.0]));
        assert_eq!(r.vehicle_length_m, 4.5);
    }

    #[test]
    fn the_organized_lane_follows_strategy_pd_lane() {
        let piece = |lane, from_m, to_m| LanePiece { lane, from_m, to_m };
        let through = [(0, 0.0, 3000.0), (1, 0.0, 3000.0), (2, 1000.0, 3000.0)];
        let right = organized_pieces(&through, LaneChoice::Rightmost, 500.0, 2000.0, 0.0);
        assert_eq!(right, vec![piece(1, 500.0, 2000.0)]);
        let index = lane_choice(Some(&json!({"index": 2}))).unwrap();
        let held = organized_pieces(&through, index, 500.0, 2000.0, 0.0);
        assert_eq!(
            held,
            vec![piece(2, 500.0, 1000.0), piece(3, 1000.0, 2000.0)]
        );
        assert_eq!(lane_choice(Some(&json!(2))).unwrap(), LaneChoice::Index(1));
        let e = lane_choice(Some(&json!("middle"))).unwrap_err().to_string();
        assert!(e.contains("strategy.pd.lane = \"middle\""), "{e}");
    }

    #[test]
    fn a_bad_lane_count_names_the_key() {
        let s = json!({"road": {"lanes": 0, "length_m": 100.0}});
        let e = Road::from_scenario(&s).unwrap_err().to_string();
        assert!(e.contains("road.lanes = 0"), "{e}");
    }
}
