//! # platoonsim-columnar: typed tables as Parquet
//!
//! The output tables (`detectors`, `trips`, `trajectories`, a sweep's or experiment's `runs`
//! and `summary`) are built as a [`Table`] of typed [`Column`]s and written as Parquet
//! ([`to_parquet`]): one row group per [`ROW_GROUP_ROWS`] rows, snappy compression, the
//! column names of the CSV files (units in the names: `x_m`, `speed_kmh`, `flow_vphpl`).
//! Missing values (the CSV's empty cells) are nulls. pandas, polars and pyarrow read the
//! files with these types.
//!
//! Arrow and Parquet stay here, out of the engine crates, which know nothing of files.

use arrow_array::builder::{
    BooleanBuilder, Float64Builder, Int64Builder, StringBuilder, UInt64Builder,
};
use arrow_array::{ArrayRef, RecordBatch};
use arrow_schema::{DataType, Field, Schema};
use parquet::arrow::ArrowWriter;
use parquet::basic::Compression;
use parquet::file::properties::WriterProperties;
use std::io::Write;
use std::sync::Arc;

/// Rows per row group (and per record batch handed to the writer).
pub const ROW_GROUP_ROWS: usize = 1 << 20;

/// One typed column; `None` is a null (an empty CSV cell).
#[derive(Clone, Debug, PartialEq)]
pub enum Values {
    F64(Vec<Option<f64>>),
    I64(Vec<Option<i64>>),
    U64(Vec<Option<u64>>),
    Str(Vec<Option<String>>),
    Bool(Vec<Option<bool>>),
}

impl Values {
    pub fn len(&self) -> usize {
        match self {
            Values::F64(v) => v.len(),
            Values::I64(v) => v.len(),
            Values::U64(v) => v.len(),
            Values::Str(v) => v.len(),
            Values::Bool(v) => v.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn data_type(&self) -> DataType {
        match self {
            Values::F64(_) => DataType::Float64,
            Values::I64(_) => DataType::Int64,
            Values::U64(_) => DataType::UInt64,
            Values::Str(_) => DataType::Utf8,
            Values::Bool(_) => DataType::Boolean,
        }
    }

    /// Rows `from..to` as an Arrow array.
    fn array(&self, from: usize, to: usize) -> ArrayRef {
        match self {
            Values::F64(v) => {
                let mut b = Float64Builder::with_capacity(to - from);
                // NaN is written as null, as the CSV writes it as an empty cell.
                b.extend(v[from..to].iter().map(|x| x.filter(|f| !f.is_nan())));
                Arc::new(b.finish())
            }
            Values::I64(v) => {
                let mut b = Int64Builder::with_capacity(to - from);
                b.extend(v[from..to].iter().copied());
                Arc::new(b.finish())
            }
            Values::U64(v) => {
                let mut b = UInt64Builder::with_capacity(to - from);
                b.extend(v[from..to].iter().copied());
                Arc::new(b.finish())
            }
            Values::Str(v) => {
                let mut b = StringBuilder::with_capacity(to - from, 16 * (to - from));
                for s in &v[from..to] {
                    b.append_option(s.as_deref());
                }
                Arc::new(b.finish())
            }
            Values::Bool(v) => {
                let mut b = BooleanBuilder::with_capacity(to - from);
                b.extend(v[from..to].iter().copied());
                Arc::new(b.finish())
            }
        }
    }
}

/// A named column.
#[derive(Clone, Debug, PartialEq)]
pub struct Column {
    pub name: String,
    pub values: Values,
}

impl Column {
    pub fn new(name: &str, values: Values) -> Column {
        Column {
            name: name.to_string(),
            values,
        }
    }
}

/// Columns of equal length.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    pub columns: Vec<Column>,
}

/// Why a table could not be written.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error("column '{name}' has {len} rows, the first column {rows}")]
    Ragged {
        name: String,
        len: usize,
        rows: usize,
    },
    #[error("cannot encode Parquet: {0}")]
    Parquet(String),
}

impl Table {
    pub fn push(&mut self, name: &str, values: Values) {
        self.columns.push(Column::new(name, values));
    }

    pub fn rows(&self) -> usize {
        self.columns.first().map_or(0, |c| c.values.len())
    }
}

