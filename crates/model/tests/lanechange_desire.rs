//! Lane-change desire (spec 4.2) and relaxation (spec 4.6).

use platoonsim_model::lanechange::{
    discretionary_desire, gap_relax, mandatory_desire, relax_at, LaneChangeParams, Side,
};
use platoonsim_model::Relax;
use proptest::prelude::*;

/// Spec 4.9 means: E = 300 m, T = 30 s, E_min = 50 m, T_min = 3 s, η_r = 0.7, v_ref floor
/// 2.3 m/s, φ = (0.4, 0.6, 0.2), t_s = 8 s.
fn p() -> LaneChangeParams {
    let p = LaneChangeParams::default();
    assert_eq!((p.mandatory_distance_m, p.mandatory_time_s), (300.0, 30.0));
    assert_eq!(
        (p.mandatory_min_distance_m, p.mandatory_min_time_s),
        (50.0, 3.0)
    );
    assert_eq!((p.right_discount, p.min_reference_speed_mps), (0.7, 2.3));
    assert_eq!(
        (
            p.relax_headway,
            p.relax_jam,
            p.relax_reaction,
            p.relax_time_s
        ),
        (0.4, 0.6, 0.5, 8.0)
    );
    p
}

fn assert_close(got: f64, want: f64, what: &str) {
    assert!(
        (got - want).abs() <= 1e-12,
        "{what}: got {got}, want {want}"
    );
}

// ---- mandatory (spec 4.2) ----------------------------------------------------------------

#[test]
fn mandatory_zero_far_away_in_distance_and_time() {
    let p = p();
    assert_eq!(mandatory_desire(&p, 1000.0, 30.0, 1), 0.0);
    assert_eq!(mandatory_desire(&p, 300.0, 10.0, 1), 0.0); // d_e = E, t_e = 30 s = T
    assert_eq!(mandatory_desire(&p, 5000.0, 0.0, 3), 0.0);
    // Far in distance but not in time: the time term speaks (t_e = 13.3 s).
    let g = mandatory_desire(&p, 400.0, 30.0, 1);
    assert_close(g, 1.0 - (400.0 / 30.0 - 3.0) / 27.0, "time term");
    assert!(g > 0.6);
}

#[test]
fn mandatory_one_within_min_distance_or_min_time() {
    let p = p();
    assert_eq!(mandatory_desire(&p, 50.0, 1.0, 1), 1.0); // d_e = E_min
    assert_eq!(mandatory_desire(&p, 10.0, 0.0, 1), 1.0); // standing, close
    assert_eq!(mandatory_desire(&p, -5.0, 20.0, 1), 1.0); // point passed
    assert_eq!(mandatory_desire(&p, 80.0, 30.0, 1), 1.0); // t_e = 2.7 s < T_min
    assert_eq!(mandatory_desire(&p, 90.0, 30.0, 1), 1.0); // t_e = T_min
}

#[test]
fn mandatory_zero_when_no_change_is_needed() {
    let p = p();
    assert_eq!(mandatory_desire(&p, 10.0, 30.0, 0), 0.0);
    assert_eq!(mandatory_desire(&p, -10.0, 0.0, 0), 0.0);
}

#[test]
fn mandatory_standing_vehicle_uses_the_distance_term_only() {
    let p = p();
    // t_e = ∞: 1 − (175 − 50)/(300 − 50) = 0.5.
    assert_close(mandatory_desire(&p, 175.0, 0.0, 1), 0.5, "v = 0");
    assert_close(mandatory_desire(&p, 175.0, -1.0, 1), 0.5, "v < 0");
    // A slow vehicle (t_e = 175 s) gives the same value.
    assert_close(mandatory_desire(&p, 175.0, 1.0, 1), 0.5, "v = 1");
}

