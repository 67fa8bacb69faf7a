//! Pure helpers of the `[network]` section (issue 4), shared by validation (file → engine) and
//! the resolved-file writer (engine → file):
//!
//! * lane counts per stretch ↔ the engine's lateral lane extents ([`through_lanes`],
//!   [`stretches`]);
//! * ramp ids inside the engine's ramp names ([`engine_name`], [`split_name`]);
//! * the generated detectors, as in the paper ([`detectors`]);
//! * the demand time offset `network.demand_offset_s` ([`offset_step`], [`offset_series`]).
//!
//! Lateral lane convention (see `platoonsim_sim::config::Network`): lanes are numbered from the
//! right; index 0 is reserved for the acceleration lanes beside the widest section. With M the
//! largest lane count, a stretch with `count` lanes has its through lanes at indices
//! `1 + M − count ..= M` (lanes are added and dropped on the right), so the leftmost lane M — the
//! PD lane — exists everywhere, and the road has M + 1 lateral positions.

use platoonsim_sim::config::{DetectorKind, LaneExtent, Network};
use platoonsim_sim::DetectorSpec;

/// Largest lane count of a stretch: with the reserved acceleration-lane position this is the
/// engine's limit of 8 lateral positions.
pub const MAX_LANE_COUNT: u32 = 7;

/// One stretch of constant lane count, `[from_m, to_m)` in engine coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stretch {
    pub from_m: f64,
    pub to_m: f64,
    pub count: u32,
}

/// The engine's lateral positions (M + 1) and through-lane extents for stretches that tile the
/// road in order. One extent per lane index per maximal run of consecutive stretches where the
/// lane is open, sorted by lane index, then position. Empty input gives `(1, [])`.
pub fn through_lanes(stretches: &[Stretch]) -> (u32, Vec<LaneExtent>) {
    let m = stretches.iter().map(|s| s.count).max().unwrap_or(0);
    let mut extents = Vec::new();
    for lane in 1..=m {
        // Open on a stretch with count c iff lane >= 1 + M − c.
        let mut open: Option<(f64, f64)> = None;
        for s in stretches {
            if lane + s.count > m {
                open = Some(match open {
                    Some((from, _)) => (from, s.to_m),
                    None => (s.from_m, s.to_m),
                });
            } else if let Some((from_m, to_m)) = open.take() {
                extents.push(LaneExtent { lane, from_m, to_m });
            }
        }
        if let Some((from_m, to_m)) = open {
            extents.push(LaneExtent { lane, from_m, to_m });
        }
    }
    (m + 1, extents)
}

/// The inverse of [`through_lanes`]: lane counts per stretch (acceleration-lane index 0
/// ignored), consecutive stretches of equal count merged. Exact for extents that
/// [`through_lanes`] made; for others it counts the lanes open on each stretch.
pub fn stretches(extents: &[LaneExtent]) -> Vec<Stretch> {
    let mut cuts: Vec<f64> = extents
        .iter()
        .filter(|e| e.lane > 0)
        .flat_map(|e| [e.from_m, e.to_m])
        .collect();
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let mut out: Vec<Stretch> = Vec::new();
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let count = extents
            .iter()
            .filter(|e| e.lane > 0 && e.from_m <= a && e.to_m >= b)
            .count() as u32;
        match out.last_mut() {
            Some(last) if last.count == count && last.to_m == a => last.to_m = b,
            _ => out.push(Stretch {
                from_m: a,
                to_m: b,
                count,
            }),
        }
    }
    out
}

/// Default id of on-ramp `i` (0-based): `OR1`, `OR2`, …
pub fn default_on_id(i: usize) -> String {
    format!("OR{}", i + 1)
}

/// Default id of off-ramp `i` (0-based): `FR1`, `FR2`, …
pub fn default_off_id(i: usize) -> String {
    format!("FR{}", i + 1)
}

/// Whether `id` can name a ramp: non-empty, letters, digits, `_`, `-`, `.` only (it is part of
/// detector names and of the engine's ramp name).
pub fn valid_id(id: &str) -> bool {
    !id.is_empty()
        && id
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'))
}

/// The engine's ramp name: `"OR7: Calvine Rd WB"`, or just the id if the name is the id.
pub fn engine_name(id: &str, name: &str) -> String {
    if name == id {
        id.to_string()
    } else {
        format!("{id}: {name}")
    }
}

