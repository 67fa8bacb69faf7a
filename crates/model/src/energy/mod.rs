//! Vehicle energy (issue 23): what a vehicle burns or draws from its battery for the speeds and
//! accelerations it actually applied, and how much less aerodynamic drag it meets close behind
//! (or in front of) other vehicles. Pure functions of speed, acceleration, step length and a
//! drag factor; the engine's energy observer (`platoonsim-sim`, `energy.rs`) feeds them.
//! The project's choices and measured figures are in docs/energy.md.
//!
//! | module | what | source |
//! |---|---|---|
//! | [`vt_cpfm`] | light-duty combustion engine fuel rate (L/s) | Rakha et al. 2011 (VT-CPFM-1) |
//! | [`electric`] | battery-electric energy per step (J) | Kurczveil, López & Schnieder 2013 (SUMO's electric model) |
//! | [`drag`] | drag factor by position in a close-following chain and the gaps | Zabat et al. 1995 (PATH), Hussein & Rakha 2021 |

pub mod drag;
pub mod electric;
pub mod vt_cpfm;

use serde::{Deserialize, Serialize};

/// Standard gravity (m/s²).
pub const G_MPS2: f64 = 9.80665;

/// Air density at sea level, 15 °C (kg/m³): the value VT-CPFM-1 is published with; the
/// electric model uses it too, so both meet the same air.
pub const AIR_DENSITY_KGPM3: f64 = 1.2256;

/// A vehicle type's powertrain (`[human] powertrain`, `[cav] powertrain`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Powertrain {
    /// Internal combustion engine: VT-CPFM-1 with the light-duty car of [`vt_cpfm::VtCpfm`].
    #[default]
    Combustion,
    /// Battery-electric: [`electric::Electric`].
    Electric,
}

impl Powertrain {
    /// The names a scenario file may use.
    pub const NAMES: [&'static str; 2] = ["combustion", "electric"];

    pub fn as_str(self) -> &'static str {
        match self {
            Powertrain::Combustion => "combustion",
            Powertrain::Electric => "electric",
        }
    }

    /// The default (combustion): not written into a resolved configuration, so that
    /// configurations from before powertrains existed keep their identity.
    pub fn is_default(&self) -> bool {
        *self == Powertrain::Combustion
    }
}

/// Scenario section `[energy]`: whether the energy observer runs and how drag reduction
/// applies. Off by default: the observer costs a sweep over the vehicles per step
/// (docs/energy.md).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EnergyParams {
    /// Compute fuel and electricity per vehicle (trips, summary).
    pub enabled: bool,
    /// Scale each vehicle's drag coefficient by [`drag::Drag::factor`] (false: every vehicle meets
    /// the drag of an isolated vehicle).
    pub drag_reduction: bool,
    /// Human-driven vehicles get the same slipstream physics as CAVs (a slipstream does not
    /// ask who drives). False: only CAVs' drag is reduced.
    pub humans_draft: bool,
}

impl Default for EnergyParams {
    fn default() -> Self {
        EnergyParams {
            enabled: false,
            drag_reduction: true,
            humans_draft: true,
        }
    }
}

impl EnergyParams {
    pub fn is_default(&self) -> bool {
        *self == EnergyParams::default()
    }
}
