//! Figures for platoonsim, written as both PNG and SVG: line charts ([`line_chart`], as
//! panels [`panels`]), speed contours ([`heatmap`], [`heatmap_panels`]) and grouped bars
//! ([`bar_chart`], [`bar_panels`]), and time-space diagrams of vehicle trajectories
//! ([`time_space`]).
//!
//! The crate takes plain data (vectors of `f64`, strings) and knows nothing about the
//! simulator. Every public function writes `<stem>.png` and `<stem>.svg` and returns both
//! paths, PNG first. Files are written atomically: each is first written to
//! `<name>.tmp` in the same directory and then renamed, so a reader never sees half a figure.
//! Missing parent directories are created.
//!
//! Text is rendered with DejaVu Sans, embedded in the binary by the `dejavu` crate and handed
//! to plotters' `ab_glyph` text backend, so no system font or fontconfig is needed. The SVG
//! files name the generic `sans-serif` family and leave the font choice to the viewer.
//! DejaVu's fonts are under the Bitstream Vera licence (DejaVu's own changes are public
//! domain), which allows redistribution with the program; the licence text ships in the
//! `dejavu` crate.
//!
//! Robustness: empty series and empty charts draw an empty frame (with the legend), points
//! with a non-finite coordinate are skipped (a line is broken there), and data outside a
//! fixed `y_range` is clipped to the plotting area. Nothing here panics on such input.
//!
//! ```no_run
//! use platoonsim_plot::{line_chart, Chart, Series, Style};
//! let chart = Chart {
//!     title: "Capacity vs penetration".into(),
//!     x_label: "Penetration (%)".into(),
//!     y_label: "Capacity (veh/h/lane)".into(),
//!     series: vec![Series {
//!         name: "simulated".into(),
//!         x: vec![0.0, 50.0, 100.0],
//!         y: vec![2000.0, 2400.0, 3600.0],
//!         band: Some((vec![1950.0, 2350.0, 3500.0], vec![2050.0, 2450.0, 3700.0])),
//!         style: Style::Line,
//!     }],
//!     y_range: None,
//! };
//! let files = line_chart(&chart, std::path::Path::new("out/fig7")).unwrap();
//! assert_eq!(files.len(), 2);
//! ```

mod bars;
mod geom;
mod heat;
mod heat_row;
mod line;
mod output;
mod theme;
mod tsd;

use std::path::{Path, PathBuf};

/// How a [`Series`] is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Style {
    /// A solid line through the points.
    #[default]
    Line,
    /// A dashed line through the points.
    Dashed,
    /// Points only (e.g. values read from the paper), drawn as filled circles.
    Markers,
}

/// One data series of a [`Chart`].
///
/// `x` and `y` are paired by index; extra values in the longer one are ignored, and a pair
/// with a non-finite value is skipped. The series gets the next colour of a colour-blind-safe
/// palette (Okabe–Ito) and a legend entry unless `name` is empty.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Series {
    /// Legend text; empty for no legend entry.
    pub name: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates.
    pub y: Vec<f64>,
    /// Optional `(lower, upper)` bounds at the same `x` (e.g. a 95 % confidence interval),
    /// drawn as a translucent area in the series' colour.
    pub band: Option<(Vec<f64>, Vec<f64>)>,
    /// Line, dashed line or markers.
    pub style: Style,
}

/// A line chart: axes with labels, any number of series, a legend.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Chart {
    /// Title above the plotting area; empty for none.
    pub title: String,
    /// X axis label with unit, e.g. `"Penetration (%)"`.
    pub x_label: String,
    /// Y axis label with unit, e.g. `"Capacity (veh/h/lane)"`.
    pub y_label: String,
    /// The series, drawn in order (bands first, then lines, then markers on top).
    pub series: Vec<Series>,
    /// Fixed y range `(min, max)`; `None` fits the data (bands included) with a small margin.
    /// Data outside a fixed range is clipped.
    pub y_range: Option<(f64, f64)>,
}