/// A Parquet file written table by table (each [`Writer::write`] adds rows with the same
/// columns), so that a large table need not be held in memory at once.
pub struct Writer<W: Write + Send> {
    inner: ArrowWriter<W>,
    schema: Arc<Schema>,
}

fn pq(e: parquet::errors::ParquetError) -> Error {
    Error::Parquet(e.to_string())
}

impl<W: Write + Send> Writer<W> {
    /// A writer for tables with the columns (names and types) of `like`.
    pub fn new(w: W, like: &Table) -> Result<Writer<W>, Error> {
        let schema = Arc::new(Schema::new(
            like.columns
                .iter()
                .map(|c| Field::new(&c.name, c.values.data_type(), true))
                .collect::<Vec<_>>(),
        ));
        let props = WriterProperties::builder()
            .set_compression(Compression::SNAPPY)
            .set_max_row_group_row_count(Some(ROW_GROUP_ROWS))
            .set_created_by(format!("platoonsim {}", env!("CARGO_PKG_VERSION")))
            .build();
        let inner = ArrowWriter::try_new(w, schema.clone(), Some(props)).map_err(pq)?;
        Ok(Writer { inner, schema })
    }

    /// Append the rows of `table` (same columns as the first).
    pub fn write(&mut self, table: &Table) -> Result<(), Error> {
        let rows = table.rows();
        for c in &table.columns {
            if c.values.len() != rows {
                return Err(Error::Ragged {
                    name: c.name.clone(),
                    len: c.values.len(),
                    rows,
                });
            }
        }
        let mut from = 0;
        loop {
            let to = (from + ROW_GROUP_ROWS).min(rows);
            let arrays: Vec<ArrayRef> = table
                .columns
                .iter()
                .map(|c| c.values.array(from, to))
                .collect();
            let batch = RecordBatch::try_new(self.schema.clone(), arrays)
                .map_err(|e| Error::Parquet(e.to_string()))?;
            self.inner.write(&batch).map_err(pq)?;
            from = to;
            if from >= rows {
                return Ok(());
            }
        }
    }

    /// Write the footer.
    pub fn finish(self) -> Result<(), Error> {
        self.inner.close().map_err(pq)?;
        Ok(())
    }
}

/// Write `table` as a Parquet file to `w` (snappy-compressed, nullable typed columns).
pub fn to_parquet<W: Write + Send>(table: &Table, w: W) -> Result<(), Error> {
    let mut writer = Writer::new(w, table)?;
    writer.write(table)?;
    writer.finish()
}

/// The type of a column read from CSV text ([`from_csv`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    F64,
    I64,
    U64,
    Str,
    Bool,
    /// Integers if every non-empty cell is one, else numbers if every one is, else text
    /// (for label columns, whose values a sweep file chooses).
    Auto,
}

/// A CSV table (header first; empty cells are nulls) as typed columns: `kind` gives each
/// column's type by name. A cell that is not of its column's type is an error naming the
/// column, the row and the text.
pub fn from_csv(bytes: &[u8], kind: &dyn Fn(&str) -> Kind) -> Result<Table, Error> {
    let mut r = csv::ReaderBuilder::new()
        .has_headers(true)
        .from_reader(bytes);
    let bad = |e: csv::Error| Error::Parquet(format!("cannot read the CSV table: {e}"));
    let header: Vec<String> = r.headers().map_err(bad)?.iter().map(String::from).collect();
    let mut cells: Vec<Vec<String>> = vec![Vec::new(); header.len()];
    for rec in r.records() {
        let rec = rec.map_err(bad)?;
        for (c, v) in rec.iter().enumerate().take(header.len()) {
            cells[c].push(v.to_string());
        }
    }
    let mut t = Table::default();
    for (name, col) in header.iter().zip(cells) {
        let k = match kind(name) {
            Kind::Auto if col.iter().all(|v| v.is_empty() || v.parse::<i64>().is_ok()) => Kind::I64,
            Kind::Auto if col.iter().all(|v| v.is_empty() || v.parse::<f64>().is_ok()) => Kind::F64,
            Kind::Auto => Kind::Str,
            k => k,
        };
        let parse = |row: usize, v: &str, what: &str| {
            Error::Parquet(format!(
                "column '{name}', row {}: '{v}' is not {what}",
                row + 2
            ))
        };
        let values = match k {
            Kind::F64 => Values::F64(
                col.iter()
                    .enumerate()
                    .map(|(i, v)| {
                        (!v.is_empty())
                            .then(|| v.parse().map_err(|_| parse(i, v, "a number")))
                            .transpose()
                    })
                    .collect::<Result<_, _>>()?,
            ),
            Kind::I64 => Values::I64(
                col.iter()
                    .enumerate()
                    .map(|(i, v)| {
                        (!v.is_empty())
                            .then(|| v.parse().map_err(|_| parse(i, v, "an integer")))
                            .transpose()
                    })
                    .collect::<Result<_, _>>()?,
            ),
            Kind::U64 => Values::U64(
                col.iter()
                    .enumerate()
                    .map(|(i, v)| {
                        (!v.is_empty())
                            .then(|| v.parse().map_err(|_| parse(i, v, "a count")))
                            .transpose()
                    })
                    .collect::<Result<_, _>>()?,
            ),
            Kind::Bool => Values::Bool(
                col.iter()
                    .enumerate()
                    .map(|(i, v)| {
                        (!v.is_empty())
                            .then(|| v.parse().map_err(|_| parse(i, v, "true or false")))
                            .transpose()
                    })
                    .collect::<Result<_, _>>()?,
            ),
            Kind::Str | Kind::Auto => Values::Str(
                col.into_iter()
                    .map(|v| (!v.is_empty()).then_some(v))
                    .collect(),
            ),
        };
        t.push(name, values);
    }
    Ok(t)
}

