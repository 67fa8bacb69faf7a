//! The field form of the CACC (`cav.cacc_law = "field"`, docs/cacc-field.md) beside the
//! published law (`"spec"`): string stability of a 10-vehicle string with actuator lag, and
//! the manoeuvres of issue 44 (approach to a standing queue, a cut-in with the gap reset, a
//! leader braking at 4 m/s², a stop-and-go wave through a string). The tables of
//! docs/cacc-field.md are printed by
//! `cargo test --release -p platoonsim-model --test cacc_field -- --ignored --nocapture`.
//!
//! Set-up (as the engine runs an automated CAV, decide.rs): one lane, Δt = 0.1 s, synchronous
//! updates; each follower computes its law from the step-start state (the predecessor's gap
//! and speed, its realized acceleration of the last step as the beacon carries it, its own),
//! then `finalize` (the safety override and the limits), then the actuation of its law (field:
//! `actuate_field`, the ISO 15622 envelope, take-over requests, AEB; spec: `actuate`), then the
//! braking limit b_e; ballistic update. The leader follows its acceleration profile exactly
//! (the disturbance). Vehicles are 4 m long.

use platoonsim_model::cav::{
    acc, acc_by_law, actuate, actuate_field, approach_accel, cacc, cacc_by_law,
    cacc_equilibrium_gap, cut_in_time_gap, envelope, field_cacc, finalize, lag_gain, ramp_time_gap,
    CaccLaw, CavMode, CavParams, Family,
};
use platoonsim_model::safety::braking_limited;
use platoonsim_model::Leader;

const DT: f64 = 0.1;
const LEN: f64 = 4.0;
const V_DES: f64 = 33.0;

#[derive(Clone, Copy, Debug)]
struct Car {
    x: f64,
    v: f64,
    a: f64,
    family: Family,
    /// Effective time gap (the cut-in reset lowers it; the transition reopens it).
    tg: f64,
}

/// What a run measured.
#[derive(Clone, Debug, Default)]
struct Trace {
    /// Per vehicle (leader first): the largest |v − v0| (m/s).
    peak_dev: Vec<f64>,
    /// Per vehicle: the largest applied deceleration (m/s², positive).
    max_decel: Vec<f64>,
    /// Smallest net gap of any follower (m).
    min_gap: f64,
    /// Follower-steps under AEB and episodes of take-over requests.
    aeb_steps: u32,
    tor_episodes: u32,
    /// Largest jerk of braking build-up (m/s³) of any follower.
    max_jerk: f64,
    /// Speeds of every vehicle, per step (for the manoeuvre tests).
    v: Vec<Vec<f64>>,
    /// Net gaps of every follower, per step.
    gap: Vec<Vec<f64>>,
}

/// The law with exactly `lag` s of lag (the field law's low-level lag set to the same).
fn params(law: CaccLaw, lag: f64) -> CavParams {
    CavParams {
        cacc_law: law,
        actuator_lag_s: lag,
        field_low_level_lag_s: lag,
        ..CavParams::default()
    }
}

