//! Ramp meters (issue 45 item 3): the `meter` of an on-ramp, its defaults, its hours, the round
//! trip of a resolved file, and every bad input refused with the key, the value and what is
//! allowed.

mod common;

use common::*;
use platoonsim_model::meter::Alinea;
use platoonsim_scenario::{from_toml, to_toml, Overrides};
use platoonsim_sim::config::{Meter, MeterLaw};
use platoonsim_sim::Config;

const SMALL_CORRIDOR: &str = include_str!("fixtures/small_corridor.toml");

fn with_meter(meter: &str, more: &[&str]) -> Result<Config, platoonsim_scenario::ScenarioError> {
    let set = format!("network.on_ramps[0].meter={meter}");
    let mut sets = vec![set.as_str()];
    sets.extend_from_slice(more);
    with_set(SMALL_CORRIDOR, &sets)
}

fn meter_of(c: &Config) -> Meter {
    c.road.network.as_ref().unwrap().on_ramps[0]
        .meter
        .clone()
        .unwrap()
}

fn meter_problems(meter: &str) -> Vec<String> {
    problems(with_meter(meter, &[]))
}

const P: &str = "network.on_ramps[0].meter";

#[test]
fn a_fixed_meter_loads_with_its_rate_and_runs_the_whole_run_by_default() {
    let c = with_meter(r#"{ kind = "fixed", rate_vph = 600 }"#, &[]).unwrap();
    c.check().unwrap();
    assert_eq!(
        meter_of(&c),
        Meter {
            law: MeterLaw::Fixed { rate_vph: 600.0 },
            from_s: 0.0,
            to_s: None,
            queue_max_veh: None,
        }
    );
    // The other ramp has none.
    assert!(c.road.network.as_ref().unwrap().on_ramps[1].meter.is_none());
}

#[test]
fn alinea_takes_the_published_gain_a_minute_and_a_detector_past_the_acceleration_lane() {
    let c = with_meter(
        r#"{ kind = "alinea", occupancy_target_pct = 12, min_rate_vph = 240, max_rate_vph = 900 }"#,
        &[],
    )
    .unwrap();
    assert_eq!(
        meter_of(&c).law,
        MeterLaw::Alinea {
            law: Alinea {
                occupancy_target_pct: 12.0,
                gain_vph: 70.0,
                min_rate_vph: 240.0,
                max_rate_vph: 900.0,
                period_s: 60.0,
            },
            // The acceleration lane (250 m by default) and 50 m.
            detector_m: 300.0,
        }
    );
}

#[test]
fn hours_are_clock_times_after_the_clock_start_or_seconds() {
    let c = with_meter(
        r#"{ kind = "fixed", rate_vph = 900, from = "06:00", to = "08:30:30", queue_max_veh = 40 }"#,
        &["run.clock_start=\"05:00\"", "run.duration_s=14400"],
    )
    .unwrap();
    let m = meter_of(&c);
    assert_eq!(
        (m.from_s, m.to_s, m.queue_max_veh),
        (3600.0, Some(12_630.0), Some(40))
    );
    let c = with_meter(
        r#"{ kind = "fixed", rate_vph = 900, from = 600, to = 1800.5 }"#,
        &[],
    )
    .unwrap();
    let m = meter_of(&c);
    assert_eq!((m.from_s, m.to_s), (600.0, Some(1800.5)));
    // A clock time before the clock start is on the next day.
    let c = with_meter(
        r#"{ kind = "fixed", rate_vph = 900, from = "04:00" }"#,
        &["run.clock_start=\"05:00\"", "run.duration_s=90000"],
    )
    .unwrap();
    assert_eq!(meter_of(&c).from_s, 82_800.0);
}

#[test]
fn a_resolved_file_with_meters_loads_back_to_the_same_config() {
    for meter in [
        r#"{ kind = "fixed", rate_vph = 700, to = 1800, queue_max_veh = 25 }"#,
        r#"{ kind = "alinea", occupancy_target_pct = 9.5, min_rate_vph = 300, max_rate_vph = 1200, gain_vph = 50, period_s = 30, detector_m = 400, from = "05:30" }"#,
    ] {
        let c = with_meter(meter, &["run.clock_start=\"05:00\""]).unwrap();
        let resolved = to_toml(&c);
        assert!(resolved.contains("meter = {"), "{resolved}");
        let back = from_toml(&resolved, "resolved", "other", &Overrides::default())
            .unwrap_or_else(|e| panic!("{e}\n{resolved}"));
        assert_eq!(back, c, "{resolved}");
    }
    // Without a meter nothing is written.
    let c = parse(SMALL_CORRIDOR).unwrap();
    assert!(!to_toml(&c).contains("meter"));
}

#[test]
fn a_rate_of_zero_negative_or_nan_is_refused_naming_the_key() {
    let allowed = "must be in (0, 3600] veh/h (one vehicle per green: a rate of 0 never releases; at most one per second)";
    for (bad, shown) in [
        ("0", "0"),
        ("-600", "-600"),
        ("nan", "nan"),
        ("inf", "inf"),
        ("4000", "4000"),
    ] {
        let p = meter_problems(&format!(r#"{{ kind = "fixed", rate_vph = {bad} }}"#));
        assert_eq!(
            p,
            vec![format!("{P}.rate_vph = {shown}: {allowed}")],
            "{bad}"
        );
    }
    let p = meter_problems(r#"{ kind = "fixed" }"#);
    assert_eq!(
        p,
        vec![format!(
            "{P}.rate_vph = (missing): required: the meter's rate (veh/h)"
        )]
    );
}

#[test]
fn an_unknown_or_missing_kind_is_refused_with_the_kinds_allowed() {
    let kinds =
        "\"fixed\" (one vehicle per green at rate_vph) or \"alinea\" (the ALINEA feedback law)";
    let p = meter_problems(r#"{ kind = "pid", rate_vph = 600 }"#);
    assert_eq!(p, vec![format!("{P}.kind = \"pid\": must be {kinds}")]);
    let p = meter_problems(r#"{ rate_vph = 600 }"#);
    assert_eq!(p, vec![format!("{P}.kind = (missing): required: {kinds}")]);
}

#[test]
fn alinea_bounds_target_and_detector_are_checked() {
    let base =
        "kind = \"alinea\", occupancy_target_pct = 12, min_rate_vph = 240, max_rate_vph = 900";
    let p = meter_problems(
        &format!("{{ {base}, min_rate_vph = 1000 }}").replace("min_rate_vph = 240, ", ""),
    );
    assert_eq!(
        p,
        vec![format!(
            "{P}.min_rate_vph = 1000: must be at most {P}.max_rate_vph = 900"
        )]
    );
    for (bad, shown) in [
        ("0", "0"),
        ("100", "100"),
        ("150", "150"),
        ("-1", "-1"),
        ("nan", "nan"),
    ] {
        let m = format!("{{ {base} }}").replace(
            "occupancy_target_pct = 12",
            &format!("occupancy_target_pct = {bad}"),
        );
        assert_eq!(
            meter_problems(&m),
            vec![format!("{P}.occupancy_target_pct = {shown}: must be in (0, 100) % (an occupancy in percent)")],
            "{bad}"
        );
    }
    let p = meter_problems(&format!("{{ {base}, gain_vph = 0, period_s = 0.5 }}"));
    assert_eq!(
        p,
        vec![
            format!("{P}.gain_vph = 0: must be a finite number > 0"),
            format!("{P}.period_s = 0.5: must be in [1, 3600] s (the control period)"),
        ]
    );
    // The corridor ends at 3000; the ramp merges at 0.
    let p = meter_problems(&format!("{{ {base}, detector_m = 3000 }}"));
    assert_eq!(
        p,
        vec![format!("{P}.detector_m = 3000: must be > 0 m and put the detector inside the corridor (the merge point 0 + it < network.end_m = 3000)")]
    );
    let p = meter_problems(r#"{ kind = "alinea" }"#);
    assert_eq!(
        p,
        vec![
            format!("{P}.occupancy_target_pct = (missing): required: o*, the critical occupancy of the detector downstream of the merge (%)"),
            format!("{P}.min_rate_vph = (missing): required: r_min, the lowest rate (veh/h)"),
            format!("{P}.max_rate_vph = (missing): required: r_max, the highest rate (veh/h)"),
        ]
    );
}

#[test]
fn keys_of_the_other_kind_are_refused() {
    let p = meter_problems(r#"{ kind = "fixed", rate_vph = 600, occupancy_target_pct = 12 }"#);
    assert_eq!(
        p,
        vec![format!("{P}.occupancy_target_pct = 12: is a key of kind = \"alinea\" only; this meter's kind has no occupancy_target_pct")]
    );
    let p = meter_problems(
        r#"{ kind = "alinea", occupancy_target_pct = 12, min_rate_vph = 240, max_rate_vph = 900, rate_vph = 600 }"#,
    );
    assert_eq!(
        p,
        vec![format!("{P}.rate_vph = 600: is a key of kind = \"fixed\" only; this meter's kind has no rate_vph")]
    );
}

#[test]
fn bad_hours_and_queue_limits_are_refused() {
    let p = meter_problems(r#"{ kind = "fixed", rate_vph = 600, from = "06:00" }"#);
    assert_eq!(
        p,
        vec![format!("{P}.from = \"06:00\": a clock time needs run.clock_start (the clock time of t = 0); or give simulated seconds")]
    );
    let p = meter_problems(r#"{ kind = "fixed", rate_vph = 600, from = "6h" }"#);
    assert_eq!(
        p,
        vec![format!("{P}.from = \"6h\": must be a clock time \"HH:MM\" or \"HH:MM:SS\" (00:00 to 23:59:59), or simulated seconds")]
    );
    let p = meter_problems(r#"{ kind = "fixed", rate_vph = 600, from = 1800, to = 900 }"#);
    assert_eq!(
        p,
        vec![format!(
            "{P}.to = 900: must be after {P}.from = 1800 (1800 s of simulated time)"
        )]
    );
    let p = meter_problems(r#"{ kind = "fixed", rate_vph = 600, from = -5 }"#);
    assert_eq!(
        p,
        vec![format!("{P}.from = -5: must be a finite number >= 0")]
    );
    let p = meter_problems(r#"{ kind = "fixed", rate_vph = 600, from = 3600 }"#);
    assert_eq!(
        p,
        vec![format!("{P}.from = 3600: must be before the end of the run (run.duration_s = 3600 s); the meter would never run")]
    );
    for bad in ["0", "-3"] {
        let p = meter_problems(&format!(
            r#"{{ kind = "fixed", rate_vph = 600, queue_max_veh = {bad} }}"#
        ));
        assert_eq!(
            p,
            vec![format!("{P}.queue_max_veh = {bad}: must be a whole number >= 1 (vehicles waiting on the ramp before the override)")]
        );
    }
}

#[test]
fn unknown_keys_and_wrong_types_name_the_meter_key() {
    let (path, message) = structure(with_meter(
        r#"{ kind = "fixed", rate_vph = 600, rate = 3 }"#,
        &[],
    ));
    assert_eq!(path, format!("{P}.rate"));
    assert!(
        message.starts_with(
            "unknown field 'rate' in [network.on_ramps[0].meter]; allowed keys: kind, rate_vph, "
        ),
        "{message}"
    );
    let (path, message) = structure(with_meter(
        r#"{ kind = "fixed", rate_vph = 600, from = true }"#,
        &[],
    ));
    assert!(path.starts_with(P), "{path}");
    assert!(message.contains("expected a clock time"), "{message}");
}
