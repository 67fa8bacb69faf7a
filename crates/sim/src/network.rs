//! Road geometry (issue 4): which lane is open where, acceleration lanes, lane ends, ramps.
//!
//! Every lateral lane index holds a sorted list of disjoint open segments. A segment that ends
//! before the road end in a *wall* is a lane drop or the end of an acceleration lane: its
//! vehicles must change out of it (mandatory desire, spec 4.2) and, failing that, stop at the
//! wall and wait (the wall is a standing obstacle in their car following). An *acceleration*
//! segment is entered only from its on-ramp, never by a lane change.
//!
//! The homogeneous road is the special case of one open segment per lane and no ramps.
//!
//! Building the acceleration lanes from the on-ramps \[D\]:
//! * an on-ramp whose merge point is the start of the rightmost through lane there (within
//!   1 m) is a *lane add*: its vehicles enter that lane directly;
//! * otherwise it gets a segment [x, x + accel_lane_m) at (rightmost through lane − 1);
//! * an acceleration segment that reaches the start of a through segment of the same index
//!   runs on into it without a wall (an auxiliary lane that becomes a through lane);
//! * acceleration segments of close ramps that overlap are merged into one auxiliary lane that
//!   ends at the end of the later one.

use crate::config::{Config, Network};
use crate::error::SimError;

/// One open stretch of a lateral lane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Seg {
    pub from: f64,
    /// `f64::INFINITY` if it runs to the road end.
    pub to: f64,
    /// Entered only from an on-ramp (no lane change into it).
    pub accel: bool,
    /// Ends in a wall at `to`: vehicles must leave it before.
    pub wall: bool,
}

impl Seg {
    #[inline]
    fn contains(&self, x: f64) -> bool {
        x >= self.from && x < self.to
    }
}

/// An on-ramp as the engine uses it.
#[derive(Clone, Debug)]
pub struct RampGeom {
    /// Merge point (engine coordinate).
    pub x: f64,
    /// Lane its vehicles enter.
    pub lane: u32,
    /// Vehicles enter a through lane directly (lane add).
    pub adds_lane: bool,
    /// Length over which the ramp density is counted: ramp roadway + acceleration lane (m).
    pub density_length_m: f64,
    /// End of the acceleration segment its vehicles enter (∞ for a lane add).
    pub accel_end: f64,
}

/// An off-ramp as the engine uses it.
#[derive(Clone, Debug)]
pub struct ExitGeom {
    pub x: f64,
    /// The through lane from which vehicles leave (rightmost through lane at `x`).
    pub lane: u32,
}

/// The geometry of a run.
#[derive(Clone, Debug)]
pub struct Geometry {
    /// Per lateral index, the open segments sorted by position.
    pub lanes: Vec<Vec<Seg>>,
    pub on_ramps: Vec<RampGeom>,
    pub off_ramps: Vec<ExitGeom>,
    /// On-ramps sorted by merge point: (x, ramp index).
    pub ramps_by_x: Vec<(f64, usize)>,
    /// Lanes open at the mainline entrance (x = 0).
    pub entry_lanes: Vec<u32>,
    /// A plain road: every lane open everywhere (fast paths skip the lookups).
    pub plain: bool,
    /// Per lane, per metre of road from x = 0: the index of the first segment that ends after
    /// the start of that metre (`seg` starts its search there; O(1) per lookup).
    index: Vec<Vec<u8>>,
    /// Per metre: rightmost and leftmost through lane at the start of the metre, or 255 when a
    /// segment boundary lies inside the metre (then the lanes are searched).
    right_tab: Vec<u8>,
    left_tab: Vec<u8>,
}

/// "No lane" in the per-metre tables and in `Here::right`.
pub const NO_LANE: u8 = 255;

impl Geometry {
    /// Build the geometry of `cfg` (a plain road if it has no network).
    pub fn new(cfg: &Config) -> Result<Geometry, SimError> {
        let n = cfg.road.lanes as usize;
        let Some(net) = &cfg.road.network else {
            let whole = Seg {
                from: f64::NEG_INFINITY,
                to: f64::INFINITY,
                accel: false,
                wall: false,
            };
            return Ok(Geometry {
                lanes: vec![vec![whole]; n],
                on_ramps: Vec::new(),
                off_ramps: Vec::new(),
                ramps_by_x: Vec::new(),
                entry_lanes: (0..n as u32).collect(),
                plain: true,
                index: Vec::new(),
                right_tab: Vec::new(),
                left_tab: Vec::new(),
            });
        };
        build(net, n, cfg.road.length_m)
    }

