//! Property tests: no human car-following function returns NaN for finite inputs with v ≥ 0
//! (gap may be slightly negative), over drawn drivers and relaxation factors.

use platoonsim_model::human::{
    equilibrium_gap, free_accel, gipps_accel, newell_accel, smooth_accel, target_accel, HumanDists,
    HUMAN_DRAWS,
};
use platoonsim_model::{Leader, Relax};
use proptest::prelude::*;

fn relax() -> impl Strategy<Value = Relax> {
    prop_oneof![
        Just(Relax::NONE),
        (0.05..1.0f64, 0.05..1.0f64, 0.05..1.0f64).prop_map(|(headway, jam, reaction)| Relax {
            headway,
            jam,
            reaction
        }),
        Just(Relax {
            headway: 0.0,
            jam: 0.0,
            reaction: 0.0
        }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn no_nan_anywhere(
        z in proptest::array::uniform6(-3.0..3.0f64),
        v_f_kmh in 80.0..130.0f64,
        v in 0.0..45.0f64,
        gap in -1.0..500.0f64,
        v_l in 0.0..45.0f64,
        v_des in 0.0..45.0f64,
        r in relax(),
        a_prev in -10.0..3.0f64,
    ) {
        let z: [f64; HUMAN_DRAWS] = z;
        let p = HumanDists::default().sample(&z, v_f_kmh / 3.6);
        let l = Leader { gap_m: gap, v_mps: v_l };
        let a_n = newell_accel(&p, v, gap, r);
        prop_assert!(a_n.is_finite() && a_n >= p.max_decel && a_n <= p.max_accel);
        let a_f = free_accel(&p, v, v_des);
        prop_assert!(a_f.is_finite() && a_f <= p.max_accel);
        let a_g = gipps_accel(&p, v, l, r);
        prop_assert!(a_g.is_finite() && a_g <= p.max_accel);
        let a = target_accel(&p, v, v_des, Some(l), r);
        prop_assert!(a.is_finite() && a <= a_n && a <= a_g && a <= a_f);
        prop_assert!(target_accel(&p, v, v_des, None, r).is_finite());
        let s = smooth_accel(a_prev, a, p.smoothing);
        prop_assert!(s.is_finite() && s >= a_prev.min(a) && s <= a_prev.max(a));
        let g = equilibrium_gap(&p, v, r);
        prop_assert!(g.is_finite());
    }

    #[test]
    fn equilibrium_gap_holds_speed(
        z in proptest::array::uniform6(-3.0..3.0f64),
        v_f_kmh in 80.0..130.0f64,
        frac in 0.0..1.0f64,
        r in relax(),
    ) {
        let p = HumanDists::default().sample(&z, v_f_kmh / 3.6);
        let v = frac * p.desired_speed;
        let g = equilibrium_gap(&p, v, r);
        let a = target_accel(&p, v, p.desired_speed, Some(Leader { gap_m: g, v_mps: v }), r);
        prop_assert!(a >= -1e-6, "v {}: a {} at gap {}", v, a, g);
    }
}
