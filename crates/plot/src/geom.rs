//! Plane geometry in data coordinates: splitting at missing values, clipping to the plotting
//! area, and choosing the emptiest corner for the legend.

use plotters::chart::SeriesLabelPosition;

/// A point `(x, y)`.
pub(crate) type P = (f64, f64);

/// An axis-aligned rectangle (the plotting area in data coordinates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rect {
    pub x0: f64,
    pub x1: f64,
    pub y0: f64,
    pub y1: f64,
}

impl Rect {
    /// Whether `p` lies inside or on the border.
    pub fn contains(&self, p: P) -> bool {
        p.0 >= self.x0 && p.0 <= self.x1 && p.1 >= self.y0 && p.1 <= self.y1
    }

    /// Maps `p` to `[0, 1]²` (x right, y up).
    fn normalise(&self, p: P) -> P {
        (
            (p.0 - self.x0) / (self.x1 - self.x0),
            (p.1 - self.y0) / (self.y1 - self.y0),
        )
    }
}

/// Splits a sequence of points into the runs between non-finite points.
pub(crate) fn finite_runs<I: IntoIterator<Item = P>>(points: I) -> Vec<Vec<P>> {
    let mut runs = vec![];
    let mut run = vec![];
    for p in points {
        if p.0.is_finite() && p.1.is_finite() {
            run.push(p);
        } else if !run.is_empty() {
            runs.push(std::mem::take(&mut run));
        }
    }
    if !run.is_empty() {
        runs.push(run);
    }
    runs
}

/// The part of segment `a`–`b` inside `r` (Liang–Barsky). End points that need no clipping
/// are returned unchanged, so consecutive clipped segments still join exactly.
pub(crate) fn clip_segment(a: P, b: P, r: &Rect) -> Option<(P, P)> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - r.x0),
        (dx, r.x1 - a.0),
        (-dy, a.1 - r.y0),
        (dy, r.y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| (a.0 + t * dx, a.1 + t * dy);
    let start = if t0 == 0.0 { a } else { at(t0) };
    let end = if t1 == 1.0 { b } else { at(t1) };
    Some((start, end))
}

/// The visible pieces of a polyline inside `r`. A one-point line yields that point if inside.
pub(crate) fn clip_polyline(points: &[P], r: &Rect) -> Vec<Vec<P>> {
    if let [p] = points {
        return if r.contains(*p) {
            vec![vec![*p]]
        } else {
            vec![]
        };
    }
    let mut pieces: Vec<Vec<P>> = vec![];
    let mut current: Vec<P> = vec![];
    for pair in points.windows(2) {
        match clip_segment(pair[0], pair[1], r) {
            Some((s, e)) => {
                if current.last() != Some(&s) && !current.is_empty() {
                    pieces.push(std::mem::take(&mut current));
                }
                if current.is_empty() {
                    current.push(s);
                }
                current.push(e);
            }
            None => {
                if !current.is_empty() {
                    pieces.push(std::mem::take(&mut current));
                }
            }
        }
    }
    if !current.is_empty() {
        pieces.push(current);
    }
    pieces
}

/// The part of polygon `poly` inside `r` (Sutherland–Hodgman); empty if none.
pub(crate) fn clip_polygon(poly: &[P], r: &Rect) -> Vec<P> {
    // Each edge: is a point inside, and where does a segment cross the edge line.
    type Inside = fn(P, &Rect) -> bool;
    type Cross = fn(P, P, &Rect) -> P;
    fn at_x(a: P, b: P, x: f64) -> P {
        (x, a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0))
    }
    fn at_y(a: P, b: P, y: f64) -> P {
        (a.0 + (b.0 - a.0) * (y - a.1) / (b.1 - a.1), y)
    }
    let edges: [(Inside, Cross); 4] = [
        (|p, r| p.0 >= r.x0, |a, b, r| at_x(a, b, r.x0)),
        (|p, r| p.0 <= r.x1, |a, b, r| at_x(a, b, r.x1)),
        (|p, r| p.1 >= r.y0, |a, b, r| at_y(a, b, r.y0)),
        (|p, r| p.1 <= r.y1, |a, b, r| at_y(a, b, r.y1)),
    ];
    let mut out = poly.to_vec();
    for (inside, cross) in edges {
        if out.is_empty() {
            break;
        }
        let input = std::mem::take(&mut out);
        let mut prev = input[input.len() - 1];
        for &cur in &input {
            match (inside(cur, r), inside(prev, r)) {
                (true, true) => out.push(cur),
                (true, false) => {
                    out.push(cross(prev, cur, r));
                    out.push(cur);
                }
                (false, true) => out.push(cross(prev, cur, r)),
                (false, false) => {}
            }
            prev = cur;
        }
    }
    out
}