/// `(id, name)` of an engine ramp name made by [`engine_name`].
pub fn split_name(engine: &str) -> (String, String) {
    match engine.split_once(": ") {
        Some((id, name)) if valid_id(id) => (id.to_string(), name.to_string()),
        _ => (engine.to_string(), engine.to_string()),
    }
}

/// Where the generated detectors go (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spacing {
    /// Upstream of every on- and off-ramp (paper: 50 m).
    pub upstream_of_ramps_m: f64,
    /// Downstream of every on-ramp (paper: 50 m).
    pub downstream_of_onramps_m: f64,
    /// The `end` (exit) detector this far before the road end.
    pub before_end_m: f64,
}

impl Default for Spacing {
    fn default() -> Self {
        Spacing {
            upstream_of_ramps_m: 50.0,
            downstream_of_onramps_m: 50.0,
            before_end_m: 10.0,
        }
    }
}

/// The field stations at the ramps (`station` keys), by ramp index; they name the ramps'
/// counters.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RampStations {
    pub on: Vec<Option<String>>,
    pub off: Vec<Option<String>>,
}

/// Name of the generated exit detector on the main lanes.
pub const END_DETECTOR: &str = "end";

/// The generated detectors of a network (engine coordinates): first the mainline detectors
/// sorted by position — `{id}-up` 50 m upstream of every ramp, `{id}-down` 50 m downstream of
/// every on-ramp, and `end` (an exit) before the road end — with exact duplicate positions
/// dropped (`end` wins, then the upstream-most ramp) and positions outside (0, length)
/// skipped; then one `{id}-off` exit detector per off-ramp, in ramp order (named by the ramp's
/// field station instead, if it has one); then a counter per on-ramp with a station, named by
/// it, in ramp order.
pub fn detectors(
    net: &Network,
    length_m: f64,
    on_ids: &[String],
    off_ids: &[String],
    stations: &RampStations,
    s: &Spacing,
) -> Vec<DetectorSpec> {
    let mut candidates = vec![DetectorSpec {
        name: END_DETECTOR.to_string(),
        position_m: length_m - s.before_end_m,
        kind: DetectorKind::Mainline,
        exit: true,
    }];
    // Ramps in downstream order (an on-ramp before an off-ramp at the same point).
    let mut ramps: Vec<(f64, bool, &str)> = Vec::new();
    for (r, id) in net.on_ramps.iter().zip(on_ids) {
        ramps.push((r.x_m, true, id));
    }
    for (r, id) in net.off_ramps.iter().zip(off_ids) {
        ramps.push((r.x_m, false, id));
    }
    ramps.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.cmp(&a.1)));
    for (x, on, id) in ramps {
        candidates.push(DetectorSpec::mainline(
            &format!("{id}-up"),
            x - s.upstream_of_ramps_m,
        ));
        if on {
            candidates.push(DetectorSpec::mainline(
                &format!("{id}-down"),
                x + s.downstream_of_onramps_m,
            ));
        }
    }
    candidates.retain(|d| d.position_m > 0.0 && d.position_m < length_m);
    candidates.sort_by(|a, b| a.position_m.total_cmp(&b.position_m));
    candidates.dedup_by(|later, kept| later.position_m == kept.position_m);
    for (i, (r, id)) in net.off_ramps.iter().zip(off_ids).enumerate() {
        let station = stations.off.get(i).cloned().flatten();
        candidates.push(DetectorSpec {
            name: station.unwrap_or_else(|| format!("{id}-off")),
            position_m: r.x_m,
            kind: DetectorKind::OffRamp { ramp: i },
            exit: true,
        });
    }
    for (i, r) in net.on_ramps.iter().enumerate() {
        if let Some(Some(station)) = stations.on.get(i) {
            candidates.push(DetectorSpec {
                name: station.clone(),
                position_m: r.x_m,
                kind: DetectorKind::OnRamp { ramp: i },
                exit: false,
            });
        }
    }
    candidates
}

/// The interval of the demand series after a time offset of `offset_s` (`network.demand_offset_s`)
/// on series of `interval_s`: `interval_s` itself if the offset is a whole number of intervals,
/// otherwise the largest step that divides both (their greatest common divisor in whole seconds),
/// so that the shifted series are exact. `None` if there is no such step (the offset is not a
/// multiple of the interval and one of them is not a whole number of seconds).
pub fn offset_step(interval_s: f64, offset_s: f64) -> Option<f64> {
    if !(interval_s.is_finite() && interval_s > 0.0 && offset_s.is_finite() && offset_s >= 0.0) {
        return None;
    }
    let k = offset_s / interval_s;
    if k == k.floor() {
        return Some(interval_s);
    }
    let whole = |v: f64| v == v.floor() && v < 9.0e15;
    if !(whole(interval_s) && whole(offset_s)) {
        return None;
    }
    let (mut a, mut b) = (interval_s as u64, offset_s as u64);
    while b != 0 {
        (a, b) = (b, a % b);
    }
    Some(a as f64)
}

