//! Shared look: palette, text sizes, axis ranges, the speed colour scale.

use plotters::style::{FontStyle, RGBColor, TextStyle};

/// Okabe–Ito colour-blind-safe palette, ordered for contrast on white (its yellow is left
/// out: too faint for lines).
pub(crate) const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(230, 159, 0),   // orange
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(0, 0, 0),       // black
];

/// The palette colour for series number `i` (cycling).
pub(crate) fn colour(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

/// Grey for missing heat-map cells.
pub(crate) const MISSING: RGBColor = RGBColor(170, 170, 170);

/// Grid line colour.
pub(crate) const GRID: RGBColor = RGBColor(225, 225, 225);

/// Text sizes in pixels.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sizes {
    pub title: u32,
    pub axis: u32,
    pub tick: u32,
    pub legend: u32,
    /// Line width.
    pub line: u32,
    /// Marker radius.
    pub marker: u32,
    /// Width reserved left of the plot for y tick labels and the y axis label.
    pub y_area: u32,
    /// Height reserved below the plot for x tick labels and the x axis label.
    pub x_area: u32,
}

/// Sizes for a figure with one chart.
pub(crate) const FULL: Sizes = Sizes {
    title: 28,
    axis: 21,
    tick: 17,
    legend: 17,
    line: 3,
    marker: 6,
    y_area: 90,
    x_area: 65,
};

/// Sizes for one panel of a grid.
pub(crate) const PANEL: Sizes = Sizes {
    title: 20,
    axis: 17,
    tick: 14,
    legend: 14,
    line: 2,
    marker: 5,
    y_area: 78,
    x_area: 55,
};

/// Regular text of `px` pixels.
pub(crate) fn text(px: u32) -> TextStyle<'static> {
    TextStyle::from(("sans-serif", px))
}

/// Bold text of `px` pixels.
pub(crate) fn bold(px: u32) -> TextStyle<'static> {
    TextStyle::from(("sans-serif", px, FontStyle::Bold))
}