/// [`to_parquet`] into memory.
pub fn parquet_bytes(table: &Table) -> Result<Vec<u8>, Error> {
    let mut out = Vec::new();
    to_parquet(table, &mut out)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use parquet::file::reader::{FileReader, SerializedFileReader};

    #[test]
    fn typed_columns_round_trip_their_shape() {
        let mut t = Table::default();
        t.push("x_m", Values::F64(vec![Some(1.5), None, Some(f64::NAN)]));
        t.push("id", Values::U64(vec![Some(1), Some(2), Some(3)]));
        t.push(
            "kind",
            Values::Str(vec![Some("cav".into()), Some("human".into()), None]),
        );
        t.push(
            "measured",
            Values::Bool(vec![Some(true), Some(false), None]),
        );
        let bytes = parquet_bytes(&t).unwrap();
        assert_eq!(&bytes[..4], b"PAR1");
        let r = SerializedFileReader::new(bytes::Bytes::from(bytes)).unwrap();
        let meta = r.metadata();
        assert_eq!(meta.file_metadata().num_rows(), 3);
        let cols: Vec<String> = meta
            .file_metadata()
            .schema_descr()
            .columns()
            .iter()
            .map(|c| c.name().to_string())
            .collect();
        assert_eq!(cols, ["x_m", "id", "kind", "measured"]);
        // Two nulls in x_m: the missing value and the NaN.
        let stats = meta.row_group(0).column(0).statistics().unwrap();
        assert_eq!(stats.null_count_opt(), Some(2));
    }

    #[test]
    fn csv_tables_get_their_types() {
        let csv = b"level,strategy,seed,x,flag\n0.2,none,1,1.5,true\n0.4,pd,2,,false\n";
        let t = from_csv(csv, &|c| match c {
            "seed" => Kind::U64,
            "x" => Kind::F64,
            "flag" => Kind::Bool,
            _ => Kind::Auto,
        })
        .unwrap();
        assert_eq!(t.columns[0].values, Values::F64(vec![Some(0.2), Some(0.4)]));
        assert_eq!(
            t.columns[1].values,
            Values::Str(vec![Some("none".into()), Some("pd".into())])
        );
        assert_eq!(t.columns[2].values, Values::U64(vec![Some(1), Some(2)]));
        assert_eq!(t.columns[3].values, Values::F64(vec![Some(1.5), None]));
        assert_eq!(
            t.columns[4].values,
            Values::Bool(vec![Some(true), Some(false)])
        );
        let e = from_csv(b"seed\nx\n", &|_| Kind::U64)
            .unwrap_err()
            .to_string();
        assert!(e.contains("'seed', row 2: 'x'"), "{e}");
    }

    #[test]
    fn ragged_tables_are_refused() {
        let mut t = Table::default();
        t.push("a", Values::I64(vec![Some(1)]));
        t.push("b", Values::I64(vec![]));
        assert!(matches!(parquet_bytes(&t), Err(Error::Ragged { .. })));
    }
}