/// A string of `cars` (leader first, positions descending) with time gap `tg` under `p`; the
/// leader's acceleration is `lead(t, v)`; `steps` steps.
fn simulate(
    p: &CavParams,
    mut cars: Vec<Car>,
    tg: f64,
    lead: &dyn Fn(f64, f64) -> f64,
    steps: usize,
) -> Trace {
    let gain = lag_gain(DT, p.effective_lag_s());
    let n = cars.len();
    let v0: Vec<f64> = cars.iter().map(|c| c.v).collect();
    let mut tr = Trace {
        peak_dev: vec![0.0; n],
        max_decel: vec![0.0; n],
        min_gap: f64::INFINITY,
        ..Trace::default()
    };
    let mut tor = vec![false; n];
    for k in 0..steps {
        let t = k as f64 * DT;
        let mut next = cars.clone();
        next[0].a = lead(t, cars[0].v);
        for i in 1..n {
            let (c, l) = (cars[i], cars[i - 1]);
            let leader = Leader {
                gap_m: l.x - LEN - c.x,
                v_mps: l.v,
            };
            let time_gap = ramp_time_gap(p, c.tg, tg, DT);
            let cmd = cacc_by_law(p, c.v, c.a, l.a, V_DES, leader, time_gap, c.family);
            let a_req = finalize(p, c.v, cmd.accel, V_DES, Some(leader), DT);
            let (a, aeb, t_or) = match p.cacc_law {
                CaccLaw::Spec => {
                    let (a, aeb) = actuate(c.a, a_req, gain, p.max_automated_decel_mps2);
                    (a, aeb, false)
                }
                CaccLaw::Field => actuate_field(
                    c.a,
                    a_req,
                    gain,
                    p.max_automated_decel_mps2,
                    envelope(p, c.v),
                    DT,
                ),
            };
            tr.aeb_steps += u32::from(aeb);
            tr.tor_episodes += u32::from(t_or && !tor[i]);
            tor[i] = t_or;
            let a = braking_limited(a, p.emergency_decel_mps2);
            if a < 0.0 && a < c.a.min(0.0) {
                tr.max_jerk = tr.max_jerk.max((c.a.min(0.0) - a) / DT);
            }
            next[i].a = a;
            next[i].family = cmd.family;
            next[i].tg = time_gap;
        }
        for (i, c) in next.iter_mut().enumerate() {
            let v1 = (c.v + c.a * DT).max(0.0);
            let a_eff = (v1 - c.v) / DT;
            c.x += 0.5 * (c.v + v1) * DT;
            c.v = v1;
            c.a = a_eff;
            tr.peak_dev[i] = tr.peak_dev[i].max((c.v - v0[i]).abs());
            tr.max_decel[i] = tr.max_decel[i].max(-a_eff);
        }
        cars = next;
        tr.v.push(cars.iter().map(|c| c.v).collect());
        let gaps: Vec<f64> = (1..n).map(|i| cars[i - 1].x - LEN - cars[i].x).collect();
        for &g in &gaps {
            tr.min_gap = tr.min_gap.min(g);
        }
        tr.gap.push(gaps);
    }
    tr
}

/// `n` vehicles in equilibrium at `v` with time gap `tg` (net gap t v + s_min).
fn string(p: &CavParams, n: usize, v: f64, tg: f64) -> Vec<Car> {
    let gap = cacc_equilibrium_gap(p, tg, v);
    (0..n)
        .map(|i| Car {
            x: 5000.0 - i as f64 * (gap + LEN),
            v,
            a: 0.0,
            family: Family::Gap,
            tg,
        })
        .collect()
}

/// The leader brakes at `decel` (positive) for `secs` from t = 2 s, then recovers at 1 m/s² to
/// its starting speed `v0`.
fn dip(decel: f64, secs: f64, v0: f64) -> impl Fn(f64, f64) -> f64 {
    move |t, v| {
        if (2.0..2.0 + secs).contains(&t) {
            -decel
        } else if t >= 2.0 + secs && v < v0 - 1e-9 {
            (1.0f64).min((v0 - v) / DT)
        } else {
            0.0
        }
    }
}

/// The largest peak(i+1)/peak(i) from the leader on.
fn worst_ratio(tr: &Trace) -> f64 {
    tr.peak_dev
        .windows(2)
        .map(|w| w[1] / w[0])
        .fold(0.0, f64::max)
}

fn dip_run(law: CaccLaw, lag: f64, tg: f64, decel: f64, secs: f64) -> Trace {
    let p = params(law, lag);
    simulate(
        &p,
        string(&p, 10, 25.0, tg),
        tg,
        &dip(decel, secs, 25.0),
        600,
    )
}

// ---------------------------------------------------------------- the pure laws

