//! `--format csv|parquet` for the output tables of `run` (detectors, trips, trajectories;
//! written by `platoonsim_runs::run_dir`), `sweep` and `experiment` (runs, summary).

use clap::ValueEnum;

/// The tables' file format.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum FormatArg {
    /// Comma-separated text (the default).
    #[default]
    Csv,
    /// Apache Parquet: typed columns, snappy-compressed, read by pandas, polars and pyarrow.
    Parquet,
}

impl FormatArg {
    pub fn ext(self) -> &'static str {
        match self {
            FormatArg::Csv => "csv",
            FormatArg::Parquet => "parquet",
        }
    }

    pub fn table(self) -> platoonsim_runs::columnar::Format {
        match self {
            FormatArg::Csv => platoonsim_runs::columnar::Format::Csv,
            FormatArg::Parquet => platoonsim_runs::columnar::Format::Parquet,
        }
    }
}
