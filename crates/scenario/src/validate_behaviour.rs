//! Validation of `[[network.behaviour]]`, the section behaviour stretches (docs
//! network-scenarios.md; the engine's `behaviour.rs`): each inside the corridor, in order and
//! not overlapping, with factors in their ranges. Split from `validate_network.rs`, whose
//! bounds they are checked against.

use super::{position, Bounds};
use crate::limits;
use crate::raw::{num, RawNetwork};
use crate::validate::Checker;
use platoonsim_sim::config::DriverStretch;

/// Allowed f_θ (`buffer_factor`): none to five times the drivers' Gipps buffer θ.
pub const BUFFER_FACTOR: (f64, f64) = (0.0, 5.0);
/// Allowed f_v (`speed_factor`).
pub const SPEED_FACTOR: (f64, f64) = (0.5, 1.5);

/// The stretches in engine coordinates (x − `origin`); the problems reported to `c`.
pub(super) fn behaviour(
    c: &mut Checker,
    n: &RawNetwork,
    b: &Bounds,
    origin: f64,
) -> Vec<DriverStretch> {
    if n.behaviour.len() > limits::MAX_STRETCHES {
        c.push(
            "network.behaviour",
            format!("({} entries)", n.behaviour.len()),
            format!("at most {} entries", limits::MAX_STRETCHES),
        );
        return Vec::new();
    }
    let mut out = Vec::with_capacity(n.behaviour.len());
    let mut prev: Option<(f64, String)> = None;
    for (i, s) in n.behaviour.iter().enumerate() {
        let at = |k: &str| format!("network.behaviour[{i}].{k}");
        let from = position(c, &at("from_m"), s.from_m, "start of the stretch (m)");
        let to = position(c, &at("to_m"), s.to_m, "end of the stretch (m)");
        if let (Some(f), Some(t)) = (from, to) {
            c.value(
                &at("to_m"),
                t,
                t > f,
                &format!("must be > network.behaviour[{i}].from_m = {}", num(f)),
            );
            if let Some((s0, e0)) = b.span {
                c.value(
                    &at("from_m"),
                    f,
                    f >= s0 && t <= e0,
                    &format!(
                        "the stretch [{}, {}) must lie inside the corridor [network.start_m, \
                         network.end_m) = [{}, {})",
                        num(f),
                        num(t),
                        num(s0),
                        num(e0)
                    ),
                );
            }
        }
        if let (Some(f), Some((p, what))) = (from, &prev) {
            c.value(
                &at("from_m"),
                f,
                f >= *p,
                &format!(
                    "must be at or after {what} = {}: the stretches must be in order and not \
                     overlap",
                    num(*p)
                ),
            );
        }
        let factor = |c: &mut Checker, key: &str, v: Option<f64>, (lo, hi): (f64, f64)| {
            let n = c.opt(v, 1.0);
            c.check(
                &at(key),
                n,
                n.v >= lo && n.v <= hi,
                format!("must be in [{}, {}] (1 = as elsewhere)", num(lo), num(hi)),
            );
            n.v
        };
        let h = factor(c, "buffer_factor", s.buffer_factor, BUFFER_FACTOR);
        let v = factor(c, "speed_factor", s.speed_factor, SPEED_FACTOR);
        if let (Some(f), Some(t)) = (from, to) {
            out.push(DriverStretch {
                from_m: f - origin,
                to_m: t - origin,
                buffer_factor: h,
                speed_factor: v,
            });
        }
        prev = to.map(|t| (t, format!("network.behaviour[{i}].to_m")));
    }
    out
}
