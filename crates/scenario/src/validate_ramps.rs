//! Validation of the ramps of `[network]`: their ids (unique across on- and off-ramps, they
//! name the detectors), names, merge and diverge points, acceleration lanes and demand
//! series. Split from `validate_network.rs`, whose bounds and demand they are checked against.

use super::{defaults, position, series, Bounds, Demand};
use crate::limits;
use crate::network::{default_off_id, default_on_id, engine_name, valid_id};
use crate::raw::{num, RawNetwork};
use crate::validate::run::Run;
use crate::validate::{quoted, Checker, Num};
use platoonsim_sim::config::{OffRamp, OnRamp};

#[path = "validate_meters.rs"]
mod meters;

/// The ramp ids, on-ramps first: (field, id, defaulted), unique across on- and off-ramps
/// (they name the detectors).
pub(super) fn ramp_ids(c: &mut Checker, n: &RawNetwork) -> Vec<(String, String, bool)> {
    // (field, id, defaulted)
    let listed = |kind: &str, i: usize, id: &Option<String>, default: fn(usize) -> String| {
        let field = format!("network.{kind}_ramps[{i}].id");
        match id {
            Some(id) => (field, id.clone(), false),
            None => (field, default(i), true),
        }
    };
    let on = n.on_ramps.iter().enumerate();
    let off = n.off_ramps.iter().enumerate();
    let ids: Vec<(String, String, bool)> = on
        .map(|(i, r)| listed("on", i, &r.id, default_on_id))
        .chain(off.map(|(i, r)| listed("off", i, &r.id, default_off_id)))
        .collect();
    for (k, (field, id, defaulted)) in ids.iter().enumerate() {
        let shown = if *defaulted {
            format!("{} (default)", quoted(id))
        } else {
            quoted(id)
        };
        if !valid_id(id) {
            c.push(
                field,
                shown,
                "must be a non-empty id of letters, digits, '_', '-' and '.' (it names the ramp's detectors)",
            );
        } else if let Some((other, _, _)) = ids[..k].iter().find(|(_, o, _)| o == id) {
            c.push(
                field,
                shown,
                format!("duplicates {other}; ramp ids must be unique (they name the detectors)"),
            );
        }
    }
    ids
}

/// A ramp's display name: its `name`, which must not be blank, or its id.
fn ramp_name(c: &mut Checker, field: String, name: &Option<String>, id: &str) -> String {
    match name {
        Some(s) if s.trim().is_empty() => {
            c.push(field, quoted(s), "must be a non-empty string");
            s.clone()
        }
        Some(s) => s.clone(),
        None => id.to_string(),
    }
}

/// A ramp's `x_m` (`kind`: "on" or "off"): a position inside the corridor, downstream of the
/// previous ramp of its list (`prev_x`, updated).
fn ramp_point(
    c: &mut Checker,
    b: &Bounds,
    kind: &str,
    i: usize,
    x: Option<f64>,
    what: &str,
    prev_x: &mut Option<f64>,
) -> Option<f64> {
    let field = format!("network.{kind}_ramps[{i}].x_m");
    let x = position(c, &field, x, what)?;
    b.inside(c, &field, x);
    if let Some(p) = *prev_x {
        c.value(
            &field,
            x,
            x > p,
            &format!(
                "must be > network.{kind}_ramps[{}].x_m = {} ({kind}-ramps are listed in downstream order)",
                i - 1,
                num(p)
            ),
        );
    }
    *prev_x = Some(x);
    Some(x)
}

/// `[[network.on_ramps]]`, in downstream order, with their demand series (`ids`: theirs).
pub(super) fn on_ramps(
    c: &mut Checker,
    n: &RawNetwork,
    ids: &[(String, String, bool)],
    b: &Bounds,
    origin: f64,
    d: &Demand,
    run: &Run,
) -> Vec<OnRamp> {
    let (ramp_cap, intervals) = (&d.ramp_cap, d.intervals);
    let mut on_ramps = Vec::with_capacity(n.on_ramps.len());
    let mut prev_x: Option<f64> = None;
    for (i, r) in n.on_ramps.iter().enumerate() {
        let at = |k: &str| format!("network.on_ramps[{i}].{k}");
        let id = &ids[i].1;
        let name = ramp_name(c, at("name"), &r.name, id);
        let x = ramp_point(
            c,
            b,
            "on",
            i,
            r.x_m,
            "the merge point (m, corridor coordinate)",
            &mut prev_x,
        );
        let ramp_m = limits::MAX_RAMP_LENGTH_M;
        let ramp_allowed = format!("must be in [0, {}] m", num(ramp_m));
        let accel = c.opt(r.accel_lane_m, defaults::ACCEL_LANE_M);
        c.check(
            &at("accel_lane_m"),
            accel,
            (0.0..=ramp_m).contains(&accel.v),
            &ramp_allowed,
        );
        let ramp_len = c.req(
            &at("ramp_length_m"),
            r.ramp_length_m,
            "the ramp roadway length upstream of the merge point (m)",
        );
        if let Some(l) = ramp_len {
            c.check(
                &at("ramp_length_m"),
                l,
                (0.0..=ramp_m).contains(&l.v),
                &ramp_allowed,
            );
        }
        let demand = series(
            c,
            &at("demand_vph"),
            &r.demand_vph,
            (ramp_cap.0, &ramp_cap.1),
            intervals,
            "the ramp demand per interval (veh/h)",
        );
        let place = meters::Place {
            x_m: x,
            end_m: b.span.map(|(_, e)| e),
            accel_lane_m: accel.v,
        };
        let meter = r
            .meter
            .as_ref()
            .and_then(|m| meters::check(c, i, m, &place, run));
        if let Some(p) = r.penetration {
            let n = c.opt(Some(p), p);
            c.check(
                &at("penetration"),
                n,
                (0.0..=1.0).contains(&p),
                "must be in [0, 1] (the share of CAVs among the ramp's arrivals)",
            );
        }
        let penetration = r.penetration;
        on_ramps.push(OnRamp {
            name: engine_name(id, &name),
            x_m: x.map_or(f64::NAN, |x| x - origin),
            accel_lane_m: accel.v,
            ramp_length_m: ramp_len.map_or(f64::NAN, |n: Num| n.v),
            demand_vph: demand,
            meter,
            penetration,
        });
    }
    on_ramps
}

/// `[[network.off_ramps]]`, in downstream order, with their exit fractions (`ids`: theirs).
pub(super) fn off_ramps(
    c: &mut Checker,
    n: &RawNetwork,
    ids: &[(String, String, bool)],
    b: &Bounds,
    origin: f64,
    d: &Demand,
) -> Vec<OffRamp> {
    let intervals = d.intervals;
    let mut off_ramps = Vec::with_capacity(n.off_ramps.len());
    let mut prev_x: Option<f64> = None;
    for (i, r) in n.off_ramps.iter().enumerate() {
        let at = |k: &str| format!("network.off_ramps[{i}].{k}");
        let id = &ids[i].1;
        let name = ramp_name(c, at("name"), &r.name, id);
        let x = ramp_point(
            c,
            b,
            "off",
            i,
            r.x_m,
            "the diverge point (m, corridor coordinate)",
            &mut prev_x,
        );
        let fraction = series(
            c,
            &at("exit_fraction"),
            &r.exit_fraction,
            (1.0, ""),
            intervals,
            "the share of arriving mainline vehicles that exit here, per interval, in [0, 1]",
        );
        off_ramps.push(OffRamp {
            name: engine_name(id, &name),
            x_m: x.map_or(f64::NAN, |x| x - origin),
            exit_fraction: fraction,
        });
    }
    off_ramps
}
