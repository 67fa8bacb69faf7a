//! The one reader of `trajectories.csv`, for the viewer and `platoonsim time-space`: the
//! columns found by header name (extra columns are ignored; `a_mps2`, `mode`, `platoon_pos` and
//! `regime` are optional, so the first format's files read too), each row parsed and checked
//! into a [`Sample`] handed to the caller, which keeps what it needs (a file can have tens of
//! millions of rows). Errors name the file and, for a bad row, the line and the column.

use crate::{TRAJECTORIES, TRAJECTORY_COLUMNS};
use std::io::Read;

/// The columns a reader needs; the others of [`TRAJECTORY_COLUMNS`] are used when present.
pub const TRAJECTORY_REQUIRED: [&str; 6] = ["t_s", "id", "kind", "lane", "x_m", "v_mps"];

/// One row of `trajectories.csv`, checked: finite numbers, a whole id, a lane from 1, a kind
/// a run writes. The word cells borrow the row.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<'a> {
    /// The row's line in the file (the header is line 1).
    pub line: u64,
    pub t_s: f64,
    pub id: u64,
    /// `cav` or `human`.
    pub kind: &'a str,
    /// Counted from the right, from 1.
    pub lane: u32,
    pub x_m: f64,
    pub v_mps: f64,
    /// `None` without the column.
    pub a_mps2: Option<f64>,
    /// The cell (possibly empty), `None` without the column.
    pub mode: Option<&'a str>,
    /// `None` without the column or for an empty cell.
    pub platoon_pos: Option<u32>,
    /// The cell (empty for a vehicle that is not an automated CAV), `None` without the column.
    pub regime: Option<&'a str>,
}

impl Sample<'_> {
    pub fn is_cav(&self) -> bool {
        self.kind == "cav"
    }
}

/// What the caller found wrong with a row: for [`read_samples`] to name its line and column.
pub struct Bad {
    pub column: &'static str,
    /// What the cell should be ("a lane of the road ...").
    pub what: String,
}

/// An error of the reader or of the caller's check, as the message for the user.
pub enum Stop {
    Bad(Bad),
    Other(String),
}

impl From<Bad> for Stop {
    fn from(b: Bad) -> Stop {
        Stop::Bad(b)
    }
}

