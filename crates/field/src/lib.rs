//! Field traffic data and how well a simulation fits it.
//!
//! No platoonsim dependency but `bounded` (its gzip mode reads the files): field files in,
//! plain data out, like `plot`. The calibrate crate (`platoonsim_calibrate::field_obs`) turns
//! a run's detector records into the same [`Obs`] rows and compares them
//! (`platoonsim compare`, docs/compare.md; `platoonsim calibrate`, docs/calibrate.md).
//!
//! * [`Obs`]: one station's flow, speed and occupancy over one interval, the tidy row every
//!   reader produces and every measure reads;
//! * [`StationMeta`]: a station of a PeMS metadata file; [`Placed`]: a station placed on a
//!   corridor (x in metres).
//!
//! Times are seconds since local midnight of the field day (`start_s`); one file holds one day.
//!
//! Input (docs/field-data.md): [`pems`] reads PeMS `station_5min` files and station metadata,
//! [`tidy`] reads and writes the tidy CSV, [`load`] reads any mix of both; [`place`] puts
//! stations on a corridor and selects their rows; [`aggregate`] makes longer intervals and
//! lists the missing ones. Errors are [`FieldError`]s naming file, line, field and value.
//!
//! Goodness of fit (docs/compare.md): [`fit`] (GEH of hourly flows, speed RMSE, RMSNE and
//! correlation), [`bottleneck`] (active bottlenecks after Chen, Skabardonis & Varaiya 2004,
//! and their pairing), [`criteria`] (the FHWA Toolbox III criteria and the project's targets
//! as data), [`report`] (the Markdown report).
//!
//! Calibration (docs/calibrate.md): [`demand`] estimates a corridor's entrance demands and
//! exit fractions from counts (non-negative least squares under flow conservation).

pub mod combine;
pub mod demand;

use serde::{Deserialize, Serialize};

pub mod aggregate;
mod bounded;
pub mod clock;
mod error;
mod input;
pub mod load;
pub mod pems;
pub mod place;
pub mod tidy;

pub use error::FieldError;

/// What a PeMS station measures (the metadata's `Type`).
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum StationKind {
    /// `ML`: mainline.
    Mainline,
    /// `OR`: on-ramp.
    OnRamp,
    /// `FR`: off-ramp.
    OffRamp,
    /// `HV`: HOV lane.
    Hov,
    /// `FF`: freeway-to-freeway connector.
    FreewayConnector,
    /// Any other code, kept as written (`CD`, `CH`, `ML` variants of other districts).
    Other(String),
}

impl StationKind {
    /// The kind of a PeMS `Type` code (`ML`, `OR`, `FR`, `HV`, `FF`; anything else is kept as
    /// [`StationKind::Other`]).
    pub fn from_code(code: &str) -> StationKind {
        match code {
            "ML" => StationKind::Mainline,
            "OR" => StationKind::OnRamp,
            "FR" => StationKind::OffRamp,
            "HV" => StationKind::Hov,
            "FF" => StationKind::FreewayConnector,
            other => StationKind::Other(other.to_string()),
        }
    }

    /// The PeMS `Type` code.
    pub fn code(&self) -> &str {
        match self {
            StationKind::Mainline => "ML",
            StationKind::OnRamp => "OR",
            StationKind::OffRamp => "FR",
            StationKind::Hov => "HV",
            StationKind::FreewayConnector => "FF",
            StationKind::Other(code) => code,
        }
    }
}

/// One station and interval: the tidy row (`station, time, flow_vph, speed_kmh, occupancy`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Obs {
    /// Station ID (PeMS) or detector name (a simulation).
    pub station: String,
    /// Start of the interval, seconds since local midnight of the day.
    pub start_s: u32,
    /// Interval length (s), e.g. 300.
    pub interval_s: u32,
    /// Flow over all lanes of the station (veh/h).
    pub flow_vph: f64,
    /// Mean speed (km/h); `None` where the station has none (ramps, broken loops).
    pub speed_kmh: Option<f64>,
    /// Occupancy, 0-1; `None` where missing.
    pub occupancy: Option<f64>,
}

/// A station of a PeMS metadata file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StationMeta {
    /// Station ID.
    pub id: String,
    /// Freeway number, e.g. `"99"`.
    pub freeway: String,
    /// Direction, e.g. `"N"`.
    pub direction: String,
    /// Absolute postmile (miles).
    pub abs_pm: f64,
    /// Mainline, ramp, HOV, …
    pub kind: StationKind,
    /// Lanes at the station.
    pub lanes: u32,
    /// Name, e.g. `"WB Florin Rd"`.
    pub name: String,
}

/// A station placed on a corridor.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Placed {
    /// Station ID.
    pub station: String,
    /// Position in the corridor's coordinate (m).
    pub x_m: f64,
    /// What it measures.
    pub kind: StationKind,
    /// Lanes (0 if unknown).
    pub lanes: u32,
    /// Name, for reports.
    pub name: String,
}

/// The speed of several observations taken together (replications of one interval, or the
/// stations of one cross-section): the flow-weighted mean of the speeds they have, their plain
/// mean if all those flows are 0, none if none has a speed.
pub fn flow_weighted_speed<'a>(obs: impl IntoIterator<Item = &'a Obs>) -> Option<f64> {
    let speeds: Vec<(f64, f64)> = obs
        .into_iter()
        .filter_map(|o| o.speed_kmh.map(|s| (s, o.flow_vph)))
        .collect();
    let weight: f64 = speeds.iter().map(|&(_, w)| w).sum();
    match speeds.len() {
        0 => None,
        n if weight <= 0.0 => Some(speeds.iter().map(|&(s, _)| s).sum::<f64>() / n as f64),
        _ => Some(speeds.iter().map(|&(s, w)| s * w).sum::<f64>() / weight),
    }
}

/// The largest plausible flow of a station over all its lanes (veh/h): ten lanes at
/// 3,000 veh/h/lane, above the highest lane flows measured on freeways (about 2,500-2,900
/// veh/h/lane). A larger value is a unit or data error (issue 48 D5: a flow of 1e308 made the
/// calibration's objective NaN); the readers refuse it naming the line and field.
pub const MAX_STATION_FLOW_VPH: f64 = 30_000.0;
/// The largest plausible mean speed (km/h); PeMS reports at most about 100 mph (161 km/h).
pub const MAX_SPEED_KMH: f64 = 200.0;
/// The most rows (station intervals) one load may hold: 5,000,000, a year of 5-minute
/// intervals of 47 stations (about 150 bytes each in memory, so at most about 750 MB).
pub const MAX_ROWS: usize = 5_000_000;
/// The most distinct stations one load may hold (a PeMS district has a few thousand).
pub const MAX_STATIONS: usize = 20_000;

/// Metres per mile (international mile), for postmiles.
pub const METRES_PER_MILE: f64 = 1609.344;

pub mod bottleneck;
pub mod criteria;
pub mod fit;
pub mod report;
