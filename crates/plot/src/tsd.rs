//! Time-space diagrams: one polyline per vehicle and stay in the lane, coloured by speed.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::line::title_band;
use crate::output::{self, msg, DrawResult};
use crate::theme::{self, bounded, extent, padded, speed_colour, text, tick_label};
use crate::{TimeSpace, TRACK_SPEED_BIN_KMH, TRACK_SPEED_RANGE_KMH};

/// Width of the colour bar area at the right.
const BAR_AREA: u32 = 170;
/// Margin above the plot, shared with the colour bar so they line up.
const TOP: u32 = 46;
/// Line widths of CAVs and humans (px).
const CAV_WIDTH: u32 = 2;
const HUMAN_WIDTH: u32 = 1;

/// One drawn polyline: points `(t, x)`, the speed bin, and whether it is a CAV's.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Piece {
    pub points: Vec<(f64, f64)>,
    pub bin: usize,
    pub cav: bool,
}

/// Number of speed bins of the fixed scale.
fn bins() -> usize {
    let (lo, hi) = TRACK_SPEED_RANGE_KMH;
    ((hi - lo) / TRACK_SPEED_BIN_KMH).round() as usize
}

/// The bin of a speed in km/h (clamped to the scale).
fn bin_of(v_kmh: f64) -> usize {
    let (lo, _) = TRACK_SPEED_RANGE_KMH;
    let b = ((v_kmh - lo) / TRACK_SPEED_BIN_KMH).floor();
    if b.is_nan() {
        0
    } else {
        (b.max(0.0) as usize).min(bins() - 1)
    }
}

/// Colour of bin `b`: the speed scale at the bin's centre.
fn bin_colour(b: usize) -> RGBColor {
    speed_colour((b as f64 + 0.5) / bins() as f64)
}

/// Splits the tracks into what is drawn. A vehicle's samples (in time order) form runs of
/// consecutive finite samples in `ts.lane`; a sample in another lane or with a non-finite
/// value ends a run. Within a run, each step between two samples takes the bin of their mean
/// speed, and consecutive steps of the same bin are merged into one piece.
pub(crate) fn pieces(ts: &TimeSpace) -> Vec<Piece> {
    let mut out = vec![];
    for track in &ts.tracks {
        let mut samples: Vec<_> = track.samples.iter().collect();
        samples.sort_by(|a, b| a.t_s.total_cmp(&b.t_s));
        let mut run: Vec<&crate::TrackSample> = vec![];
        let flush = |run: &mut Vec<&crate::TrackSample>, out: &mut Vec<Piece>| {
            push_run(run, track.cav, out);
            run.clear();
        };
        for s in samples {
            let ok =
                s.lane == ts.lane && s.t_s.is_finite() && s.x_m.is_finite() && s.v_mps.is_finite();
            if ok {
                run.push(s);
            } else {
                flush(&mut run, &mut out);
            }
        }
        flush(&mut run, &mut out);
    }
    out
}

/// The pieces of one run (a single sample is drawn as a piece of one point).
fn push_run(run: &[&crate::TrackSample], cav: bool, out: &mut Vec<Piece>) {
    match run {
        [] => {}
        [s] => out.push(Piece {
            points: vec![(s.t_s, s.x_m)],
            bin: bin_of(s.v_mps * 3.6),
            cav,
        }),
        _ => {
            let mut piece: Option<Piece> = None;
            for w in run.windows(2) {
                let bin = bin_of((w[0].v_mps + w[1].v_mps) / 2.0 * 3.6);
                match &mut piece {
                    Some(p) if p.bin == bin => p.points.push((w[1].t_s, w[1].x_m)),
                    _ => {
                        if let Some(p) = piece.take() {
                            out.push(p);
                        }
                        piece = Some(Piece {
                            points: vec![(w[0].t_s, w[0].x_m), (w[1].t_s, w[1].x_m)],
                            bin,
                            cav,
                        });
                    }
                }
            }
            out.extend(piece);
        }
    }
}

/// A time-space diagram ready to draw.
pub(crate) struct Figure<'a> {
    ts: &'a TimeSpace,
    pieces: Vec<Piece>,
}

impl<'a> Figure<'a> {
    pub fn new(ts: &'a TimeSpace) -> Self {
        Figure {
            ts,
            pieces: pieces(ts),
        }
    }
}

impl output::Figure for Figure<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, 750)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        let body = title_band(root, &self.ts.title, 56)?;
        let (w, _) = body.dim_in_pixel();
        let (plot_area, bar_area) = body.split_horizontally(w.saturating_sub(BAR_AREA));
        self.plot(&plot_area)?;
        colour_bar(&bar_area)
    }
}

