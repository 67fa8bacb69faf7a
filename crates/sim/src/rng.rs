//! Named random streams (determinism rule: all randomness flows from the scenario seed).
//!
//! A stream is identified by (scenario seed, purpose, entity id) and seeded through a
//! SplitMix64 mix of the three, so every vehicle and every entrance draws from its own
//! generator: adding a vehicle or an entrance does not shift anybody else's draws.

use rand::{Rng, SeedableRng};
use rand_distr::{Distribution, StandardNormal};
use rand_pcg::Pcg64Mcg;

/// Purposes of the named streams. The discriminant is part of the seed: never reorder.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u64)]
pub enum Purpose {
    /// Arrivals at an entrance (entity = entrance index).
    Arrivals = 1,
    /// A vehicle's own draws: type, parameters, lane choice, yielding (entity = vehicle id).
    Vehicle = 2,
    /// A CAV's V2V beacon receptions (spec 9.3; entity = the receiving vehicle's id, index =
    /// the step): counter-based ([`uniform_at`]), so no state is kept per vehicle.
    Beacons = 3,
}

fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The `index`-th uniform deviate in [0, 1) of the named stream (seed, purpose, entity),
/// counter-based: a SplitMix64 hash of the four, so a draw needs no stored generator and does
/// not depend on which other draws were made or in which order.
#[inline]
pub fn uniform_at(seed: u64, purpose: Purpose, entity: u64, index: u64) -> f64 {
    let a = splitmix64(seed ^ (purpose as u64).wrapping_mul(0xA24B_AED4_963E_E407));
    let b = splitmix64(a ^ entity.wrapping_mul(0x9FB2_1C65_1E98_DF25));
    let c = splitmix64(b ^ index.wrapping_mul(0xD6E8_FEB8_6659_FD93));
    (c >> 11) as f64 / (1u64 << 53) as f64
}

/// A deterministic random stream.
#[derive(Clone, Debug)]
pub struct Stream(Pcg64Mcg);

impl Stream {
    /// The stream for (seed, purpose, entity).
    pub fn new(seed: u64, purpose: Purpose, entity: u64) -> Stream {
        let a = splitmix64(seed);
        let b = splitmix64(a ^ (purpose as u64).wrapping_mul(0xA24B_AED4_963E_E407));
        let c = splitmix64(b ^ entity.wrapping_mul(0x9FB2_1C65_1E98_DF25));
        let hi = splitmix64(c);
        Stream(Pcg64Mcg::seed_from_u64(c ^ hi.rotate_left(17)))
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0.gen::<f64>()
    }

    /// Standard normal deviate.
    pub fn normal(&mut self) -> f64 {
        StandardNormal.sample(&mut self.0)
    }

    /// Exponential with the given rate (1/s); `f64::INFINITY` for rate 0.
    pub fn exponential(&mut self, rate: f64) -> f64 {
        if rate <= 0.0 {
            return f64::INFINITY;
        }
        // 1 - U in (0, 1] so the log is finite.
        -(1.0 - self.uniform()).ln() / rate
    }

    /// Uniform index in 0..n (n > 0).
    pub fn index(&mut self, n: usize) -> usize {
        self.0.gen_range(0..n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_reproducible_and_distinct() {
        let mut a = Stream::new(7, Purpose::Vehicle, 3);
        let mut b = Stream::new(7, Purpose::Vehicle, 3);
        let mut c = Stream::new(7, Purpose::Vehicle, 4);
        let mut d = Stream::new(7, Purpose::Arrivals, 3);
        let xa: Vec<f64> = (0..4).map(|_| a.uniform()).collect();
        let xb: Vec<f64> = (0..4).map(|_| b.uniform()).collect();
        let xc: Vec<f64> = (0..4).map(|_| c.uniform()).collect();
        let xd: Vec<f64> = (0..4).map(|_| d.uniform()).collect();
        assert_eq!(xa, xb);
        assert_ne!(xa, xc);
        assert_ne!(xa, xd);
    }

    #[test]
    fn counter_draws_are_reproducible_distinct_and_uniform() {
        let at = |seed, entity, index| uniform_at(seed, Purpose::Beacons, entity, index);
        assert_eq!(at(7, 3, 11), at(7, 3, 11));
        assert_ne!(at(7, 3, 11), at(8, 3, 11));
        assert_ne!(at(7, 3, 11), at(7, 4, 11));
        assert_ne!(at(7, 3, 11), at(7, 3, 12));
        assert_ne!(at(7, 3, 11), uniform_at(7, Purpose::Vehicle, 3, 11));
        let n = 20_000;
        let below: usize = (0..n).filter(|&k| at(1, 5, k) < 0.1).count();
        assert!((below as f64 / n as f64 - 0.1).abs() < 0.01, "{below}");
    }

    #[test]
    fn exponential_mean_matches_rate() {
        let mut s = Stream::new(1, Purpose::Arrivals, 0);
        let n = 20_000;
        let mean: f64 = (0..n).map(|_| s.exponential(0.5)).sum::<f64>() / n as f64;
        assert!((mean - 2.0).abs() < 0.05, "mean {mean}");
    }
}