/// A speed contour (space–time heat map).
///
/// `z[i][j]` is the value of the cell centred at `(x[i], y[j])`: the outer index runs along
/// the x axis. For a time × detector matrix, put times in `x` and detector positions (or
/// indices) in `y`. So `z.len() == x.len()` and every `z[i].len() == y.len()`; other shapes
/// are rejected with [`PlotError::Invalid`]. `x` and `y` must be finite and strictly
/// increasing; cell edges lie halfway between neighbouring centres.
///
/// Colours run from red (`z_range.0`, slow) through yellow to green (`z_range.1`, fast);
/// values outside the range take the end colour, non-finite cells are drawn grey. If
/// `z_range` is not a finite increasing pair, the finite data's extent is used.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Heatmap {
    /// Title above the figure; empty for none.
    pub title: String,
    /// X axis label with unit, e.g. `"Time (min)"`.
    pub x_label: String,
    /// Y axis label with unit, e.g. `"Position (km)"`.
    pub y_label: String,
    /// Cell centres along x (one per row of `z`).
    pub x: Vec<f64>,
    /// Cell centres along y (one per column of `z`).
    pub y: Vec<f64>,
    /// Values, `z[i][j]` at `(x[i], y[j])`.
    pub z: Vec<Vec<f64>>,
    /// Colour bar label with unit, e.g. `"Speed (km/h)"`.
    pub z_label: String,
    /// Value range of the colour scale `(slow, fast)`.
    pub z_range: (f64, f64),
}

/// A grouped bar chart (paper Fig. 8 style).
///
/// Each entry of `series` is `(name, values, errors)`: `values[g]` is the bar height in group
/// `g`, and `errors[g]`, if given, the half-length of its error bar (e.g. a 95 % CI
/// half-width), drawn as `value ± error`. Values beyond `groups.len()` are ignored, missing or
/// non-finite values leave a gap, non-finite errors draw no error bar.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Bars {
    /// Title above the plotting area; empty for none.
    pub title: String,
    /// Y axis label with unit.
    pub y_label: String,
    /// Group names along the x axis.
    pub groups: Vec<String>,
    /// `(name, values per group, optional error half-lengths per group)`.
    pub series: Vec<(String, Vec<f64>, Option<Vec<f64>>)>,
    /// Values the y axis must also cover (non-finite ones are ignored): charts given the same
    /// values and data within them get the same y range, e.g. ours and the paper's panels.
    pub y_include: Vec<f64>,
}

/// The fixed speed scale of [`time_space`] (km/h): 0 (red) through yellow to 120 (green);
/// faster samples take the end colour.
pub const TRACK_SPEED_RANGE_KMH: (f64, f64) = (0.0, 120.0);

/// Width of one colour step of [`time_space`]'s speed scale (km/h).
pub const TRACK_SPEED_BIN_KMH: f64 = 5.0;

/// One sample of a vehicle's trajectory.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TrackSample {
    /// Simulated time (s).
    pub t_s: f64,
    /// Lane (any numbering; compared with [`TimeSpace::lane`]).
    pub lane: u32,
    /// Position of the vehicle's front (m).
    pub x_m: f64,
    /// Speed (m/s).
    pub v_mps: f64,
}

/// One vehicle's samples, in any order (they are sorted by time).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Track {
    /// A CAV (drawn thick) or a human-driven vehicle (drawn thin).
    pub cav: bool,
    /// The samples; those in other lanes only break the line.
    pub samples: Vec<TrackSample>,
}

/// A time-space diagram of one lane: time on the x axis, position on the y axis.
///
/// Each track is drawn through its samples in `lane`, in time order; a sample in another lane
/// (or with a non-finite value) breaks the line, so a vehicle that leaves the lane and comes
/// back gives two lines. Each step between two samples is coloured by their mean speed on the
/// fixed scale [`TRACK_SPEED_RANGE_KMH`] in steps of [`TRACK_SPEED_BIN_KMH`]; consecutive steps
/// of one colour form one polyline. A lone sample in the lane is drawn as a dot.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TimeSpace {
    /// Title above the figure; empty for none.
    pub title: String,
    /// The lane drawn.
    pub lane: u32,
    /// The vehicles.
    pub tracks: Vec<Track>,
}

