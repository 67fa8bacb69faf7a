use super::*;

fn obs(station: &str, start_s: u32, flow: f64, speed: Option<f64>) -> Obs {
    Obs {
        station: station.into(),
        start_s,
        interval_s: 300,
        flow_vph: flow,
        speed_kmh: speed,
        occupancy: Some(0.1),
    }
}

/// Two hours (05:00-07:00) of 5-min data at station `s`: flow alternating `a`, `b`; speed
/// falling from 100 km/h by 2 km/h an interval.
fn day(s: &str, a: f64, b: f64) -> Vec<Obs> {
    (0..24)
        .map(|k| {
            let flow = if k % 2 == 0 { a } else { b };
            obs(s, 18_000 + 300 * k, flow, Some(100.0 - 2.0 * f64::from(k)))
        })
        .collect()
}

#[test]
fn identical_data_fit_exactly() {
    let sim = [day("A", 1000.0, 1200.0), day("B", 800.0, 900.0)].concat();
    let f = fit(&sim, &sim);
    assert_eq!(f.stations_compared, ["A", "B"]);
    assert_eq!(
        f.hour_coverage,
        Coverage {
            matched: 4,
            ..Coverage::default()
        }
    );
    assert_eq!(f.quarter_coverage.matched, 16);
    assert_eq!(f.geh_pass_share, Some(1.0));
    assert_eq!(f.geh_mean, Some(0.0));
    assert_eq!(f.total_flow_diff, Some(0.0));
    assert_eq!(f.speed_rmse_kmh, Some(0.0));
    assert_eq!(f.speed_rmsne, Some(0.0));
    assert!((f.speed_correlation.unwrap() - 1.0).abs() < 1e-12);
    assert_eq!(f.objective(), Some(0.0));
    // Hourly volume: the mean of 1000 and 1200 veh/h; total over 2 hours × 2 stations.
    assert_eq!(f.hours[0].sim_vph, 1100.0);
    assert_eq!(f.total_field_veh, 2.0 * 1100.0 + 2.0 * 850.0);
}

#[test]
fn hourly_geh_of_aggregated_flows() {
    // Sim 1100 veh/h every hour, field 1000 veh/h: GEH 3.086 < 5, total +10 %.
    let sim = day("A", 1000.0, 1200.0);
    let field = day("A", 900.0, 1100.0);
    let f = fit(&sim, &field);
    assert_eq!(f.hours.len(), 2);
    assert_eq!(f.hours[0].geh, geh(1100.0, 1000.0));
    assert_eq!(f.geh_pass_share, Some(1.0));
    assert!((f.total_flow_diff.unwrap() - 0.1).abs() < 1e-12);
    // Per hour, one station: Σ M = 1100, Σ C = 1000.
    assert_eq!(f.hour_sums.len(), 2);
    assert_eq!(f.hour_sums[1].start_s, 6 * 3600);
    assert_eq!(f.hour_sum_geh_max, Some(geh(1100.0, 1000.0)));
    assert!((f.hour_sum_diff_worst.unwrap() - 0.1).abs() < 1e-12);
    assert_eq!(f.flow_tolerance_share, Some(1.0));
}

#[test]
fn hourly_sums_add_the_stations_of_each_hour() {
    // Hour 05:00: A +10 %, B −10 % of equal counts: the sum matches. Hour 06:00: A and B
    // both +20 %.
    let flows = |s: &str, first: f64, second: f64| -> Vec<Obs> {
        (0..24)
            .map(|k| {
                obs(
                    s,
                    18_000 + 300 * k,
                    if k < 12 { first } else { second },
                    None,
                )
            })
            .collect()
    };
    let sim = [flows("A", 1100.0, 1200.0), flows("B", 900.0, 1200.0)].concat();
    let field = [flows("A", 1000.0, 1000.0), flows("B", 1000.0, 1000.0)].concat();
    let f = fit(&sim, &field);
    let sums: Vec<(u32, usize, f64, f64)> = f
        .hour_sums
        .iter()
        .map(|h| (h.start_s, h.stations, h.sim_vph, h.field_vph))
        .collect();
    assert_eq!(
        sums,
        [(18_000, 2, 2000.0, 2000.0), (21_600, 2, 2400.0, 2000.0)]
    );
    assert_eq!(f.hour_sums[0].diff, Some(0.0));
    assert!((f.hour_sum_diff_worst.unwrap() - 0.2).abs() < 1e-12);
    assert_eq!(f.hour_sum_geh_max, Some(geh(2400.0, 2000.0)));
}

