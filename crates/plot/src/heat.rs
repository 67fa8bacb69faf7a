//! Speed contours: coloured cells with a colour bar.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::line::title_band;
use crate::output::{self, msg, DrawResult};
use crate::theme::{
    self, bounded, extent, padded, speed_colour, text, tick_label, valid_range, MISSING,
};
use crate::Heatmap;

/// Width of the colour bar area at the right.
pub(crate) const BAR_AREA: u32 = 170;
/// Margin above the plots, shared by the cells and the colour bar so they line up.
const TOP: u32 = 16;

/// A validated heat map with its cell edges.
#[derive(Debug)]
pub(crate) struct Figure<'a> {
    h: &'a Heatmap,
    x_edges: Vec<f64>,
    y_edges: Vec<f64>,
    z_range: (f64, f64),
}

impl<'a> Figure<'a> {
    /// Checks the shape of `h` and computes the cell edges and the colour range.
    pub fn new(h: &'a Heatmap) -> Result<Self, String> {
        check_axis("x", &h.x)?;
        check_axis("y", &h.y)?;
        if h.z.len() != h.x.len() {
            return Err(format!(
                "z has {} rows but x has {} values (z[i][j] is the cell at x[i], y[j])",
                h.z.len(),
                h.x.len()
            ));
        }
        if let Some((i, row)) = h.z.iter().enumerate().find(|(_, r)| r.len() != h.y.len()) {
            return Err(format!(
                "z[{i}] has {} values but y has {} (z[i][j] is the cell at x[i], y[j])",
                row.len(),
                h.y.len()
            ));
        }
        let z_range = valid_range(h.z_range)
            .unwrap_or_else(|| padded(extent(h.z.iter().flatten().copied()), 0.0));
        Ok(Figure {
            h,
            x_edges: edges(&h.x),
            y_edges: edges(&h.y),
            z_range,
        })
    }

    /// The map drawn.
    pub fn map(&self) -> &Heatmap {
        self.h
    }

    /// The colour scale's range.
    pub fn z_range(&self) -> (f64, f64) {
        self.z_range
    }

    /// Fill colour of a value.
    fn colour(&self, z: f64) -> RGBColor {
        if z.is_finite() {
            let (lo, hi) = self.z_range;
            speed_colour((z - lo) / (hi - lo))
        } else {
            MISSING
        }
    }
}

/// Coordinates must be finite and strictly increasing.
fn check_axis(name: &str, v: &[f64]) -> Result<(), String> {
    if let Some(i) = v.iter().position(|c| !c.is_finite()) {
        return Err(format!("{name}[{i}] is not finite"));
    }
    if let Some(i) = v.windows(2).position(|w| w[1] <= w[0]) {
        return Err(format!(
            "{name} is not strictly increasing at index {}",
            i + 1
        ));
    }
    Ok(())
}

/// Cell edges around centres `c`: halfway between neighbours, half a spacing beyond the ends
/// (a single centre gets a cell of width 1).
fn edges(c: &[f64]) -> Vec<f64> {
    let n = c.len();
    match n {
        0 => vec![],
        1 => vec![c[0] - 0.5, c[0] + 0.5],
        _ => {
            let mut e = Vec::with_capacity(n + 1);
            e.push(c[0] - (c[1] - c[0]) / 2.0);
            e.extend(c.windows(2).map(|w| (w[0] + w[1]) / 2.0));
            e.push(c[n - 1] + (c[n - 1] - c[n - 2]) / 2.0);
            e
        }
    }
}

/// Range spanned by `edges`, or `0..1` without cells.
fn span(edges: &[f64]) -> (f64, f64) {
    match (edges.first(), edges.last()) {
        (Some(&a), Some(&b)) => bounded((a, b)),
        _ => (0.0, 1.0),
    }
}

impl output::Figure for Figure<'_> {
    fn size(&self) -> (u32, u32) {
        (1100, 700)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        let body = title_band(root, &self.h.title, 56)?;
        let (w, _) = body.dim_in_pixel();
        let (cells_area, bar_area) = body.split_horizontally(w.saturating_sub(BAR_AREA));
        self.cells(&cells_area, &theme::FULL, false)?;
        let missing = self.h.z.iter().flatten().any(|z| !z.is_finite());
        colour_bar(&bar_area, self.z_range, &self.h.z_label, missing)
    }
}

