//! Battery-electric vehicle: the energy drawn from (or fed back into) the battery per step,
//! from the vehicle's physics.
//!
//! Paper: T. Kurczveil, P. A. López, E. Schnieder (2013), "Implementation of an energy model
//! and a charging infrastructure in SUMO", SUMO 2013 (Eclipse SUMO's electric vehicle model,
//! whose current default vehicle is a 2020 Kia Soul EV).
//!
//! ```text
//! ΔE = m g sinθ · d                         potential (θ = 0 on the project's roads)
//!    + ½ (m + m_rot) (v² − v₀²)             kinetic, of the body and of the rotating parts
//!    + ½ ρ A c_w f v̄² · d                   air, with the drag factor f (super::drag)
//!    + c_roll m g · d                       rolling
//!    + c_rad m v̄²/r · Δt                    radial (curves; 0 on a straight freeway)
//!    + P_const Δt                           auxiliaries
//! E_battery = ΔE / η_prop   if ΔE > 0,   ΔE · η_recup   otherwise
//! ```
//!
//! over a step of Δt with start speed v₀, end speed v, mean speed v̄ = d/Δt and distance d.
//! The rotating parts are an equivalent mass m_rot whose kinetic energy is ½ m_rot v². SUMO's
//! form takes every term at the step's end speed; we take the resistive terms over the
//! distance actually travelled (mean speed), the same at steady speed. As in SUMO, the sum is
//! taken before the efficiencies, the auxiliary power included.
//!
//! | symbol | field | default | unit |
//! |---|---|---|---|
//! | m | `mass_kg` | 1830 | kg |
//! | A | `frontal_area_m2` | 2.6 | m² |
//! | c_w | `drag_coefficient` | 0.35 | – |
//! | m_rot | `rotating_mass_kg` | 40 | kg |
//! | c_roll | `rolling_coefficient` | 0.01 | – |
//! | c_rad | `radial_drag_coefficient` | 0.1 | – (unused: no curves) |
//! | P_const | `constant_power_w` | 100 | W |
//! | η_prop | `propulsion_efficiency` | 0.98 | – |
//! | η_recup | `recuperation_efficiency` | 0.96 | – |
//! | ρ | [`super::AIR_DENSITY_KGPM3`] | 1.2256 | kg/m³ |
//! | g | [`super::G_MPS2`] | 9.80665 | m/s² |
//!
//! At a steady 100 km/h: 17.39 kJ per second, 173.9 Wh/km (17.4 kWh/100 km).

use super::{AIR_DENSITY_KGPM3, G_MPS2};

/// A battery-electric car (SUMO's default, a 2020 Kia Soul EV).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Electric {
    pub mass_kg: f64,
    pub frontal_area_m2: f64,
    pub drag_coefficient: f64,
    pub rotating_mass_kg: f64,
    pub rolling_coefficient: f64,
    pub radial_drag_coefficient: f64,
    pub constant_power_w: f64,
    pub propulsion_efficiency: f64,
    pub recuperation_efficiency: f64,
}

impl Default for Electric {
    fn default() -> Self {
        Electric {
            mass_kg: 1830.0,
            frontal_area_m2: 2.6,
            drag_coefficient: 0.35,
            rotating_mass_kg: 40.0,
            rolling_coefficient: 0.01,
            radial_drag_coefficient: 0.1,
            constant_power_w: 100.0,
            propulsion_efficiency: 0.98,
            recuperation_efficiency: 0.96,
        }
    }
}

/// Joules per kWh.
pub const J_PER_KWH: f64 = 3.6e6;

impl Electric {
    /// Air resistance (N) at `v_mps` with the drag coefficient scaled by `drag_factor`.
    #[inline]
    pub fn aero_n(&self, v_mps: f64, drag_factor: f64) -> f64 {
        0.5 * AIR_DENSITY_KGPM3
            * self.frontal_area_m2
            * self.drag_coefficient
            * drag_factor
            * v_mps
            * v_mps
    }