#[test]
fn the_field_law_is_feed_forward_plus_pd_on_the_spacing_error() {
    let p = CavParams::default();
    assert_eq!(p.cacc_law, CaccLaw::Field);
    let l = Leader {
        gap_m: 20.0,
        v_mps: 24.0,
    };
    // e = 20 − 0.6·25 − 1.5 = 3.5, ė = −1 − 0.6·0.5 = −1.3; a = −1 + 0.2·3.5 + 0.7·(−1.3),
    // above the approach bound −1/(2·18.5).
    let c = field_cacc(&p, 25.0, 0.5, -1.0, 30.0, l, 0.6, Family::Gap);
    assert!((c.accel - (-1.0 + 0.7 - 0.91)).abs() < 1e-12, "{}", c.accel);
    assert_eq!((c.mode, c.family), (CavMode::GapClosing, Family::Gap));
    // The dispatcher: the field law, or the published one bit for bit.
    assert_eq!(
        cacc_by_law(&p, 25.0, 0.5, -1.0, 30.0, l, 0.6, Family::Gap),
        c
    );
    let spec = CavParams {
        cacc_law: CaccLaw::Spec,
        ..p.clone()
    };
    assert_eq!(
        cacc_by_law(&spec, 25.0, 0.5, -1.0, 30.0, l, 0.6, Family::Gap),
        cacc(&spec, 25.0, 0.5, 30.0, l, 0.6, Family::Gap)
    );
    assert_eq!(
        acc_by_law(&spec, 25.0, 30.0, Some(l), 0.0, 1.1, Family::Gap),
        acc(&spec, 25.0, 30.0, Some(l), 1.1, Family::Gap)
    );
}

#[test]
fn the_approach_bound_is_the_constant_deceleration_to_the_leaders_speed() {
    let p = CavParams::default();
    let standing = Leader {
        gap_m: 251.5,
        v_mps: 0.0,
    };
    assert!((approach_accel(&p, 30.0, standing, 0.0) - (-900.0 / 500.0)).abs() < 1e-12);
    let slower = Leader {
        gap_m: 51.5,
        v_mps: 20.0,
    };
    assert!((approach_accel(&p, 30.0, slower, 0.0) - (-1.0)).abs() < 1e-12);
    assert_eq!(approach_accel(&p, 20.0, slower, 0.0), f64::INFINITY);
    // It binds from 0.5 m/s² on: 5 m/s faster at 24 m beyond s_min asks for 25/48 = 0.52 m/s²,
    // at 26 m for 0.48 m/s² (no bound: the gap law closes the gap).
    let near = Leader {
        gap_m: 25.5,
        v_mps: 25.0,
    };
    assert!((approach_accel(&p, 30.0, near, 0.0) - (-25.0 / 48.0)).abs() < 1e-12);
    let farther = Leader {
        gap_m: 27.5,
        v_mps: 25.0,
    };
    assert_eq!(approach_accel(&p, 30.0, farther, 0.0), f64::INFINITY);
    // It caps the ACC too under the field law (min of the two), not under the published one.
    let far = Leader {
        gap_m: 240.0,
        v_mps: 14.0,
    };
    let a = acc_by_law(&p, 30.0, 30.0, Some(far), 0.0, 1.1, Family::Speed).accel;
    let own = acc(&p, 30.0, 30.0, Some(far), 1.1, Family::Speed).accel;
    assert_eq!(a, own.min(approach_accel(&p, 30.0, far, 0.0)));
    let spec = CavParams {
        cacc_law: CaccLaw::Spec,
        ..p
    };
    assert_eq!(
        acc_by_law(&spec, 30.0, 30.0, Some(far), 0.0, 1.1, Family::Speed).accel,
        own
    );
}

