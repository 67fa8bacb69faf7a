//! Per-driver parameter distributions (spec 1 "Per-driver stochasticity", table 2.6).
//!
//! A parameter is drawn once per vehicle at creation: draw N(mean, sd), then clamp to
//! [min, max] ([P15-code]). `sd = 0` gives a fixed value. The draw takes a standard-normal
//! deviate `z` so that this module stays free of any random-number generator; the engine
//! supplies `z` from the vehicle's own named stream.

use serde::{Deserialize, Serialize};

/// A truncated (clamped) normal distribution `clamp(N(mean, sd), min, max)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Dist {
    pub mean: f64,
    #[serde(default)]
    pub sd: f64,
    pub min: f64,
    pub max: f64,
}

impl Dist {
    /// A fixed value (sd = 0, min = max = mean).
    pub const fn fixed(v: f64) -> Dist {
        Dist {
            mean: v,
            sd: 0.0,
            min: v,
            max: v,
        }
    }

    /// N(mean, sd) clamped to [min, max].
    pub const fn clamped(mean: f64, sd: f64, min: f64, max: f64) -> Dist {
        Dist { mean, sd, min, max }
    }

    /// The value for a standard-normal deviate `z`: `clamp(mean + sd·z, min, max)`.
    pub fn sample(&self, z: f64) -> f64 {
        (self.mean + self.sd * z).clamp(self.min, self.max)
    }

    /// `None` if the distribution is well formed (finite, sd ≥ 0, min ≤ mean ≤ max),
    /// otherwise a sentence saying what is wrong (used by scenario validation).
    pub fn problem(&self) -> Option<String> {
        if !(self.mean.is_finite()
            && self.sd.is_finite()
            && self.min.is_finite()
            && self.max.is_finite())
        {
            return Some("all of mean, sd, min, max must be finite numbers".into());
        }
        if self.sd < 0.0 {
            return Some(format!("sd = {} must be >= 0", self.sd));
        }
        if self.min > self.max {
            return Some(format!("min = {} must be <= max = {}", self.min, self.max));
        }
        if self.mean < self.min || self.mean > self.max {
            return Some(format!(
                "mean = {} must lie in [min, max] = [{}, {}]",
                self.mean, self.min, self.max
            ));
        }
        None
    }
}
