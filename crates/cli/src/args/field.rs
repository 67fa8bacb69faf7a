//! The field-data flags `platoonsim compare` and `platoonsim calibrate` share.

use clap::Args;
use std::path::PathBuf;

/// Where the field data is and how its stations sit on the corridor.
#[derive(Debug, Args)]
pub struct FieldFlags {
    /// Field data: PeMS station_5min files (plain or .gz) or tidy CSV files
    /// (station,time,flow_vph,speed_kmh,occupancy), read together. A field station is compared
    /// with the simulated detector of the same name. Takes every following value up to the
    /// next flag.
    #[arg(long, value_name = "FILE", required = true, num_args = 1..)]
    pub field: Vec<PathBuf>,

    /// PeMS station metadata: adds each HOV station to the mainline station at its postmile
    /// (the simulated corridor runs the HOV lane as an ordinary lane) and, with --origin-pm,
    /// places the stations by postmile (bottlenecks, contours, the [demand] step).
    #[arg(long, value_name = "META.txt")]
    pub meta: Option<PathBuf>,

    /// With --meta: the absolute postmile of the corridor's x = 0, so that a station sits at
    /// x = (Abs_PM - PM) x 1609.344 m (SR-99: 287.230).
    #[arg(
        long = "origin-pm",
        value_name = "PM",
        requires = "meta",
        allow_negative_numbers = true
    )]
    pub origin_pm: Option<f64>,

    /// Instead of --origin-pm: a CSV station,x_m,kind[,lanes,name] placing the field
    /// stations (kind ML, OR, FR, HV or FF).
    #[arg(long, value_name = "TABLE.csv", conflicts_with = "origin_pm")]
    pub stations: Option<PathBuf>,
}