#[test]
fn the_approach_bound_anticipates_a_braking_leader() {
    let p = CavParams::default();
    // Same speed, 101.5 m apart (s = 100 m beyond s_min), the leader braking at 2 m/s² from
    // 25 m/s: it stops first (v_l Δv = 0 ≤ 2 s |ã|), so the follower must stop within
    // s + 25²/4 = 256.25 m: 625 / 512.5 = 1.2195 m/s², where a constant-speed leader would
    // ask for nothing.
    let braking = Leader {
        gap_m: 101.5,
        v_mps: 25.0,
    };
    let a = approach_accel(&p, 25.0, braking, -2.0);
    assert!(
        (a - 625.0 * -2.0 / (625.0 + 400.0)).abs() < 1e-12,
        "a = {a}"
    );
    assert!((a + 625.0 / 512.5).abs() < 1e-12);
    assert_eq!(approach_accel(&p, 25.0, braking, 0.0), f64::INFINITY);
    // A slower follower still brakes for a leader that will stop: 20 m/s behind 25 m/s.
    let b = approach_accel(&p, 20.0, braking, -3.0);
    assert!(
        (b - 400.0 * -3.0 / (625.0 + 600.0)).abs() < 1e-12,
        "b = {b}"
    );
    // Closing fast on a leader that brakes gently: the follower matches its speed while it
    // still moves (v_l Δv = 20 · 10 = 200 > 2 · 20 · 1 = 40): ã − Δv² / (2 s) = −1 − 2.5.
    let close = Leader {
        gap_m: 21.5,
        v_mps: 20.0,
    };
    let c = approach_accel(&p, 30.0, close, -1.0);
    assert!((c - (-1.0 - 100.0 / 40.0)).abs() < 1e-12, "c = {c}");
    // The cases meet: as the leader's braking vanishes the bound tends to the constant-speed
    // one; a standing leader's last braking step changes nothing; an accelerating leader
    // counts as a constant-speed one; NaN counts as 0.
    let faint = approach_accel(&p, 30.0, close, -1e-9);
    assert!((faint - approach_accel(&p, 30.0, close, 0.0)).abs() < 1e-6);
    let standing = Leader {
        gap_m: 251.5,
        v_mps: 0.0,
    };
    assert!((approach_accel(&p, 30.0, standing, -3.0) - (-900.0 / 500.0)).abs() < 1e-12);
    assert_eq!(
        approach_accel(&p, 30.0, close, 1.0),
        approach_accel(&p, 30.0, close, 0.0)
    );
    assert_eq!(
        approach_accel(&p, 30.0, close, f64::NAN),
        approach_accel(&p, 30.0, close, 0.0)
    );
}

#[test]
fn the_envelope_bounds_deceleration_and_jerk_by_speed() {
    let p = CavParams::default();
    assert_eq!(envelope(&p, 0.0), (5.0, 5.0));
    assert_eq!(envelope(&p, 5.0), (5.0, 5.0));
    assert_eq!(envelope(&p, 12.5), (4.25, 3.75));
    assert_eq!(envelope(&p, 30.0), (3.5, 2.5));
    let env = envelope(&p, 30.0);
    // Within the envelope, no lag, braking building up slowly enough: the demand itself.
    assert_eq!(
        actuate_field(-1.0, -1.2, 1.0, 5.0, env, 0.1),
        (-1.2, false, false)
    );
    // Braking builds up at most at J: from −1 at most to −1.25 in a step.
    assert_eq!(
        actuate_field(-1.0, -3.0, 1.0, 5.0, env, 0.1),
        (-1.25, false, false)
    );
    // Releasing is free; accelerating is not bounded by the jerk bound.
    assert_eq!(
        actuate_field(-3.0, 1.0, 1.0, 5.0, env, 0.1),
        (1.0, false, false)
    );
    // Beyond D: a take-over request, braking at D (here reached already).
    assert_eq!(
        actuate_field(-3.5, -4.5, 1.0, 5.0, env, 0.1),
        (-3.5, false, true)
    );
    // Beyond D_auto: AEB applies the demand.
    assert_eq!(
        actuate_field(-3.5, -7.0, 1.0, 5.0, env, 0.1),
        (-7.0, true, false)
    );
}

