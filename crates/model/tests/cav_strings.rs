//! String behaviour of the CAV controllers (spec 5.3.1, 5.3.2): a single lane, Δt = 0.1 s,
//! synchronous updates, ballistic integration (spec 1), `finalize` applied every step.
//!
//! The CACC string-stability tests (spec 5.3.2: dips and sinusoids at t_C = 0.6-1.1 s) are in
//! `cav_string.rs`, with the findings in `docs/cacc-string-stability.md`: at 0.6 s the string
//! attenuates at the first follower and then grows by up to about 2 % per vehicle.

use platoonsim_model::cav::{acc, cacc, finalize, CavParams, Family};
use platoonsim_model::Leader;

const DT: f64 = 0.1;
const LEN: f64 = 4.0;

#[derive(Clone, Copy, Debug)]
struct Veh {
    x: f64,
    v: f64,
    a: f64,
    family: Family,
}

/// Leader acceleration: −2 m/s² for 3 s from t = 2 s, then +1 m/s² until back at v0.
fn leader_accel(t: f64, v: f64, v0: f64, decel: f64, dur: f64) -> f64 {
    if (2.0..2.0 + dur).contains(&t) {
        decel
    } else if t >= 2.0 + dur && v < v0 {
        1.0_f64.min((v0 - v) / DT)
    } else {
        0.0
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Law {
    Cacc(f64),
    Acc(f64),
}

struct Outcome {
    peak_dev: Vec<f64>,
    min_gap: f64,
    min_accel: f64,
}

fn run_string(
    p: &CavParams,
    law: Law,
    n: usize,
    v0: f64,
    decel: f64,
    dur: f64,
    t_end: f64,
) -> Outcome {
    let v_des = 110.0 / 3.6;
    let gap0 = match law {
        Law::Cacc(t) => platoonsim_model::cav::cacc_equilibrium_gap(p, t, v0),
        Law::Acc(t) => platoonsim_model::cav::acc_equilibrium_gap(p, t, v0),
    };
    let mut vs: Vec<Veh> = (0..n)
        .map(|i| Veh {
            x: -(i as f64) * (gap0 + LEN),
            v: v0,
            a: 0.0,
            family: Family::Gap,
        })
        .collect();
    let mut peak = vec![0.0_f64; n];
    let mut min_gap = f64::INFINITY;
    let mut min_accel = f64::INFINITY;
    let steps = (t_end / DT).round() as usize;
    for k in 0..steps {
        let t = k as f64 * DT;
        let mut acc_new = vec![0.0; n];
        let mut fam_new = vec![Family::Gap; n];
        for i in 0..n {
            let me = vs[i];
            if i == 0 {
                let a = leader_accel(t, me.v, v0, decel, dur);
                acc_new[i] = finalize(p, me.v, a, v_des, None, DT);
                continue;
            }
            let l = vs[i - 1];
            let leader = Leader {
                gap_m: l.x - LEN - me.x,
                v_mps: l.v,
            };
            let cmd = match law {
                Law::Cacc(tc) => cacc(p, me.v, me.a, v_des, leader, tc, me.family),
                Law::Acc(ta) => acc(p, me.v, v_des, Some(leader), ta, me.family),
            };
            fam_new[i] = cmd.family;
            acc_new[i] = finalize(p, me.v, cmd.accel, v_des, Some(leader), DT);
            min_accel = min_accel.min(acc_new[i]);
        }
        for i in 0..n {
            let v_old = vs[i].v;
            let v_new = (v_old + acc_new[i] * DT).max(0.0);
            vs[i].x += 0.5 * (v_old + v_new) * DT;
            vs[i].v = v_new;
            vs[i].a = acc_new[i];
            vs[i].family = fam_new[i];
            peak[i] = peak[i].max((v_new - v0).abs());
        }
        for i in 1..n {
            min_gap = min_gap.min(vs[i - 1].x - LEN - vs[i].x);
        }
    }
    Outcome {
        peak_dev: peak,
        min_gap,
        min_accel,
    }
}

fn round3(x: &[f64]) -> Vec<f64> {
    x.iter().map(|v| (v * 1000.0).round() / 1000.0).collect()
}

/// The leader dip of the task: −2 m/s² for 3 s, then +1 m/s² back to 25 m/s.
const DIP: (f64, f64) = (-2.0, 3.0);

#[test]
fn cacc_string_in_equilibrium_stays_in_equilibrium() {
    let p = CavParams::default();
    let o = run_string(&p, Law::Cacc(0.6), 5, 25.0, 0.0, 0.0, 60.0);
    assert!(o.peak_dev.iter().all(|&d| d < 1e-9), "{:?}", o.peak_dev);
    assert!(o.min_accel.abs() < 1e-9, "{}", o.min_accel);
}

#[test]
fn acc_with_milanes_gains_everywhere_is_string_unstable_xiao_gains_less_so() {
    // spec 5.3.1: closing and avoidance gains set back to the regulation gains 0.23/0.07.
    let xiao = CavParams::default();
    let milanes = CavParams {
        acc_closing_gains: [0.23, 0.07],
        acc_avoid_gains: [0.23, 0.07],
        ..CavParams::default()
    };
    let n = 8;
    let om = run_string(&milanes, Law::Acc(1.1), n, 25.0, DIP.0, DIP.1, 200.0);
    let ox = run_string(&xiao, Law::Acc(1.1), n, 25.0, DIP.0, DIP.1, 200.0);
    println!(
        "ACC Milanes gains: peak |v − 25| = {:?}, min gap {:.2} m",
        round3(&om.peak_dev),
        om.min_gap
    );
    println!(
        "ACC Xiao gains:    peak |v − 25| = {:?}, min gap {:.2} m",
        round3(&ox.peak_dev),
        ox.min_gap
    );
    // Milanés everywhere: the perturbation grows from vehicle 2 on and ends well above the
    // leader's (string instability, Milanés & Shladover 2014 Fig. 12 via SUMO docs).
    for i in 1..n - 1 {
        assert!(om.peak_dev[i + 1] > om.peak_dev[i], "{:?}", om.peak_dev);
    }
    assert!(om.peak_dev[n - 1] > 1.5 * om.peak_dev[0]);
    // Xiao's closing gains: no growth along the string for this disturbance.
    for i in 0..n - 1 {
        assert!(ox.peak_dev[i + 1] <= ox.peak_dev[i], "{:?}", ox.peak_dev);
    }
    let growth = |o: &Outcome| o.peak_dev[n - 1] / o.peak_dev[1];
    assert!(growth(&ox) < growth(&om));
    assert!(om.min_gap > 0.0 && ox.min_gap > 0.0);
}