/// Read `input` (the file `name`) row by row, calling `each` with every sample in file order;
/// returns the header's columns. A header without one of [`TRAJECTORY_REQUIRED`] is refused,
/// saying what a run writes.
pub fn read_samples<R: Read>(
    input: R,
    name: &str,
    mut each: impl FnMut(&Sample<'_>) -> Result<(), Stop>,
) -> Result<Vec<String>, String> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .flexible(true)
        .from_reader(input);
    let header = reader
        .headers()
        .map_err(|e| format!("cannot read {name}: {e}"))?
        .clone();
    let joined = header.iter().collect::<Vec<_>>().join(",");
    let col = |c: &str| header.iter().position(|h| h == c);
    let mut req = [0usize; 6];
    for (i, c) in TRAJECTORY_REQUIRED.iter().enumerate() {
        req[i] = col(c).ok_or_else(|| {
            format!(
                "{name} is not a {}: column {c} is missing (the header is '{joined}'; a \
                 {} written by `platoonsim run --trajectories PERIOD_S` has {})",
                TRAJECTORIES.csv,
                TRAJECTORIES.csv,
                TRAJECTORY_COLUMNS.join(",")
            )
        })?;
    }
    let [c_t, c_id, c_kind, c_lane, c_x, c_v] = req;
    let (c_a, c_mode, c_pos, c_regime) = (
        col("a_mps2"),
        col("mode"),
        col("platoon_pos"),
        col("regime"),
    );
    let mut record = csv::StringRecord::new();
    let mut line = 1u64;
    loop {
        match reader.read_record(&mut record) {
            Ok(false) => return Ok(header.iter().map(String::from).collect()),
            Ok(true) => line = record.position().map_or(line + 1, |p| p.line()),
            Err(e) => return Err(format!("cannot read {name} after line {line}: {e}")),
        }
        if record.len() != header.len() {
            return Err(format!(
                "{name} line {line}: {} fields, expected {} ({joined})",
                record.len(),
                header.len()
            ));
        }
        let cell = |c: usize| record.get(c).unwrap_or("").trim();
        let bad = |c: usize, what: &str| {
            format!(
                "{name} line {line}, column {}: '{}' is not {what}",
                header.get(c).unwrap_or("?"),
                cell(c)
            )
        };
        let float = |c: usize| -> Result<f64, String> {
            cell(c)
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| bad(c, "a finite number"))
        };
        let sample = Sample {
            line,
            t_s: float(c_t)?,
            id: cell(c_id)
                .parse()
                .map_err(|_| bad(c_id, "a vehicle id (a whole number >= 0)"))?,
            kind: match cell(c_kind) {
                // The kinds a run writes; anything else is not a run's file.
                k @ ("cav" | "human") => k,
                _ => return Err(bad(c_kind, "a vehicle kind (cav or human)")),
            },
            lane: cell(c_lane)
                .parse()
                .ok()
                .filter(|&l| l >= 1)
                .ok_or_else(|| bad(c_lane, "a lane number (1, 2, ...)"))?,
            x_m: float(c_x)?,
            v_mps: float(c_v)?,
            a_mps2: c_a.map(float).transpose()?,
            mode: c_mode.map(cell),
            platoon_pos: match c_pos {
                Some(c) if !cell(c).is_empty() => Some(
                    cell(c)
                        .parse()
                        .map_err(|_| bad(c, "a platoon position (1, 2, ...)"))?,
                ),
                _ => None,
            },
            regime: c_regime.map(cell),
        };
        match each(&sample) {
            Ok(()) => {}
            Err(Stop::Other(message)) => return Err(message),
            Err(Stop::Bad(b)) => {
                let c = col(b.column).unwrap_or(usize::MAX);
                return Err(bad(c, &b.what));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all(text: &str) -> Result<Vec<String>, String> {
        let mut out = Vec::new();
        read_samples(text.as_bytes(), "t.csv", |s| {
            out.push(format!(
                "{} {} {} {} {} {} {:?} {:?} {:?} {:?}",
                s.line,
                s.t_s,
                s.id,
                s.kind,
                s.lane,
                s.x_m,
                s.a_mps2,
                s.mode,
                s.platoon_pos,
                s.regime
            ));
            Ok(())
        })?;
        Ok(out)
    }

    #[test]
    fn rows_are_read_by_header_name_with_the_optional_columns() {
        let text = "t_s,id,kind,lane,x_m,v_mps,a_mps2,mode,platoon_pos,regime\n\
                    0.5,7,cav,2,-1.5,30,0.25,cf-auto,2,gap\n1,8,human,1,3,0,-1,blc,1,\n";
        assert_eq!(
            all(text).unwrap(),
            [
                "2 0.5 7 cav 2 -1.5 Some(0.25) Some(\"cf-auto\") Some(2) Some(\"gap\")",
                "3 1 8 human 1 3 Some(-1.0) Some(\"blc\") Some(1) Some(\"\")"
            ]
        );
        // Reordered, extra and missing optional columns.
        let text = "id,extra,t_s,kind,lane,x_m,v_mps\n7,x,0,cav,1,2,3\n";
        assert_eq!(all(text).unwrap(), ["2 0 7 cav 1 2 None None None None"]);
    }

    #[test]
    fn refusals_name_the_line_and_the_column() {
        let head = "t_s,id,kind,lane,x_m,v_mps\n";
        for (row, want) in [
            (
                "0,7,cav,1,zz,3",
                "t.csv line 2, column x_m: 'zz' is not a finite number",
            ),
            (
                "0,7,cav,1,1,inf",
                "column v_mps: 'inf' is not a finite number",
            ),
            ("0,-7,cav,1,1,1", "column id: '-7' is not a vehicle id"),
            (
                "0,7,truck,1,1,1",
                "column kind: 'truck' is not a vehicle kind (cav or human)",
            ),
            (
                "0,7,cav,0,1,1",
                "column lane: '0' is not a lane number (1, 2, ...)",
            ),
            ("0,7,cav,1,1", "t.csv line 2: 5 fields, expected 6"),
        ] {
            let e = all(&format!("{head}{row}\n")).unwrap_err();
            assert!(e.contains(want), "{e}");
        }
        let e = all("a,b,c\n1,2,3\n").unwrap_err();
        assert!(
            e.starts_with(
                "t.csv is not a trajectories.csv: column t_s is missing (the header is 'a,b,c'"
            ),
            "{e}"
        );
        let e = read_samples(format!("{head}0,7,cav,4,1,1\n").as_bytes(), "t.csv", |s| {
            Err(Bad {
                column: "lane",
                what: format!("a lane of this road (not {})", s.lane),
            }
            .into())
        })
        .unwrap_err();
        assert_eq!(
            e,
            "t.csv line 2, column lane: '4' is not a lane of this road (not 4)"
        );
    }
}
