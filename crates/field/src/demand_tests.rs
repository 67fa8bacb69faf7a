//! Tests of the demand estimate on a synthetic corridor with known flows.

use super::*;

/// Entrance at 0; on-ramps A (1 km) and C (3 km); off-ramps B (2 km) and D (4 km).
fn corridor() -> Corridor {
    Corridor {
        entrance_x: 0.0,
        on_ramps: vec![("A".into(), 1000.0), ("C".into(), 3000.0)],
        off_ramps: vec![("B".into(), 2000.0), ("D".into(), 4000.0)],
    }
}

/// Known flows per interval: [q0, rA, rC, eB, eD] (unknown order: entrance, on, off).
const TRUTH: [[f64; 5]; 3] = [
    [3000.0, 600.0, 450.0, 500.0, 700.0],
    [3600.0, 900.0, 300.0, 800.0, 400.0],
    [2000.0, 0.0, 250.0, 300.0, 100.0],
];
const STATIONS: [f64; 5] = [500.0, 1500.0, 2500.0, 3500.0, 4500.0];

/// Counts from the truth; `measured` ramps counted; mainline counts times (1 + noise_k).
fn counts(measured: &[&str], noise: f64) -> Vec<Counts> {
    let c = corridor();
    TRUTH
        .iter()
        .map(|u| Counts {
            mainline: STATIONS
                .iter()
                .enumerate()
                .map(|(k, &x)| {
                    // A fixed pattern of signs and sizes, so the test is deterministic.
                    let e = noise * [1.0, -0.7, 0.4, -1.0, 0.8][k];
                    (x, balance(&c, u, x) * (1.0 + e))
                })
                .collect(),
            ramps: [("A", 1), ("C", 2), ("B", 3), ("D", 4)]
                .iter()
                .filter(|(id, _)| measured.contains(id))
                .map(|(id, i)| (id.to_string(), u[*i]))
                .collect(),
            storage_vph: Vec::new(),
        })
        .collect()
}

fn close(a: f64, b: f64, tol: f64) {
    assert!((a - b).abs() <= tol, "{a} vs {b} (tolerance {tol})");
}

fn check(e: &Estimate, tol: f64) {
    for (k, u) in TRUTH.iter().enumerate() {
        close(e.mainline_vph[k], u[0], tol);
        close(e.on_ramp_vph[0][k], u[1], tol);
        close(e.on_ramp_vph[1][k], u[2], tol);
        close(e.exit_vph[0][k], u[3], tol);
        close(e.exit_vph[1][k], u[4], tol);
    }
}

#[test]
fn every_ramp_measured_recovers_the_flows_exactly() {
    let e = estimate(&corridor(), &counts(&["A", "B", "C", "D"], 0.0)).unwrap();
    check(&e, 1e-3);
    // Exit fractions: eB / (q0 + rA), eD / (q0 + rA - eB + rC).
    for (k, u) in TRUTH.iter().enumerate() {
        close(e.exit_fraction[0][k], u[3] / (u[0] + u[1]), 1e-9);
        close(
            e.exit_fraction[1][k],
            u[4] / (u[0] + u[1] - u[3] + u[2]),
            1e-9,
        );
    }
}

#[test]
fn an_unmeasured_ramp_is_estimated_from_the_mainline() {
    // C is not counted: q(3500) - q(2500) gives it.
    let exact = estimate(&corridor(), &counts(&["A", "B", "D"], 0.0)).unwrap();
    check(&exact, 1e-3);
    // With noisy mainline counts the estimate is off by about the noise, and closes in as the
    // noise shrinks (consistency); measured ramps keep their counts.
    let err = |noise: f64| -> f64 {
        let e = estimate(&corridor(), &counts(&["A", "B", "D"], noise)).unwrap();
        for (k, u) in TRUTH.iter().enumerate() {
            close(e.on_ramp_vph[0][k], u[1], 0.5);
            close(e.exit_vph[0][k], u[3], 0.5);
        }
        TRUTH
            .iter()
            .enumerate()
            .map(|(k, u)| (e.on_ramp_vph[1][k] - u[2]).abs())
            .fold(0.0, f64::max)
    };
    let (big, small) = (err(0.02), err(0.002));
    assert!(big > 1.0 && big < 0.02 * 4000.0, "{big}");
    close(small, big / 10.0, big / 100.0);
}

#[test]
fn flows_are_never_negative() {
    // The mainline loses flow across an on-ramp with nothing counted there: least squares
    // would make the on-ramp negative; the estimate is 0 and the entrance takes the mean.
    let c = Corridor {
        entrance_x: 0.0,
        on_ramps: vec![("A".into(), 1000.0)],
        off_ramps: vec![],
    };
    let e = estimate(
        &c,
        &[Counts {
            mainline: vec![(500.0, 2000.0), (1500.0, 1800.0)],
            ramps: vec![],
            storage_vph: Vec::new(),
        }],
    )
    .unwrap();
    assert_eq!(e.on_ramp_vph[0][0], 0.0);
    close(e.mainline_vph[0], 1900.0, 1e-3);
}

