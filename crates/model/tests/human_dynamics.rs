//! Dynamic behaviour of the human car-following terms (spec 2.1-2.5, 1).

use platoonsim_model::human::{
    equilibrium_gap, free_accel, friction_desired_speed, gipps_accel, newell_accel, smooth_accel,
    target_accel, HumanParams,
};
use platoonsim_model::{Leader, Relax};

const DT: f64 = 0.1;
/// Documented relaxation factors (spec 4.6 recommendation).
const RELAXED: Relax = Relax {
    headway: 0.4,
    jam: 0.6,
    reaction: 0.2,
};

/// The spec 2.6 mean driver with θ = 0.15 s (the hand computations below use it).
fn p() -> HumanParams {
    HumanParams {
        buffer_s: 0.15,
        ..HumanParams::default()
    }
}

#[test]
fn free_road_accelerates_toward_desired_speed_and_is_zero_there() {
    let p = p();
    let v_f = p.desired_speed;
    assert!((target_accel(&p, 0.0, v_f, None, Relax::NONE) - p.max_accel).abs() < 1e-12);
    assert!(target_accel(&p, v_f, v_f, None, Relax::NONE).abs() < 1e-12);
    let mut prev = f64::INFINITY;
    for i in 0..30 {
        let v = i as f64;
        let a = target_accel(&p, v, v_f, None, Relax::NONE);
        assert!(a > 0.0 && a <= p.max_accel && a < prev, "v {v}: {a}");
        prev = a;
    }
    // IDM δ = 4: at half the desired speed a_F = a_M (1 − 1/16).
    assert!((free_accel(&p, v_f / 2.0, v_f) - p.max_accel * 15.0 / 16.0).abs() < 1e-12);
}

#[test]
fn free_road_above_desired_speed_sheds_speed_no_harder_than_b_c() {
    let p = p();
    // Far above: raw IDM term would be 1.5 (1 − 1.4⁴) = −4.26; bounded by b_c = −2.
    assert_eq!(free_accel(&p, 35.0, 25.0), p.comfort_decel);
    // Slightly above: the raw term (−0.024) is gentler than b_c and is kept.
    let a = free_accel(&p, 25.1, 25.0);
    assert!(a < 0.0 && a > p.comfort_decel);
    assert!((a - p.max_accel * (1.0 - (25.1_f64 / 25.0).powi(4))).abs() < 1e-12);
    // Degenerate desired speed: no NaN.
    assert_eq!(free_accel(&p, 0.0, 0.0), 0.0);
    assert_eq!(free_accel(&p, 3.0, 0.0), p.comfort_decel);
}

#[test]
fn behind_a_stopped_leader_at_small_gap_it_brakes() {
    let p = p();
    let stopped = |gap_m| Some(Leader { gap_m, v_mps: 0.0 });
    // 20 m/s, 30 m from a stopped car: Gipps demands more than b_f (not clamped below).
    let a = target_accel(&p, 20.0, p.desired_speed, stopped(30.0), Relax::NONE);
    assert!(a < p.max_decel, "{a}");
    // The Newell term alone is clamped at b_f: at 15 m it supports (15 − 1.5)/1.25 = 10.8 m/s,
    // raw a_N = (10.8 − 20)/0.625 = −14.7.
    assert_eq!(newell_accel(&p, 20.0, 15.0, Relax::NONE), p.max_decel);
    // At 30 m it supports 22.8 m/s > 20: a_N = 2.8/0.625 capped at a_M.
    assert_eq!(newell_accel(&p, 20.0, 30.0, Relax::NONE), p.max_accel);
    assert!((newell_accel(&p, 20.0, 26.0, Relax::NONE) - (19.6 - 20.0) / 0.625).abs() < 1e-12);
    // Moderate closing: 15 m/s at 35 m → Gipps v_G = −3 + sqrt(205) = 11.3 m/s, a_G = −3.1.
    let a = target_accel(&p, 15.0, p.desired_speed, stopped(35.0), Relax::NONE);
    assert!(
        (a - (-3.0 + 205.0_f64.sqrt() - 15.0) / 1.2).abs() < 1e-12,
        "{a}"
    );
    assert!(a < 0.0 && a > p.max_decel, "{a}");
    // Standing inside the jam gap: no acceleration.
    assert!(target_accel(&p, 0.0, p.desired_speed, stopped(1.0), Relax::NONE) <= 0.0);
    // Standing far behind: the free term limits it (1.5 m/s²).
    assert!(
        (target_accel(&p, 0.0, p.desired_speed, stopped(100.0), Relax::NONE) - p.max_accel).abs()
            < 1e-12
    );
}

