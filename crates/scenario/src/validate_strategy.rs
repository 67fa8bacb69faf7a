//! Validation of the `[strategy]` section (the kind, the PD zone and time window, the
//! Flow-Aware thresholds and radius), split from `validate.rs` by responsibility.

use super::run::Run;
use super::{defaults, quoted, Checker, Frame, Num};
use crate::limits;
use crate::overrides::StrategyKind;
use crate::raw::{num, RawStrategy};
use platoonsim_sim::{FlowAwareConfig, LaneChoice, PdConfig, Strategy};
use toml::Value;

/// `[strategy]`. The zone defaults to the control section (`control`, in the file's
/// coordinate) and the time window to the measurement window of `run`.
pub(super) fn check_strategy(
    c: &mut Checker,
    s: &RawStrategy,
    frame: &Frame,
    control: (Option<Num>, Option<Num>),
    run: &Run,
    lanes: u32,
) -> Strategy {
    let (cstart, cend) = control;
    let kind = match s.kind.as_deref() {
        None => StrategyKind::NONE,
        Some(k) => k.parse().unwrap_or_else(|_| {
            c.push(
                "strategy.kind",
                quoted(k),
                format!("must be one of {}", StrategyKind::names()),
            );
            StrategyKind::NONE
        }),
    };
    let lane = match &s.lane {
        None => LaneChoice::Leftmost,
        Some(Value::String(n)) if n == "leftmost" => LaneChoice::Leftmost,
        Some(Value::String(n)) if n == "rightmost" => LaneChoice::Rightmost,
        Some(Value::Integer(i)) if (1..=i64::from(lanes.max(1))).contains(i) => {
            LaneChoice::Index(*i as u32 - 1)
        }
        Some(other) => {
            let shown = match other {
                Value::String(n) => quoted(n),
                v => v.to_string(),
            };
            c.push(
                "strategy.lane",
                shown,
                format!(
                    "must be \"leftmost\", \"rightmost\" or a lane number 1 to {lanes} \
                     (the road's lanes; 1 = the rightmost lane)"
                ),
            );
            LaneChoice::Leftmost
        }
    };
    let zs = c.opt(s.zone_start_m, cstart.map_or(0.0, |n| n.v));
    let ze = c.opt(s.zone_end_m, cend.map_or(0.0, |n| n.v));
    // (Both in the file's coordinate.)
    // Zone and window default to the control section and the measurement window, which are
    // checked above; only values the file gives are checked again.
    let zone_given = !(zs.defaulted && ze.defaulted);
    if let (Some(hi), true) = (frame.hi, zone_given) {
        let ok = c.check(
            "strategy.zone_start_m",
            zs,
            zs.v >= frame.origin && zs.v < hi,
            format!(
                "must lie in [{}, {}) (the zone must be on the road)",
                frame.lo_text(),
                frame.hi_text(hi)
            ),
        );
        if ok {
            c.check(
                "strategy.zone_end_m",
                ze,
                ze.v > zs.v && ze.v <= hi,
                format!(
                    "must be > strategy.zone_start_m = {} and <= {}",
                    zs.shown(),
                    frame.hi_text(hi)
                ),
            );
        }
    }
    // The PD window defaults to the measurement window on the homogeneous road and to the
    // whole run on a network.
    let ts = c.opt(s.start_s, if frame.network { 0.0 } else { run.warmup.v });
    let te = c.opt(s.end_s, run.duration.v);
    let window_given = !(ts.defaulted && te.defaulted);
    if window_given && c.non_negative("strategy.start_s", ts) {
        c.check(
            "strategy.end_s",
            te,
            te.v > ts.v,
            format!("must be > strategy.start_s = {}", ts.shown()),
        );
    }
    // Unset thresholds come from the calibrated table at this penetration (issue 3 item 4).
    let (flow_default, speed_default) = crate::thresholds::default_at(
        run.penetration.v,
        (
            defaults::FLOW_THRESHOLD_VPHPL,
            defaults::SPEED_THRESHOLD_KMH,
        ),
    );
    let flow = c.opt(s.flow_threshold_vphpl, flow_default);
    c.check(
        "strategy.flow_threshold_vphpl",
        flow,
        flow.v > 0.0 && flow.v <= limits::MAX_FLOW_THRESHOLD_VPHPL,
        format!(
            "must be in (0, {}] veh/h/lane",
            num(limits::MAX_FLOW_THRESHOLD_VPHPL)
        ),
    );
    let speed = c.opt(s.speed_threshold_kmh, speed_default);
    c.check(
        "strategy.speed_threshold_kmh",
        speed,
        (0.0..=limits::MAX_SPEED_THRESHOLD_KMH).contains(&speed.v),
        format!(
            "must be in [0, {}] km/h",
            num(limits::MAX_SPEED_THRESHOLD_KMH)
        ),
    );
    let radius = c.opt(s.radius_m, defaults::RADIUS_M);
    c.check(
        "strategy.radius_m",
        radius,
        radius.v > 0.0 && radius.v <= limits::MAX_LENGTH_M,
        format!("must be in (0, {}] m", num(limits::MAX_LENGTH_M)),
    );
    let pd = PdConfig {
        zone_start_m: zs.v - frame.origin,
        zone_end_m: ze.v - frame.origin,
        start_s: ts.v,
        end_s: te.v,
        lane,
    };
    let entry = kind.entry();
    Strategy {
        kind,
        pd: entry.organizes.then_some(pd),
        thresholds: entry.needs_thresholds.then_some(FlowAwareConfig {
            flow_threshold_vphpl: flow.v,
            speed_threshold_kmh: speed.v,
            radius_m: radius.v,
        }),
    }
}