#[test]
fn a_cut_in_resets_the_reference_to_the_actual_gap() {
    let p = CavParams::default();
    // (13 − 1.5)/25 = 0.46 s, below the 0.6 s reference.
    assert!((cut_in_time_gap(&p, 0.6, 13.0, 25.0) - 0.46).abs() < 1e-12);
    // Never below τ_r = 0.4 s, never above the reference, nothing below 1 m/s.
    assert_eq!(cut_in_time_gap(&p, 0.6, 5.0, 25.0), 0.4);
    assert_eq!(cut_in_time_gap(&p, 0.6, 40.0, 25.0), 0.6);
    assert_eq!(cut_in_time_gap(&p, 0.6, 2.0, 0.5), 0.6);
    // Under the published law: unchanged.
    let spec = CavParams {
        cacc_law: CaccLaw::Spec,
        ..p
    };
    assert_eq!(cut_in_time_gap(&spec, 0.6, 13.0, 25.0), 0.6);
}

// ---------------------------------------------------------------- string stability

/// The acceptance case of issue 44: 10 vehicles at t_C = 0.6 s with a 0.3 s actuator lag. Under
/// the field law every dip shrinks from each vehicle to the next (amplification ≤ 1); under
/// the published law the same string amplifies it.
#[test]
fn the_field_law_is_string_stable_at_0p6_s_with_a_0p3_s_lag() {
    for (decel, secs) in [(2.0, 3.0), (1.0, 1.0), (4.0, 2.0)] {
        let f = dip_run(CaccLaw::Field, 0.3, 0.6, decel, secs);
        assert!(
            worst_ratio(&f) <= 1.0,
            "field, −{decel} m/s² × {secs} s: {:?}",
            f.peak_dev
        );
        // Within the envelope (3.5 m/s² at 25 m/s) the string brakes no harder than its
        // leader; a leader at 4 m/s² is beyond it: take-over requests, and AEB for at most a
        // step or two.
        if decel < 3.5 {
            assert_eq!((f.aeb_steps, f.tor_episodes), (0, 0), "{decel} {secs}");
            let md = f.max_decel.iter().copied().fold(0.0, f64::max);
            assert!(md <= decel + 1e-9, "{md}");
        } else {
            assert!(f.tor_episodes > 0 && f.aeb_steps <= 2, "{f:?}");
        }
        assert!(f.min_gap > 9.0, "{}", f.min_gap);
        let s = dip_run(CaccLaw::Spec, 0.3, 0.6, decel, secs);
        assert!(
            worst_ratio(&s) > 1.0,
            "spec, −{decel} m/s² × {secs} s: {:?}",
            s.peak_dev
        );
    }
}

/// From 0.2 to 0.5 s of lag, the field law keeps the 0.6 s string stable for the −2 m/s² dip of
/// 3 s (the published law amplifies it at every lag from 0.2 s).
#[test]
fn the_field_law_stays_string_stable_from_0p2_to_0p5_s_of_lag() {
    for lag in [0.2, 0.3, 0.4, 0.5] {
        let f = dip_run(CaccLaw::Field, lag, 0.6, 2.0, 3.0);
        assert!(worst_ratio(&f) <= 1.0, "lag {lag}: {:?}", f.peak_dev);
        let s = dip_run(CaccLaw::Spec, lag, 0.6, 2.0, 3.0);
        assert!(worst_ratio(&s) > 1.0, "lag {lag}: {:?}", s.peak_dev);
    }
}

#[test]
#[ignore = "prints the tables of docs/cacc-field.md"]
fn print_string_tables() {
    println!("| law | lag | dip | peaks veh 0..9 (m/s) | worst ratio | max decel | min gap | AEB steps | TOR |");
    for lag in [0.0, 0.2, 0.3, 0.5] {
        for (decel, secs) in [(2.0, 3.0), (1.0, 1.0), (4.0, 2.0)] {
            for law in [CaccLaw::Spec, CaccLaw::Field] {
                let t = dip_run(law, lag, 0.6, decel, secs);
                let peaks: Vec<String> = t.peak_dev.iter().map(|p| format!("{p:.3}")).collect();
                let md = t.max_decel.iter().copied().fold(0.0, f64::max);
                println!(
                    "| {} | {lag} | −{decel}×{secs} | {} | {:.3} | {md:.2} | {:.1} | {} | {} |",
                    law.as_str(),
                    peaks.join(" "),
                    worst_ratio(&t),
                    t.min_gap,
                    t.aeb_steps,
                    t.tor_episodes
                );
            }
        }
    }
}

