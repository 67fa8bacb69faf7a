//! Unit checks of the CAV control functions (spec 3.2-3.5, 3.8, 5.2.4).

use platoonsim_model::cav::{
    acc, acc_equilibrium_gap, acc_standstill_margin, acc_with_leader_length, cacc,
    cacc_equilibrium_gap, draw_time_gap, finalize, safe_speed, safety_gap, speed_regulation,
    CaccLaw, CavMode, CavParams, Family,
};
use platoonsim_model::human::{equilibrium_gap, HumanParams};
use platoonsim_model::{Leader, Relax};

const V110: f64 = 110.0 / 3.6;

fn p() -> CavParams {
    CavParams::default()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

fn leader(gap_m: f64, v_mps: f64) -> Leader {
    Leader { gap_m, v_mps }
}

// ---------- safety bound (spec 3.8, 5.2.4) ----------

#[test]
fn cav_safety_gap_at_110_kmh_is_0p4_s_and_below_the_0p6_s_cacc_gap() {
    let p = p();
    let g = safety_gap(&p, V110);
    println!(
        "CAV safety gap at 110 km/h: {g:.2} m (s_min + {:.2} m)",
        g - p.standstill_gap_m
    );
    // spec 3.8 prints 12.2 m (0.40 s): that is τ_r v; our gap adds the s_min jam gap of the
    // Gipps term (spec 3.4 "jam gap s_min"), 13.72 m in total.
    assert!(((g - p.standstill_gap_m) - 12.2).abs() < 0.05);
    assert!(((g - p.standstill_gap_m) / V110 - 0.40).abs() < 1e-9);
    // It is the smallest gap at which the safe speed allows holding 110 km/h.
    assert!((safe_speed(&p, g, V110) - V110).abs() < 1e-9);
    assert!(safe_speed(&p, g - 0.1, V110) < V110);
    // Every CACC setting (0.6-1.1 s) is feasible: its gap is larger, so the override is idle.
    for &(t, _) in &p.time_gap_shares {
        let g_c = cacc_equilibrium_gap(&p, t, V110);
        assert!(close(g_c, t * V110 + p.standstill_gap_m));
        assert!(g_c > g + 5.0, "t_C {t}: {g_c} vs {g}");
        let a = finalize(&p, V110, 0.0, V110, Some(leader(g_c, V110)), 0.1);
        assert_eq!(a, 0.0);
    }
}

#[test]
fn cav_bound_matches_the_human_gipps_term_and_b_hat_1p1_b_would_forbid_short_gaps() {
    let p = p();
    // The human Gipps term (spec 2.3) with τ_r = 0.4, θ = 0, c_b = 1, d_jam = s_min and b = −4.
    let as_human = HumanParams {
        reaction_s: 0.4,
        buffer_s: 0.0,
        leader_brake_factor: 1.0,
        jam_gap_m: p.standstill_gap_m,
        headway_s: 0.01,
        ..HumanParams::default()
    };
    for v in [0.0, 5.0, 15.0, 25.0, V110, 40.0] {
        assert!((equilibrium_gap(&as_human, v, Relax::NONE) - safety_gap(&p, v)).abs() < 1e-9);
    }
    // With b̂ = 1.1 b (spec 3.8): 22.8 m beyond s_min (0.75 s) → 0.6 and 0.7 s are infeasible.
    let b_hat_11 = HumanParams {
        leader_brake_factor: 1.1,
        ..as_human
    };
    let g = equilibrium_gap(&b_hat_11, V110, Relax::NONE);
    println!(
        "b_hat = 1.1 b: {g:.2} m (s_min + {:.2} m)",
        g - p.standstill_gap_m
    );
    assert!(((g - p.standstill_gap_m) - 22.8).abs() < 0.05);
    assert!(g > cacc_equilibrium_gap(&p, 0.6, V110) && g > cacc_equilibrium_gap(&p, 0.7, V110));
}

#[test]
fn safe_speed_values() {
    let p = p();
    // Standing leader, 100 m beyond s_min: −bτ_r... = −1.6 + sqrt(2.56 + 800).
    assert!(close(safe_speed(&p, 101.5, 0.0), -1.6 + 802.56_f64.sqrt()));
    assert_eq!(safe_speed(&p, p.standstill_gap_m, 0.0), 0.0);
    assert_eq!(safe_speed(&p, -1.0, 0.0), 0.0);
    assert_eq!(
        safe_speed(&p, -1.0, 30.0),
        -1.6 + (2.56 + 900.0 - 20.0_f64).sqrt()
    );
    let mut prev = -1.0;
    for i in 0..400 {
        let g = -2.0 + 0.5 * i as f64;
        let s = safe_speed(&p, g, 10.0);
        assert!(s >= prev && s >= 0.0);
        assert!(safe_speed(&p, g, 20.0) >= s);
        prev = s;
    }
}

// ---------- speed regulation, ACC (spec 3.2, 3.3) ----------

#[test]
fn speed_regulation_is_proportional() {
    assert!(close(speed_regulation(&p(), 20.0, 30.0), 4.0));
    assert!(close(speed_regulation(&p(), 30.0, 25.0), -2.0));
}

#[test]
fn acc_standstill_margin_values() {
    let p = p();
    assert_eq!(acc_standstill_margin(&p, 0.0), 2.0);
    assert_eq!(acc_standstill_margin(&p, 5.0), 2.0);
    assert!(close(acc_standstill_margin(&p, 11.0), 75.0 / 11.0 - 5.0));
    assert_eq!(acc_standstill_margin(&p, 12.0), 1.5);
    assert_eq!(acc_standstill_margin(&p, 30.0), 1.5);
    assert!(close(acc_equilibrium_gap(&p, 1.1, 30.0), 34.5));
    assert!(close(acc_equilibrium_gap(&p, 1.1, 0.0), 2.0));
    assert!(close(
        acc_equilibrium_gap(&p, 1.1, 11.0),
        12.1 + 75.0 / 11.0 - 5.0
    ));
    // Very short ACC gaps are lifted to the safety gap.
    assert!(close(
        acc_equilibrium_gap(&p, 0.2, 30.0),
        safety_gap(&p, 30.0)
    ));
}

#[test]
fn acc_without_leader_or_beyond_sensor_cruises() {
    let p = p();
    for l in [None, Some(leader(300.0, 0.0))] {
        for prev in [Family::Speed, Family::Gap] {
            let c = acc(&p, 20.0, 30.0, l, 1.1, prev);
            assert_eq!(
                (c.mode, c.family),
                (CavMode::SpeedRegulation, Family::Speed)
            );
            assert!(close(c.accel, 4.0));
        }
    }
}

#[test]
fn acc_spacing_hysteresis_100_120_m() {
    let p = p();
    let at = |gap: f64, prev| acc(&p, 25.0, 30.0, Some(leader(gap, 25.0)), 1.1, prev).family;
    // spacing = gap + 4 m
    assert_eq!(at(117.0, Family::Gap), Family::Speed); // 121 m
    assert_eq!(at(95.0, Family::Speed), Family::Gap); // 99 m
    assert_eq!(at(106.0, Family::Speed), Family::Speed); // 110 m: keep
    assert_eq!(at(106.0, Family::Gap), Family::Gap);
    assert_eq!(at(115.9, Family::Gap), Family::Gap); // 119.9 m
                                                     // With the actual leader length (a 15 m truck): 106 + 15 = 121 m → cruise.
    let c = acc_with_leader_length(
        &p,
        25.0,
        30.0,
        Some(leader(106.0, 25.0)),
        15.0,
        1.1,
        Family::Gap,
    );
    assert_eq!(c.family, Family::Speed);
}

#[test]
fn acc_sub_modes_and_gains() {
    let p = p();
    let v = 25.0; // d0 = 1.5, equilibrium gap 1.1·25 + 1.5 = 29
    let cmd = |gap: f64, v_l: f64| acc(&p, v, 30.0, Some(leader(gap, v_l)), 1.1, Family::Gap);
    let c = cmd(29.0, 25.0);
    assert_eq!(c.mode, CavMode::GapRegulation);
    assert!(close(c.accel, 0.0));
    let c = cmd(29.1, 25.05);
    assert_eq!(c.mode, CavMode::GapRegulation);
    assert!(close(c.accel, 0.23 * 0.1 + 0.07 * 0.05));
    let c = cmd(25.0, 24.0);
    assert_eq!(c.mode, CavMode::CollisionAvoidance);
    assert!(close(c.accel, 0.8 * -4.0 - 0.23));
    let c = cmd(50.0, 23.0);
    assert_eq!(c.mode, CavMode::GapClosing);
    assert!(close(c.accel, 0.04 * 21.0 + 0.8 * -2.0));
    // Inside the gap band but with a relative speed: not regulation.
    assert_eq!(cmd(29.1, 25.5).mode, CavMode::GapClosing);
    assert_eq!(cmd(28.9, 25.5).mode, CavMode::CollisionAvoidance);
}

// ---------- CACC (spec 3.4) ----------

#[test]
fn cacc_sub_modes_and_speed_update() {
    let p = p();
    let v = 25.0; // equilibrium gap 0.6·25 + 1.5 = 16.5
    let cmd = |gap: f64, v_l: f64, a_own: f64| {
        cacc(&p, v, a_own, 30.0, leader(gap, v_l), 0.6, Family::Gap)
    };
    let c = cmd(16.5, 25.0, 0.0);
    assert!(close(c.accel, 0.0));
    assert_eq!(c.family, Family::Gap);
    let c = cmd(16.6, 25.0, 0.0);
    assert_eq!(c.mode, CavMode::GapRegulation);
    assert!(close(c.accel, 0.45 * 0.1 / 0.1));
    let c = cmd(16.6, 25.05, 0.5);
    assert_eq!(c.mode, CavMode::GapRegulation);
    assert!(close(c.accel, (0.45 * 0.1 + 0.0125 * (0.05 - 0.3)) / 0.1));
    let c = cmd(15.5, 24.5, 0.2);
    assert_eq!(c.mode, CavMode::CollisionAvoidance);
    assert!(close(c.accel, (-0.45 + 0.05 * (-0.5 - 0.12)) / 0.1));
    // Gap above target, leader not slower: by default (model-choices 6.21) the regulation
    // gains; as spec 3.4 writes it, gap closing.
    let c = cmd(20.0, 25.0, 0.0);
    assert_eq!(c.mode, CavMode::GapRegulation);
    assert!(close(c.accel, 0.45 * 3.5 / 0.1));
    let c = cmd(20.0, 25.5, 0.5);
    assert_eq!(c.mode, CavMode::GapRegulation);
    assert!(close(c.accel, (0.45 * 3.5 + 0.0125 * (0.5 - 0.3)) / 0.1));
    // Approaching (Δv < 0): gap closing either way.
    let c = cmd(20.0, 24.0, 0.0);
    assert_eq!(c.mode, CavMode::GapClosing);
    assert!(close(c.accel, (0.005 * 3.5 - 0.05) / 0.1));
    let written = CavParams {
        cacc_closing_only_approaching: false,
        ..p.clone()
    };
    let c = cacc(&written, v, 0.0, 30.0, leader(20.0, 25.0), 0.6, Family::Gap);
    assert_eq!(c.mode, CavMode::GapClosing);
    assert!(close(c.accel, 0.005 * 3.5 / 0.1));
}

#[test]
fn cacc_time_gap_family_and_hysteresis() {
    let p = p();
    let fam = |v: f64, gap: f64, prev| cacc(&p, v, 0.0, 30.0, leader(gap, v), 0.6, prev);
    // tg = 60/25 = 2.4 s and e = 43.5 m → speed regulation.
    let c = fam(25.0, 60.0, Family::Gap);
    assert_eq!(
        (c.mode, c.family),
        (CavMode::SpeedRegulation, Family::Speed)
    );
    assert!(close(c.accel, 0.4 * 5.0));
    // tg = 1.8 s → previous family.
    assert_eq!(fam(25.0, 45.0, Family::Speed).family, Family::Speed);
    assert_eq!(fam(25.0, 45.0, Family::Gap).family, Family::Gap);
    // tg = 1.4 s → CACC family.
    assert_eq!(fam(25.0, 35.0, Family::Speed).family, Family::Gap);
    // v = 0: a positive gap is a large tg; speed regulation only if e > 1.66 m.
    assert_eq!(fam(0.0, 10.0, Family::Gap).family, Family::Speed);
    assert_eq!(fam(0.0, 2.0, Family::Speed).family, Family::Gap);
    assert_eq!(fam(0.0, 0.0, Family::Speed).family, Family::Gap);
    assert_eq!(
        fam(0.0, -0.5, Family::Speed).mode,
        CavMode::CollisionAvoidance
    );
    // tg = 2.5 s but e = 0.4 m ≤ 1.66 m → CACC family (choice [D]).
    assert_eq!(fam(1.0, 2.5, Family::Speed).family, Family::Gap);
    // The inter-platoon gap (1.5 s) works the same way: 1.5·25 + 1.5 = 39 m is equilibrium.
    let c = cacc(
        &p,
        25.0,
        0.0,
        30.0,
        leader(39.0, 25.0),
        p.inter_platoon_gap_s,
        Family::Gap,
    );
    assert!(close(c.accel, 0.0) && c.family == Family::Gap);
}

#[test]
fn cacc_speed_regulation_cap_follows_the_closing_rule() {
    // Leaving a queue: 2 m/s, 10 m behind a leader at 3 m/s (tg 5 s, e = 10 − 1.2 − 1.5 =
    // 7.3 m) → speed family, cruise asks 0.4·(30 − 2) = 11.2 m/s². The cap is the law the gap
    // family would use: by default (6.21) the regulation gains, as the leader is not slower:
    // (0.45·7.3 + 0.0125·1)/0.1 = 32.975, so cruise applies; as spec 3.4 writes it, gap
    // closing: (0.005·7.3 + 0.05·1)/0.1 = 0.865 m/s², which held strings back in queues.
    let p = p();
    let c = cacc(&p, 2.0, 0.0, 30.0, leader(10.0, 3.0), 0.6, Family::Gap);
    assert_eq!(c.mode, CavMode::SpeedRegulation);
    assert!(close(c.accel, 0.4 * 28.0));
    let written = CavParams {
        cacc_closing_only_approaching: false,
        ..p.clone()
    };
    let c = cacc(
        &written,
        2.0,
        0.0,
        30.0,
        leader(10.0, 3.0),
        0.6,
        Family::Gap,
    );
    assert_eq!(c.mode, CavMode::SpeedRegulation);
    assert!(close(c.accel, (0.005 * 7.3 + 0.05 * 1.0) / 0.1));
    // Approaching a slower leader, the cap is gap closing in both: 2 m/s behind one at 1 m/s.
    let c = cacc(&p, 2.0, 0.0, 30.0, leader(10.0, 1.0), 0.6, Family::Gap);
    assert!(close(c.accel, (0.005 * 7.3 - 0.05) / 0.1));
}

// ---------- finalize (spec 3.4 "After the law") ----------

#[test]
fn finalize_applies_vehicle_limits_without_leader() {
    let p = p();
    assert_eq!(finalize(&p, 20.0, 3.0, 30.0, None, 0.1), 1.5);
    assert_eq!(finalize(&p, 20.0, -10.0, 30.0, None, 0.1), -4.0);
    assert_eq!(finalize(&p, 20.0, 0.7, 30.0, None, 0.1), 0.7);
    // v_new ≤ v_des.
    assert!(close(finalize(&p, 29.95, 1.5, 30.0, None, 0.1), 0.5));
    assert_eq!(finalize(&p, 30.0, 1.0, 30.0, None, 0.1), 0.0);
    // Above v_des the acceleration limit wins: excess speed is shed at b.
    assert_eq!(finalize(&p, 35.0, 0.0, 30.0, None, 0.1), -4.0);
    // Never below standstill.
    assert!(close(finalize(&p, 0.2, -4.0, 30.0, None, 0.1), -2.0));
    assert_eq!(finalize(&p, 0.0, -4.0, 30.0, None, 0.1), 0.0);
}

#[test]
fn finalize_safety_override_may_exceed_b() {
    // The spec 3.4 override (the published law).
    let p = CavParams {
        cacc_law: CaccLaw::Spec,
        ..p()
    };
    // 30 m/s, 20 m behind a stopped car: cap = v_safe(20) + 2 = −1.6 + sqrt(150.56) + 2.
    let cap = -1.6 + 150.56_f64.sqrt() + 2.0;
    let a = finalize(&p, 30.0, 0.0, 30.0, Some(leader(20.0, 0.0)), 0.1);
    assert!(close(a, (cap - 30.0) / 0.1), "{a}");
    assert!(a < p.max_decel);
    // Gap already negative: stop within the step, no further.
    let a = finalize(&p, 10.0, 1.0, 30.0, Some(leader(-0.5, 0.0)), 0.1);
    assert!(close(a, -100.0));
    // Far leader: no effect.
    assert_eq!(
        finalize(&p, 20.0, 1.0, 30.0, Some(leader(200.0, 20.0)), 0.1),
        1.0
    );
    // Degenerate step: finite.
    assert!(finalize(&p, 10.0, 1.0, 30.0, Some(leader(5.0, 0.0)), 0.0).is_finite());
}

#[test]
fn under_the_field_law_the_override_sheds_the_excess_at_b_unless_the_law_asks_for_more() {
    let p = p();
    assert_eq!(p.cacc_law, CaccLaw::Field);
    // 30 m/s, 20 m behind a stopped car: the cap asks for (cap − 30)/0.1 = −159 m/s² within
    // the step; under the field law the override brakes at b = 4 when the law asks for less…
    let cap = -1.6 + 150.56_f64.sqrt() + 2.0;
    assert!((cap - 30.0) / 0.1 < -100.0);
    let a = finalize(&p, 30.0, 0.0, 30.0, Some(leader(20.0, 0.0)), 0.1);
    assert_eq!(a, p.max_decel);
    // … and at what the law asks for (its kinematic approach: 30² / (2 · 18.5) = 24.3 m/s²)
    // when that is more, never beyond the cap's own demand.
    let need = -900.0 / 37.0;
    let a = finalize(&p, 30.0, need, 30.0, Some(leader(20.0, 0.0)), 0.1);
    assert!(close(a, need), "{a}");
    let a = finalize(&p, 30.0, -500.0, 30.0, Some(leader(20.0, 0.0)), 0.1);
    assert!(close(a, (cap - 30.0) / 0.1), "{a}");
    // Below the cap nothing changes: the law's demand within the limits.
    assert_eq!(
        finalize(&p, 20.0, 1.0, 30.0, Some(leader(200.0, 20.0)), 0.1),
        1.0
    );
}

// ---------- time gaps (spec 3.5) ----------

#[test]
fn draw_time_gap_thresholds() {
    let p = p();
    for (u, t) in [
        (0.0, 0.6),
        (0.3, 0.6),
        (0.5699, 0.6),
        (0.5701, 0.7),
        (0.7, 0.7),
        (0.8099, 0.7),
        (0.8101, 0.9),
        (0.8799, 0.9),
        (0.8801, 1.1),
        (0.999_999, 1.1),
        (1.0, 1.1),
        (-0.2, 0.6),
    ] {
        assert_eq!(draw_time_gap(&p, u), t, "u = {u}");
    }
}

#[test]
fn draw_time_gap_shares_and_mean() {
    let p = p();
    let n = 100_000;
    let mut counts = [0usize; 4];
    let mut sum = 0.0;
    for i in 0..n {
        let t = draw_time_gap(&p, (i as f64 + 0.5) / n as f64);
        sum += t;
        let k = p.time_gap_shares.iter().position(|&(g, _)| g == t).unwrap();
        counts[k] += 1;
    }
    for (k, &(_, share)) in p.time_gap_shares.iter().enumerate() {
        assert!((counts[k] as f64 / n as f64 - share).abs() < 1e-3);
    }
    assert!(
        (sum / n as f64 - 0.705).abs() < 1e-3,
        "mean {}",
        sum / n as f64
    );
}

#[test]
fn draw_time_gap_degenerate_share_lists() {
    let mut p = p();
    p.time_gap_shares = vec![(0.6, 0.0), (0.8, 0.0)];
    assert_eq!(draw_time_gap(&p, 0.2), 0.6);
    assert_eq!(draw_time_gap(&p, 0.7), 0.8);
    p.time_gap_shares = vec![(0.6, 2.0), (0.8, 2.0)]; // unnormalised
    assert_eq!(draw_time_gap(&p, 0.49), 0.6);
    assert_eq!(draw_time_gap(&p, 0.51), 0.8);
    p.time_gap_shares.clear();
    assert_eq!(draw_time_gap(&p, 0.5), p.acc_time_gap_s);
}
