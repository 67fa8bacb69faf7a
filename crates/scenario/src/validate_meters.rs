//! Validation of an on-ramp's `meter` (issue 45 item 3): its kind and the keys of that kind,
//! the rates, ALINEA's target occupancy and detector, the queue override and the hours. Split
//! from `validate_ramps.rs`; the laws are `platoonsim_model::meter`.

use crate::raw::{num, RawMeter, RawTime};
use crate::validate::run::Run;
use crate::validate::{quoted, Checker, Num};
use platoonsim_model::meter::{Alinea, DEFAULT_GAIN_VPH, DEFAULT_PERIOD_S};
use platoonsim_sim::config::{Meter, MeterLaw, MAX_METER_RATE_VPH};

/// Past a meter's detector, the default distance beyond the end of the acceleration lane (m):
/// where the merging is over and a queue it causes shows first.
const DETECTOR_PAST_ACCEL_LANE_M: f64 = 50.0;

/// Longest ALINEA control period (s).
const MAX_PERIOD_S: f64 = 3600.0;

/// Where the ramp is, for its meter's detector: the merge point and the corridor's end (file
/// coordinate), and the acceleration lane's length.
pub(super) struct Place {
    pub x_m: Option<f64>,
    pub end_m: Option<f64>,
    pub accel_lane_m: f64,
}

/// The meter of on-ramp `i`, checked; `None` (after reporting) if it has a problem.
pub(super) fn check(
    c: &mut Checker,
    i: usize,
    m: &RawMeter,
    at: &Place,
    run: &Run,
) -> Option<Meter> {
    let field = |k: &str| format!("network.on_ramps[{i}].meter.{k}");
    let before = c.problems.len();
    let kinds =
        "\"fixed\" (one vehicle per green at rate_vph) or \"alinea\" (the ALINEA feedback law)";
    let law = match m.kind.as_deref() {
        None => {
            c.missing(&field("kind"), kinds);
            None
        }
        Some("fixed") => {
            only_for(c, &field, "alinea", m);
            let rate = c.req(&field("rate_vph"), m.rate_vph, "the meter's rate (veh/h)");
            rate.map(|r| {
                check_rate(c, &field("rate_vph"), r);
                MeterLaw::Fixed { rate_vph: r.v }
            })
        }
        Some("alinea") => {
            only_for(c, &field, "fixed", m);
            alinea(c, &field, m, at)
        }
        Some(other) => {
            c.push(field("kind"), quoted(other), format!("must be {kinds}"));
            None
        }
    };
    let queue_max_veh = m.queue_max_veh.and_then(|n| {
        let ok = (1..=i64::from(u32::MAX)).contains(&n);
        if !ok {
            c.push(
                field("queue_max_veh"),
                n.to_string(),
                "must be a whole number >= 1 (vehicles waiting on the ramp before the override)",
            );
        }
        ok.then_some(n as u32)
    });
    let from_s = m
        .from
        .as_ref()
        .map_or(Some(0.0), |t| time(c, &field("from"), t, run));
    let to_s = m.to.as_ref().map(|t| time(c, &field("to"), t, run));
    if let (Some(from), Some(Some(to))) = (from_s, to_s) {
        if to <= from {
            c.push(
                field("to"),
                shown_time(m.to.as_ref()),
                format!(
                    "must be after {} = {} ({} s of simulated time)",
                    field("from"),
                    shown_time(m.from.as_ref()),
                    num(from)
                ),
            );
        }
    }
    if let (Some(from), true) = (from_s, run.duration_ok) {
        if from >= run.duration.v {
            c.push(
                field("from"),
                shown_time(m.from.as_ref()),
                format!(
                    "must be before the end of the run (run.duration_s = {} s); the meter would never run",
                    num(run.duration.v)
                ),
            );
        }
    }
    if c.problems.len() > before {
        return None;
    }
    Some(Meter {
        law: law?,
        from_s: from_s?,
        to_s: to_s.flatten(),
        queue_max_veh,
    })
}

