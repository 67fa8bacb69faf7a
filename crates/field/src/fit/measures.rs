//! The goodness-of-fit measures, one pure function each, of simulated values `m` and field
//! (counted, measured) values `c`.
//!
//! | measure | equation | source |
//! |---|---|---|
//! | GEH of an hourly flow | GEH = √(2 (M − C)² / (M + C)), M, C hourly volumes (veh/h) | UK DMRB Vol. 12 (traffic appraisal); FHWA Traffic Analysis Toolbox Vol. III (2004), Table 4 |
//! | link flow tolerance | \|M − C\| ≤ 100 veh/h for C < 700; ≤ 15 % of C for 700 ≤ C ≤ 2,700; ≤ 400 veh/h for C > 2,700 | FHWA Toolbox III (2004), Table 4 (after Wisconsin DOT 2002) |
//! | RMSE | √(mean (m − c)²) | — |
//! | RMSNE | √(mean ((m − c)/c)²), over pairs with c > 0 | root mean square normalized error, e.g. Hollander & Liu (2008), "The principles of calibrating traffic microsimulation models", Transportation 35 |
//! | correlation | Pearson's r = cov(m, c) / (σ_m σ_c) | — |
//!
//! Empty input (or, for r, fewer than two pairs or a constant series) has no value: `None`,
//! never a made-up 0.

/// GEH's limit for an individual hourly flow (FHWA Toolbox III 2004, Table 4).
pub const GEH_LIMIT: f64 = 5.0;

/// The GEH statistic of a simulated hourly volume `m` and a counted one `c` (veh/h). Both
/// zero is a perfect fit (0).
pub fn geh(m: f64, c: f64) -> f64 {
    let sum = m + c;
    if sum <= 0.0 {
        0.0
    } else {
        (2.0 * (m - c) * (m - c) / sum).sqrt()
    }
}

/// Whether a simulated hourly flow `m` is within the Toolbox III (2004, Table 4) tolerance of
/// the counted flow `c` (veh/h): 100 veh/h below 700 veh/h, 15 % from 700 to 2,700 veh/h,
/// 400 veh/h above 2,700 veh/h.
pub fn flow_within_tolerance(m: f64, c: f64) -> bool {
    let d = (m - c).abs();
    if c < 700.0 {
        d <= 100.0
    } else if c <= 2700.0 {
        d <= 0.15 * c
    } else {
        d <= 400.0
    }
}

/// Root mean square error of `(m, c)` pairs.
pub fn rmse(pairs: &[(f64, f64)]) -> Option<f64> {
    if pairs.is_empty() {
        return None;
    }
    let s: f64 = pairs.iter().map(|&(m, c)| (m - c) * (m - c)).sum();
    Some((s / pairs.len() as f64).sqrt())
}

/// Root mean square normalized error of `(m, c)` pairs; pairs with c ≤ 0 cannot be normalized
/// and are left out.
pub fn rmsne(pairs: &[(f64, f64)]) -> Option<f64> {
    let rel: Vec<f64> = pairs
        .iter()
        .filter(|&&(_, c)| c > 0.0)
        .map(|&(m, c)| (m - c) / c)
        .collect();
    if rel.is_empty() {
        return None;
    }
    Some((rel.iter().map(|r| r * r).sum::<f64>() / rel.len() as f64).sqrt())
}