#[test]
fn gipps_term_special_cases() {
    let p = p();
    // Large gap: capped at a_M.
    assert_eq!(
        gipps_accel(
            &p,
            10.0,
            Leader {
                gap_m: 500.0,
                v_mps: 10.0
            },
            Relax::NONE
        ),
        p.max_accel
    );
    // Negative radicand (gap below the jam gap, moving): v_G = 0 → a_G = −v/τ_r.
    let a = gipps_accel(
        &p,
        10.0,
        Leader {
            gap_m: -0.5,
            v_mps: 0.0,
        },
        Relax::NONE,
    );
    assert!((a - (-10.0 / 1.2)).abs() < 1e-12, "{a}");
    // Relaxed reaction time: τ_r' = 0.2 τ_r makes the same emergency 5x harsher.
    let a_r = gipps_accel(
        &p,
        10.0,
        Leader {
            gap_m: -0.5,
            v_mps: 0.0,
        },
        RELAXED,
    );
    assert!((a_r - (-10.0 / 0.24)).abs() < 1e-9, "{a_r}");
    // a_G is monotone in the gap (v_G floored at 0: no jump at the radicand's root).
    let mut prev = f64::NEG_INFINITY;
    for i in 0..2000 {
        let g = -2.0 + i as f64 * 0.05;
        let a = gipps_accel(
            &p,
            15.0,
            Leader {
                gap_m: g,
                v_mps: 5.0,
            },
            Relax::NONE,
        );
        assert!(a >= prev - 1e-12, "gap {g}: {a} < {prev}");
        prev = a;
    }
}

#[test]
fn relaxation_permits_a_smaller_gap() {
    let p = p();
    let v = 25.0;
    let g_none = equilibrium_gap(&p, v, Relax::NONE);
    let g_rel = equilibrium_gap(&p, v, RELAXED);
    assert!(g_rel < 0.5 * g_none, "{g_rel} vs {g_none}");
    // A cut-in at 60 % of the normal equilibrium gap, same speeds.
    let l = Some(Leader {
        gap_m: 0.6 * g_none,
        v_mps: v,
    });
    let a_none = target_accel(&p, v, p.desired_speed, l, Relax::NONE);
    let a_rel = target_accel(&p, v, p.desired_speed, l, RELAXED);
    assert!(a_none < -1.0, "{a_none}");
    assert!(a_rel > a_none, "{a_rel} vs {a_none}");
    assert!(a_rel >= 0.0, "relaxed driver accepts the gap: {a_rel}");
    // The [P15-code] default factors (0.5, 0.5, 1.0) also shrink the gap, less so.
    let code = Relax {
        headway: 0.5,
        jam: 0.5,
        reaction: 1.0,
    };
    let g_code = equilibrium_gap(&p, v, code);
    assert!(g_code < g_none && g_code > g_rel);
}

#[test]
fn smoothing_is_a_first_order_filter() {
    assert_eq!(smooth_accel(0.0, 2.0, 2.0), 1.0);
    assert_eq!(smooth_accel(-1.0, 1.0, 1.0), 1.0);
    assert_eq!(smooth_accel(0.5, -3.5, 4.0), -0.5);
    // ω < 1 (invalid) is treated as ω = 1.
    assert_eq!(smooth_accel(0.0, 2.0, 0.3), 2.0);
    // Repeated application halves the error each step for ω = 2.
    let mut a = 0.0;
    for k in 1..=10 {
        a = smooth_accel(a, 1.0, 2.0);
        assert!((1.0 - a - 0.5_f64.powi(k)).abs() < 1e-12);
    }
}