/// The ALINEA keys.
fn alinea(
    c: &mut Checker,
    field: &dyn Fn(&str) -> String,
    m: &RawMeter,
    at: &Place,
) -> Option<MeterLaw> {
    let target = c.req(
        &field("occupancy_target_pct"),
        m.occupancy_target_pct,
        "o*, the critical occupancy of the detector downstream of the merge (%)",
    );
    if let Some(o) = target {
        c.check(
            &field("occupancy_target_pct"),
            o,
            o.v > 0.0 && o.v < 100.0,
            "must be in (0, 100) % (an occupancy in percent)",
        );
    }
    let gain = c.opt(m.gain_vph, DEFAULT_GAIN_VPH);
    c.positive(&field("gain_vph"), gain);
    let lo = c.req(
        &field("min_rate_vph"),
        m.min_rate_vph,
        "r_min, the lowest rate (veh/h)",
    );
    let hi = c.req(
        &field("max_rate_vph"),
        m.max_rate_vph,
        "r_max, the highest rate (veh/h)",
    );
    let lo_ok = lo.is_some_and(|r| check_rate(c, &field("min_rate_vph"), r));
    let hi_ok = hi.is_some_and(|r| check_rate(c, &field("max_rate_vph"), r));
    if let (Some(lo), Some(hi), true, true) = (lo, hi, lo_ok, hi_ok) {
        c.check(
            &field("min_rate_vph"),
            lo,
            lo.v <= hi.v,
            format!("must be at most {} = {}", field("max_rate_vph"), hi.shown()),
        );
    }
    let period = c.opt(m.period_s, DEFAULT_PERIOD_S);
    c.check(
        &field("period_s"),
        period,
        (1.0..=MAX_PERIOD_S).contains(&period.v),
        format!(
            "must be in [1, {}] s (the control period)",
            num(MAX_PERIOD_S)
        ),
    );
    let detector = c.opt(m.detector_m, at.accel_lane_m + DETECTOR_PAST_ACCEL_LANE_M);
    let inside = match (at.x_m, at.end_m) {
        (Some(x), Some(end)) => detector.v > 0.0 && x + detector.v < end,
        _ => detector.v > 0.0,
    };
    c.check(
        &field("detector_m"),
        detector,
        inside,
        match (at.x_m, at.end_m) {
            (Some(x), Some(end)) => format!(
                "must be > 0 m and put the detector inside the corridor (the merge point {} + it < network.end_m = {})",
                num(x),
                num(end)
            ),
            _ => "must be > 0 m (downstream of the merge point)".to_string(),
        },
    );
    Some(MeterLaw::Alinea {
        law: Alinea {
            occupancy_target_pct: target?.v,
            gain_vph: gain.v,
            min_rate_vph: lo?.v,
            max_rate_vph: hi?.v,
            period_s: period.v,
        },
        detector_m: detector.v,
    })
}

/// A rate in (0, MAX_METER_RATE_VPH] veh/h.
fn check_rate(c: &mut Checker, field: &str, r: Num) -> bool {
    c.check(
        field,
        r,
        r.v > 0.0 && r.v <= MAX_METER_RATE_VPH,
        format!(
            "must be in (0, {}] veh/h (one vehicle per green: a rate of 0 never releases; at most one per second)",
            num(MAX_METER_RATE_VPH)
        ),
    )
}

/// Report the keys of the other kind (`other`): they would have no effect.
fn only_for(c: &mut Checker, field: &dyn Fn(&str) -> String, other: &str, m: &RawMeter) {
    let keys: &[(&str, Option<f64>)] = if other == "alinea" {
        &[
            ("occupancy_target_pct", m.occupancy_target_pct),
            ("gain_vph", m.gain_vph),
            ("min_rate_vph", m.min_rate_vph),
            ("max_rate_vph", m.max_rate_vph),
            ("period_s", m.period_s),
            ("detector_m", m.detector_m),
        ]
    } else {
        &[("rate_vph", m.rate_vph)]
    };
    for (k, v) in keys {
        if let Some(v) = v {
            c.push(
                field(k),
                num(*v),
                format!("is a key of kind = \"{other}\" only; this meter's kind has no {k}"),
            );
        }
    }
}

/// A time of the meter's hours in simulated seconds: a clock time relative to
/// `run.clock_start` (the next such time of day at or after it), or seconds >= 0.
fn time(c: &mut Checker, field: &str, t: &RawTime, run: &Run) -> Option<f64> {
    match t {
        RawTime::Seconds(s) => {
            let n = Num {
                v: *s,
                defaulted: false,
            };
            c.non_negative(field, n).then_some(*s)
        }
        RawTime::Clock(text) => {
            let Some(clock) = crate::clock::parse_clock(text) else {
                c.push(
                    field,
                    quoted(text),
                    "must be a clock time \"HH:MM\" or \"HH:MM:SS\" (00:00 to 23:59:59), or simulated seconds",
                );
                return None;
            };
            let Some(start) = run.clock_start_s else {
                c.push(
                    field,
                    quoted(text),
                    "a clock time needs run.clock_start (the clock time of t = 0); or give simulated seconds",
                );
                return None;
            };
            Some(f64::from((clock + 86_400 - start) % 86_400))
        }
    }
}

fn shown_time(t: Option<&RawTime>) -> String {
    match t {
        Some(RawTime::Clock(s)) => quoted(s),
        Some(RawTime::Seconds(s)) => num(*s),
        None => "0 (default)".to_string(),
    }
}
