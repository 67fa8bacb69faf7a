//! Validation of the `[strategy]` section (the kind, the PD zone and time window, the
//! Flow-Aware thresholds and radius), split from `validate.rs` by responsibility.

use super::run::Run;
use super::{defaults, quoted, Checker, Frame, Num};
use crate::limits;
use crate::overrides::StrategyKind;
use crate::raw::{num, RawStrategy};
use crate::thresholds;
use platoonsim_sim::{FlowAwareConfig, LaneChoice, PdConfig, Strategy};
use std::path::Path;
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
    base_dir: Option<&Path>,
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
    // Unset thresholds come from the table the file names, at this penetration (issue 3 item
    // 4); without a table they have no default, and Flow-Aware needs both.
    let table =
        s.thresholds_table
            .as_deref()
            .and_then(|r| match crate::tables::thresholds(r, base_dir) {
                Ok(rows) => Some(thresholds::at(
                    &rows,
                    run.penetration.v,
                    (f64::NAN, f64::NAN),
                )),
                Err(e) => {
                    c.push(
                        "strategy.thresholds_table",
                        quoted(r),
                        format!("must name a table of Flow-Aware thresholds by penetration: {e}"),
                    );
                    None
                }
            });
    let flow = threshold(
        c,
        (kind, s.thresholds_table.is_some()),
        "strategy.flow_threshold_vphpl",
        s.flow_threshold_vphpl.or(table.map(|t| t.0)),
        table.is_some(),
        (0.0, limits::MAX_FLOW_THRESHOLD_VPHPL, "veh/h/lane", false),
    );
    let speed = threshold(
        c,
        (kind, s.thresholds_table.is_some()),
        "strategy.speed_threshold_kmh",
        s.speed_threshold_kmh.or(table.map(|t| t.1)),
        table.is_some(),
        (0.0, limits::MAX_SPEED_THRESHOLD_KMH, "km/h", true),
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
            // NaN only with a problem reported above (a threshold missing).
            flow_threshold_vphpl: flow.unwrap_or(f64::NAN),
            speed_threshold_kmh: speed.unwrap_or(f64::NAN),
            radius_m: radius.v,
        }),
    }
}

/// One Flow-Aware threshold: given (in the file or by its table: `from_table`) it is checked
/// against (`lo`, `hi`] (or [`lo`, `hi`] if `lo_closed`); missing, it is a problem only if
/// `kind` is Flow-Aware, with a message that says how to name it.
fn threshold(
    c: &mut Checker,
    (kind, table_named): (StrategyKind, bool),
    field: &str,
    value: Option<f64>,
    from_table: bool,
    (lo, hi, unit, lo_closed): (f64, f64, &str, bool),
) -> Option<f64> {
    let Some(v) = value else {
        // A table that was named but could not be read is reported at its own key.
        if kind.entry().needs_thresholds && !table_named {
            c.push(
                field,
                "(missing)",
                format!(
                    "strategy.kind = \"flow-aware\" needs both thresholds: set \
                     strategy.flow_threshold_vphpl (veh/h/lane) and strategy.speed_threshold_kmh \
                     (km/h), or strategy.thresholds_table = \"{}\" (the built-in table \
                     calibrated on the homogeneous road, {}) or the path of a table file in \
                     its format",
                    crate::tables::FLOW_AWARE_THRESHOLDS,
                    thresholds::TABLE_PATH
                ),
            );
        }
        return None;
    };
    let n = Num {
        v,
        defaulted: from_table,
    };
    let (open, close) = (if lo_closed { "[" } else { "(" }, "]");
    let ok = (if lo_closed { v >= lo } else { v > lo }) && v <= hi;
    c.check(
        field,
        n,
        ok,
        format!("must be in {open}{}, {}{close} {unit}", num(lo), num(hi)),
    );
    Some(v)
}