// ---------------------------------------------------------------- manoeuvres

fn max_decel(t: &Trace) -> f64 {
    t.max_decel[1..].iter().copied().fold(0.0, f64::max)
}

/// A follower at 30 m/s finds a standing queue at the sensor range (250 m): `lag` s of lag.
fn approach(law: CaccLaw, lag: f64) -> Trace {
    let p = params(law, lag);
    let cars = vec![
        Car {
            x: 5000.0,
            v: 0.0,
            a: 0.0,
            family: Family::Gap,
            tg: 0.6,
        },
        Car {
            x: 5000.0 - LEN - 250.0,
            v: 30.0,
            a: 0.0,
            family: Family::Speed,
            tg: 0.6,
        },
    ];
    simulate(&p, cars, 0.6, &|_, _| 0.0, 600)
}

/// The field law starts braking at the sensor range at the constant deceleration that stops
/// it in time (30²/(2·248.5) = 1.81 m/s², a little more at the end) and stops behind the
/// queue; the published law closes in at speed and brakes later and harder (3.5 m/s² without
/// lag, 2.8 m/s² with 0.3 s).
#[test]
fn approach_to_a_standing_queue_is_early_and_comfortable() {
    for lag in [0.0, 0.3] {
        let f = approach(CaccLaw::Field, lag);
        assert!(max_decel(&f) < 2.2, "lag {lag}: {}", max_decel(&f));
        assert_eq!((f.aeb_steps, f.tor_episodes), (0, 0));
        let end = f.gap.last().unwrap()[0];
        // Stopped at s_min = 1.5 m (within 1 cm; never 0.1 mm inside it).
        assert!(
            f.min_gap > 1.5 - 1e-4 && (end - 1.5).abs() < 0.01,
            "{} {end}",
            f.min_gap
        );
        assert!(f.v.last().unwrap()[1] < 0.001, "{:?}", f.v.last());
        let s = approach(CaccLaw::Spec, lag);
        assert!(max_decel(&s) > 2.7, "lag {lag}: {}", max_decel(&s));
    }
}

/// A CAV cuts in 13 m ahead of a CACC follower at 25 m/s (both at 25 m/s; the follower's own
/// gap is 0.6·25 + 1.5 = 16.5 m). The field law resets its gap reference to the actual gap
/// (time gap 0.46 s) and reopens it at the transition rate (0.06 s/s): it hardly brakes and is
/// back at its own gap in some 15 s. The published law brakes at once (collision avoidance,
/// e = −3.5 m).
#[test]
fn a_cut_in_resets_the_gap_reference_and_reopens_it() {
    let run = |law: CaccLaw| {
        let p = params(law, 0.3);
        let tg = cut_in_time_gap(&p, 0.6, 13.0, 25.0);
        let cars = vec![
            Car {
                x: 5000.0,
                v: 25.0,
                a: 0.0,
                family: Family::Gap,
                tg: 0.6,
            },
            Car {
                x: 5000.0 - LEN - 13.0,
                v: 25.0,
                a: 0.0,
                family: Family::Gap,
                tg,
            },
        ];
        (tg, simulate(&p, cars, 0.6, &|_, _| 0.0, 400))
    };
    let (tg, f) = run(CaccLaw::Field);
    assert!((tg - 11.5 / 25.0).abs() < 1e-12, "{tg}");
    assert!(max_decel(&f) < 0.5, "{}", max_decel(&f));
    // Reopened: within 0.5 m of 16.5 m after 20 s, never below the cut-in gap.
    assert!((f.gap[200][0] - 16.5).abs() < 0.5, "{}", f.gap[200][0]);
    assert!(f.min_gap > 12.99, "{}", f.min_gap);
    let (tg, s) = run(CaccLaw::Spec);
    assert_eq!(tg, 0.6);
    assert!(max_decel(&s) > 2.0 * max_decel(&f), "{}", max_decel(&s));
}