/// One human follower behind a stopped vehicle (spec 1 update, spec 2.4 smoothing).
/// Returns (min gap, final gap, final speed, min acceleration, max acceleration).
fn approach_stopped(p: &HumanParams, gap0: f64, v0: f64, t_end: f64) -> (f64, f64, f64, f64, f64) {
    let (mut gap, mut v, mut a) = (gap0, v0, 0.0);
    let (mut min_gap, mut min_a, mut max_a) = (gap0, f64::INFINITY, f64::NEG_INFINITY);
    for _ in 0..(t_end / DT) as usize {
        let target = target_accel(
            p,
            v,
            p.desired_speed,
            Some(Leader {
                gap_m: gap,
                v_mps: 0.0,
            }),
            Relax::NONE,
        );
        a = smooth_accel(a, target, p.smoothing);
        let v_new = (v + a * DT).max(0.0);
        gap -= 0.5 * (v + v_new) * DT;
        v = v_new;
        min_gap = min_gap.min(gap);
        min_a = min_a.min(a);
        max_a = max_a.max(a);
    }
    (min_gap, gap, v, min_a, max_a)
}

#[test]
fn human_approaching_a_stopped_vehicle_stops_behind_it() {
    let p = p();
    let (min_gap, final_gap, final_v, min_a, max_a) = approach_stopped(&p, 200.0, 30.0, 120.0);
    println!("human approach 30 m/s from 200 m: min gap {min_gap:.3} m, final gap {final_gap:.3} m, final v {final_v:.4}, accel [{min_a:.2}, {max_a:.2}]");
    assert!(min_gap > 0.0);
    assert!(final_v < 1e-3);
    assert!(final_gap > 1.0 && final_gap < 3.0, "{final_gap}");
    // The Gipps term starts braking early enough that the driver never exceeds b_f.
    assert!(min_a >= p.max_decel - 1e-9, "{min_a}");
    // The same from 120 m at 30 m/s is an emergency: Gipps brakes harder than b_f, still no crash.
    let (min_gap, _, final_v, min_a, _) = approach_stopped(&p, 120.0, 30.0, 120.0);
    println!("human approach 30 m/s from 120 m: min gap {min_gap:.3} m, min accel {min_a:.2}");
    assert!(min_gap > 0.0 && final_v < 1e-3);
}

#[test]
fn a_human_platoon_in_equilibrium_stays_there() {
    // Leader at 22 m/s, follower at the equilibrium gap: a* = 0 and stays 0.
    let p = p();
    let v = 22.0;
    let g = equilibrium_gap(&p, v, Relax::NONE);
    let a = target_accel(
        &p,
        v,
        p.desired_speed,
        Some(Leader { gap_m: g, v_mps: v }),
        Relax::NONE,
    );
    assert!(a.abs() < 1e-9, "{a}");
}

/// Cross-lane friction (spec 2.7): v_adj + c_fr (v_F − v_adj) below v_F, v_F otherwise.
#[test]
fn friction_pulls_the_desired_speed_toward_a_slower_adjacent_lane() {
    let v_f = 30.0;
    // Spec form, hand-computed: 5 + 0.2 · (30 − 5) = 10 m/s.
    assert_eq!(friction_desired_speed(v_f, 5.0, 0.2), 10.0);
    // c_fr = 1 is off (exactly v_F); c_fr = 0 drives at the adjacent lane's speed.
    assert_eq!(friction_desired_speed(v_f, 5.0, 1.0), v_f);
    assert_eq!(friction_desired_speed(v_f, 5.0, 0.0), 5.0);
    // A faster (or equally fast) adjacent lane adds nothing.
    assert_eq!(friction_desired_speed(v_f, 35.0, 0.2), v_f);
    assert_eq!(friction_desired_speed(v_f, v_f, 0.2), v_f);
    // Monotone in v_adj and in c_fr, and inside [v_adj, v_F].
    let mut prev = f64::NEG_INFINITY;
    for i in 0..=30 {
        let v_adj = f64::from(i);
        let d = friction_desired_speed(v_f, v_adj, 0.3);
        assert!(d >= prev && d >= v_adj && d <= v_f, "v_adj {v_adj}: {d}");
        prev = d;
    }
    let mut prev = f64::NEG_INFINITY;
    for i in 0..=10 {
        let d = friction_desired_speed(v_f, 12.0, f64::from(i) / 10.0);
        assert!(d >= prev);
        prev = d;
    }
}
