//! Aerodynamic drag reduction of passenger cars driving close together: the factor f by which a
//! vehicle's drag coefficient is scaled, from its position in a chain of close-following
//! vehicles and its gaps to the vehicles ahead and behind.
//!
//! Sources (the measured points; docs/energy.md has the discussion):
//!
//! * M. Zabat, N. Stabile, S. Frascaroli, F. Browand (1995), "The Aerodynamic Performance of
//!   Platoons: Final Report", California PATH UCB-ITS-PRR-95-35 (also SAE 940421): wind-tunnel
//!   platoons of 2-4 passenger-vehicle models. At a spacing of half a vehicle length the mean
//!   drag of a 4-car platoon is **0.62** of an isolated vehicle's; every member gains there,
//!   interior members most; beyond about one length the interaction is weak, the leader's
//!   drag no longer changes and only the followers gain.
//! * The passenger-car curves of the same report as tabulated for positions 1-4 at a 20 m
//!   spacing: reductions of **0, 2, 6 and 7 %**.
//! * Alternative: H. A. Hussein, H. A. Rakha (2021), "Vehicle Platooning Impact on Drag
//!   Coefficients and Energy/Fuel Saving Implications", IEEE Trans. Veh. Technol.: a power
//!   function of position and gap fitted to the literature; light-duty platoons at a 0.5 s gap
//!   and 100 km/h save at most about 4.5 % fuel, and negligibly at longer gaps.
//!
//! The model, with g the net gap (m), k the position in the chain (1 = no vehicle within the
//! cut-off ahead; positions beyond 4 take the 4th's values):
//!
//! ```text
//! f = 1 − wake(k, g_ahead) − push(g_behind)
//! wake(k, g) = W · exp(−(max(g, g₀) − g₀) / λ_k)     k ≥ 2, g ≤ g_c   (the slipstream of those ahead)
//! push(g)    = P · exp(−(max(g, g₀) − g₀) / μ)       g ≤ g_c          (a close follower's base-pressure relief)
//! ```
//!
//! | symbol | value | unit | from |
//! |---|---|---|---|
//! | g₀ | 2.4 | m | half the length of a 4.8 m car: the closest measured spacing; below it the value at g₀ holds |
//! | P | 0.15 | – | our split of the 4-car average at g₀: leader 0.85 |
//! | W | (4 · (1 − 0.62) − 3P)/3 = 0.3567 | – | the rest of the average: interior 0.493, last 0.643, mean 0.62 |
//! | μ | 2.4 | m | one e-fold per half length: 0.055 at one length, < 0.1 % at 20 m (the leader is unaffected) |
//! | λ₂, λ₃, λ₄ | 6.11, 9.87, 10.81 | m | fitted: wake(k, 20 m) = 2, 6, 7 % |
//! | g_c | 50 | m | cut-off: no reduction beyond (the largest wake there is 0.44 %) |
//!
//! The split of the 0.62 average among positions is ours (the average is what is quoted); the
//! exponential decay through the two anchors of each position is ours too.

/// The default drag-reduction model (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Drag {
    /// Closest spacing of the data (m); smaller gaps take its value.
    pub g0_m: f64,
    /// A close follower's relief on the vehicle ahead at g₀.
    pub push: f64,
    /// Its decay length (m).
    pub push_length_m: f64,
    /// The slipstream's reduction at g₀ for every follower.
    pub wake: f64,
    /// Its decay length by position 2, 3, 4+ (m).
    pub wake_length_m: [f64; 3],
    /// No interaction beyond this gap (m).
    pub cutoff_m: f64,
}

/// Mean drag of a 4-car platoon at half a vehicle length, relative to an isolated car (Zabat
/// et al. 1995).
pub const MEAN_4CAR_AT_HALF_LENGTH: f64 = 0.62;
/// Spacing of the second anchor (m) and the reductions of positions 2, 3, 4 there.
pub const ANCHOR_GAP_M: f64 = 20.0;
pub const ANCHOR_REDUCTION: [f64; 3] = [0.02, 0.06, 0.07];

impl Default for Drag {
    fn default() -> Self {
        let g0 = 2.4;
        let push = 0.15;
        let wake = (4.0 * (1.0 - MEAN_4CAR_AT_HALF_LENGTH) - 3.0 * push) / 3.0;
        let fit = |r: f64| (ANCHOR_GAP_M - g0) / (wake / r).ln();
        Drag {
            g0_m: g0,
            push,
            push_length_m: 2.4,
            wake,
            wake_length_m: ANCHOR_REDUCTION.map(fit),
            cutoff_m: 50.0,
        }
    }
}

impl Drag {
    /// The slipstream reduction of the vehicle at position `k` (1 = leads its chain) with
    /// net gap `gap_m` to the vehicle ahead.
    #[inline]
    pub fn wake(&self, k: u32, gap_m: f64) -> f64 {
        if k < 2 || !self.linked(gap_m) {
            return 0.0;
        }
        let len = self.wake_length_m[(k as usize - 2).min(2)];
        self.wake * (-(gap_m.max(self.g0_m) - self.g0_m) / len).exp()
    }

    /// The reduction a follower at net gap `gap_m` behind gives.
    #[inline]
    pub fn push(&self, gap_m: f64) -> f64 {
        if !self.linked(gap_m) {
            return 0.0;
        }
        self.push * (-(gap_m.max(self.g0_m) - self.g0_m) / self.push_length_m).exp()
    }

