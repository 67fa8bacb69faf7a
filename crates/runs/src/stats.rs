//! Sample statistics of one metric over the seeds of a cell: mean, sample standard
//! deviation, n and the two-sided 95 % confidence interval of the mean,
//! `mean ± t(0.975, n-1) · sd / √n` (Student t).

use serde::Serialize;

/// Two-sided 95 % quantiles t(0.975, df) of Student's t distribution for df = 1..=30.
const T975: [f64; 30] = [
    12.7062, 4.3027, 3.1824, 2.7764, 2.5706, 2.4469, 2.3646, 2.3060, 2.2622, 2.2281, 2.2010,
    2.1788, 2.1604, 2.1448, 2.1314, 2.1199, 2.1098, 2.1009, 2.0930, 2.0860, 2.0796, 2.0739, 2.0687,
    2.0639, 2.0595, 2.0555, 2.0518, 2.0484, 2.0452, 2.0423,
];

/// Beyond df = 30: (df, t) anchors, interpolated linearly in 1/df; the last is the normal
/// limit (1/df = 0).
const T975_TAIL: [(f64, f64); 4] = [
    (40.0, 2.0211),
    (60.0, 2.0003),
    (120.0, 1.9799),
    (f64::INFINITY, 1.9600),
];

/// t(0.975, df): exact to the table's four decimals for df ≤ 30, within 0.001 beyond.
/// `df = 0` has no quantile (NaN).
pub fn t975(df: usize) -> f64 {
    if df == 0 {
        return f64::NAN;
    }
    if df <= T975.len() {
        return T975[df - 1];
    }
    let inv = 1.0 / df as f64;
    let (mut d0, mut t0) = (30.0, T975[29]);
    for &(d1, t1) in &T975_TAIL {
        if (df as f64) <= d1 {
            let (a, b) = (1.0 / d0, 1.0 / d1);
            return t0 + (t1 - t0) * (a - inv) / (a - b);
        }
        (d0, t0) = (d1, t1);
    }
    1.96
}

/// Statistics of a sample. Non-finite values are left out (`n` counts the finite ones).
/// With n = 0 everything is NaN; with n = 1 the mean is the value and sd and the interval
/// are NaN (written as empty cells).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Stats {
    pub n: usize,
    pub mean: f64,
    /// Sample standard deviation (divisor n - 1).
    pub sd: f64,
    pub ci_low: f64,
    pub ci_high: f64,
}

impl Stats {
    pub fn of(values: &[f64]) -> Stats {
        let xs: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
        let n = xs.len();
        if n == 0 {
            return Stats {
                n,
                mean: f64::NAN,
                sd: f64::NAN,
                ci_low: f64::NAN,
                ci_high: f64::NAN,
            };
        }
        let mean = xs.iter().sum::<f64>() / n as f64;
        if n == 1 {
            return Stats {
                n,
                mean,
                sd: f64::NAN,
                ci_low: f64::NAN,
                ci_high: f64::NAN,
            };
        }
        let ss: f64 = xs.iter().map(|x| (x - mean) * (x - mean)).sum();
        let sd = (ss / (n - 1) as f64).sqrt();
        let half = t975(n - 1) * sd / (n as f64).sqrt();
        Stats {
            n,
            mean,
            sd,
            ci_low: mean - half,
            ci_high: mean + half,
        }
    }

    /// Half-width of the 95 % interval (NaN if there is none).
    pub fn half_width(&self) -> f64 {
        (self.ci_high - self.ci_low) / 2.0
    }

    /// Whether `v` lies in the 95 % interval (false if there is none).
    pub fn covers(&self, v: f64) -> bool {
        self.ci_low <= v && v <= self.ci_high
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// P(T ≤ t) for Student's t with `df` degrees of freedom, by Simpson's rule after the
    /// substitution t = √df · tan θ, which turns the density into cos^(df-1) θ on [0, π/2).
    fn t_cdf(t: f64, df: usize) -> f64 {
        let f = |th: f64| th.cos().powi(df as i32 - 1);
        let simpson = |b: f64| {
            let n = 20_000;
            let h = b / n as f64;
            let mut s = f(0.0) + f(b);
            for i in 1..n {
                s += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
            }
            s * h / 3.0
        };
        let theta = (t / (df as f64).sqrt()).atan();
        0.5 + 0.5 * simpson(theta) / simpson(std::f64::consts::FRAC_PI_2)
    }

    #[test]
    fn t_table_matches_the_distribution() {
        for df in 1..=200 {
            let p = t_cdf(t975(df), df);
            let tol = if df <= 30 { 1e-5 } else { 6e-5 };
            assert!(
                (p - 0.975).abs() < tol,
                "df {df}: t = {} gives P = {p}",
                t975(df)
            );
        }
        // Closed forms: df 1 (Cauchy) and df 2.
        assert!((t975(1) - (std::f64::consts::PI * 0.475).tan()).abs() < 1e-4);
        let p: f64 = 0.975;
        assert!((t975(2) - (2.0 * p - 1.0) * (2.0 / (4.0 * p * (1.0 - p))).sqrt()).abs() < 1e-4);
        assert!((t975(1_000_000) - 1.96).abs() < 1e-3);
        assert!(t975(0).is_nan());
        // Decreasing in df.
        for df in 1..500 {
            assert!(t975(df + 1) <= t975(df), "df {df}");
        }
    }

    #[test]
    fn interval_of_a_known_sample() {
        let s = Stats::of(&[1.0, 2.0, 3.0, 4.0, 5.0]);
        assert_eq!(s.n, 5);
        assert!((s.mean - 3.0).abs() < 1e-12);
        assert!((s.sd - 2.5f64.sqrt()).abs() < 1e-12);
        // half-width = 2.7764 · √2.5 / √5 = 2.7764 / √2 = 1.96323...
        assert!(
            (s.half_width() - 1.963_23).abs() < 1e-4,
            "{}",
            s.half_width()
        );
        assert!((s.ci_low - 1.036_77).abs() < 1e-4);
        assert!((s.ci_high - 4.963_23).abs() < 1e-4);
        assert!(s.covers(3.0) && !s.covers(5.0));
    }

    #[test]
    fn degenerate_samples() {
        let one = Stats::of(&[7.0]);
        assert_eq!((one.n, one.mean), (1, 7.0));
        assert!(one.sd.is_nan() && one.ci_low.is_nan() && one.ci_high.is_nan());
        let none = Stats::of(&[]);
        assert_eq!(none.n, 0);
        assert!(none.mean.is_nan());
        let with_nan = Stats::of(&[1.0, f64::NAN, 3.0]);
        assert_eq!(with_nan.n, 2);
        assert_eq!(with_nan.mean, 2.0);
        let constant = Stats::of(&[2.0, 2.0, 2.0]);
        assert_eq!(
            (constant.sd, constant.ci_low, constant.ci_high),
            (0.0, 2.0, 2.0)
        );
    }
}
