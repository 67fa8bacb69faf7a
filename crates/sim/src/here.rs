//! What the geometry says at a vehicle's position (`Here`), as one step function per lane.
//!
//! `Here` is a function of the lane and the position only, and every part of it is constant
//! between two consecutive *breaks*: the starts and ends of the lane segments (spec 4.2's lane
//! ends and acceleration lanes, network.rs; the rightmost through lane too changes only at
//! one of them) and the on-ramps' merge points. Segments are half-open stretches [from, to)
//! and a ramp counts from its merge point on, so `Here` is constant on [break_i, break_i+1).
//!
//! The sense phase walks each lane's list front to back and used to look the parts up one by
//! one (four segment walks and a ramp cursor per vehicle); the table gives the same value with
//! one interval test for most vehicles. The pieces are computed once per run by the geometry's
//! own lookups at each piece's first position.

use crate::network::{Geometry, NO_LANE};

/// Where a vehicle is at the start of the step, by the geometry (network.rs).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Here {
    /// The wall ending its lane segment, if it ends in one (`Geometry::wall_ahead`).
    pub wall: Option<f64>,
    /// It is in an acceleration segment.
    pub accel: bool,
    /// May change into the lane to the left / to the right here (`Geometry::can_enter`).
    pub enter_left: bool,
    pub enter_right: bool,
    /// On-ramps with their merge point at or before it (`Geometry::ramps_upto`).
    pub ramps_upto: u32,
    /// The rightmost through lane there (`Geometry::rightmost_through`; `NO_LANE`: none; 0 on
    /// a plain road).
    pub right: u8,
}

/// `Here` along every lane: in lane `l`, `pieces[l][i]` holds on [breaks[i − 1], breaks[i])
/// (from −∞ for the first piece, to +∞ for the last). The breaks are the same for every lane.
#[derive(Clone, Debug)]
pub struct HereTables {
    breaks: Vec<f64>,
    pieces: Vec<Vec<Here>>,
}

/// `Here` in `lane` at `x`, by the geometry's own lookups.
pub fn here_at(geom: &Geometry, lane: usize, x: f64) -> Here {
    let l = lane as u32;
    let seg = geom.seg(l, x);
    let open = |l: u32| geom.seg(l, x).is_some_and(|g| !g.accel);
    Here {
        wall: seg.filter(|g| g.wall).map(|g| g.to),
        accel: seg.is_some_and(|g| g.accel),
        enter_left: open(l + 1),
        enter_right: l > 0 && open(l - 1),
        ramps_upto: geom.ramps_upto(x) as u32,
        right: geom.rightmost_through(x).map_or(NO_LANE, |r| r as u8),
    }
}

impl HereTables {
    /// The tables of a geometry. A plain road has no finite break: one piece per lane (no wall,
    /// no ramps, `right` 0).
    pub fn new(geom: &Geometry) -> HereTables {
        // Every segment end of every lane (the rightmost through lane can change at any of
        // them), and the merge points.
        let mut breaks: Vec<f64> = geom
            .lanes
            .iter()
            .flatten()
            .flat_map(|s| [s.from, s.to])
            .chain(geom.ramps_by_x.iter().map(|r| r.0))
            .filter(|e| e.is_finite())
            .collect();
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        // One probe per piece: below the first break (f64::MIN), then each break itself.
        let pieces = (0..geom.lanes.len())
            .map(|l| {
                std::iter::once(f64::MIN)
                    .chain(breaks.iter().copied())
                    .map(|x| here_at(geom, l, x))
                    .collect()
            })
            .collect();
        HereTables { breaks, pieces }
    }

    /// A cursor for a run of lookups along `lane`.
    pub fn walk(&self, lane: usize) -> HereWalk<'_> {
        HereWalk {
            breaks: &self.breaks,
            pieces: &self.pieces[lane],
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
            here: Here::default(),
            i: usize::MAX,
        }
    }
}

/// See `HereTables::walk`: `at(x)` is `here_at(geom, lane, x)` for every finite `x`.
pub struct HereWalk<'a> {
    breaks: &'a [f64],
    pieces: &'a [Here],
    /// The answer `here` holds for every x in [lo, hi) (empty until the first lookup).
    lo: f64,
    hi: f64,
    here: Here,
    /// The piece of the last lookup.
    i: usize,
}

impl HereWalk<'_> {
    #[inline]
    pub fn at(&mut self, x: f64) -> Here {
        if x >= self.lo && x < self.hi {
            return self.here;
        }
        self.lookup(x)
    }

    #[cold]
    fn lookup(&mut self, x: f64) -> Here {
        let b = self.breaks;
        // Along a front-first lane list x falls: step down from the piece of the last lookup
        // (`i` pieces' breaks at or before x: the same index as `partition_point`, since the
        // breaks are sorted); otherwise search.
        let i = if x < self.lo && self.i <= b.len() {
            let mut i = self.i;
            while i > 0 && b[i - 1] > x {
                i -= 1;
            }
            i
        } else {
            b.partition_point(|&e| e <= x)
        };
        self.i = i;
        self.lo = if i > 0 { b[i - 1] } else { f64::NEG_INFINITY };
        self.hi = b.get(i).copied().unwrap_or(f64::INFINITY);
        self.here = self.pieces[i];
        self.here
    }
}

/// The walls of the two lanes beside one lane list (`Geometry::wall_ahead` of lane ± 1), for
/// the lookups of the decide phase along that list: one walk per side lane instead of a
/// segment search per query. The queries come front to back with the list, so the walks
/// mostly stay in their piece or step down one.
pub struct SideWalls<'a> {
    lane: usize,
    left: Option<HereWalk<'a>>,
    right: Option<HereWalk<'a>>,
}

impl<'a> SideWalls<'a> {
    /// For the list of `lane` (of `n_lanes`).
    pub fn new(tables: &'a HereTables, lane: usize, n_lanes: usize) -> SideWalls<'a> {
        SideWalls {
            lane,
            left: (lane + 1 < n_lanes).then(|| tables.walk(lane + 1)),
            right: (lane > 0).then(|| tables.walk(lane - 1)),
        }
    }

    /// `geom.wall_ahead(target, x)` on a road that is not plain, for a finite `x`. A target
    /// that is not beside this list's lane (a vehicle off its list) takes the geometry's own
    /// lookup.
    #[inline]
    pub fn wall_ahead(&mut self, geom: &Geometry, target: usize, x: f64) -> Option<f64> {
        let walk = if target == self.lane + 1 {
            self.left.as_mut()
        } else if target == self.lane.wrapping_sub(1) {
            self.right.as_mut()
        } else {
            None
        };
        match walk {
            Some(w) => w.at(x).wall,
            None => geom.wall_ahead(target as u32, x),
        }
    }
}