    /// The energy the vehicle needs over a step (J, before the efficiencies): from `v0_mps` to
    /// `v_mps` in `dt_s` over `dist_m` on a flat, straight road.
    #[inline]
    pub fn demand_j(
        &self,
        v0_mps: f64,
        v_mps: f64,
        dist_m: f64,
        dt_s: f64,
        drag_factor: f64,
    ) -> f64 {
        let v_mean = dist_m / dt_s;
        0.5 * (self.mass_kg + self.rotating_mass_kg) * (v_mps * v_mps - v0_mps * v0_mps)
            + self.aero_n(v_mean, drag_factor) * dist_m
            + self.rolling_coefficient * self.mass_kg * G_MPS2 * dist_m
            + self.constant_power_w * dt_s
    }

    /// The battery energy of a step (J): positive drawn, negative recuperated.
    #[inline]
    pub fn step_energy_j(
        &self,
        v0_mps: f64,
        v_mps: f64,
        dist_m: f64,
        dt_s: f64,
        drag_factor: f64,
    ) -> f64 {
        let e = self.demand_j(v0_mps, v_mps, dist_m, dt_s, drag_factor);
        if e > 0.0 {
            e / self.propulsion_efficiency
        } else {
            e * self.recuperation_efficiency
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    /// Steady speeds: one second at v, written out from the equation and the parameters.
    #[test]
    fn steady_speeds_match_the_equation() {
        let ev = Electric::default();
        for (kmh, wh_per_km) in [
            (50.0, 83.399_286),
            (80.0, 130.199_383),
            (100.0, 173.850_807),
            (120.0, 227.344_270),
        ] {
            let v: f64 = kmh / 3.6;
            let by_hand =
                (0.5 * 1.2256 * 2.6 * 0.35 * v * v * v + 0.01 * 1830.0 * 9.80665 * v + 100.0)
                    / 0.98;
            let e = ev.step_energy_j(v, v, v, 1.0, 1.0);
            assert!(close(e, by_hand, 1e-12));
            // J per m → Wh per km: ×1000/3600.
            assert!(
                close(e / v / 3.6, wh_per_km, 1e-6),
                "{kmh}: {}",
                e / v / 3.6
            );
        }
    }

    /// 0-100 km/h in 10 s at constant acceleration, in the engine's 0.1 s steps: 0.2203 kWh,
    /// of which the kinetic energy ½ (m + m_rot) v² / η_prop is 0.2046 kWh.
    #[test]
    fn acceleration_from_rest_to_100_kmh() {
        let ev = Electric::default();
        let a = 100.0 / 3.6 / 10.0;
        let mut e = 0.0;
        for k in 0..100 {
            let (v0, v1) = (a * k as f64 * 0.1, a * (k + 1) as f64 * 0.1);
            e += ev.step_energy_j(v0, v1, 0.5 * (v0 + v1) * 0.1, 0.1, 1.0);
        }
        assert!(
            close(e / J_PER_KWH, 0.220_310_43, 1e-6),
            "{}",
            e / J_PER_KWH
        );
        let kinetic = 0.5 * 1870.0 * (100.0f64 / 3.6).powi(2) / 0.98 / J_PER_KWH;
        assert!(close(kinetic, 0.204_6, 1e-3), "{kinetic}");
        assert!(e / J_PER_KWH > kinetic);
    }

    #[test]
    fn idling_draws_the_auxiliaries_and_braking_recuperates() {
        let ev = Electric::default();
        // 100 W over the propulsion efficiency: 102.04 J per second.
        assert!(close(
            ev.step_energy_j(0.0, 0.0, 0.0, 1.0, 1.0),
            100.0 / 0.98,
            1e-12
        ));
        // Braking from 100 to 90 km/h in a second: the kinetic energy comes back, less the
        // resistances, times η_recup.
        let (v0, v1) = (100.0 / 3.6, 90.0 / 3.6);
        let d = 0.5 * (v0 + v1);
        let e = ev.step_energy_j(v0, v1, d, 1.0, 1.0);
        let demand = 0.5 * 1870.0 * (v1 * v1 - v0 * v0)
            + 0.5 * 1.2256 * 2.6 * 0.35 * d * d * d
            + 0.01 * 1830.0 * 9.80665 * d
            + 100.0;
        assert!(demand < 0.0);
        assert!(close(e, demand * 0.96, 1e-12));
    }
}