impl Figure<'_> {
    /// The axes and the coloured cells in `area`; with `caption`, the heat map's title above
    /// them (panels of a grid).
    pub(crate) fn cells<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        sz: &theme::Sizes,
        caption: bool,
    ) -> DrawResult {
        let (x0, x1) = span(&self.x_edges);
        let (y0, y1) = span(&self.y_edges);
        let mut builder = ChartBuilder::on(area);
        builder
            .margin(12)
            .margin_top(TOP)
            .x_label_area_size(sz.x_area)
            .y_label_area_size(sz.y_area);
        if caption && !self.h.title.is_empty() {
            builder.caption(&self.h.title, theme::bold(sz.title));
        }
        let mut ctx = builder.build_cartesian_2d(x0..x1, y0..y1).map_err(msg)?;
        let (x_tick, y_tick) = (tick_label(x0, x1), tick_label(y0, y1));
        ctx.configure_mesh()
            .disable_mesh()
            .x_label_formatter(&x_tick)
            .y_label_formatter(&y_tick)
            .x_desc(self.h.x_label.as_str())
            .y_desc(self.h.y_label.as_str())
            .axis_desc_style(text(sz.axis))
            .label_style(text(sz.tick))
            .x_labels(8)
            .y_labels(8)
            .draw()
            .map_err(msg)?;

        // One rectangle per run of equally coloured cells along y (fewer SVG elements).
        let mut rects = vec![];
        for (i, row) in self.h.z.iter().enumerate() {
            let (xa, xb) = (self.x_edges[i], self.x_edges[i + 1]);
            let mut j = 0;
            while j < row.len() {
                let c = self.colour(row[j]);
                let mut k = j + 1;
                while k < row.len() && self.colour(row[k]) == c {
                    k += 1;
                }
                let corners = [(xa, self.y_edges[j]), (xb, self.y_edges[k])];
                rects.push(Rectangle::new(corners, c.filled()));
                j = k;
            }
        }
        ctx.draw_series(rects).map_err(msg)?;
        Ok(())
    }
}

/// Heat maps side by side in a grid under a common title, sharing the colour scale of the
/// first (its `z_range`, or the extent of all finite data, and its `z_label`).
pub(crate) struct Grid<'a> {
    figures: Vec<Figure<'a>>,
    cols: usize,
    rows: usize,
    title: &'a str,
    z_range: (f64, f64),
    z_label: &'a str,
}

impl<'a> Grid<'a> {
    /// Checks every map (an error names the panel); `cols` is clamped to 1..=maps.
    pub fn new(maps: &'a [Heatmap], cols: usize, title: &'a str) -> Result<Self, String> {
        let z_range = maps
            .first()
            .and_then(|h| valid_range(h.z_range))
            .unwrap_or_else(|| {
                padded(
                    extent(maps.iter().flat_map(|h| h.z.iter().flatten().copied())),
                    0.0,
                )
            });
        let mut figures = Vec::with_capacity(maps.len());
        for (i, h) in maps.iter().enumerate() {
            let mut f = Figure::new(h).map_err(|e| format!("panel {}: {e}", i + 1))?;
            f.z_range = z_range;
            figures.push(f);
        }
        let cols = cols.clamp(1, maps.len().max(1));
        let rows = maps.len().div_ceil(cols).max(1);
        Ok(Grid {
            figures,
            cols,
            rows,
            title,
            z_range,
            z_label: maps.first().map_or("", |h| h.z_label.as_str()),
        })
    }
}

impl output::Figure for Grid<'_> {
    fn size(&self) -> (u32, u32) {
        let w = 560 * self.cols as u32 + BAR_AREA;
        let h = (440 * self.rows as u32 + 56).max(560);
        (w.max(1000), h)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        let body = title_band(root, self.title, 56)?;
        let (w, _) = body.dim_in_pixel();
        let (cells_area, bar_area) = body.split_horizontally(w.saturating_sub(BAR_AREA));
        let areas = cells_area.split_evenly((self.rows, self.cols));
        for (f, area) in self.figures.iter().zip(&areas) {
            f.cells(area, &theme::PANEL, true)?;
        }
        let missing = self
            .figures
            .iter()
            .any(|f| f.h.z.iter().flatten().any(|z| !z.is_finite()));
        colour_bar(&bar_area, self.z_range, self.z_label, missing)
    }
}