    /// The drag factor f ∈ (0, 1] of the vehicle at position `k` of its chain, with net gaps
    /// `ahead_m` and `behind_m` (∞: nobody there).
    #[inline]
    pub fn factor(&self, k: u32, ahead_m: f64, behind_m: f64) -> f64 {
        1.0 - self.wake(k, ahead_m) - self.push(behind_m)
    }

    /// Is a vehicle at net gap `gap_m` behind another part of its chain? (Not for a NaN or
    /// infinite gap: nobody there.)
    #[inline]
    pub fn linked(&self, gap_m: f64) -> bool {
        matches!(
            gap_m.partial_cmp(&self.cutoff_m),
            Some(std::cmp::Ordering::Less | std::cmp::Ordering::Equal)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The factors of a platoon of `n` at equal gaps `g`.
    fn platoon(d: &Drag, n: u32, g: f64) -> Vec<f64> {
        (1..=n)
            .map(|k| {
                let ahead = if k > 1 { g } else { f64::INFINITY };
                let behind = if k < n { g } else { f64::INFINITY };
                d.factor(k, ahead, behind)
            })
            .collect()
    }

    #[test]
    fn fitted_constants() {
        let d = Drag::default();
        assert!((d.wake - 0.356_667).abs() < 1e-6, "{}", d.wake);
        let [l2, l3, l4] = d.wake_length_m;
        assert!((l2 - 6.109).abs() < 1e-3, "{l2}");
        assert!((l3 - 9.874).abs() < 1e-3, "{l3}");
        assert!((l4 - 10.809).abs() < 1e-3, "{l4}");
    }

    /// Zabat et al. 1995: a 4-car platoon at half a vehicle length (2.4 m) has a mean drag of
    /// 0.62 of an isolated car's; every member gains, interior members most.
    #[test]
    fn four_cars_at_half_a_length_average_062() {
        let d = Drag::default();
        let f = platoon(&d, 4, 2.4);
        let mean = f.iter().sum::<f64>() / 4.0;
        assert!((mean - 0.62).abs() < 1e-12, "{f:?}");
        assert!((f[0] - 0.85).abs() < 1e-12);
        assert!((f[1] - 0.493_333).abs() < 1e-6 && f[1] == f[2]);
        assert!((f[3] - 0.643_333).abs() < 1e-6);
        assert!(f[1] < f[3] && f[3] < f[0] && f[0] < 1.0);
        // Closer than the data: held at the 2.4 m values.
        assert_eq!(platoon(&d, 4, 1.0), f);
    }

    /// The passenger-car curves at 20 m: 0, 2, 6 and 7 % for positions 1-4 (whole percents).
    #[test]
    fn four_cars_at_20_m_follow_the_tabulated_reductions() {
        let d = Drag::default();
        let f = platoon(&d, 4, 20.0);
        for (got, want) in f.iter().zip([1.0, 0.98, 0.94, 0.93]) {
            assert!((got - want).abs() < 1e-3, "{f:?}");
        }
        // The leader is unaffected there (< 0.01 %).
        assert!(1.0 - f[0] < 1e-4);
        // Wake part exactly on the anchors.
        for k in 2..=4 {
            let w = d.wake(k, 20.0);
            assert!(
                (w - ANCHOR_REDUCTION[k as usize - 2]).abs() < 1e-12,
                "{k}: {w}"
            );
        }
        // Deeper positions take the 4th's values.
        assert_eq!(d.wake(9, 20.0), d.wake(4, 20.0));
    }

    #[test]
    fn little_effect_beyond_one_length_none_beyond_the_cutoff() {
        let d = Drag::default();
        // A follower's relief on the car ahead falls off within a length or two.
        assert!(d.push(4.8) < 0.06 && d.push(9.6) < 0.01);
        // Alone, or everyone beyond 50 m: no reduction.
        assert_eq!(d.factor(1, f64::INFINITY, f64::INFINITY), 1.0);
        assert_eq!(d.factor(4, 50.1, 50.1), 1.0);
        assert!(d.factor(4, 50.0, f64::INFINITY) < 1.0);
        // Monotone: a closer gap never raises the drag.
        let mut last = 0.0;
        for g in [2.0, 5.0, 10.0, 18.0, 25.0, 33.0, 45.0] {
            let f = d.factor(3, g, f64::INFINITY);
            assert!(f > last, "{g}");
            last = f;
        }
    }

    /// At platoonsim's CACC gaps at 100 km/h (t_C = 0.6-1.1 s: net gaps t_C · v + 1.5 m =
    /// 18.2-32.1 m): a few percent at most (docs/energy.md's table).
    #[test]
    fn reductions_at_the_cacc_gaps() {
        let d = Drag::default();
        let gap = |t: f64| t * 100.0 / 3.6 + 1.5;
        let at = |k, t| 1.0 - d.factor(k, gap(t), f64::INFINITY);
        for (t, want) in [
            (0.6, [0.0270, 0.0722, 0.0829]),
            (0.7, [0.0171, 0.0545, 0.0641]),
            (0.9, [0.0069, 0.0311, 0.0384]),
            (1.1, [0.0028, 0.0177, 0.0229]),
        ] {
            for (k, w) in (2..=4).zip(want) {
                assert!(
                    (at(k, t) - w).abs() < 1e-4,
                    "t_C {t}, position {k}: {}",
                    at(k, t)
                );
            }
        }
    }
}
