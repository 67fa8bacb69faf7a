//! Room for a vehicle at the merge points and lane ends of a `[network]` (issue 35 item 4),
//! checked on the engine's own geometry once everything else is valid, and the warnings for
//! geometry that is legal but known to collide.
//!
//! Refused, since the engine cannot place or hold a vehicle there: on-ramp merge points closer
//! together than the longest vehicle, a merge point less than a vehicle length downstream of
//! the end (a wall) of the lane it enters, an acceleration lane shorter than a vehicle, and a
//! lane open over less than a vehicle length that ends in a wall.
//!
//! Warned about ([`warnings`]): a lane drop within [`LANE_DROP_WARN_M`] downstream of an
//! on-ramp's merge point (the merging and the dropped lane's vehicles compete for the same
//! gaps; the generated corridors of the issue collided at every step size and penetration)
//! and an acceleration lane shorter than [`SHORT_ACCEL_LANE_M`].

use super::Checker;
use crate::raw::num;
use platoonsim_sim::network::Geometry;
use platoonsim_sim::Config;

/// A lane drop at most this far downstream of a merge point gets a warning (m).
pub const LANE_DROP_WARN_M: f64 = 300.0;
/// An acceleration lane shorter than this gets a warning (m).
pub const SHORT_ACCEL_LANE_M: f64 = 50.0;

/// The longest vehicle a driver can draw (m): the room every rule below asks for.
fn longest(cfg: &Config) -> f64 {
    cfg.human.length_m.max.max(cfg.human.length_m.mean)
}

/// Corridor coordinate of an engine position.
fn corridor(cfg: &Config, x: f64) -> f64 {
    x + cfg.road.origin_m()
}

pub(super) fn check_room(c: &mut Checker, cfg: &Config) {
    let Some(net) = &cfg.road.network else {
        return;
    };
    let g = match Geometry::new(cfg) {
        Ok(g) => g,
        Err(e) => {
            c.push("network", "-", e.to_string());
            return;
        }
    };
    let l = longest(cfg);
    let need = format!("{} m (the longest vehicle, human.length_m.max)", num(l));
    for (i, (r, rg)) in net.on_ramps.iter().zip(&g.on_ramps).enumerate() {
        let field = format!("network.on_ramps[{i}].x_m");
        let x = corridor(cfg, r.x_m);
        if let Some(p) = i.checked_sub(1).map(|k| &net.on_ramps[k]) {
            if r.x_m - p.x_m < l {
                c.value(
                    &field,
                    x,
                    false,
                    &format!(
                        "must be at least {need} downstream of network.on_ramps[{}].x_m = {}: \
                         merge points closer than a vehicle leave no room to enter",
                        i - 1,
                        num(corridor(cfg, p.x_m))
                    ),
                );
                continue;
            }
        }
        let end_before = g.lanes[rg.lane as usize]
            .iter()
            .filter(|s| s.wall && s.to <= r.x_m && s.to > r.x_m - l)
            .map(|s| s.to)
            .next_back();
        if let Some(w) = end_before {
            c.value(
                &field,
                x,
                false,
                &format!(
                    "must be at least {need} downstream of the end of the lane it enters \
                     (lateral lane {}, ending at {} m): a vehicle waiting at that end reaches \
                     into the merge point",
                    rg.lane,
                    num(corridor(cfg, w))
                ),
            );
            continue;
        }
        if !rg.adds_lane && r.accel_lane_m < l {
            c.value(
                &format!("network.on_ramps[{i}].accel_lane_m"),
                r.accel_lane_m,
                false,
                &format!(
                    "must be at least {need}: a shorter acceleration lane leaves an entering \
                     vehicle no room"
                ),
            );
        }
    }
    for (lane, segs) in g.lanes.iter().enumerate() {
        for s in segs
            .iter()
            .filter(|s| s.wall && !s.accel && s.to - s.from < l)
        {
            c.push(
                "network.lanes",
                format!(
                    "lateral lane {lane} open over [{}, {}) m",
                    num(corridor(cfg, s.from)),
                    num(corridor(cfg, s.to))
                ),
                format!(
                    "a lane that ends must be open over at least {need}: a shorter one leaves \
                     no room for a vehicle"
                ),
            );
        }
    }
}

/// Geometry of a valid `[network]` that is legal but known to collide, one sentence each,
/// naming the elements (empty for a homogeneous road).
pub fn warnings(cfg: &Config) -> Vec<String> {
    let Some(net) = &cfg.road.network else {
        return Vec::new();
    };
    let Ok(g) = Geometry::new(cfg) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    // Lane drops: through segments that end in a wall (acceleration lanes end by design).
    let drops: Vec<(usize, f64)> = g
        .lanes
        .iter()
        .enumerate()
        .flat_map(|(lane, segs)| {
            segs.iter()
                .filter(|s| s.wall && !s.accel)
                .map(move |s| (lane, s.to))
        })
        .collect();
    for (i, (r, rg)) in net.on_ramps.iter().zip(&g.on_ramps).enumerate() {
        let at = corridor(cfg, r.x_m);
        for &(lane, w) in &drops {
            let d = w - r.x_m;
            if d > 0.0 && d <= LANE_DROP_WARN_M {
                out.push(format!(
                    "network.on_ramps[{i}] ({}) merges at {} m, {} m upstream of a lane drop \
                     (lateral lane {lane} ends at {} m): a lane drop within {} m downstream of \
                     an on-ramp is known to collide; move one of them",
                    r.name,
                    num(at),
                    num(d),
                    num(corridor(cfg, w)),
                    num(LANE_DROP_WARN_M)
                ));
            }
        }
        if !rg.adds_lane && r.accel_lane_m < SHORT_ACCEL_LANE_M {
            out.push(format!(
                "network.on_ramps[{i}] ({}) at {} m: an acceleration lane of {} m (under {} m) \
                 gives merging vehicles little room and is known to collide",
                r.name,
                num(at),
                num(r.accel_lane_m),
                num(SHORT_ACCEL_LANE_M)
            ));
        }
    }
    out
}
