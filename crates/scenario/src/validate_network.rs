//! Validation of the `[network]` section (issue 4): corridor bounds, lane stretches, ramps,
//! demand series and detector spacing, split from `validate.rs` by responsibility. Positions
//! are checked in the file's corridor coordinate and converted to engine coordinates
//! (x_engine = x_file − network.start_m).

use super::{quoted, Checker, Num};
use crate::demand_scales;
use crate::limits;
use crate::network::{
    offset_series, offset_step, through_lanes, RampStations, Spacing, Stretch, MAX_LANE_COUNT,
};
use crate::raw::{num, RawNetwork};
use platoonsim_sim::config::{Network, OffRamp, OnRamp};
use std::path::Path;

#[path = "validate_ramps.rs"]
mod ramps;
use ramps::{off_ramps, on_ramps, ramp_ids};

#[path = "validate_behaviour.rs"]
pub mod behaviour;

/// Defaults of the optional `[network]` keys.
pub mod defaults {
    pub const INTERVAL_S: f64 = 900.0;
    pub const DEMAND_OFFSET_S: f64 = 0.0;
    pub const BASE_DEMAND_MULTIPLIER: f64 = 1.0;
    pub const RAMP_SPEED_KMH: f64 = 90.0;
    pub const ACCEL_LANE_M: f64 = 250.0;
}

/// What the rest of validation needs from a checked `[network]`. Values are only meaningful
/// if no problem was reported.
pub(super) struct Checked {
    /// Lateral lane positions (largest lane count + 1 for the acceleration lanes).
    pub lanes: u32,
    /// Corridor coordinate of the entrance (`network.start_m`).
    pub origin: f64,
    /// Corridor end coordinate (`network.end_m`), if the bounds are valid.
    pub end: Option<f64>,
    /// Road length (engine), if the bounds are valid.
    pub length: Option<f64>,
    pub network: Network,
    pub on_ids: Vec<String>,
    pub off_ids: Vec<String>,
    /// The field stations at the ramps (`station`), which name their counters.
    pub stations: RampStations,
    pub spacing: Spacing,
}

/// A per-interval series: present, non-empty, at most [`limits::MAX_INTERVALS`] long, every
/// value finite and in [0, `hi`] (`why` explains the bound), and (if `intervals` is given) as
/// long as `network.mainline_vph`. Returns the values (empty if missing or too long).
fn series(
    c: &mut Checker,
    field: &str,
    v: &Option<Vec<f64>>,
    (hi, why): (f64, &str),
    intervals: Option<usize>,
    what: &str,
) -> Vec<f64> {
    // Only the first few bad values of a series are listed; the rest are counted.
    const LISTED: usize = 3;
    let Some(v) = v else {
        c.missing(field, what);
        return Vec::new();
    };
    if v.is_empty() {
        c.push(field, "[]", "must have at least one interval");
        return Vec::new();
    }
    if v.len() > limits::MAX_INTERVALS {
        c.push(
            field,
            format!("({} values)", v.len()),
            format!(
                "must have at most {} intervals (7 days of one-minute intervals)",
                limits::MAX_INTERVALS
            ),
        );
        return Vec::new();
    }
    let allowed = format!("must be in [0, {}]{why}", num(hi));
    let bad: Vec<usize> = (0..v.len())
        .filter(|&k| !(v[k].is_finite() && v[k] >= 0.0 && v[k] <= hi))
        .collect();
    for &k in bad.iter().take(LISTED) {
        c.push(format!("{field}[{k}]"), num(v[k]), allowed.clone());
    }
    if bad.len() > LISTED {
        c.push(
            field,
            format!("({} values out of range)", bad.len()),
            format!("every value {allowed}"),
        );
    }
    if let Some(n) = intervals.filter(|&n| n != v.len()) {
        c.push(
            field,
            format!("({} values)", v.len()),
            format!(
                "must have {n} intervals, as many as network.mainline_vph (one per network.interval_s)"
            ),
        );
    }
    v.clone()
}

/// A required finite position; `None` (after reporting) if missing or not finite.
fn position(c: &mut Checker, field: &str, v: Option<f64>, what: &str) -> Option<f64> {
    let n = c.req(field, v, what)?;
    let m = limits::MAX_COORDINATE_M;
    c.check(
        field,
        n,
        n.v.abs() <= m,
        format!("must be a finite number in [-{}, {}] m", num(m), num(m)),
    )
    .then_some(n.v)
}