#[test]
fn mandatory_scales_with_the_number_of_changes() {
    let p = p();
    for x in [0.0, 10.0, 60.0, 125.0, 200.0, 249.0] {
        let one = mandatory_desire(&p, 50.0 + x, 0.0, 1);
        for n in 2..=4u32 {
            // With only the distance term, N stretches the ramp: γ(E_min + N x; N) = γ(E_min + x; 1).
            let many = mandatory_desire(&p, 50.0 + f64::from(n) * x, 0.0, n);
            assert_close(many, one, "stretched ramp");
        }
    }
    // Same place, more changes needed: more desire.
    assert_close(mandatory_desire(&p, 300.0, 0.0, 2), 0.5, "N = 2 at E");
    assert_eq!(mandatory_desire(&p, 300.0, 0.0, 1), 0.0);
    assert!(mandatory_desire(&p, 540.0, 0.0, 2) > 0.0);
}

// ---- discretionary (spec 4.2, [P15-code] Oct 2015 form) -----------------------------------

#[test]
fn discretionary_zero_when_target_not_faster() {
    let p = p();
    for side in [Side::Left, Side::Right] {
        assert_eq!(discretionary_desire(&p, 20.0, 25.0, side), 0.0);
        assert_eq!(discretionary_desire(&p, 25.0, 25.0, side), 0.0);
        assert_eq!(discretionary_desire(&p, 0.0, 0.0, side), 0.0);
    }
}

#[test]
fn discretionary_relative_gain_with_right_discount() {
    let p = p();
    assert_close(
        discretionary_desire(&p, 30.0, 25.0, Side::Left),
        0.2,
        "left",
    );
    assert_close(
        discretionary_desire(&p, 30.0, 25.0, Side::Right),
        0.7 * 0.2,
        "right",
    );
}

#[test]
fn discretionary_capped_at_one() {
    let p = p();
    assert_eq!(discretionary_desire(&p, 60.0, 20.0, Side::Left), 1.0);
    assert_close(
        discretionary_desire(&p, 60.0, 20.0, Side::Right),
        0.7,
        "right cap",
    );
    assert_eq!(discretionary_desire(&p, 40.0, 20.0, Side::Left), 1.0); // gain exactly 1
}

#[test]
fn discretionary_reference_speed_floor() {
    let p = p();
    // v_cur below 2.3 m/s: v_ref = 2.3, gain (3.45 − 2.3)/2.3 = 0.5 (not (3.45 − 0.5)/0.5 → 1).
    assert_close(
        discretionary_desire(&p, 3.45, 0.5, Side::Left),
        0.5,
        "floor, crawling",
    );
    assert_close(
        discretionary_desire(&p, 3.45, 0.0, Side::Left),
        0.5,
        "floor, standing",
    );
    // Target faster than the current lane but below the floor: no desire.
    assert_eq!(discretionary_desire(&p, 2.0, 1.0, Side::Left), 0.0);
    // Floor configured away: a standing current lane and a moving target give the full gain.
    let mut q = p;
    q.min_reference_speed_mps = 0.0;
    q.min_speed_gain_mps = 0.0;
    assert_eq!(discretionary_desire(&q, 1.0, 0.0, Side::Left), 1.0);
    assert_eq!(discretionary_desire(&q, 0.0, 0.0, Side::Left), 0.0);
}

#[test]
fn no_discretionary_desire_below_the_absolute_speed_gain() {
    // [P15-doc]: the gain v_ant − v̄_0 must reach 2.34 m/s (5 mph).
    let p = p();
    assert_eq!(p.min_speed_gain_mps, 2.34);
    // Crawling queue: 3 m/s next to 1 m/s is a relative gain of 0.3 but only 2 m/s absolute.
    assert_eq!(discretionary_desire(&p, 3.0, 1.0, Side::Left), 0.0);
    // 2.5 m/s absolute: relative to the 2.3 m/s floor, (3.5 − 2.3)/2.3 capped at 1 … (3.5 − 2.3)/2.3 = 0.52.
    assert!((discretionary_desire(&p, 3.5, 1.0, Side::Left) - (3.5 - 2.3) / 2.3).abs() < 1e-12);
    // Free flow: 30 vs 25 m/s passes the gate, gain 0.2.
    assert!((discretionary_desire(&p, 30.0, 25.0, Side::Left) - 0.2).abs() < 1e-12);
}

