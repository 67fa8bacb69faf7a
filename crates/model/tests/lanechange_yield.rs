//! Cooperative yielding (spec 4.5): who agrees, and how the yielder drives.

use platoonsim_model::human::{target_accel, HumanParams};
use platoonsim_model::lanechange::{agrees_to_yield, yield_accel, LaneChangeParams};
use platoonsim_model::{Leader, Relax};

#[test]
fn mandatory_requests_are_granted_with_probability_zeta_discretionary_half_of_it() {
    let p = LaneChangeParams {
        cooperativeness: 0.8,
        discretionary_coop_factor: 0.5,
        ..LaneChangeParams::default()
    };
    assert!(agrees_to_yield(&p, true, 0.79));
    assert!(!agrees_to_yield(&p, true, 0.81));
    assert!(agrees_to_yield(&p, false, 0.39));
    assert!(!agrees_to_yield(&p, false, 0.41));
    // Over a uniform grid of draws the shares are ζ and ζ/2.
    let n = 10_000;
    let share = |m| {
        (0..n)
            .filter(|&i| agrees_to_yield(&p, m, (i as f64 + 0.5) / n as f64))
            .count() as f64
            / n as f64
    };
    assert!((share(true) - 0.8).abs() < 1e-3);
    assert!((share(false) - 0.4).abs() < 1e-3);
}

#[test]
fn yielder_slows_for_a_requester_ahead_but_never_harder_than_comfortable() {
    let h = HumanParams::default();
    let p = LaneChangeParams::default();
    let v = 25.0;
    // Free road ahead in its own lane: normal car following accelerates toward v_F.
    let a_cf = target_accel(&h, v, h.desired_speed, None, Relax::NONE);
    assert!(a_cf > 0.0);
    // A slower requester in the next lane 15 m ahead: the yielder gives up accelerating.
    let near = Leader {
        gap_m: 15.0,
        v_mps: 20.0,
    };
    let a = yield_accel(&h, &p, v, h.desired_speed, a_cf, near);
    assert!(a < 0.0, "{a}");
    // Very close and much slower: the yield is capped at the comfortable deceleration b_c.
    let close = Leader {
        gap_m: 2.0,
        v_mps: 10.0,
    };
    assert_eq!(
        yield_accel(&h, &p, v, h.desired_speed, a_cf, close),
        h.comfort_decel
    );
    // The real leader still wins when it is more restrictive (e.g. an emergency stop).
    assert_eq!(yield_accel(&h, &p, v, h.desired_speed, -6.0, close), -6.0);
    // The virtual leader is followed with relaxed parameters: a requester at a gap the relaxed
    // model accepts costs nothing beyond normal car following.
    let comfortable = Leader {
        gap_m: 60.0,
        v_mps: 25.0,
    };
    let a = yield_accel(&h, &p, v, h.desired_speed, a_cf, comfortable);
    assert_eq!(a, a_cf);
}
