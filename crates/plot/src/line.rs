//! Line charts, alone or as panels of a grid.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::geom::{
    clip_polygon, clip_polyline, finite_runs, legend_corner, legend_headroom, legend_size, Rect, P,
};
use crate::output::{msg, DrawResult, Figure};
use crate::theme::{self, bold, colour, extent, padded, text, tick_label, valid_range, Sizes};
use crate::{Chart, Series, Style};

/// One chart filling the figure.
pub(crate) struct Single<'a>(pub &'a Chart);

impl Figure for Single<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 700)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        draw_chart(root, self.0, &theme::FULL)
    }
}

/// Charts in a grid under a common title.
pub(crate) struct Grid<'a> {
    charts: &'a [Chart],
    cols: usize,
    rows: usize,
    title: &'a str,
}

impl<'a> Grid<'a> {
    /// `cols` is taken as at least 1 and at most the number of charts.
    pub fn new(charts: &'a [Chart], cols: usize, title: &'a str) -> Self {
        let cols = cols.clamp(1, charts.len().max(1));
        let rows = charts.len().div_ceil(cols).max(1);
        Grid {
            charts,
            cols,
            rows,
            title,
        }
    }
}

/// Height of the common title band of a grid.
const GRID_TITLE: u32 = 56;

impl Figure for Grid<'_> {
    fn size(&self) -> (u32, u32) {
        let w = (540 * self.cols as u32).max(1000);
        let h = (430 * self.rows as u32 + GRID_TITLE).max(700);
        (w, h)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        let body = title_band(root, self.title, GRID_TITLE)?;
        let cells = body.split_evenly((self.rows, self.cols));
        for (chart, cell) in self.charts.iter().zip(&cells) {
            draw_chart(cell, chart, &theme::PANEL)?;
        }
        Ok(())
    }
}

/// Draws `title` centred in a band of `height` pixels at the top of `root` and returns the
/// area below; an empty title takes no room.
pub(crate) fn title_band<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    height: u32,
) -> Result<DrawingArea<DB, Shift>, String> {
    if title.is_empty() {
        return Ok(root.clone());
    }
    let (head, body) = root.split_vertically(height);
    let style = bold(theme::FULL.title).pos(Pos::new(HPos::Center, VPos::Center));
    let (w, h) = head.dim_in_pixel();
    head.draw_text(title, &style, (w as i32 / 2, h as i32 / 2))
        .map_err(msg)?;
    Ok(body)
}

/// A series reduced to what is drawn: finite runs of points and band outlines.
struct Prepared {
    /// Runs of finite `(x, y)` points.
    runs: Vec<Vec<P>>,
    /// Runs of finite `(x, lower, upper)` triples.
    bands: Vec<Vec<(f64, f64, f64)>>,
}

impl Prepared {
    fn new(s: &Series) -> Self {
        let runs = finite_runs(s.x.iter().copied().zip(s.y.iter().copied()));
        let mut bands = vec![];
        if let Some((lo, hi)) = &s.band {
            let mut run = vec![];
            for ((&x, &l), &h) in s.x.iter().zip(lo).zip(hi) {
                if x.is_finite() && l.is_finite() && h.is_finite() {
                    run.push((x, l, h));
                } else if !run.is_empty() {
                    bands.push(std::mem::take(&mut run));
                }
            }
            if !run.is_empty() {
                bands.push(run);
            }
        }
        Prepared { runs, bands }
    }

    fn xs(&self) -> impl Iterator<Item = f64> + '_ {
        let line = self.runs.iter().flatten().map(|p| p.0);
        line.chain(self.bands.iter().flatten().map(|b| b.0))
    }

    fn ys(&self) -> impl Iterator<Item = f64> + '_ {
        let line = self.runs.iter().flatten().map(|p| p.1);
        line.chain(self.bands.iter().flatten().flat_map(|b| [b.1, b.2]))
    }
}