/// One per-interval series read at `t + offset_s` instead of `t`: value `j` of the result covers
/// `[j·step, (j+1)·step)` of the simulation clock and is the input value of the interval that
/// contains `offset_s + j·step`. The result spans the input's remaining time, `n·interval_s −
/// offset_s`; past it the engine holds the last value, so the last input interval holds beyond
/// the end, as without an offset. `step` comes from [`offset_step`]; an offset at or past the end
/// of the series gives the last value alone.
pub fn offset_series(v: &[f64], interval_s: f64, offset_s: f64, step: f64) -> Vec<f64> {
    if offset_s == 0.0 || v.is_empty() {
        return v.to_vec();
    }
    let span = v.len() as f64 * interval_s - offset_s;
    let count = (span / step).round().max(1.0) as usize;
    (0..count)
        .map(|j| {
            let k = ((offset_s + j as f64 * step) / interval_s).floor() as usize;
            v[k.min(v.len() - 1)]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use platoonsim_sim::config::{OffRamp, OnRamp};

    fn st(from_m: f64, to_m: f64, count: u32) -> Stretch {
        Stretch {
            from_m,
            to_m,
            count,
        }
    }

    fn ext(lane: u32, from_m: f64, to_m: f64) -> LaneExtent {
        LaneExtent { lane, from_m, to_m }
    }

    #[test]
    fn three_to_four_lanes_adds_lane_one_on_the_right() {
        let (lanes, e) = through_lanes(&[st(0.0, 1000.0, 3), st(1000.0, 3000.0, 4)]);
        assert_eq!(lanes, 5);
        assert_eq!(
            e,
            vec![
                ext(1, 1000.0, 3000.0),
                ext(2, 0.0, 3000.0),
                ext(3, 0.0, 3000.0),
                ext(4, 0.0, 3000.0)
            ]
        );
    }

    #[test]
    fn a_dropped_and_re_added_lane_has_two_extents() {
        let s = [
            st(0.0, 10.0, 3),
            st(10.0, 20.0, 2),
            st(20.0, 30.0, 2),
            st(30.0, 40.0, 3),
        ];
        let (lanes, e) = through_lanes(&s);
        assert_eq!(lanes, 4);
        assert_eq!(
            e,
            vec![
                ext(1, 0.0, 10.0),
                ext(1, 30.0, 40.0),
                ext(2, 0.0, 40.0),
                ext(3, 0.0, 40.0)
            ]
        );
        // Back: equal neighbours merged.
        assert_eq!(
            stretches(&e),
            vec![st(0.0, 10.0, 3), st(10.0, 30.0, 2), st(30.0, 40.0, 3)]
        );
    }

    #[test]
    fn sr99_layout_round_trips() {
        let s = [
            st(0.0, 6234.0, 3),
            st(6234.0, 15552.0, 4),
            st(15552.0, 17660.0, 5),
        ];
        let (lanes, e) = through_lanes(&s);
        assert_eq!(lanes, 6);
        assert_eq!(e.len(), 5);
        assert_eq!(e[0], ext(1, 15552.0, 17660.0));
        assert_eq!(e[1], ext(2, 6234.0, 17660.0));
        assert_eq!(e[4], ext(5, 0.0, 17660.0));
        assert_eq!(stretches(&e), s.to_vec());
        assert_eq!(through_lanes(&[]), (1, vec![]));
    }

    #[test]
    fn ramp_names_carry_the_id() {
        assert_eq!(engine_name("OR7", "Calvine Rd WB"), "OR7: Calvine Rd WB");
        assert_eq!(engine_name("OR7", "OR7"), "OR7");
        for (id, name) in [("OR7", "Calvine Rd WB"), ("x", "x"), ("a.b-c_1", "Rd: 2")] {
            assert_eq!(split_name(&engine_name(id, name)), (id.into(), name.into()));
        }
        assert!(!valid_id("") && !valid_id("OR 1") && !valid_id("a:b"));
    }

    #[test]
    fn detectors_as_in_the_paper() {
        let net = Network {
            origin_m: 0.0,
            through_lanes: vec![],
            on_ramps: vec![
                OnRamp {
                    name: "a".into(),
                    x_m: 30.0,
                    accel_lane_m: 250.0,
                    ramp_length_m: 300.0,
                    demand_vph: vec![0.0],
                    meter: None,
                    penetration: None,
                },
                OnRamp {
                    name: "b".into(),
                    x_m: 1000.0,
                    accel_lane_m: 250.0,
                    ramp_length_m: 300.0,
                    demand_vph: vec![0.0],
                    meter: None,
                    penetration: None,
                },
            ],
            off_ramps: vec![OffRamp {
                name: "c".into(),
                x_m: 1100.0,
                exit_fraction: vec![0.1],
            }],
            interval_s: 900.0,
            mainline_vph: vec![0.0],
            demand_scale: 1.0,
            ramp_speed_kmh: 90.0,
            lane_speed_limits_kmh: Vec::new(),
            cross_lane_friction: None,
            behaviour: Vec::new(),
        };
        let on = ["OR1".to_string(), "OR2".to_string()];
        let off = ["FR1".to_string()];
        let d = detectors(
            &net,
            1200.0,
            &on,
            &off,
            &RampStations::default(),
            &Spacing::default(),
        );
        let got: Vec<(&str, f64, bool)> = d
            .iter()
            .map(|d| (d.name.as_str(), d.position_m, d.exit))
            .collect();
        // OR1-up (-20) is off the road; OR2-down (1050) and FR1-up (1050) coincide: OR2 wins.
        assert_eq!(
            got,
            vec![
                ("OR1-down", 80.0, false),
                ("OR2-up", 950.0, false),
                ("OR2-down", 1050.0, false),
                ("end", 1190.0, true),
                ("FR1-off", 1100.0, true),
            ]
        );
        assert_eq!(d[4].kind, DetectorKind::OffRamp { ramp: 0 });
        assert_eq!(d[3].kind, DetectorKind::Mainline);
    }

    #[test]
    fn offset_by_whole_intervals_drops_the_first_ones() {
        assert_eq!(offset_step(900.0, 1800.0), Some(900.0));
        let v = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(offset_series(&v, 900.0, 1800.0, 900.0), vec![3.0, 4.0]);
        assert_eq!(offset_series(&v, 900.0, 0.0, 900.0), v.to_vec());
        assert_eq!(offset_step(900.0, 0.0), Some(900.0));
    }

    #[test]
    fn offset_by_part_of_an_interval_refines_the_step() {
        // 600 s into 900 s intervals: step gcd(900, 600) = 300 s.
        assert_eq!(offset_step(900.0, 600.0), Some(300.0));
        let v = [1.0, 2.0, 3.0];
        // Clock 0-300 s reads 600-900 s (interval 0), 300-1200 s reads 900-1800 s (interval 1), ...
        assert_eq!(
            offset_series(&v, 900.0, 600.0, 300.0),
            vec![1.0, 2.0, 2.0, 2.0, 3.0, 3.0, 3.0]
        );
        assert_eq!(offset_step(900.0, 7.0), Some(1.0));
        // No exact step: a fractional offset that is not a whole number of intervals.
        assert_eq!(offset_step(900.0, 0.5), None);
        assert_eq!(offset_step(0.5, 1.0), Some(0.5));
        assert_eq!(offset_step(0.5, 0.75), None);
        assert_eq!(offset_step(900.0, -900.0), None);
        assert_eq!(offset_step(900.0, f64::NAN), None);
    }

    #[test]
    fn offset_series_reads_the_clock_plus_the_offset() {
        // Property: value at clock t equals the input at t + offset (last value held).
        let v = [5.0, 7.0, 11.0, 13.0, 17.0];
        let at = |s: &[f64], i: f64, t: f64| s[((t / i).floor() as usize).min(s.len() - 1)];
        for offset in [0.0, 100.0, 300.0, 900.0, 1000.0, 2700.0, 4400.0] {
            let step = offset_step(900.0, offset).unwrap();
            let w = offset_series(&v, 900.0, offset, step);
            for t in (0..6000).step_by(50).map(f64::from) {
                assert_eq!(at(&w, step, t), at(&v, 900.0, t + offset), "{offset} {t}");
            }
        }
    }
}