/// `network.demand_offset_s`: a whole number of seconds (or a multiple of `network.interval_s`)
/// in [0, span of the series). Returns the interval of the shifted series if the offset is
/// valid and not 0 (`None` otherwise, after reporting any problem).
fn demand_offset(
    c: &mut Checker,
    offset: Num,
    interval: Num,
    intervals: Option<usize>,
) -> Option<f64> {
    let field = "network.demand_offset_s";
    if !(limits::MIN_INTERVAL_S..=limits::MAX_DURATION_S).contains(&interval.v) {
        // network.interval_s is reported; only the offset's own range can be checked.
        c.non_negative(field, offset);
        return None;
    }
    let span = intervals.map(|n| n as f64 * interval.v);
    let range = match span {
        Some(s) => format!(
            "in [0, {}) s (the span of the demand series: {} intervals of network.interval_s = {} s)",
            num(s),
            intervals.unwrap_or(0),
            num(interval.v)
        ),
        None => "a finite number >= 0".to_string(),
    };
    let in_range = offset.v >= 0.0 && span.is_none_or(|s| offset.v < s);
    if !c.check(field, offset, in_range, format!("must be {range}")) {
        return None;
    }
    let Some(step) = offset_step(interval.v, offset.v) else {
        c.push(
            field,
            offset.shown(),
            format!(
                "must be a whole number of seconds or a multiple of network.interval_s = {} s, {range}",
                num(interval.v)
            ),
        );
        return None;
    };
    (offset.v > 0.0 && span.is_some()).then_some(step)
}

pub(super) fn check_network(
    c: &mut Checker,
    n: &RawNetwork,
    run: &super::run::Run,
    base_dir: Option<&Path>,
) -> Checked {
    let penetration = run.penetration.v;
    // The sections in the order their problems are reported.
    let b = bounds(c, n);
    let origin = b.start.unwrap_or(f64::NAN);
    let length = b.span.map(|(s, e)| e - s);
    let d = demand(c, n, penetration, base_dir);
    let (ramp_speed, lane_caps) = speeds(c, n);
    let stretches = stretches(c, n, &b, origin);
    let (lanes, through) = through_lanes(&stretches);
    let ids = ramp_ids(c, n);
    let n_on = n.on_ramps.len();
    let on_ramps = on_ramps(c, n, &ids[..n_on], &b, origin, &d, run);
    let off_ramps = off_ramps(c, n, &ids[n_on..], &b, origin, &d);
    let spacing = detector_spacing(c, n, length);
    let behaviour = behaviour::behaviour(c, n, &b, origin);
    let (mainline, on_ramps, off_ramps, interval_s) =
        shifted(c, &d, d.mainline.clone(), on_ramps, off_ramps);

    Checked {
        lanes,
        origin,
        end: b.span.map(|(_, e)| e),
        length,
        network: Network {
            origin_m: origin,
            through_lanes: through,
            on_ramps,
            off_ramps,
            interval_s,
            mainline_vph: mainline,
            demand_scale: d.base.v * d.scale.v,
            ramp_speed_kmh: ramp_speed.v,
            lane_speed_limits_kmh: lane_caps,
            cross_lane_friction: n.cross_lane_friction,
            behaviour,
        },
        on_ids: ids[..n_on].iter().map(|(_, id, _)| id.clone()).collect(),
        off_ids: ids[n_on..].iter().map(|(_, id, _)| id.clone()).collect(),
        stations: super::stations::check(c, n),
        spacing,
    }
}

/// The corridor's bounds as checked: the start and end that are valid positions, and the
/// span if the end also lies after the start (and not too far).
struct Bounds {
    start: Option<f64>,
    end: Option<f64>,
    span: Option<(f64, f64)>,
}

impl Bounds {
    /// Report a position `x` outside the corridor (nothing to check without a valid span).
    fn inside(&self, c: &mut Checker, field: &str, x: f64) {
        if let Some((s, e)) = self.span {
            c.value(
                field,
                x,
                x > s && x < e,
                &format!(
                    "must lie inside the corridor (network.start_m, network.end_m) = ({}, {})",
                    num(s),
                    num(e)
                ),
            );
        }
    }
}