#[test]
fn nnls_projects_onto_the_nonnegative_orthant() {
    let a = DMatrix::from_row_slice(3, 2, &[1.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
    // Unconstrained: x = (2, -1) fits exactly; with x >= 0: min (x1-2)^2 + 1 + (x1-1)^2 -> 1.5.
    let x = nnls(&a, &DVector::from_vec(vec![2.0, -1.0, 1.0]));
    close(x[0], 1.5, 1e-12);
    assert_eq!(x[1], 0.0);
}

#[test]
fn errors_name_the_ramp_or_station() {
    let bad = |counts: Counts| estimate(&corridor(), &[counts]).unwrap_err().to_string();
    let e = bad(Counts {
        mainline: vec![],
        ramps: vec![("Z".into(), 10.0)],
        storage_vph: Vec::new(),
    });
    assert!(e.contains("'Z'") && e.contains("A, C, B, D"), "{e}");
    let e = bad(Counts {
        mainline: vec![(-5.0, 10.0)],
        ramps: vec![],
        storage_vph: Vec::new(),
    });
    assert!(e.contains("x = -5"), "{e}");
    let e = bad(Counts::default());
    assert!(e.contains("interval 0") && e.contains("no count"), "{e}");
}

#[test]
fn nnls_equals_the_best_of_every_active_set() {
    // Small random problems (a fixed LCG): the brute-force optimum over every set of free
    // variables (least squares on it, feasible only if every value is >= 0) is the NNLS one.
    let mut s: u64 = 12345;
    let mut rand = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let (m, n) = (6, 4);
    for _ in 0..200 {
        let a = DMatrix::from_fn(m, n, |_, _| rand());
        let b = DVector::from_fn(m, |_, _| rand());
        let x = nnls(&a, &b);
        assert!(x.iter().all(|&v| v >= 0.0));
        let cost = |x: &DVector<f64>| (&a * x - &b).norm_squared();
        let mut best = f64::INFINITY;
        for mask in 0u32..(1 << n) {
            let free: Vec<bool> = (0..n).map(|j| mask >> j & 1 == 1).collect();
            let z = restricted_ls(&a, &b, &free);
            if z.iter().all(|&v| v >= -1e-12) {
                best = best.min(cost(&z));
            }
        }
        close(cost(&x), best, 1e-9);
    }
}

#[test]
fn a_growing_queue_restores_the_demand_behind_its_discharge() {
    // One station 2 km in, inside a queue that discharges 1,800 veh/h while it gains 150
    // vehicles in the 15-min interval (600 veh/h): 2,400 veh/h arrived at the entrance.
    let c = Corridor {
        entrance_x: 0.0,
        on_ramps: vec![],
        off_ramps: vec![],
    };
    let one = |g: Vec<f64>| {
        estimate(
            &c,
            &[Counts {
                mainline: vec![(2000.0, 1800.0)],
                ramps: vec![],
                storage_vph: g,
            }],
        )
        .unwrap()
        .mainline_vph[0]
    };
    close(one(vec![600.0]), 2400.0, 1e-3);
    close(one(Vec::new()), 1800.0, 1e-3); // the served flow, as before
    close(one(vec![-300.0]), 1500.0, 1e-3); // a draining queue: less arrived than passed
}

#[test]
fn stored_vehicles_integrate_the_densities_from_the_entrance() {
    // 20 veh/km from the entrance to 1 km, then linear to 60 veh/km at 3 km: 20 + 80.
    let st = [(1000.0, 20.0), (3000.0, 60.0), (5000.0, 10.0)];
    close(stored_vehicles(&st, 3000.0), 100.0, 1e-9);
    close(stored_vehicles(&st, 999.0), 0.0, 1e-9);
    close(stored_vehicles(&st, 1000.0), 20.0, 1e-9);
    close(stored_vehicles(&st, 6000.0), 170.0, 1e-9);
}

#[test]
fn an_exit_fraction_is_of_the_flow_that_reaches_the_diverge_not_of_the_queued_demand() {
    // 2,400 veh/h arrive, 600 veh/h of them queue before the station at 2 km; the exit at 3 km
    // counts 240 veh/h of the 1,800 that reach it: 0.1333, not 240/2400 = 0.1.
    let c = Corridor {
        entrance_x: 0.0,
        on_ramps: vec![],
        off_ramps: vec![("X".into(), 3000.0)],
    };
    let e = estimate(
        &c,
        &[Counts {
            mainline: vec![(2000.0, 1800.0)],
            ramps: vec![("X".into(), 240.0)],
            storage_vph: vec![600.0],
        }],
    )
    .unwrap();
    close(e.mainline_vph[0], 2400.0, 1e-3);
    close(e.exit_fraction[0][0], 240.0 / 1800.0, 1e-6);
}