// ---- relaxation (spec 4.6) -----------------------------------------------------------------

#[test]
fn relaxation_recovers_linearly_over_t_s() {
    let p = p();
    assert_eq!(relax_at(&p, 0.0), gap_relax(&p));
    assert_eq!(relax_at(&p, -3.0), gap_relax(&p));
    let half = relax_at(&p, 4.0);
    assert_close(half.headway, 0.7, "φ_h at t_s/2");
    assert_close(half.jam, 0.8, "φ_j at t_s/2");
    assert_close(half.reaction, 0.75, "φ_r at t_s/2");
    let q = relax_at(&p, 2.0);
    assert_close(q.reaction, 0.5 + 0.5 * 0.25, "φ_r at t_s/4");
    let almost = relax_at(&p, 7.999);
    assert!(almost.headway < 1.0 && almost.jam < 1.0 && almost.reaction < 1.0);
    assert_eq!(relax_at(&p, 8.0), Relax::NONE);
    assert_eq!(relax_at(&p, 100.0), Relax::NONE);
}

#[test]
fn relaxation_with_zero_duration_is_none() {
    let mut p = p();
    p.relax_time_s = 0.0;
    assert_eq!(relax_at(&p, 0.0), Relax::NONE);
}

// ---- properties ----------------------------------------------------------------------------

proptest! {
    // No failure persistence: integration tests have no lib.rs for proptest to anchor it.
    #![proptest_config(ProptestConfig {
        cases: 3000,
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn mandatory_in_unit_interval_and_decreasing_in_distance(
        d1 in -1.0f64..=2000.0,
        extra in 0.0f64..=1000.0,
        v in 0.0f64..=45.0,
        n in 1u32..=4,
    ) {
        let p = p();
        let near = mandatory_desire(&p, d1, v, n);
        let far = mandatory_desire(&p, d1 + extra, v, n);
        prop_assert!((0.0..=1.0).contains(&near) && (0.0..=1.0).contains(&far));
        prop_assert!(near >= far, "γ({d1}) = {near} < γ({}) = {far}", d1 + extra);
    }

    #[test]
    fn mandatory_grows_with_number_of_changes(
        d in -1.0f64..=2000.0,
        v in 0.0f64..=45.0,
        n in 1u32..=4,
    ) {
        let p = p();
        prop_assert!(mandatory_desire(&p, d, v, n + 1) >= mandatory_desire(&p, d, v, n));
    }

    #[test]
    fn mandatory_grows_with_speed(
        d in -1.0f64..=2000.0,
        v in 0.0f64..=45.0,
        dv in 0.0f64..=10.0,
        n in 1u32..=4,
    ) {
        let p = p();
        prop_assert!(mandatory_desire(&p, d, v + dv, n) >= mandatory_desire(&p, d, v, n));
    }

    #[test]
    fn discretionary_in_range_and_right_is_discounted(
        v_ant in 0.0f64..=45.0,
        v_cur in 0.0f64..=45.0,
    ) {
        let p = p();
        let left = discretionary_desire(&p, v_ant, v_cur, Side::Left);
        let right = discretionary_desire(&p, v_ant, v_cur, Side::Right);
        prop_assert!((0.0..=1.0).contains(&left));
        prop_assert!((right - 0.7 * left).abs() <= 1e-12);
        if v_ant <= v_cur {
            prop_assert_eq!(left, 0.0);
        }
    }

    #[test]
    fn relaxation_between_phi_and_one_and_monotone(
        t in -1.0f64..=20.0,
        dt in 0.0f64..=5.0,
    ) {
        let p = p();
        let (a, b) = (relax_at(&p, t), relax_at(&p, t + dt));
        for (x, y, phi) in [
            (a.headway, b.headway, 0.4),
            (a.jam, b.jam, 0.6),
            (a.reaction, b.reaction, 0.2),
        ] {
            prop_assert!(x >= phi && x <= 1.0 && !x.is_nan());
            prop_assert!(y >= x);
        }
    }
}