/// `network.start_m` and `network.end_m`.
fn bounds(c: &mut Checker, n: &RawNetwork) -> Bounds {
    let start = position(
        c,
        "network.start_m",
        n.start_m,
        "the corridor coordinate of the mainline entrance (m)",
    );
    let end = position(
        c,
        "network.end_m",
        n.end_m,
        "the corridor coordinate of the road end (m), > network.start_m",
    );
    let span = match (start, end) {
        (Some(s), Some(e)) if e > s + limits::MAX_LENGTH_M => {
            c.value(
                "network.end_m",
                e,
                false,
                &format!(
                    "must be at most network.start_m + {} = {} (a corridor is at most {} km long)",
                    num(limits::MAX_LENGTH_M),
                    num(s + limits::MAX_LENGTH_M),
                    num(limits::MAX_LENGTH_M / 1000.0)
                ),
            );
            None
        }
        (Some(s), Some(e)) if e > s => Some((s, e)),
        (Some(s), Some(e)) => {
            c.value(
                "network.end_m",
                e,
                false,
                &format!("must be > network.start_m = {}", num(s)),
            );
            None
        }
        _ => None,
    };
    Bounds { start, end, span }
}

/// What the demand keys give: the interval, the multipliers, the mainline series and its
/// length, the on-ramp demand cap, and the offset with the step it refines the series to.
struct Demand {
    interval: Num,
    base: Num,
    scale: Num,
    ramp_cap: (f64, String),
    mainline: Vec<f64>,
    intervals: Option<usize>,
    offset: Num,
    shift: Option<f64>,
}

/// The demand keys: interval, multipliers (the scale from the named table at this
/// penetration), the mainline series and the time offset.
fn demand(c: &mut Checker, n: &RawNetwork, penetration: f64, base_dir: Option<&Path>) -> Demand {
    let interval = c.opt(n.interval_s, defaults::INTERVAL_S);
    c.check(
        "network.interval_s",
        interval,
        (limits::MIN_INTERVAL_S..=limits::MAX_DURATION_S).contains(&interval.v),
        format!(
            "must be in [{}, {}] s",
            num(limits::MIN_INTERVAL_S),
            num(limits::MAX_DURATION_S)
        ),
    );
    let base = c.opt(n.base_demand_multiplier, defaults::BASE_DEMAND_MULTIPLIER);
    c.non_negative("network.base_demand_multiplier", base);
    // The scale defaults to the table the file names, at this penetration, and to 1 without
    // one: no corridor gets another corridor's calibration silently.
    let table_scale = n.demand_scale_table.as_deref().and_then(|r| {
        match crate::tables::demand_scales(r, base_dir) {
            Ok(rows) => Some(demand_scales::at(
                &rows,
                penetration,
                demand_scales::FALLBACK,
            )),
            Err(e) => {
                c.push(
                    "network.demand_scale_table",
                    quoted(r),
                    format!("must name a table of demand scales by penetration: {e}"),
                );
                None
            }
        }
    });
    let scale = c.opt(
        n.demand_scale,
        table_scale.unwrap_or(demand_scales::FALLBACK),
    );
    c.non_negative("network.demand_scale", scale);
    // Entrance demands are capped after scaling, at 10,000 veh/h per entrance lane: the lanes
    // open at the mainline entrance, one lane for an on-ramp.
    let product = base.v * scale.v;
    let product = if product.is_finite() && product > 0.0 {
        product
    } else {
        1.0
    };
    let entry_lanes = match n.lanes.first().and_then(|l| l.count) {
        Some(k) if (1..=MAX_LANE_COUNT).contains(&k) => k,
        _ => MAX_LANE_COUNT,
    };
    let scaled = if base.v * scale.v == 1.0 {
        String::new()
    } else {
        format!(
            ", divided by network.base_demand_multiplier × network.demand_scale = {}",
            num(base.v * scale.v)
        )
    };
    let cap = num(limits::MAX_DEMAND_VPHPL);
    let mainline_cap = (
        limits::MAX_DEMAND_VPHPL * f64::from(entry_lanes) / product,
        format!(" veh/h ({cap} veh/h per lane open at the entrance × {entry_lanes} lanes{scaled})"),
    );
    let ramp_cap = (
        limits::MAX_DEMAND_VPHPL / product,
        format!(" veh/h (an on-ramp is one lane: {cap} veh/h{scaled})"),
    );
    let mainline = series(
        c,
        "network.mainline_vph",
        &n.mainline_vph,
        (mainline_cap.0, &mainline_cap.1),
        None,
        "the demand at the mainline entrance per interval (veh/h, all lanes)",
    );
    let intervals = (!mainline.is_empty()).then_some(mainline.len());
    let offset = c.opt(n.demand_offset_s, defaults::DEMAND_OFFSET_S);
    let shift = demand_offset(c, offset, interval, intervals);
    Demand {
        interval,
        base,
        scale,
        ramp_cap,
        mainline,
        intervals,
        offset,
        shift,
    }
}

