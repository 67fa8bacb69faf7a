//! Validation of the `[run]` section (step, duration, warm-up, penetration) and of the number of
//! vehicles the run would bring, split from `validate.rs` by responsibility.

use super::{defaults, Checker, Num};
use crate::limits;
use crate::raw::{num, RawRun};
use platoonsim_sim::config::Network;

/// The checked `[run]` keys (defaults applied). Values are only meaningful if no problem was
/// reported; `dt_ok` and `duration_ok` tell the later checks whether they can rely on them.
pub(super) struct Run {
    pub seed: u64,
    pub dt: Num,
    pub dt_ok: bool,
    pub duration: Num,
    pub duration_ok: bool,
    pub warmup: Num,
    pub penetration: Num,
    /// `run.clock_start` in seconds after midnight.
    pub clock_start_s: Option<u32>,
}

pub(super) fn check_run(c: &mut Checker, r: &RawRun) -> Run {
    let seed = r.seed.unwrap_or(defaults::SEED);
    let dt = c.opt(r.dt_s, defaults::DT_S);
    let dt_ok = c.check(
        "run.dt_s",
        dt,
        (limits::DT_MIN_S..=limits::DT_MAX_S).contains(&dt.v),
        format!(
            "must be in [{}, {}] s ({})",
            num(limits::DT_MIN_S),
            num(limits::DT_MAX_S),
            limits::DT_REASON
        ),
    );
    let duration = c.opt(r.duration_s, defaults::DURATION_S);
    let duration_ok = c.check(
        "run.duration_s",
        duration,
        duration.v > 0.0 && duration.v <= limits::MAX_DURATION_S,
        format!(
            "must be in (0, {}] s (at most 7 simulated days)",
            num(limits::MAX_DURATION_S)
        ),
    );
    let warmup = c.opt(r.warmup_s, defaults::WARMUP_S);
    if duration_ok {
        c.check(
            "run.warmup_s",
            warmup,
            warmup.v >= 0.0 && warmup.v < duration.v,
            format!("must be >= 0 and < run.duration_s = {}", duration.shown()),
        );
    } else {
        c.non_negative("run.warmup_s", warmup);
    }
    if dt_ok && duration_ok && duration.v < dt.v {
        c.push(
            "run.duration_s",
            duration.shown(),
            format!("must be at least one step (run.dt_s = {})", dt.shown()),
        );
    }
    let penetration = c.opt(r.penetration, defaults::PENETRATION);
    c.unit("run.penetration", penetration);
    let clock_start_s = r.clock_start.as_deref().and_then(|text| {
        let parsed = crate::clock::parse_clock(text);
        if parsed.is_none() {
            c.push(
                "run.clock_start",
                format!("{text:?}"),
                "must be a clock time \"HH:MM\" or \"HH:MM:SS\" (00:00 to 23:59:59)",
            );
        }
        parsed
    });
    Run {
        seed,
        dt,
        dt_ok,
        duration,
        duration_ok,
        warmup,
        penetration,
        clock_start_s,
    }
}

/// The vehicles the run would bring: each one waiting in an entry queue is held in memory, so
/// the total is bounded even when every rate and the duration are in range. Checked only when
/// nothing else was reported. `network` is the checked network, if any; otherwise the demand is
/// `vph_per_lane` on each of `lanes` lanes.
pub(super) fn check_arrivals(
    c: &mut Checker,
    run: &Run,
    network: Option<&Network>,
    vph_per_lane: Option<f64>,
    lanes: u32,
) {
    if run.duration_ok && c.problems.is_empty() {
        let duration = run.duration;
        let arrivals = match network {
            Some(n) => expected_network_arrivals(n, duration.v),
            None => vph_per_lane.unwrap_or(0.0) * f64::from(lanes) * duration.v / 3600.0,
        };
        if arrivals > limits::MAX_ARRIVALS {
            c.push(
                "run.duration_s",
                duration.shown(),
                format!(
                    "with this demand the run brings about {} vehicles; at most {} (a vehicle \
                     waiting at an entrance is held in memory): shorten the run or lower the demand",
                    num(arrivals.round()),
                    num(limits::MAX_ARRIVALS)
                ),
            );
        }
    }
}

/// The expected number of arrivals at every entrance of a network over `duration_s` (the last
/// interval's demand holds past the end of the series, as in the engine).
fn expected_network_arrivals(n: &Network, duration_s: f64) -> f64 {
    let over = |series: &[f64]| -> f64 {
        let mut total = 0.0;
        let mut t = 0.0;
        for (k, q) in series.iter().enumerate() {
            if t >= duration_s {
                break;
            }
            let end = if k + 1 == series.len() {
                duration_s
            } else {
                (t + n.interval_s).min(duration_s)
            };
            total += q * (end - t) / 3600.0;
            t = end;
        }
        total
    };
    let ramps: f64 = n.on_ramps.iter().map(|r| over(&r.demand_vph)).sum();
    (over(&n.mainline_vph) + ramps) * n.demand_scale
}

#[cfg(test)]
mod tests {
    use super::expected_network_arrivals;

    #[test]
    fn network_arrivals_integrate_the_series_and_hold_the_last_value() {
        let c = crate::load("sr99").unwrap();
        let n = c.road.network.unwrap();
        let per_interval = |k: usize| {
            let ramps: f64 = n.on_ramps.iter().map(|r| r.demand_vph[k]).sum();
            (n.mainline_vph[k] + ramps) * n.demand_scale * n.interval_s / 3600.0
        };
        let len = n.mainline_vph.len();
        let series: f64 = (0..len).map(per_interval).sum();
        let span = len as f64 * n.interval_s;
        assert!((expected_network_arrivals(&n, span) - series).abs() < 1e-6 * series);
        // Half the first interval; then one more interval at the last value.
        let half = expected_network_arrivals(&n, n.interval_s / 2.0);
        assert!((half - per_interval(0) / 2.0).abs() < 1e-6 * half);
        let more = expected_network_arrivals(&n, span + n.interval_s);
        assert!((more - series - per_interval(len - 1)).abs() < 1e-6 * more);
    }
}