/// Why a figure could not be written. Every variant names the file concerned.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// Creating the directory, writing the temporary file or renaming it failed.
    #[error("cannot write {}: {source}", .path.display())]
    Io {
        /// The file (or directory) being written.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// plotters reported an error while drawing.
    #[error("cannot draw {}: {message}", .path.display())]
    Draw {
        /// The file being drawn.
        path: PathBuf,
        /// plotters' message.
        message: String,
    },
    /// The rendered image could not be encoded as PNG.
    #[error("cannot encode {}: {message}", .path.display())]
    Encode {
        /// The PNG file.
        path: PathBuf,
        /// The encoder's message.
        message: String,
    },
    /// The input cannot be drawn (e.g. a heat map whose `z` does not match `x` and `y`).
    #[error("cannot plot {}: {message}", .path.display())]
    Invalid {
        /// The file that was to be written.
        path: PathBuf,
        /// What is wrong with the input.
        message: String,
    },
    /// The embedded font could not be registered (should not happen).
    #[error("cannot draw {}: the embedded DejaVu Sans font failed to load", .path.display())]
    Font {
        /// The file that was to be written.
        path: PathBuf,
    },
}

/// Writes one line chart to `<stem>.png` and `<stem>.svg` (1000 × 700 px); returns both paths.
pub fn line_chart(chart: &Chart, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    output::write_figure(&line::Single(chart), stem)
}

/// Writes several charts as one figure, in a grid of `cols` columns (0 is taken as 1) filled
/// row by row, under a common `title`; returns both paths. Each panel is about 540 × 430 px.
pub fn panels(
    charts: &[Chart],
    cols: usize,
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>, PlotError> {
    output::write_figure(&line::Grid::new(charts, cols, title), stem)
}

/// Writes a speed contour with a colour bar (1100 × 700 px); returns both paths.
/// See [`Heatmap`] for the layout of `z` and the colour scale.
pub fn heatmap(h: &Heatmap, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let figure = heat::Figure::new(h).map_err(|message| PlotError::Invalid {
        path: output::file_path(stem, "png"),
        message,
    })?;
    output::write_figure(&figure, stem)
}

/// Writes a grouped bar chart with optional error bars (1000 × 700 px); returns both paths.
pub fn bar_chart(b: &Bars, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    output::write_figure(&bars::Figure(b), stem)
}

/// Writes several bar charts as one figure, in a grid of `cols` columns (0 is taken as 1)
/// filled row by row, under a common `title`; returns both paths. Each panel is about
/// 560 × 440 px.
pub fn bar_panels(
    charts: &[Bars],
    cols: usize,
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>, PlotError> {
    output::write_figure(&bars::Grid::new(charts, cols, title), stem)
}

/// Writes a time-space diagram (1200 × 750 px) with a speed colour bar and a key of the line
/// widths; returns both paths. Without samples in the lane it draws an empty frame. See
/// [`TimeSpace`].
pub fn time_space(ts: &TimeSpace, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    output::write_figure(&tsd::Figure::new(ts), stem)
}

/// Writes several speed contours as one figure, in a grid of `cols` columns (at least one)
/// under a common `title`, with one colour bar for all of them: the first map's
/// `z_range` and `z_label` (or, if that range is not a finite increasing pair, the extent
/// of all the maps' finite values). Each map's `title` is its panel's caption. Every map is
/// checked as in [`heatmap`]; an error names the panel. Returns both paths.
pub fn heatmap_panels(
    maps: &[Heatmap],
    cols: usize,
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>, PlotError> {
    let grid = heat::Grid::new(maps, cols, title).map_err(|message| PlotError::Invalid {
        path: output::file_path(stem, "png"),
        message,
    })?;
    output::write_figure(&grid, stem)
}

/// Writes several speed contours side by side in one row under a common `title`, each with
/// its own colour bar: its own `z_range` (or, if that is not a finite increasing pair, the
/// extent of its finite values) and `z_label`, so maps on different scales (speeds and a
/// speed difference) share a figure. Each map's `title` is its panel's caption. Every map
/// is checked as in [`heatmap`]; an error names the panel. Returns both paths.
pub fn heatmap_row(maps: &[Heatmap], title: &str, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    let row = heat_row::Row::new(maps, title).map_err(|message| PlotError::Invalid {
        path: output::file_path(stem, "png"),
        message,
    })?;
    output::write_figure(&row, stem)
}