/// A leader braking at 4 m/s² to a stop from 25 m/s, 10 vehicles at 0.6 s with 0.3 s of lag:
/// the envelope (3.5 m/s² at speed) is not enough, the followers ask their drivers to take
/// over, and near standstill AEB brakes them (to b_e): no collision, but AEB under both laws,
/// under a third as many AEB steps under the field law as under the published one.
#[test]
fn a_leader_braking_at_4_to_a_stop() {
    let f = dip_run(CaccLaw::Field, 0.3, 0.6, 4.0, 6.25);
    let s = dip_run(CaccLaw::Spec, 0.3, 0.6, 4.0, 6.25);
    // Both strings stop at s_min = 1.5 m without touching. Under the field law the override
    // sheds the excess over its cap at b over a few steps (docs/cacc-field.md, the override),
    // so the last follower settles within a millimetre of s_min (1.4996 m).
    assert!(
        f.min_gap > 1.49 && s.min_gap > 1.5,
        "{} {}",
        f.min_gap,
        s.min_gap
    );
    assert!(f.tor_episodes > 0);
    assert!(
        f.aeb_steps > 0 && 3 * f.aeb_steps < s.aeb_steps,
        "{} {}",
        f.aeb_steps,
        s.aeb_steps
    );
}

/// A stop-and-go wave: the leader brakes at 2 m/s² from 25 to 5 m/s, holds 10 s, accelerates
/// at 1 m/s² back. Field law, 0.6 s, 0.3 s lag: no take-over request, nobody brakes more than
/// 0.05 m/s² harder than the leader, but the dip is not strictly damped: each follower
/// undershoots the 5 m/s plateau a little (growth ≤ 0.4 % per vehicle); the published law
/// grows it more than twice as fast.
fn stop_and_go(law: CaccLaw) -> Trace {
    let p = params(law, 0.3);
    let lead = |t: f64, v: f64| {
        if (2.0..12.0).contains(&t) {
            -2.0
        } else if (12.0..22.0).contains(&t) {
            0.0
        } else if t >= 22.0 && v < 25.0 - 1e-9 {
            (1.0f64).min((25.0 - v) / DT)
        } else {
            0.0
        }
    };
    simulate(&p, string(&p, 10, 25.0, 0.6), 0.6, &lead, 900)
}

#[test]
fn a_stop_and_go_wave_through_a_string() {
    let f = stop_and_go(CaccLaw::Field);
    assert!(worst_ratio(&f) <= 1.004, "{:?}", f.peak_dev);
    assert!(max_decel(&f) <= 2.05, "{}", max_decel(&f));
    assert_eq!((f.aeb_steps, f.tor_episodes), (0, 0));
    let s = stop_and_go(CaccLaw::Spec);
    assert!(
        worst_ratio(&s) - 1.0 > 2.0 * (worst_ratio(&f) - 1.0),
        "{:?}",
        s.peak_dev
    );
}

#[test]
#[ignore = "prints the manoeuvre table of docs/cacc-field.md"]
fn print_manoeuvres() {
    println!(
        "| manoeuvre | law | largest deceleration | smallest gap | worst ratio | TOR | AEB steps |"
    );
    let row = |name: &str, law: CaccLaw, t: &Trace| {
        println!(
            "| {name} | {} | {:.2} | {:.2} | {:.3} | {} | {} |",
            law.as_str(),
            max_decel(t),
            t.min_gap,
            worst_ratio(t),
            t.tor_episodes,
            t.aeb_steps
        );
    };
    for law in [CaccLaw::Spec, CaccLaw::Field] {
        row("approach 30 m/s → queue, lag 0", law, &approach(law, 0.0));
        row("approach, lag 0.3", law, &approach(law, 0.3));
        row("leader −4 to stop", law, &dip_run(law, 0.3, 0.6, 4.0, 6.25));
        row("stop-and-go", law, &stop_and_go(law));
    }
}