/// The legend box as fractions of the plotting area `(width, height)` in pixels: about 0.6 em
/// per character of the longest name plus the colour key, one line per name.
pub(crate) fn legend_size(names: &[&str], font_px: f64, area_px: (u32, u32)) -> (f64, f64) {
    let longest = names.iter().map(|n| n.chars().count()).max().unwrap_or(0);
    let w = (longest as f64 * 0.6 * font_px + 60.0) / area_px.0.max(1) as f64;
    let h = (names.len() as f64 * (font_px + 10.0) + 20.0) / area_px.1.max(1) as f64;
    (w, h)
}

/// The corner of `r` where a legend of `size` (fractions of the plot's width and height)
/// covers the fewest samples of `lines`. Ties prefer upper right, upper left, lower right,
/// lower left.
pub(crate) fn legend_corner(lines: &[Vec<P>], r: &Rect, size: (f64, f64)) -> SeriesLabelPosition {
    best_corner(lines, r, size).0
}

/// The y range of `r`, raised at the top when a legend of `size` would cover samples of
/// `lines` in every corner: the data then fill the lower 1 − h − 3 % of the height, and the
/// upper corners are free for the legend.
pub(crate) fn legend_headroom(lines: &[Vec<P>], r: &Rect, size: (f64, f64)) -> (f64, f64) {
    if best_corner(lines, r, size).1 == 0 {
        return (r.y0, r.y1);
    }
    let h = size.1.clamp(0.05, 0.6);
    (r.y0, r.y0 + (r.y1 - r.y0) / (1.0 - h - 0.03))
}

