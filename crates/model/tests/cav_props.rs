//! Property tests: no CAV function returns NaN for finite inputs with v ≥ 0 (gap may be
//! slightly negative), and `finalize` keeps its promises.

use platoonsim_model::cav::{
    acc, acc_equilibrium_gap, cacc, cacc_equilibrium_gap, draw_time_gap, finalize, safe_speed,
    safety_gap, speed_regulation, CavParams, Family,
};
use platoonsim_model::Leader;
use proptest::prelude::*;

fn family() -> impl Strategy<Value = Family> {
    prop_oneof![Just(Family::Speed), Just(Family::Gap)]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn no_nan_anywhere(
        v in 0.0..45.0f64,
        gap in -1.0..500.0f64,
        v_l in 0.0..45.0f64,
        a_own in -10.0..3.0f64,
        v_des in 0.0..45.0f64,
        t in 0.5..2.0f64,
        prev in family(),
        u in 0.0..1.0f64,
    ) {
        let p = CavParams::default();
        let l = Leader { gap_m: gap, v_mps: v_l };
        let c = acc(&p, v, v_des, Some(l), t, prev);
        prop_assert!(c.accel.is_finite());
        let c = acc(&p, v, v_des, None, t, prev);
        prop_assert!(c.accel.is_finite());
        let c = cacc(&p, v, a_own, v_des, l, t, prev);
        prop_assert!(c.accel.is_finite());
        prop_assert!(speed_regulation(&p, v, v_des).is_finite());
        let s = safe_speed(&p, gap, v_l);
        prop_assert!(s.is_finite() && s >= 0.0);
        prop_assert!(safety_gap(&p, v).is_finite());
        prop_assert!(cacc_equilibrium_gap(&p, t, v).is_finite());
        prop_assert!(acc_equilibrium_gap(&p, t, v).is_finite());
        let tg = draw_time_gap(&p, u);
        prop_assert!(p.time_gap_shares.iter().any(|&(g, _)| g == tg));
    }

    #[test]
    fn finalize_keeps_its_promises(
        v in 0.0..45.0f64,
        a_cmd in -60.0..60.0f64,
        v_des in 0.0..45.0f64,
        gap in -1.0..500.0f64,
        v_l in 0.0..45.0f64,
        has_leader in any::<bool>(),
        dt in prop_oneof![Just(0.1f64), Just(0.05f64), Just(0.2f64)],
    ) {
        let p = CavParams::default();
        let leader = has_leader.then_some(Leader { gap_m: gap, v_mps: v_l });
        let a = finalize(&p, v, a_cmd, v_des, leader, dt);
        prop_assert!(a.is_finite());
        let v_new = v + a * dt;
        let tol = 1e-9;
        prop_assert!(v_new >= -tol, "negative speed {}", v_new);
        prop_assert!(a <= p.max_accel + tol);
        prop_assert!(v_new <= v.max(v_des) + tol);
        // The override only ever lowers the limited command; braking beyond b only through it.
        let limited = finalize(&p, v, a_cmd, v_des, None, dt);
        prop_assert!(limited >= p.max_decel.min(-v / dt) - tol && limited <= p.max_accel + tol);
        prop_assert!(a <= limited + tol);
        if a < p.max_decel - tol {
            prop_assert!(leader.is_some() && a < limited);
        }
        // No leader, or a leader far away moving as fast: the override is idle.
        if let Some(l) = leader {
            if l.gap_m > 100.0 + 5.0 * v && l.v_mps >= v {
                prop_assert!((a - limited).abs() < tol);
            }
        }
    }

    #[test]
    fn safe_speed_holds_exactly_at_the_safety_gap(v in 0.0..45.0f64) {
        let p = CavParams::default();
        prop_assert!((safe_speed(&p, safety_gap(&p, v), v) - v).abs() < 1e-6);
    }
}
