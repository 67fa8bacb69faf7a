//! Grouped bar charts with optional error bars.

use plotters::coord::combinators::BindKeyPoints;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::geom::{legend_corner, legend_size, Rect, P};
use crate::output::{self, msg, DrawResult};
use crate::theme::{self, bold, bounded, colour, extent, text, tick_label};
use crate::Bars;

/// Axis units per group: the x axis is integer (plotters formats integer axes with custom
/// tick positions), so positions within a group are in thousandths of a group.
const UNIT: f64 = 1000.0;

/// A position in groups as axis units.
fn u(v: f64) -> i32 {
    (v * UNIT).round() as i32
}

/// Share of a group's width covered by its bars.
const GROUP_WIDTH: f64 = 0.8;

/// One bar ready to draw.
struct Bar {
    series: usize,
    left: f64,
    right: f64,
    value: f64,
    /// Error half-length, if finite.
    error: Option<f64>,
}

/// A bar chart figure.
pub(crate) struct Figure<'a>(pub &'a Bars);

impl Figure<'_> {
    /// The bars with finite values, placed side by side within their groups.
    fn bars(&self) -> Vec<Bar> {
        let b = self.0;
        let n = b.series.len().max(1) as f64;
        let width = GROUP_WIDTH / n;
        let mut out = vec![];
        for (s, (_, values, errors)) in b.series.iter().enumerate() {
            for (g, &value) in values.iter().enumerate().take(b.groups.len()) {
                if !value.is_finite() {
                    continue;
                }
                let left = g as f64 - GROUP_WIDTH / 2.0 + s as f64 * width;
                let error = errors
                    .as_ref()
                    .and_then(|e| e.get(g))
                    .map(|e| e.abs())
                    .filter(|e| e.is_finite());
                out.push(Bar {
                    series: s,
                    left: left + width * 0.06,
                    right: left + width * 0.94,
                    value,
                    error,
                });
            }
        }
        out
    }
}

impl output::Figure for Figure<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 700)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        self.draw_in(root, &theme::FULL)
    }
}

/// Bar charts in a grid under a common title.
pub(crate) struct Grid<'a> {
    charts: &'a [Bars],
    cols: usize,
    rows: usize,
    title: &'a str,
}