    /// The segment of `lane` that contains `x`.
    #[inline]
    pub fn seg(&self, lane: u32, x: f64) -> Option<&Seg> {
        let segs = self.lanes.get(lane as usize)?;
        let start = match self.index.get(lane as usize) {
            Some(ix) if x >= 0.0 && !ix.is_empty() => ix[(x as usize).min(ix.len() - 1)] as usize,
            _ => 0,
        };
        // Sorted and disjoint: the segment ending after the metre's start, or (a boundary
        // inside the metre) the next one; a lookup without an index scans them all.
        let n = if self.index.is_empty() { segs.len() } else { 2 };
        segs.get(start..)?
            .iter()
            .take(n)
            .take_while(|s| s.from <= x)
            .find(|s| s.contains(x))
    }

    /// May a vehicle change into `lane` at `x`? (Open there and not an acceleration lane.)
    #[inline]
    pub fn can_enter(&self, lane: u32, x: f64) -> bool {
        if self.plain {
            return (lane as usize) < self.lanes.len();
        }
        self.seg(lane, x).is_some_and(|s| !s.accel)
    }

    /// Is `lane` a through lane at `x`?
    #[inline]
    pub fn through(&self, lane: u32, x: f64) -> bool {
        self.can_enter(lane, x)
    }

    /// The wall ahead of a vehicle in `lane` at `x`, if its segment ends in one.
    #[inline]
    pub fn wall_ahead(&self, lane: u32, x: f64) -> Option<f64> {
        if self.plain {
            return None;
        }
        self.seg(lane, x).filter(|s| s.wall).map(|s| s.to)
    }

    /// The rightmost through lane at `x`.
    #[inline]
    pub fn rightmost_through(&self, x: f64) -> Option<u32> {
        if let Some(l) = tabled(&self.right_tab, x) {
            return Some(l);
        }
        (0..self.lanes.len() as u32).find(|&l| self.through(l, x))
    }

    /// The leftmost through lane at `x` (the PD lane there).
    #[inline]
    pub fn leftmost_through(&self, x: f64) -> Option<u32> {
        if let Some(l) = tabled(&self.left_tab, x) {
            return Some(l);
        }
        (0..self.lanes.len() as u32)
            .rev()
            .find(|&l| self.through(l, x))
    }

    /// The next on-ramp whose merge point lies in (x, x + range]: (ramp index, distance).
    pub fn next_on_ramp(&self, x: f64, range: f64) -> Option<(usize, f64)> {
        self.next_on_ramp_after(self.ramps_upto(x), x, range)
    }

    /// Number of on-ramps whose merge point is at or before `x`.
    #[inline]
    pub fn ramps_upto(&self, x: f64) -> usize {
        self.ramps_by_x.partition_point(|&(rx, _)| rx <= x)
    }

    /// `next_on_ramp` with `k = ramps_upto(x)` already known.
    #[inline]
    pub fn next_on_ramp_after(&self, k: usize, x: f64, range: f64) -> Option<(usize, f64)> {
        let &(rx, i) = self.ramps_by_x.get(k)?;
        (rx - x <= range).then_some((i, rx - x))
    }
}

/// The per-metre table entry for `x`, if the table covers `x` and no segment boundary lies
/// inside its metre (the answer is then the same everywhere in the metre).
#[inline]
fn tabled(tab: &[u8], x: f64) -> Option<u32> {
    if x >= 0.0 {
        if let Some(&l) = tab.get(x as usize) {
            if l != 255 {
                return Some(u32::from(l));
            }
        }
    }
    None
}