/// The ramp speed, the lane-based desired-speed caps and the cross-lane friction (spec 2.7).
fn speeds(c: &mut Checker, n: &RawNetwork) -> (Num, Vec<f64>) {
    let speed_cap = limits::MAX_SPEED_THRESHOLD_KMH;
    let ramp_speed = c.opt(n.ramp_speed_kmh, defaults::RAMP_SPEED_KMH);
    c.check(
        "network.ramp_speed_kmh",
        ramp_speed,
        ramp_speed.v > 0.0 && ramp_speed.v <= speed_cap,
        format!("must be in (0, {}] km/h", num(speed_cap)),
    );
    // Lane-based desired-speed caps (spec 2.7): off unless given.
    let lane_caps = n.lane_speed_limits_kmh.clone().unwrap_or_default();
    if lane_caps.len() > limits::MAX_LANE_SPEED_LIMITS {
        c.push(
            "network.lane_speed_limits_kmh",
            format!("({} values)", lane_caps.len()),
            format!("at most {} values", limits::MAX_LANE_SPEED_LIMITS),
        );
    }
    for (i, &cap) in lane_caps
        .iter()
        .enumerate()
        .take(limits::MAX_LANE_SPEED_LIMITS)
    {
        let f = format!("network.lane_speed_limits_kmh[{i}]");
        let cap = c.opt(Some(cap), cap);
        c.check(
            &f,
            cap,
            cap.v > 0.0 && cap.v <= speed_cap,
            format!("must be in (0, {}] km/h", num(speed_cap)),
        );
    }
    // Cross-lane friction (spec 2.7): off unless given; c_fr in (0, 1], 1 = off.
    if let Some(fr) = n.cross_lane_friction {
        c.value(
            "network.cross_lane_friction",
            fr,
            fr > 0.0 && fr <= 1.0,
            "must be in (0, 1] (1 = off)",
        );
    }
    (ramp_speed, lane_caps)
}

/// `[[network.lanes]]`: the stretches tile [start_m, end_m) in order; their engine
/// coordinates (x − `origin`). Also the entry counts of the three lists.
fn stretches(c: &mut Checker, n: &RawNetwork, b: &Bounds, origin: f64) -> Vec<Stretch> {
    let (start, end) = (b.start, b.end);
    if n.lanes.is_empty() {
        c.push(
            "network.lanes",
            "[]",
            "at least one [[network.lanes]] stretch (from_m, to_m, count) is required",
        );
    }
    let counts = [
        ("network.lanes", n.lanes.len(), limits::MAX_STRETCHES),
        ("network.on_ramps", n.on_ramps.len(), limits::MAX_RAMPS),
        ("network.off_ramps", n.off_ramps.len(), limits::MAX_RAMPS),
    ];
    for (field, len, max) in counts {
        if len > max {
            c.push(
                field,
                format!("({len} entries)"),
                format!("at most {max} entries"),
            );
        }
    }
    let tile = "the stretches must tile [network.start_m, network.end_m) in order, without gaps or overlaps";
    let mut prev: Option<(f64, String)> =
        start.map(|s| (s, format!("network.start_m = {}", num(s))));
    let mut stretches = Vec::with_capacity(n.lanes.len());
    for (i, l) in n.lanes.iter().enumerate() {
        let f_field = format!("network.lanes[{i}].from_m");
        let t_field = format!("network.lanes[{i}].to_m");
        let from = position(c, &f_field, l.from_m, "start of the stretch (m)");
        let to = position(c, &t_field, l.to_m, "end of the stretch (m)");
        let count = match l.count {
            None => {
                c.missing(
                    &format!("network.lanes[{i}].count"),
                    &format!("the number of through lanes, 1 to {MAX_LANE_COUNT}"),
                );
                None
            }
            Some(k) if !(1..=MAX_LANE_COUNT).contains(&k) => {
                c.push(
                    format!("network.lanes[{i}].count"),
                    k.to_string(),
                    format!("must be an integer from 1 to {MAX_LANE_COUNT}"),
                );
                None
            }
            Some(k) => Some(k),
        };
        if let (Some(f), Some((p, what))) = (from, &prev) {
            if f != *p {
                let kind = if f > *p { "a gap" } else { "an overlap" };
                c.value(
                    &f_field,
                    f,
                    false,
                    &format!("must equal {what} ({kind}; {tile})"),
                );
            }
        }
        if let (Some(f), Some(t)) = (from, to) {
            c.value(
                &t_field,
                t,
                t > f,
                &format!("must be > network.lanes[{i}].from_m = {}", num(f)),
            );
        }
        prev = to.map(|t| (t, format!("network.lanes[{i}].to_m = {}", num(t))));
        if let (Some(f), Some(t), Some(k)) = (from, to, count) {
            stretches.push(Stretch {
                from_m: f - origin,
                to_m: t - origin,
                count: k,
            });
        }
    }
    if let (Some((p, _)), Some(e), Some(last)) = (&prev, end, n.lanes.len().checked_sub(1)) {
        if *p != e {
            c.value(
                &format!("network.lanes[{last}].to_m"),
                *p,
                false,
                &format!("must equal network.end_m = {} ({tile})", num(e)),
            );
        }
    }
    stretches
}