/// Draws `chart` into `area` with text sizes `sz`.
pub(crate) fn draw_chart<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &Chart,
    sz: &Sizes,
) -> DrawResult {
    let prepared: Vec<Prepared> = chart.series.iter().map(Prepared::new).collect();
    // 4 % on each side of x: a marker at the first or last x is drawn whole.
    let (x0, x1) = padded(extent(prepared.iter().flat_map(Prepared::xs)), 0.04);
    let (y0, y1) = chart
        .y_range
        .and_then(valid_range)
        .unwrap_or_else(|| padded(extent(prepared.iter().flat_map(Prepared::ys)), 0.06));
    let names: Vec<&str> = chart
        .series
        .iter()
        .map(|s| s.name.as_str())
        .filter(|n| !n.is_empty())
        .collect();
    // A legend never covers data: where no corner is free, the y axis is raised to make one.
    let (y0, y1) = if names.is_empty() {
        (y0, y1)
    } else {
        let data: Vec<Vec<P>> = prepared
            .iter()
            .flat_map(|p| {
                let upper = p
                    .bands
                    .iter()
                    .map(|b| b.iter().map(|&(x, _, h)| (x, h)).collect());
                let lower = p
                    .bands
                    .iter()
                    .map(|b| b.iter().map(|&(x, l, _)| (x, l)).collect());
                p.runs.iter().cloned().chain(upper).chain(lower)
            })
            .collect();
        let (aw, ah) = area.dim_in_pixel();
        let title = if chart.title.is_empty() {
            0
        } else {
            sz.title + 12
        };
        let plot_px = (
            aw.saturating_sub(sz.y_area + 40),
            ah.saturating_sub(sz.x_area + 24 + title),
        );
        let size = legend_size(&names, sz.legend as f64, plot_px);
        legend_headroom(&data, &Rect { x0, x1, y0, y1 }, size)
    };
    let rect = Rect { x0, x1, y0, y1 };

    let mut builder = ChartBuilder::on(area);
    builder
        .margin(12)
        .margin_right(28)
        .x_label_area_size(sz.x_area)
        .y_label_area_size(sz.y_area);
    if !chart.title.is_empty() {
        builder.caption(&chart.title, bold(sz.title));
    }
    let mut ctx = builder.build_cartesian_2d(x0..x1, y0..y1).map_err(msg)?;
    let (x_tick, y_tick) = (tick_label(x0, x1), tick_label(y0, y1));
    ctx.configure_mesh()
        .x_label_formatter(&x_tick)
        .y_label_formatter(&y_tick)
        .x_desc(chart.x_label.as_str())
        .y_desc(chart.y_label.as_str())
        .axis_desc_style(text(sz.axis))
        .label_style(text(sz.tick))
        .x_labels(8)
        .y_labels(8)
        .bold_line_style(theme::GRID)
        .light_line_style(TRANSPARENT)
        .draw()
        .map_err(msg)?;

    // Everything drawn, for placing the legend where it hides the least.
    let mut drawn: Vec<Vec<P>> = vec![];

    for (i, p) in prepared.iter().enumerate() {
        let fill = colour(i).mix(0.22);
        for run in &p.bands {
            if let [(x, l, h)] = run[..] {
                // A lone interval: a translucent vertical bar.
                if let Some((a, b)) = crate::geom::clip_segment((x, l), (x, h), &rect) {
                    let style = fill.stroke_width(sz.marker * 2);
                    ctx.draw_series([PathElement::new(vec![a, b], style)])
                        .map_err(msg)?;
                    drawn.push(vec![a, b]);
                }
                continue;
            }
            let upper = run.iter().map(|&(x, _, h)| (x, h));
            let lower = run.iter().rev().map(|&(x, l, _)| (x, l));
            let outline: Vec<P> = upper.chain(lower).collect();
            let poly = clip_polygon(&outline, &rect);
            if poly.len() >= 3 {
                drawn.push(poly.clone());
                ctx.draw_series([Polygon::new(poly, fill.filled())])
                    .map_err(msg)?;
            }
        }
    }

    // Lines before markers, so paper values stay visible on top.
    let order = (0..chart.series.len())
        .filter(|&i| chart.series[i].style != Style::Markers)
        .chain((0..chart.series.len()).filter(|&i| chart.series[i].style == Style::Markers));
    for i in order {
        let (series, p) = (&chart.series[i], &prepared[i]);
        let c = colour(i);
        let line = c.stroke_width(sz.line);
        let anno = match series.style {
            Style::Line | Style::Dashed => {
                let pieces: Vec<Vec<P>> = p
                    .runs
                    .iter()
                    .flat_map(|run| clip_polyline(run, &rect))
                    .collect();
                drawn.extend(pieces.iter().cloned());
                // An isolated point (between gaps) would be invisible as a line: a dot.
                let dots = pieces
                    .iter()
                    .filter(|pc| pc.len() == 1)
                    .map(|pc| Circle::new(pc[0], sz.line + 1, c.filled()));
                ctx.draw_series(dots).map_err(msg)?;
                if series.style == Style::Line {
                    let elems = pieces.into_iter().map(|pc| PathElement::new(pc, line));
                    ctx.draw_series(elems).map_err(msg)?
                } else {
                    let dash = (sz.line * 4, sz.line * 3);
                    let elems = pieces
                        .into_iter()
                        .map(|pc| DashedPathElement::new(pc, dash.0, dash.1, line));
                    ctx.draw_series(elems).map_err(msg)?
                }
            }
            Style::Markers => {
                let pts: Vec<P> = p
                    .runs
                    .iter()
                    .flatten()
                    .copied()
                    .filter(|&q| rect.contains(q))
                    .collect();
                drawn.extend(pts.iter().map(|&q| vec![q]));
                let r = sz.marker;
                let elems = pts.into_iter().map(|q| {
                    EmptyElement::at(q)
                        + Circle::new((0, 0), r, c.filled())
                        + Circle::new((0, 0), r, BLACK.stroke_width(1))
                });
                ctx.draw_series(elems).map_err(msg)?
            }
        };
        if !series.name.is_empty() {
            let has_band = !p.bands.is_empty();
            let (style, r) = (series.style, sz.marker as i32);
            // Legend sample: a line (solid or dashed) or a marker, over a translucent block
            // if the series has a band. One element type for all styles; unused parts are
            // transparent.
            let band = if has_band {
                c.mix(0.22).filled()
            } else {
                TRANSPARENT.filled()
            };
            let none = ShapeStyle::from(TRANSPARENT);
            let (first, second, dot, ring) = match style {
                Style::Line => (c.stroke_width(sz.line), c.stroke_width(sz.line), none, none),
                Style::Dashed => (c.stroke_width(sz.line), none, none, none),
                Style::Markers => (none, none, c.filled(), BLACK.stroke_width(1)),
            };
            anno.label(series.name.as_str()).legend(move |at| {
                EmptyElement::at(at)
                    + Rectangle::new([(0, -8), (26, 8)], band)
                    + PathElement::new(vec![(0, 0), (10, 0)], first)
                    + PathElement::new(vec![(10, 0), (16, 0)], second)
                    + PathElement::new(vec![(16, 0), (26, 0)], first)
                    + Circle::new((13, 0), r, dot)
                    + Circle::new((13, 0), r, ring)
            });
        }
    }

    if !names.is_empty() {
        let (pw, ph) = ctx.plotting_area().dim_in_pixel();
        let (w, h) = legend_size(&names, sz.legend as f64, (pw, ph));
        ctx.configure_series_labels()
            .position(legend_corner(&drawn, &rect, (w, h)))
            .margin(10)
            .label_font(text(sz.legend))
            .background_style(WHITE.mix(0.88))
            .border_style(RGBColor(160, 160, 160))
            .draw()
            .map_err(msg)?;
    }
    Ok(())
}
