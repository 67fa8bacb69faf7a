//! The files of a comparison, written atomically into one directory:
//!
//! | file | what |
//! |---|---|
//! | `compare.md` | the report ([`platoonsim_field::report`]) |
//! | `compare.html` | the same, self-contained (figure inlined; [`platoonsim_runs::page::html`]) |
//! | `fit.json` | the measures, machine readable ([`FitFile`]) |
//! | `contours.png`, `contours.svg` | simulated \| field \| difference speed contours |

use super::{contours, Evaluation, Options};
use crate::atomic::write_atomic;
use crate::Error;
use platoonsim_field::report::{self, clock, Report};
use platoonsim_field::{Obs, Placed};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Stem of the contour figure inside the output directory.
pub const CONTOURS: &str = "contours";

/// What the comparison read, for the report and `fit.json`.
#[derive(Clone, Debug, Default)]
pub struct Inputs {
    /// Run directories (replications).
    pub runs: Vec<String>,
    /// Field files.
    pub field_files: Vec<String>,
    /// Notes on the data (e.g. field intervals left out when stations were combined).
    pub notes: Vec<String>,
}

/// `fit.json`.
#[derive(Debug, Serialize)]
pub struct FitFile<'a> {
    pub version: &'static str,
    pub runs: &'a [String],
    pub field_files: &'a [String],
    /// The period compared, "HH:MM".
    pub from: String,
    pub to: String,
    /// [`Evaluation::objective`]; null without matched data.
    pub objective: Option<f64>,
    /// Whether every criterion holds.
    pub pass: bool,
    pub options: &'a Options,
    pub notes: &'a [String],
    #[serde(flatten)]
    pub evaluation: &'a Evaluation,
}

/// Write the report, the page, `fit.json` and the figure into `dir`; returns the paths
/// written (report first).
#[allow(clippy::too_many_arguments)]
pub fn write(
    dir: &Path,
    inputs: &Inputs,
    eval: &Evaluation,
    opts: &Options,
    sim: &[Obs],
    field: &[Obs],
    sim_places: &[Placed],
    field_places: &[Placed],
) -> Result<Vec<PathBuf>, Error> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let (sim_line, field_line) =
        super::bottleneck_lines(&eval.fit.stations_compared, sim_places, field_places);
    let mut written = Vec::new();
    let figure = if sim_line.is_empty() {
        None
    } else {
        let maps = contours::panels(sim, field, &sim_line, &field_line, eval.window);
        let title = format!(
            "5-min speeds, {}–{}",
            clock(eval.window.0),
            clock(eval.window.1)
        );
        let files = platoonsim_plot::heatmap_row(&maps, &title, &dir.join(CONTOURS))
            .map_err(|e| Error::Other(e.to_string()))?;
        written.extend(files);
        Some(format!("{CONTOURS}.png"))
    };
    let md = report::markdown(&Report {
        runs: &inputs.runs,
        field_files: &inputs.field_files,
        window: eval.window,
        fit: &eval.fit,
        criteria: &eval.criteria,
        ramps: Some((&eval.ramp_fit, &eval.ramp_criteria)),
        bottlenecks: &eval.bottlenecks,
        figure: figure.as_deref(),
        notes: &inputs.notes,
    });
    let page = platoonsim_runs::page::html(&md, dir, "platoonsim compare");
    let json = serde_json::to_string_pretty(&FitFile {
        version: crate::VERSION,
        runs: &inputs.runs,
        field_files: &inputs.field_files,
        from: clock(eval.window.0),
        to: clock(eval.window.1),
        objective: eval.objective(),
        pass: eval.passes(),
        options: opts,
        notes: &inputs.notes,
        evaluation: eval,
    })
    .map_err(|e| Error::Other(format!("cannot encode fit.json: {e}")))?;
    let mut out = Vec::new();
    for (name, bytes) in [
        ("compare.md", md.into_bytes()),
        ("compare.html", page.into_bytes()),
        ("fit.json", (json + "\n").into_bytes()),
    ] {
        let path = dir.join(name);
        write_atomic(&path, &bytes).map_err(|e| Error::io(&path, e))?;
        out.push(path);
    }
    out.extend(written);
    Ok(out)
}