impl Figure<'_> {
    fn plot<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult {
        let sz = &theme::FULL;
        let all = || self.pieces.iter().flat_map(|p| p.points.iter());
        let (t0, t1) = bounded(padded(extent(all().map(|p| p.0)), 0.0));
        let (x0, x1) = bounded(padded(extent(all().map(|p| p.1)), 0.02));
        let mut ctx = ChartBuilder::on(area)
            .margin(12)
            .margin_top(TOP)
            .x_label_area_size(sz.x_area)
            .y_label_area_size(sz.y_area)
            .build_cartesian_2d(t0..t1, x0..x1)
            .map_err(msg)?;
        let (t_tick, x_tick) = (tick_label(t0, t1), tick_label(x0, x1));
        ctx.configure_mesh()
            .light_line_style(theme::GRID)
            .bold_line_style(theme::GRID)
            .x_label_formatter(&t_tick)
            .y_label_formatter(&x_tick)
            .x_desc("Time (s)")
            .y_desc("Position (m)")
            .axis_desc_style(text(sz.axis))
            .label_style(text(sz.tick))
            .x_labels(10)
            .y_labels(10)
            .max_light_lines(0)
            .draw()
            .map_err(msg)?;

        // Humans first, CAVs (thicker) on top.
        for cav in [false, true] {
            let width = if cav { CAV_WIDTH } else { HUMAN_WIDTH };
            for p in self.pieces.iter().filter(|p| p.cav == cav) {
                let style = bin_colour(p.bin).stroke_width(width);
                if let [pt] = p.points[..] {
                    ctx.draw_series([Circle::new(pt, width, style.filled())])
                        .map_err(msg)?;
                } else {
                    ctx.draw_series([PathElement::new(p.points.clone(), style)])
                        .map_err(msg)?;
                }
            }
        }

        // Line-width key above the plot (in the top margin), so it covers no trajectory.
        let (px0, py0) = ctx.backend_coord(&(t0, x1));
        let key = |dx: i32, width: u32, label: &str| {
            EmptyElement::at((px0 + dx, py0 - 24))
                + PathElement::new(vec![(0, 0), (36, 0)], BLACK.stroke_width(width))
                + Text::new(
                    label.to_string(),
                    (46, 0),
                    text(sz.legend).pos(Pos::new(HPos::Left, VPos::Center)),
                )
        };
        area.draw(&key(4, CAV_WIDTH, "CAV (thick)")).map_err(msg)?;
        area.draw(&key(220, HUMAN_WIDTH, "human (thin)"))
            .map_err(msg)?;
        Ok(())
    }
}

/// The fixed speed scale, one block per bin.
fn colour_bar<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>) -> DrawResult {
    let (lo, hi) = TRACK_SPEED_RANGE_KMH;
    let mut ctx = crate::heat::colour_bar_frame(area, (lo, hi), "Speed (km/h)", 7)?;
    ctx.draw_series((0..bins()).map(|b| {
        let a = lo + TRACK_SPEED_BIN_KMH * b as f64;
        Rectangle::new(
            [(0.0, a), (1.0, a + TRACK_SPEED_BIN_KMH)],
            bin_colour(b).filled(),
        )
    }))
    .map_err(msg)?;
    ctx.draw_series([Rectangle::new(
        [(0.0, lo), (1.0, hi)],
        BLACK.stroke_width(1),
    )])
    .map_err(msg)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Track, TrackSample};

    fn s(t_s: f64, lane: u32, x_m: f64, v_mps: f64) -> TrackSample {
        TrackSample {
            t_s,
            lane,
            x_m,
            v_mps,
        }
    }

    #[test]
    fn bins_cover_the_scale_and_clamp() {
        assert_eq!(bins(), 24);
        assert_eq!(bin_of(0.0), 0);
        assert_eq!(bin_of(-3.0), 0);
        assert_eq!(bin_of(4.99), 0);
        assert_eq!(bin_of(5.0), 1);
        assert_eq!(bin_of(119.0), 23);
        assert_eq!(bin_of(500.0), 23);
        assert_eq!(bin_of(f64::NAN), 0);
    }

    #[test]
    fn a_lane_change_splits_a_track_and_speed_changes_split_pieces() {
        // 20 m/s = 72 km/h throughout, out of lane 1 at t = 3 and back at t = 5.
        let samples = (0..8)
            .map(|k| {
                let lane = if (3..5).contains(&k) { 2 } else { 1 };
                s(k as f64, lane, 20.0 * k as f64, 20.0)
            })
            .collect();
        let mut ts = TimeSpace {
            title: String::new(),
            lane: 1,
            tracks: vec![Track { cav: true, samples }],
        };
        let p = pieces(&ts);
        assert_eq!(p.len(), 2);
        assert_eq!(p[0].points, vec![(0.0, 0.0), (1.0, 20.0), (2.0, 40.0)]);
        assert_eq!(p[1].points.len(), 3);
        assert!(p.iter().all(|p| p.cav && p.bin == bin_of(72.0)));
        // Lane 2 holds one run of two samples.
        ts.lane = 2;
        assert_eq!(pieces(&ts).len(), 1);
        // Samples out of order are sorted; a speed change starts a new piece at the shared point.
        ts.lane = 1;
        ts.tracks[0].samples = vec![
            s(1.0, 1, 10.0, 10.0),
            s(0.0, 1, 0.0, 10.0),
            s(2.0, 1, 30.0, 30.0),
        ];
        let p = pieces(&ts);
        assert_eq!(p.len(), 2);
        assert_eq!(p[0].points, vec![(0.0, 0.0), (1.0, 10.0)]);
        assert_eq!(p[1].points, vec![(1.0, 10.0), (2.0, 30.0)]);
        // A NaN breaks the run like a lane change.
        ts.tracks[0].samples[0].x_m = f64::NAN;
        assert_eq!(pieces(&ts).len(), 2);
    }
}