/// `[network.detectors]`: the spacing of the generated detectors (`length`: the corridor's,
/// if its bounds are valid).
fn detector_spacing(c: &mut Checker, n: &RawNetwork, length: Option<f64>) -> Spacing {
    let d = &n.detectors;
    let spacing_default = Spacing::default();
    let spacing = |c: &mut Checker, field: &str, n: Num| {
        c.check(
            field,
            n,
            (0.0..=limits::MAX_LENGTH_M).contains(&n.v),
            format!("must be in [0, {}] m", num(limits::MAX_LENGTH_M)),
        );
    };
    let up = c.opt(d.upstream_of_ramps_m, spacing_default.upstream_of_ramps_m);
    spacing(c, "network.detectors.upstream_of_ramps_m", up);
    let down = c.opt(
        d.downstream_of_onramps_m,
        spacing_default.downstream_of_onramps_m,
    );
    spacing(c, "network.detectors.downstream_of_onramps_m", down);
    let before_end = c.opt(d.before_end_m, spacing_default.before_end_m);
    match length {
        Some(l) => {
            c.check(
                "network.detectors.before_end_m",
                before_end,
                before_end.v > 0.0 && before_end.v < l,
                format!(
                    "must be > 0 and < the corridor length network.end_m − network.start_m = {}",
                    num(l)
                ),
            );
        }
        None => {
            c.positive("network.detectors.before_end_m", before_end);
        }
    }
    Spacing {
        upstream_of_ramps_m: up.v,
        downstream_of_onramps_m: down.v,
        before_end_m: before_end.v,
    }
}

/// The demand time offset: every series is read at clock + offset, refined to the offset's
/// step if it is not a multiple of the interval. Returns the series and their interval.
fn shifted(
    c: &mut Checker,
    d: &Demand,
    mut mainline: Vec<f64>,
    mut on_ramps: Vec<OnRamp>,
    mut off_ramps: Vec<OffRamp>,
) -> (Vec<f64>, Vec<OnRamp>, Vec<OffRamp>, f64) {
    let (interval, offset, shift) = (d.interval, d.offset, d.shift);
    let mut interval_s = interval.v;
    // The offset may refine the series to a shorter step (their common divisor): bound the
    // values that would make before making them.
    let shift = shift.filter(|&step| {
        let span = mainline.len() as f64 * interval.v - offset.v;
        let values = (span / step).round().max(1.0) * (1 + on_ramps.len() + off_ramps.len()) as f64;
        let ok = values <= limits::MAX_SERIES_VALUES as f64;
        if !ok {
            c.push(
                "network.demand_offset_s",
                offset.shown(),
                format!(
                    "refines the demand series to steps of {} s, {} values in all; at most {}: \
                     use an offset that is a multiple of network.interval_s = {} s",
                    num(step),
                    num(values),
                    limits::MAX_SERIES_VALUES,
                    num(interval.v)
                ),
            );
        }
        ok
    });
    if let Some(step) = shift {
        let f = |v: &[f64]| offset_series(v, interval.v, offset.v, step);
        mainline = f(&mainline);
        on_ramps
            .iter_mut()
            .for_each(|r| r.demand_vph = f(&r.demand_vph));
        off_ramps
            .iter_mut()
            .for_each(|r| r.exit_fraction = f(&r.exit_fraction));
        interval_s = step;
    }
    (mainline, on_ramps, off_ramps, interval_s)
}