/// [`legend_corner`] and the number of samples the legend covers there.
fn best_corner(lines: &[Vec<P>], r: &Rect, size: (f64, f64)) -> (SeriesLabelPosition, usize) {
    let (w, h) = (size.0.clamp(0.05, 1.0), size.1.clamp(0.05, 1.0));
    let corners = [
        (SeriesLabelPosition::UpperRight, 1.0 - w, 1.0, 1.0 - h, 1.0),
        (SeriesLabelPosition::UpperLeft, 0.0, w, 1.0 - h, 1.0),
        (SeriesLabelPosition::LowerRight, 1.0 - w, 1.0, 0.0, h),
        (SeriesLabelPosition::LowerLeft, 0.0, w, 0.0, h),
    ];
    let mut hits = [0usize; 4];
    let mut count = |p: P| {
        for (k, c) in corners.iter().enumerate() {
            if p.0 >= c.1 && p.0 <= c.2 && p.1 >= c.3 && p.1 <= c.4 {
                hits[k] += 1;
            }
        }
    };
    for line in lines {
        let pts: Vec<P> = line.iter().map(|&p| r.normalise(p)).collect();
        if let [p] = pts[..] {
            count(p);
        }
        for pair in pts.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
            let n = ((len / 0.01).ceil() as usize).clamp(1, 200);
            for k in 0..=n {
                let t = k as f64 / n as f64;
                count((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
            }
        }
    }
    let best = (0..4).min_by_key(|&k| (hits[k], k)).unwrap_or(0);
    (corners[best].0.clone(), hits[best])
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: Rect = Rect {
        x0: 0.0,
        x1: 10.0,
        y0: 0.0,
        y1: 10.0,
    };

    #[test]
    fn runs_break_at_nan() {
        let runs = finite_runs([(0.0, 1.0), (1.0, f64::NAN), (2.0, 2.0), (3.0, 3.0)]);
        assert_eq!(runs, vec![vec![(0.0, 1.0)], vec![(2.0, 2.0), (3.0, 3.0)]]);
        assert!(finite_runs([(f64::NAN, 0.0)]).is_empty());
    }

    #[test]
    fn segments_are_clipped() {
        assert_eq!(
            clip_segment((-5.0, 5.0), (15.0, 5.0), &R),
            Some(((0.0, 5.0), (10.0, 5.0)))
        );
        assert_eq!(clip_segment((-5.0, 20.0), (15.0, 20.0), &R), None);
        assert_eq!(
            clip_segment((1.0, 1.0), (2.0, 2.0), &R),
            Some(((1.0, 1.0), (2.0, 2.0)))
        );
    }

    #[test]
    fn polyline_leaving_and_returning_splits() {
        let line = [(0.0, 5.0), (5.0, 15.0), (10.0, 5.0)];
        let pieces = clip_polyline(&line, &R);
        assert_eq!(pieces.len(), 2);
        assert_eq!(pieces[0], vec![(0.0, 5.0), (2.5, 10.0)]);
        assert_eq!(pieces[1], vec![(7.5, 10.0), (10.0, 5.0)]);
        let inside = [(1.0, 1.0), (2.0, 2.0), (3.0, 1.0)];
        assert_eq!(clip_polyline(&inside, &R), vec![inside.to_vec()]);
    }

    #[test]
    fn polygon_is_cut_to_the_rectangle() {
        let square = [(-5.0, -5.0), (5.0, -5.0), (5.0, 5.0), (-5.0, 5.0)];
        let clipped = clip_polygon(&square, &R);
        let area: f64 = (0..clipped.len())
            .map(|i| {
                let (a, b) = (clipped[i], clipped[(i + 1) % clipped.len()]);
                a.0 * b.1 - b.0 * a.1
            })
            .sum::<f64>()
            / 2.0;
        assert!((area.abs() - 25.0).abs() < 1e-9);
        assert!(clip_polygon(&[(20.0, 20.0), (30.0, 20.0), (30.0, 30.0)], &R).is_empty());
    }

    #[test]
    fn a_legend_with_no_free_corner_gets_room_at_the_top() {
        // A line through all four corners: no corner is free.
        let zigzag = vec![vec![(0.0, 0.0), (10.0, 10.0), (0.0, 10.0), (10.0, 0.0)]];
        let (y0, y1) = legend_headroom(&zigzag, &R, (0.3, 0.2));
        assert_eq!(y0, 0.0);
        assert!((y1 - 10.0 / 0.77).abs() < 1e-9, "{y1}");
        let raised = Rect { y1, ..R };
        assert_eq!(best_corner(&zigzag, &raised, (0.3, 0.2)).1, 0);
        // A free corner: the range stays.
        let rising = vec![vec![(0.0, 0.0), (10.0, 10.0)]];
        assert_eq!(legend_headroom(&rising, &R, (0.3, 0.2)), (0.0, 10.0));
    }

    #[test]
    fn legend_avoids_the_data() {
        // A rising line occupies the lower left and upper right corners.
        let rising = vec![vec![(0.0, 0.0), (10.0, 10.0)]];
        let pos = legend_corner(&rising, &R, (0.3, 0.2));
        assert!(matches!(pos, SeriesLabelPosition::UpperLeft));
        let falling = vec![vec![(0.0, 10.0), (10.0, 0.0)]];
        let pos = legend_corner(&falling, &R, (0.3, 0.2));
        assert!(matches!(pos, SeriesLabelPosition::UpperRight));
    }
}