#[test]
fn scaled_field_flows_fail_geh() {
    let sim = day("A", 1000.0, 1000.0);
    let field: Vec<Obs> = sim
        .iter()
        .map(|o| Obs {
            flow_vph: o.flow_vph * 1.5,
            ..o.clone()
        })
        .collect();
    let f = fit(&sim, &field);
    assert_eq!(f.geh_pass_share, Some(0.0));
    assert_eq!(f.geh_max, Some(200.0f64.sqrt()));
    assert_eq!(f.flow_tolerance_share, Some(0.0));
    // Speeds are the same: they still fit.
    assert_eq!(f.speed_rmse_kmh, Some(0.0));
}

#[test]
fn speed_errors_pooled_over_quarters() {
    let sim = day("A", 1000.0, 1000.0);
    // Field speeds 10 km/h lower everywhere: RMSE 10 exactly, r = 1.
    let field: Vec<Obs> = sim
        .iter()
        .map(|o| Obs {
            speed_kmh: o.speed_kmh.map(|v| v - 10.0),
            ..o.clone()
        })
        .collect();
    let f = fit(&sim, &field);
    assert_eq!(f.speed_intervals, 8);
    let rmse = f.speed_rmse_kmh.unwrap();
    assert!((rmse - 10.0).abs() < 1e-12, "{rmse}");
    assert!((f.speed_correlation.unwrap() - 1.0).abs() < 1e-12);
    // Quarter 1: speeds 100, 98, 96 with equal flows → sim 98, field 88.
    assert_eq!(f.speeds[0].sim_kmh, 98.0);
    assert_eq!(f.speeds[0].field_kmh, 88.0);
}

#[test]
fn missing_intervals_are_counted_never_filled() {
    let sim = day("A", 1000.0, 1000.0);
    let mut field = sim.clone();
    field.remove(5); // 05:25: its quarter (05:15) and hour (05:00) are incomplete
    let f = fit(&sim, &field);
    assert_eq!(
        f.hour_coverage,
        Coverage {
            matched: 1,
            missing_in_field: 1,
            missing_in_sim: 0
        }
    );
    assert_eq!(f.quarter_coverage.matched, 7);
    assert_eq!(f.quarter_coverage.missing_in_field, 1);
    assert_eq!(f.per_station[0].quarters.missing_in_field, 1);
    // A speed missing on one side leaves the quarter out of the speed measures only.
    let mut no_speed = sim.clone();
    for o in no_speed.iter_mut().take(3) {
        o.speed_kmh = None;
    }
    let f = fit(&no_speed, &sim);
    assert_eq!(f.quarter_coverage.matched, 8);
    assert_eq!((f.quarters_without_speed, f.speed_intervals), (1, 7));
}

#[test]
fn only_stations_on_both_sides_are_compared() {
    let sim = [day("A", 1000.0, 1000.0), day("S", 1.0, 1.0)].concat();
    let field = [day("A", 1000.0, 1000.0), day("F", 1.0, 1.0)].concat();
    let f = fit(&sim, &field);
    assert_eq!(f.stations_compared, ["A"]);
    assert_eq!(f.sim_only_stations, ["S"]);
    assert_eq!(f.field_only_stations, ["F"]);
    assert_eq!(f.hour_coverage.matched, 2);
    assert_eq!(f.hour_coverage.missing_in_sim, 0);
}

#[test]
fn nothing_matched_has_no_measures() {
    let f = fit(&day("A", 1.0, 1.0), &day("B", 1.0, 1.0));
    assert_eq!(f.geh_pass_share, None);
    assert_eq!(f.total_flow_diff, None);
    assert_eq!((f.hour_sum_diff_worst, f.hour_sum_geh_max), (None, None));
    assert_eq!(f.speed_correlation, None);
    assert_eq!(f.objective(), None);
}

#[test]
fn window_keeps_whole_intervals_inside() {
    let d = day("A", 1.0, 1.0);
    // 05:10 to 05:30: intervals starting 05:10, 05:15, 05:20, 05:25.
    let w = within(&d, 18_600, 19_800);
    assert_eq!(w.len(), 4);
    assert_eq!(w[0].start_s, 18_600);
    assert_eq!(w[3].start_s, 19_500);
}