fn build(net: &Network, n: usize, length: f64) -> Result<Geometry, SimError> {
    let mut lanes: Vec<Vec<Seg>> = vec![Vec::new(); n];
    for e in &net.through_lanes {
        lanes[e.lane as usize].push(Seg {
            from: if e.from_m <= 0.0 {
                f64::NEG_INFINITY
            } else {
                e.from_m
            },
            to: if e.to_m >= length {
                f64::INFINITY
            } else {
                e.to_m
            },
            accel: false,
            wall: e.to_m < length,
        });
    }
    for l in &mut lanes {
        sort_and_join(l);
    }
    let through_lanes = lanes.clone();
    let rightmost = |x: f64| -> Option<u32> {
        (0..n as u32).find(|&l| through_lanes[l as usize].iter().any(|s| s.contains(x)))
    };
    // On-ramps in merge-point order.
    let mut order: Vec<usize> = (0..net.on_ramps.len()).collect();
    order.sort_by(|&a, &b| net.on_ramps[a].x_m.total_cmp(&net.on_ramps[b].x_m));
    let mut on_ramps: Vec<Option<RampGeom>> = vec![None; net.on_ramps.len()];
    for &i in &order {
        let r = &net.on_ramps[i];
        let x = r.x_m;
        let Some(right) = rightmost(x) else {
            return Err(SimError::Geometry(format!(
                "network.on_ramps[{i}] ({}) at x = {x}: no through lane is open there",
                r.name
            )));
        };
        let starts_here = through_lanes[right as usize]
            .iter()
            .any(|s| (s.from - x).abs() <= 1.0);
        if starts_here {
            on_ramps[i] = Some(RampGeom {
                x,
                lane: right,
                adds_lane: true,
                density_length_m: r.ramp_length_m.max(1.0),
                accel_end: f64::INFINITY,
            });
            continue;
        }
        if right == 0 {
            return Err(SimError::Geometry(format!(
                "network.on_ramps[{i}] ({}) at x = {x}: the rightmost through lane there has index 0, so there is no lane index for its acceleration lane (number through lanes from 1)",
                r.name
            )));
        }
        let a = right - 1;
        let mut end = x + r.accel_lane_m.max(1.0);
        let mut wall = true;
        // Runs on into a through segment of the same index that starts before its end.
        if let Some(t) = through_lanes[a as usize]
            .iter()
            .find(|s| s.from > x && s.from <= end)
        {
            end = t.from;
            wall = false;
        }
        lanes[a as usize].push(Seg {
            from: x,
            to: end,
            accel: true,
            wall,
        });
        sort_and_join(&mut lanes[a as usize]);
        on_ramps[i] = Some(RampGeom {
            x,
            lane: a,
            adds_lane: false,
            density_length_m: (r.ramp_length_m + r.accel_lane_m).max(1.0),
            accel_end: end,
        });
    }
    let on_ramps: Vec<RampGeom> = on_ramps.into_iter().map(|r| r.expect("built")).collect();
    // After merging, a ramp's acceleration segment may end later than its own length.
    let mut on_ramps = on_ramps;
    for r in &mut on_ramps {
        if !r.adds_lane {
            if let Some(s) = lanes[r.lane as usize].iter().find(|s| s.contains(r.x)) {
                r.accel_end = s.to;
            }
        }
    }
    let mut off_ramps = Vec::with_capacity(net.off_ramps.len());
    for (i, r) in net.off_ramps.iter().enumerate() {
        let Some(lane) = rightmost(r.x_m) else {
            return Err(SimError::Geometry(format!(
                "network.off_ramps[{i}] ({}) at x = {}: no through lane is open there",
                r.name, r.x_m
            )));
        };
        off_ramps.push(ExitGeom { x: r.x_m, lane });
    }
    let mut ramps_by_x: Vec<(f64, usize)> =
        on_ramps.iter().enumerate().map(|(i, r)| (r.x, i)).collect();
    ramps_by_x.sort_by(|a, b| a.0.total_cmp(&b.0));
    let entry_lanes: Vec<u32> = (0..n as u32)
        .filter(|&l| through_lanes[l as usize].iter().any(|s| s.contains(0.0)))
        .collect();
    if entry_lanes.is_empty() {
        return Err(SimError::Geometry(
            "network: no through lane is open at the entrance".into(),
        ));
    }
    let metres = length.max(0.0).ceil() as usize + 2;
    let index = lanes
        .iter()
        .map(|segs| {
            assert!(segs.len() < 255, "at most 254 segments per lane");
            let mut k = 0usize;
            (0..metres)
                .map(|m| {
                    while k < segs.len() && segs[k].to <= m as f64 {
                        k += 1;
                    }
                    k as u8
                })
                .collect()
        })
        .collect();
    let mut g = Geometry {
        lanes,
        on_ramps,
        off_ramps,
        ramps_by_x,
        entry_lanes,
        plain: false,
        index,
        right_tab: Vec::new(),
        left_tab: Vec::new(),
    };
    let inside = |m: usize| {
        g.lanes.iter().flatten().any(|s| {
            let (a, b) = (m as f64, m as f64 + 1.0);
            (s.from > a && s.from < b) || (s.to > a && s.to < b)
        })
    };
    let (mut right, mut left) = (Vec::with_capacity(metres), Vec::with_capacity(metres));
    for m in 0..metres {
        if inside(m) {
            right.push(255);
            left.push(255);
        } else {
            right.push(g.rightmost_through(m as f64).map_or(255, |l| l as u8));
            left.push(g.leftmost_through(m as f64).map_or(255, |l| l as u8));
        }
    }
    g.right_tab = right;
    g.left_tab = left;
    Ok(g)
}