/// Pearson's correlation of `(m, c)` pairs; `None` with fewer than two pairs or if either
/// series is constant (r is undefined).
pub fn pearson(pairs: &[(f64, f64)]) -> Option<f64> {
    if pairs.len() < 2 {
        return None;
    }
    let n = pairs.len() as f64;
    let mm = pairs.iter().map(|p| p.0).sum::<f64>() / n;
    let mc = pairs.iter().map(|p| p.1).sum::<f64>() / n;
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for &(m, c) in pairs {
        sxy += (m - mm) * (c - mc);
        sxx += (m - mm) * (m - mm);
        syy += (c - mc) * (c - mc);
    }
    if sxx <= 0.0 || syy <= 0.0 {
        return None;
    }
    Some((sxy / (sxx * syy).sqrt()).clamp(-1.0, 1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn geh_of_known_pairs() {
        // √(2 × 100² / 2100) = √(20000/2100) = 3.0860669992418384
        assert_eq!(geh(1100.0, 1000.0), (20_000.0f64 / 2100.0).sqrt());
        assert!((geh(1100.0, 1000.0) - 3.086_066_999_241_838).abs() < 1e-12);
        // Symmetric; 0 for equal flows and for both zero.
        assert_eq!(geh(1000.0, 1100.0), geh(1100.0, 1000.0));
        assert_eq!(geh(1234.0, 1234.0), 0.0);
        assert_eq!(geh(0.0, 0.0), 0.0);
        // 1500 vs 1000: √(2 × 500² / 2500) = √200 = 14.142…, far over the limit.
        assert_eq!(geh(1500.0, 1000.0), 200.0f64.sqrt());
        // The limit 5 is reached at m = 1000 + d with 2 d² = 25 (2000 + d):
        // d = (25 + √400625) / 4 = 164.49…
        assert!(geh(1164.0, 1000.0) < GEH_LIMIT && geh(1165.0, 1000.0) > GEH_LIMIT);
    }

    #[test]
    fn flow_tolerance_by_band() {
        assert!(flow_within_tolerance(600.0, 500.0));
        assert!(!flow_within_tolerance(600.5, 500.0));
        assert!(flow_within_tolerance(1150.0, 1000.0));
        assert!(!flow_within_tolerance(1151.0, 1000.0));
        // 15 % of 2,700 is 405 veh/h.
        assert!(flow_within_tolerance(2300.0, 2700.0));
        assert!(!flow_within_tolerance(2294.0, 2700.0));
        assert!(flow_within_tolerance(3400.0, 3000.0));
        assert!(!flow_within_tolerance(3401.0, 3000.0));
    }

    #[test]
    fn rmse_and_rmsne_exact() {
        let p = [(110.0, 100.0), (40.0, 50.0), (80.0, 80.0)];
        // (100 + 100 + 0) / 3
        assert_eq!(rmse(&p), Some((200.0f64 / 3.0).sqrt()));
        // ((0.1)² + (0.2)² + 0) / 3 = 0.05 / 3
        let r = rmsne(&p).unwrap();
        assert!((r - (0.05f64 / 3.0).sqrt()).abs() < 1e-15, "{r}");
        // A zero field value cannot be normalized: left out.
        let one = rmsne(&[(5.0, 0.0), (110.0, 100.0)]).unwrap();
        assert!((one - 0.1).abs() < 1e-15, "{one}");
        assert_eq!(rmse(&[]), None);
        assert_eq!(rmsne(&[(1.0, 0.0)]), None);
    }

    #[test]
    fn pearson_exact_and_undefined() {
        // Perfectly linear (m = 2c + 1): r = 1; reversed: r = −1.
        let up = [(3.0, 1.0), (5.0, 2.0), (9.0, 4.0)];
        assert!((pearson(&up).unwrap() - 1.0).abs() < 1e-15);
        let down = [(3.0, 4.0), (5.0, 2.0), (9.0, 1.0)];
        assert!(pearson(&down).unwrap() < -0.9);
        // m = (1, 2, 3), c = (1, 3, 2): Σ dm dc = 1, Σ dm² = Σ dc² = 2, so r = 1/2.
        let half = [(1.0, 1.0), (2.0, 3.0), (3.0, 2.0)];
        assert!((pearson(&half).unwrap() - 0.5).abs() < 1e-15);
        assert_eq!(pearson(&[(1.0, 2.0)]), None);
        assert_eq!(pearson(&[(1.0, 2.0), (3.0, 2.0)]), None);
    }
}