/// Smallest and largest finite value, if any.
pub(crate) fn extent<I: IntoIterator<Item = f64>>(values: I) -> Option<(f64, f64)> {
    values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold(None, |acc, v| match acc {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
}

/// A drawable range from a data extent: widened by `frac` of its width on each side, a
/// single value is given some width around it, no data gives `0..1`.
pub(crate) fn padded(ext: Option<(f64, f64)>, frac: f64) -> (f64, f64) {
    let Some((lo, hi)) = ext else {
        return (0.0, 1.0);
    };
    let width = hi - lo;
    let scale = lo.abs().max(hi.abs());
    let (lo, hi, pad) = if width > scale * 1e-9 && width.is_finite() {
        (lo, hi, width * frac)
    } else {
        let half = if scale > 0.0 { scale * 0.1 } else { 1.0 };
        (lo, hi, half)
    };
    let (a, b) = (lo - pad, hi + pad);
    if a.is_finite() && b.is_finite() && a < b {
        bounded((a, b))
    } else {
        bounded((lo, hi))
    }
}

/// A range plotters can draw: finite, increasing, with a finite width (plotters does not
/// return for an axis of infinite width). Ends beyond ±`f64::MAX / 4` are pulled in; a range
/// that is still unusable becomes `0..1`.
pub(crate) fn bounded((lo, hi): (f64, f64)) -> (f64, f64) {
    const LIMIT: f64 = f64::MAX / 4.0;
    if lo.is_nan() || hi.is_nan() {
        return (0.0, 1.0);
    }
    let (a, b) = (lo.clamp(-LIMIT, LIMIT), hi.clamp(-LIMIT, LIMIT));
    if a < b {
        (a, b)
    } else {
        (0.0, 1.0)
    }
}

/// A user-given range, if it is finite and not empty (reversed pairs are swapped).
pub(crate) fn valid_range((a, b): (f64, f64)) -> Option<(f64, f64)> {
    if a.is_finite() && b.is_finite() && a != b {
        Some(bounded((a.min(b), a.max(b))))
    } else {
        None
    }
}

/// Tick label text for an axis spanning `lo..hi` with about 8 ticks: as many decimals as the
/// tick spacing needs, no trailing zeros (`2000`, `0.25`, `-1.5`); very large or very small
/// magnitudes in scientific notation (`1.5e7`).
pub(crate) fn tick_label(lo: f64, hi: f64) -> impl Fn(&f64) -> String {
    let step = (hi - lo).abs() / 8.0;
    let scale = lo.abs().max(hi.abs());
    let decimals = if step.is_finite() && step > 0.0 {
        (1.0 - step.log10().floor()).max(0.0)
    } else {
        2.0
    };
    let scientific = scale >= 1e7 || decimals > 6.0;
    // Mantissa digits in scientific notation: enough to tell neighbouring ticks apart.
    let digits = if step > 0.0 && scale.is_finite() {
        (scale / step).log10().ceil().clamp(1.0, 6.0) as usize
    } else {
        3
    };
    let decimals = decimals.min(6.0) as usize;
    move |v: &f64| {
        let mut s = if scientific && *v != 0.0 {
            format!("{v:.digits$e}")
        } else {
            format!("{v:.decimals$}")
        };
        let (mantissa, exponent) = match s.find('e') {
            Some(i) => (s[..i].to_string(), s[i..].to_string()),
            None => (s.clone(), String::new()),
        };
        if mantissa.contains('.') {
            let trimmed = mantissa.trim_end_matches('0').trim_end_matches('.');
            s = format!("{trimmed}{exponent}");
        }
        if s == "-0" {
            s.remove(0);
        }
        s
    }
}

/// Speed colour scale: `t = 0` red (slow), `0.5` yellow, `1` green (fast); clamped.
pub(crate) fn speed_colour(t: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 3] = [
        (0.0, [200.0, 30.0, 35.0]),
        (0.5, [250.0, 215.0, 70.0]),
        (1.0, [30.0, 145.0, 70.0]),
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let (a, b) = if t <= STOPS[1].0 {
        (STOPS[0], STOPS[1])
    } else {
        (STOPS[1], STOPS[2])
    };
    let f = (t - a.0) / (b.0 - a.0);
    let mix = |k: usize| (a.1[k] + (b.1[k] - a.1[k]) * f).round() as u8;
    RGBColor(mix(0), mix(1), mix(2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extent_skips_non_finite() {
        assert_eq!(
            extent([f64::NAN, 2.0, -1.0, f64::INFINITY]),
            Some((-1.0, 2.0))
        );
        assert_eq!(extent([f64::NAN]), None);
    }

    #[test]
    fn padded_handles_degenerate_extents() {
        assert_eq!(padded(None, 0.05), (0.0, 1.0));
        assert_eq!(padded(Some((0.0, 0.0)), 0.05), (-1.0, 1.0));
        let (a, b) = padded(Some((5.0, 5.0)), 0.05);
        assert!(a < 5.0 && b > 5.0);
        let (a, b) = padded(Some((0.0, 10.0)), 0.1);
        assert!((a + 1.0).abs() < 1e-12 && (b - 11.0).abs() < 1e-12);
        let (a, b) = padded(Some((-f64::MAX, f64::MAX)), 0.1);
        assert!(a.is_finite() && b.is_finite() && a < b);
    }

    #[test]
    fn bounded_ranges_have_finite_width() {
        let (a, b) = bounded((-f64::MAX, f64::MAX));
        assert!((b - a).is_finite() && a < b);
        assert_eq!(bounded((f64::NAN, 1.0)), (0.0, 1.0));
        assert_eq!(bounded((2.0, 1.0)), (0.0, 1.0));
        assert_eq!(bounded((1.0, 2.0)), (1.0, 2.0));
        let (a, b) = padded(Some((-f64::MAX, f64::MAX)), 0.1);
        assert!((b - a).is_finite() && a < b);
    }

    #[test]
    fn valid_range_rejects_empty_and_non_finite() {
        assert_eq!(valid_range((3.0, 1.0)), Some((1.0, 3.0)));
        assert_eq!(valid_range((1.0, 1.0)), None);
        assert_eq!(valid_range((f64::NAN, 1.0)), None);
    }

    #[test]
    fn tick_labels_have_just_enough_decimals() {
        let f = tick_label(1800.0, 3700.0);
        assert_eq!(f(&3500.0), "3500");
        let f = tick_label(0.0, 1.0);
        assert_eq!(f(&0.25), "0.25");
        assert_eq!(f(&0.30000000000000004), "0.3");
        assert_eq!(f(&1.0), "1");
        assert_eq!(f(&-0.0001), "0");
        let f = tick_label(0.0, 0.0);
        assert_eq!(f(&0.5), "0.5");
        let f = tick_label(0.0, 4e7);
        assert_eq!(f(&1.5e7), "1.5e7");
        assert_eq!(f(&0.0), "0");
        let f = tick_label(1e-300, 2e-300);
        assert_eq!(f(&1.25e-300), "1.25e-300");
    }

    #[test]
    fn speed_colours_run_red_to_green() {
        let slow = speed_colour(0.0);
        let fast = speed_colour(1.0);
        assert!(slow.0 > slow.1 && fast.1 > fast.0);
        assert_eq!(speed_colour(-3.0), slow);
        assert_eq!(speed_colour(7.0), fast);
        assert_eq!(speed_colour(f64::NAN), slow);
    }
}