impl<'a> Grid<'a> {
    /// `cols` is taken as at least 1 and at most the number of charts.
    pub fn new(charts: &'a [Bars], cols: usize, title: &'a str) -> Self {
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

impl output::Figure for Grid<'_> {
    fn size(&self) -> (u32, u32) {
        let w = (560 * self.cols as u32).max(1000);
        let h = (440 * self.rows as u32 + 56).max(560);
        (w, h)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        let body = crate::line::title_band(root, self.title, 56)?;
        let cells = body.split_evenly((self.rows, self.cols));
        for (chart, cell) in self.charts.iter().zip(&cells) {
            Figure(chart).draw_in(cell, &theme::PANEL)?;
        }
        Ok(())
    }
}

impl Figure<'_> {
    /// Draws the chart into `area` with text sizes `sz`.
    fn draw_in<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        sz: &theme::Sizes,
    ) -> DrawResult {
        let b = self.0;
        let bars = self.bars();

        // The value axis always shows zero, the bars' feet.
        let ends = bars.iter().flat_map(|r| {
            let e = r.error.unwrap_or(0.0);
            [r.value - e, r.value + e]
        });
        let include = b.y_include.iter().copied().filter(|v| v.is_finite());
        let (lo, hi) = extent(ends.chain(include).chain([0.0])).unwrap_or((0.0, 1.0));
        let (lo, hi) = if hi > lo { (lo, hi) } else { (0.0, 1.0) };
        let pad = (hi - lo) * 0.08;
        // Room above the bars for the legend, so it covers none of them.
        let legend_rows = b.series.iter().filter(|s| !s.0.is_empty()).count();
        let top = if legend_rows > 0 {
            (hi - lo) * (0.1 + 0.08 * legend_rows as f64)
        } else {
            pad
        };
        let y0 = if lo < 0.0 { lo - pad } else { 0.0 };
        let y1 = if hi > 0.0 { hi + top } else { 0.0 };
        let (y0, y1) = bounded((y0, y1));

        let n = b.groups.len();
        let (x0, x1) = (-0.5, n.max(1) as f64 - 0.5);
        let ticks: Vec<i32> = (0..n).map(|g| u(g as f64)).collect();

        let mut builder = ChartBuilder::on(root);
        builder
            .margin(12)
            .margin_right(28)
            .x_label_area_size(sz.x_area)
            .y_label_area_size(sz.y_area);
        if !b.title.is_empty() {
            builder.caption(&b.title, bold(sz.title));
        }
        let mut ctx = builder
            .build_cartesian_2d((u(x0)..u(x1)).with_key_points(ticks), y0..y1)
            .map_err(msg)?;
        let group_name = |v: &i32| {
            let g = v / UNIT as i32;
            if v % UNIT as i32 == 0 && g >= 0 {
                b.groups.get(g as usize).cloned().unwrap_or_default()
            } else {
                String::new()
            }
        };
        let y_tick = tick_label(y0, y1);
        ctx.configure_mesh()
            .disable_x_mesh()
            .x_label_formatter(&group_name)
            .y_label_formatter(&y_tick)
            .y_desc(b.y_label.as_str())
            .axis_desc_style(text(sz.axis))
            .label_style(text(sz.tick))
            .y_labels(8)
            .bold_line_style(theme::GRID)
            .light_line_style(TRANSPARENT)
            .draw()
            .map_err(msg)?;

        let mut drawn: Vec<Vec<P>> = vec![];
        for (s, (name, _, _)) in b.series.iter().enumerate() {
            let c = colour(s);
            let mine: Vec<&Bar> = bars.iter().filter(|r| r.series == s).collect();
            let boxes = mine.iter().flat_map(|r| {
                let corners = [(u(r.left), 0.0), (u(r.right), r.value)];
                [
                    Rectangle::new(corners, c.filled()),
                    Rectangle::new(corners, BLACK.stroke_width(1)),
                ]
            });
            let anno = ctx.draw_series(boxes).map_err(msg)?;
            if !name.is_empty() {
                anno.label(name.as_str()).legend(move |(x, y)| {
                    Rectangle::new([(x, y - 8), (x + 22, y + 8)], c.filled())
                });
            }
            for r in &mine {
                let mid = (r.left + r.right) / 2.0;
                drawn.push(vec![(mid, 0.0), (mid, r.value)]);
            }
        }

        // Error bars on top of all bars: a whisker with caps.
        let whiskers = bars.iter().filter_map(|r| {
            let e = r.error?;
            let mid = (r.left + r.right) / 2.0;
            let cap = (r.right - r.left) * 0.2;
            let (a, z) = (r.value - e, r.value + e);
            drawn.push(vec![(mid, a), (mid, z)]);
            let style = BLACK.stroke_width(2);
            let (m, l, h) = (u(mid), u(mid - cap), u(mid + cap));
            Some([
                PathElement::new(vec![(m, a), (m, z)], style),
                PathElement::new(vec![(l, a), (h, a)], style),
                PathElement::new(vec![(l, z), (h, z)], style),
            ])
        });
        let whiskers: Vec<_> = whiskers.flatten().collect();
        ctx.draw_series(whiskers).map_err(msg)?;

        let names: Vec<&str> = b
            .series
            .iter()
            .map(|s| s.0.as_str())
            .filter(|n| !n.is_empty())
            .collect();
        if !names.is_empty() {
            let (pw, ph) = ctx.plotting_area().dim_in_pixel();
            let (w, h) = legend_size(&names, sz.legend as f64, (pw, ph));
            let rect = Rect { x0, x1, y0, y1 };
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
}