/// Sort segments and merge the ones that overlap or touch with the same kind; an overlap of
/// an acceleration segment with another acceleration segment becomes one segment.
fn sort_and_join(segs: &mut Vec<Seg>) {
    segs.sort_by(|a, b| a.from.total_cmp(&b.from));
    let mut out: Vec<Seg> = Vec::with_capacity(segs.len());
    for s in segs.drain(..) {
        if let Some(last) = out.last_mut() {
            let touches = s.from <= last.to;
            if touches && last.accel == s.accel && (s.from < last.to || !last.wall) {
                if s.to > last.to {
                    last.to = s.to;
                    last.wall = s.wall;
                }
                continue;
            }
        }
        out.push(s);
    }
    *segs = out;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::{LaneExtent, OffRamp, OnRamp};

    fn net() -> Network {
        // 3 lanes (indices 2..=4) over [0, 3000), a 4th (index 1) added at 1000 by a ramp.
        let mut through = Vec::new();
        for l in 2..=4 {
            through.push(LaneExtent {
                lane: l,
                from_m: 0.0,
                to_m: 3000.0,
            });
        }
        through.push(LaneExtent {
            lane: 1,
            from_m: 1000.0,
            to_m: 3000.0,
        });
        let ramp = |name: &str, x: f64| OnRamp {
            name: name.into(),
            x_m: x,
            accel_lane_m: 250.0,
            ramp_length_m: 300.0,
            demand_vph: vec![100.0],
            meter: None,
            penetration: None,
        };
        Network {
            origin_m: 0.0,
            through_lanes: through,
            on_ramps: vec![
                ramp("a", 300.0),
                ramp("b", 500.0),
                ramp("add", 1000.0),
                ramp("c", 900.0),
                ramp("d", 2000.0),
            ],
            off_ramps: vec![OffRamp {
                name: "off".into(),
                x_m: 1500.0,
                exit_fraction: vec![0.1],
            }],
            interval_s: 900.0,
            mainline_vph: vec![1000.0],
            demand_scale: 1.0,
            ramp_speed_kmh: 90.0,
            lane_speed_limits_kmh: Vec::new(),
            cross_lane_friction: None,
            behaviour: Vec::new(),
        }
    }

    #[test]
    fn builds_acceleration_lanes_lane_adds_and_exits() {
        let g = build(&net(), 5, 3000.0).unwrap();
        // a (300) and b (500) overlap: one auxiliary lane [300, 750) with a wall.
        assert_eq!(g.on_ramps[0].lane, 1);
        assert_eq!(g.on_ramps[0].accel_end, 750.0);
        assert_eq!(g.on_ramps[1].accel_end, 750.0);
        assert_eq!(g.wall_ahead(1, 400.0), Some(750.0));
        assert!(
            !g.can_enter(1, 400.0),
            "acceleration lane: no entry by lane change"
        );
        // c at 900 runs on into the added lane at 1000: no wall.
        assert_eq!(g.on_ramps[3].lane, 1);
        assert_eq!(g.wall_ahead(1, 950.0), None);
        // the ramp at 1000 adds lane 1.
        assert!(g.on_ramps[2].adds_lane);
        assert_eq!(g.on_ramps[2].lane, 1);
        assert!(g.can_enter(1, 1200.0));
        // d at 2000: the rightmost through lane is 1, so its acceleration lane is 0.
        assert_eq!(g.on_ramps[4].lane, 0);
        assert_eq!(g.wall_ahead(0, 2100.0), Some(2250.0));
        assert_eq!(g.off_ramps[0].lane, 1);
        assert_eq!(g.rightmost_through(500.0), Some(2));
        assert_eq!(g.leftmost_through(500.0), Some(4));
        assert_eq!(g.entry_lanes, vec![2, 3, 4]);
        assert_eq!(g.next_on_ramp(1500.0, 1000.0).map(|r| r.0), Some(4));
        assert_eq!(g.next_on_ramp(1500.0, 400.0), None);
        // Through lanes run to the end without a wall.
        assert_eq!(g.wall_ahead(4, 2999.0), None);
    }

    #[test]
    fn through_lane_tables_agree_with_the_segment_search() {
        let g = build(&net(), 5, 3000.0).unwrap();
        for i in -8..=(3010 * 8) {
            let x = f64::from(i) / 8.0 + 0.01;
            let right = (0..5).find(|&l| g.through(l, x));
            let left = (0..5).rev().find(|&l| g.through(l, x));
            assert_eq!(g.rightmost_through(x), right, "x = {x}");
            assert_eq!(g.leftmost_through(x), left, "x = {x}");
        }
    }

    #[test]
    fn here_tables_agree_with_the_geometry_lookups() {
        use crate::here::{here_at, HereTables, SideWalls};
        let g = build(&net(), 5, 3000.0).unwrap();
        let t = HereTables::new(&g);
        let xs: Vec<f64> = (-8..=(3010 * 4)).map(|i| f64::from(i) / 4.0).collect();
        for lane in 0..g.lanes.len() {
            let l = lane as u32;
            // The lookups one by one, as `Geometry`'s own functions give them.
            for &x in xs.iter().step_by(13) {
                let h = here_at(&g, lane, x);
                assert_eq!(h.wall, g.wall_ahead(l, x), "lane {lane}, x = {x}");
                assert_eq!(h.accel, g.seg(l, x).is_some_and(|s| s.accel));
                assert_eq!(h.enter_left, g.can_enter(l + 1, x), "lane {lane}, x = {x}");
                assert_eq!(h.enter_right, lane > 0 && g.can_enter(l - 1, x));
                assert_eq!(h.ramps_upto as usize, g.ramps_upto(x));
                assert_eq!(h.right, g.rightmost_through(x).map_or(NO_LANE, |r| r as u8));
            }
            // The table's walk, down (as the sense phase walks a lane), up and in any order.
            let mut down = t.walk(lane);
            for &x in xs.iter().rev() {
                assert_eq!(down.at(x), here_at(&g, lane, x), "lane {lane}, x = {x}");
            }
            let mut up = t.walk(lane);
            for &x in &xs {
                assert_eq!(up.at(x), here_at(&g, lane, x), "lane {lane}, x = {x} (up)");
            }
            let mut mixed = t.walk(lane);
            for (i, &x) in xs.iter().enumerate().step_by(97) {
                let y = xs[(i * 7919) % xs.len()];
                assert_eq!(mixed.at(x), here_at(&g, lane, x), "lane {lane}, x = {x}");
                assert_eq!(mixed.at(y), here_at(&g, lane, y), "lane {lane}, x = {y}");
            }
        }
        // The walls beside each lane list, walked down the list as the decide phase does, and
        // for a lane that is not beside it.
        for lane in 0..g.lanes.len() {
            let mut walls = SideWalls::new(&t, lane, g.lanes.len());
            for &x in xs.iter().rev() {
                for target in [lane + 1, lane.wrapping_sub(1), lane + 2] {
                    if target < g.lanes.len() {
                        let w = walls.wall_ahead(&g, target, x);
                        assert_eq!(w, g.wall_ahead(target as u32, x), "{lane} → {target}, {x}");
                    }
                }
            }
        }
        // In the acceleration lane of ramps a and b: a wall at 750; a change left, none right.
        let h = t.walk(1).at(400.0);
        assert_eq!(h.wall, Some(750.0));
        assert!(h.accel && h.enter_left && !h.enter_right);
        assert_eq!((h.ramps_upto, h.right), (1, 2));
    }

    #[test]
    fn a_ramp_with_no_room_on_the_right_is_an_error() {
        let mut n = net();
        n.through_lanes.push(LaneExtent {
            lane: 0,
            from_m: 0.0,
            to_m: 3000.0,
        });
        let e = build(&n, 5, 3000.0).unwrap_err();
        assert!(
            matches!(&e, SimError::Geometry(m) if m.contains("on_ramps[0]")),
            "{e}"
        );
    }
}
