//! A ramp meter's configuration (`meter` of an on-ramp, docs/network-scenarios.md): its law
//! (`platoonsim_model::meter`), when it runs and its queue override.

use crate::error::SimError;
use platoonsim_model::meter::Alinea;
use serde::Serialize;

/// Highest meter rate (veh/h): one release per second. The engine places at most one vehicle
/// per step from a ramp, and a one-car-per-green meter runs far below it (about 900 veh/h per
/// lane at the stop line).
pub const MAX_METER_RATE_VPH: f64 = 3600.0;

/// A ramp meter. The ramp's queue head is placed on the road only at a green, and still only
/// where the insertion rule admits it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Meter {
    #[serde(flatten)]
    pub law: MeterLaw,
    /// Simulated time (s) from which the meter runs (0: from the start).
    pub from_s: f64,
    /// Simulated time (s) at which it stops; `None`: it runs to the end.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub to_s: Option<f64>,
    /// Queue override: with more vehicles than this waiting on the ramp, an ALINEA meter
    /// releases at its maximum rate and a fixed-rate meter stops metering. `None`: never.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub queue_max_veh: Option<u32>,
}

/// How a meter sets its rate.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum MeterLaw {
    /// A fixed rate (veh/h), one vehicle per green.
    Fixed { rate_vph: f64 },
    /// ALINEA on the occupancy of the through lanes `detector_m` downstream of the merge point.
    Alinea {
        #[serde(flatten)]
        law: Alinea,
        /// Distance of its detector downstream of the ramp's merge point (m).
        detector_m: f64,
    },
}

impl MeterLaw {
    /// `fixed` or `alinea`, as in scenario files and the summary.
    pub fn name(&self) -> &'static str {
        match self {
            MeterLaw::Fixed { .. } => "fixed",
            MeterLaw::Alinea { .. } => "alinea",
        }
    }

    /// The largest rate it can run (veh/h).
    pub fn max_rate_vph(&self) -> f64 {
        match self {
            MeterLaw::Fixed { rate_vph } => *rate_vph,
            MeterLaw::Alinea { law, .. } => law.max_rate_vph,
        }
    }
}

impl Meter {
    /// The invariants the engine relies on, for the meter of on-ramp `i` at merge point `x_m`
    /// on a road of `length_m` (the scenario crate checks the same with file context).
    pub fn check(&self, i: usize, x_m: f64, length_m: f64) -> Result<(), SimError> {
        let at = |k: &str| format!("network.on_ramps[{i}].meter.{k}");
        let rate = |k: &str, v: f64| -> Result<(), SimError> {
            if v.is_finite() && v > 0.0 && v <= MAX_METER_RATE_VPH {
                Ok(())
            } else {
                Err(SimError::Config(format!(
                    "{} = {v}: must be in (0, {MAX_METER_RATE_VPH}] veh/h",
                    at(k)
                )))
            }
        };
        match &self.law {
            MeterLaw::Fixed { rate_vph } => rate("rate_vph", *rate_vph)?,
            MeterLaw::Alinea { law, detector_m } => {
                rate("min_rate_vph", law.min_rate_vph)?;
                rate("max_rate_vph", law.max_rate_vph)?;
                if law.min_rate_vph > law.max_rate_vph {
                    return Err(SimError::Config(format!(
                        "{} = {}: must be at most {} = {}",
                        at("min_rate_vph"),
                        law.min_rate_vph,
                        at("max_rate_vph"),
                        law.max_rate_vph
                    )));
                }
                let o = law.occupancy_target_pct;
                if !(o > 0.0 && o < 100.0) {
                    return Err(SimError::Config(format!(
                        "{} = {o}: must be in (0, 100) %",
                        at("occupancy_target_pct")
                    )));
                }
                if !(law.gain_vph.is_finite() && law.gain_vph > 0.0) {
                    return Err(SimError::Config(format!(
                        "{} = {}: must be a finite number > 0",
                        at("gain_vph"),
                        law.gain_vph
                    )));
                }
                if !(law.period_s.is_finite() && law.period_s > 0.0) {
                    return Err(SimError::Config(format!(
                        "{} = {}: must be a finite number > 0",
                        at("period_s"),
                        law.period_s
                    )));
                }
                let x = x_m + detector_m;
                if !(detector_m.is_finite() && *detector_m > 0.0 && x < length_m) {
                    return Err(SimError::Config(format!(
                        "{} = {detector_m}: must be > 0 and put the detector inside the road \
                         (merge point {x_m} + it < {length_m})",
                        at("detector_m")
                    )));
                }
            }
        }
        if !(self.from_s.is_finite() && self.from_s >= 0.0) {
            return Err(SimError::Config(format!(
                "{} = {}: must be a finite number >= 0",
                at("from"),
                self.from_s
            )));
        }
        if let Some(to) = self.to_s {
            if !(to.is_finite() && to > self.from_s) {
                return Err(SimError::Config(format!(
                    "{} = {to}: must be a finite time after {} = {}",
                    at("to"),
                    at("from"),
                    self.from_s
                )));
            }
        }
        Ok(())
    }
}