/// The colour scale for `(lo, hi)` in `area`, labelled with `label`; a "no data" key if
/// `missing`.
pub(crate) fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    (lo, hi): (f64, f64),
    label: &str,
    missing: bool,
) -> DrawResult {
    let sz = &theme::FULL;
    let mut ctx = colour_bar_frame(area, (lo, hi), label, 8)?;
    const STEPS: usize = 128;
    let step = (hi - lo) / STEPS as f64;
    ctx.draw_series((0..STEPS).map(|k| {
        let a = lo + step * k as f64;
        let c = speed_colour((k as f64 + 0.5) / STEPS as f64);
        Rectangle::new([(0.0, a), (1.0, a + step)], c.filled())
    }))
    .map_err(msg)?;
    ctx.draw_series([Rectangle::new(
        [(0.0, lo), (1.0, hi)],
        BLACK.stroke_width(1),
    )])
    .map_err(msg)?;

    if missing {
        let (_, h) = area.dim_in_pixel();
        let key = EmptyElement::at((10, h as i32 - 30))
            + Rectangle::new([(0, -9), (18, 9)], MISSING.filled())
            + Rectangle::new([(0, -9), (18, 9)], BLACK.stroke_width(1))
            + Text::new(
                "no data",
                (26, 0),
                text(sz.tick).pos(Pos::new(HPos::Left, VPos::Center)),
            );
        area.draw(&key).map_err(msg)?;
    }
    Ok(())
}

/// The frame of a vertical colour scale over `(lo, hi)` in `area`: a unit-wide chart with the
/// values labelled on the right (`y_labels` ticks) and `label` as the axis description. The
/// caller fills it with the scale's blocks.
pub(crate) fn colour_bar_frame<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    (lo, hi): (f64, f64),
    label: &str,
    y_labels: usize,
) -> Result<
    ChartContext<
        'a,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    String,
> {
    let sz = &theme::FULL;
    let mut ctx = ChartBuilder::on(area)
        .margin_top(TOP)
        .margin_bottom(12)
        .margin_left(8)
        .margin_right(8)
        .x_label_area_size(sz.x_area)
        .right_y_label_area_size(100)
        .build_cartesian_2d(0.0..1.0, lo..hi)
        .map_err(msg)?;
    let tick = tick_label(lo, hi);
    ctx.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_label_formatter(&tick)
        .set_tick_mark_size(LabelAreaPosition::Right, 8)
        .y_desc(label)
        .axis_desc_style(text(sz.axis))
        .label_style(text(sz.tick))
        .y_labels(y_labels)
        .draw()
        .map_err(msg)?;
    Ok(ctx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edges_surround_centres() {
        assert_eq!(edges(&[]), Vec::<f64>::new());
        assert_eq!(edges(&[3.0]), vec![2.5, 3.5]);
        assert_eq!(edges(&[0.0, 1.0]), vec![-0.5, 0.5, 1.5]);
        assert_eq!(edges(&[0.0, 2.0, 3.0]), vec![-1.0, 1.0, 2.5, 3.5]);
    }

    #[test]
    fn shape_and_axes_are_checked() {
        let mut h = Heatmap {
            x: vec![0.0, 1.0],
            y: vec![0.0, 1.0, 2.0],
            z: vec![vec![1.0; 3]; 2],
            ..Heatmap::default()
        };
        assert!(Figure::new(&h).is_ok());
        h.z[1].pop();
        assert!(Figure::new(&h).unwrap_err().contains("z[1]"));
        h.z = vec![vec![1.0; 3]; 3];
        assert!(Figure::new(&h).unwrap_err().contains("rows"));
        h.z = vec![vec![1.0; 3]; 2];
        h.x = vec![1.0, 0.0];
        assert!(Figure::new(&h).unwrap_err().contains("increasing"));
        h.x = vec![0.0, f64::NAN];
        assert!(Figure::new(&h).unwrap_err().contains("finite"));
    }

    #[test]
    fn colour_range_falls_back_to_the_data() {
        let h = Heatmap {
            x: vec![0.0],
            y: vec![0.0, 1.0],
            z: vec![vec![20.0, f64::NAN]],
            z_range: (f64::NAN, 0.0),
            ..Heatmap::default()
        };
        let f = Figure::new(&h).unwrap();
        assert!(f.z_range.0 < 20.0 && f.z_range.1 > 20.0);
        assert_eq!(f.colour(f64::NAN), MISSING);
    }
}
