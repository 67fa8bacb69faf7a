//! The format of the result tables (`runs`, `summary`): CSV, or Parquet with typed columns
//! (see `platoonsim-columnar`): the label columns as integers, numbers or text by their
//! values, `seed` and the counts (`n`, `diff_n`, `runs_with_collisions`) as uint64, the words
//! (`key`, `metric`, `reference`, `paper_source`) as strings, every other column float64.

use crate::atomic::write_atomic;
use crate::Error;
use platoonsim_columnar::{from_csv, parquet_bytes, Kind};
use serde::Serialize;
use std::path::Path;

/// How the tables are written.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    #[default]
    Csv,
    Parquet,
}

impl Format {
    pub fn ext(self) -> &'static str {
        match self {
            Format::Csv => "csv",
            Format::Parquet => "parquet",
        }
    }
}

/// The type of a column of `runs.csv` or `summary.csv`; `labels` are the cells' label
/// columns.
pub fn kind(labels: &[String], column: &str) -> Kind {
    if labels.iter().any(|l| l == column) {
        return Kind::Auto;
    }
    match column {
        "seed" | "n" | "diff_n" | "runs_with_collisions" => Kind::U64,
        "key" | "metric" | "reference" | "paper_source" => Kind::Str,
        _ => Kind::F64,
    }
}

/// Write the table `<dir>/<stem>.<ext>` from its CSV bytes, in `format`; the file of the
/// other format, left by an earlier invocation, is removed so that the directory holds one
/// version of each table.
pub fn write_table(
    dir: &Path,
    stem: &str,
    csv: &[u8],
    labels: &[String],
    format: Format,
) -> Result<(), Error> {
    let path = dir.join(format!("{stem}.{}", format.ext()));
    let bytes = match format {
        Format::Csv => csv.to_vec(),
        Format::Parquet => {
            let table = from_csv(csv, &|c| kind(labels, c))
                .map_err(|e| Error::Other(format!("{stem}: {e}")))?;
            parquet_bytes(&table).map_err(|e| Error::Other(format!("{stem}: {e}")))?
        }
    };
    write_atomic(&path, &bytes).map_err(|e| Error::io(&path, e))?;
    let other = match format {
        Format::Csv => Format::Parquet,
        Format::Parquet => Format::Csv,
    };
    let stale = dir.join(format!("{stem}.{}", other.ext()));
    crate::atomic::remove_output(&stale).map_err(|e| Error::io(&stale, e))
}
