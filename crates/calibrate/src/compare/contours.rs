//! Speed contours of a comparison: simulated | field | difference (simulated − field), one
//! figure ([`platoonsim_plot::heatmap_row`], each panel with its own colour bar), time of day
//! across, the compared mainline stations up. Cells are the 5-min speeds at each station
//! ([`bottleneck::rule_speed`]: a standing queue is 0 km/h, no data is grey); the difference
//! exists where both sides have a speed.

use platoonsim_field::bottleneck;
use platoonsim_field::{Obs, Placed};
use platoonsim_plot::Heatmap;
use std::collections::BTreeMap;

/// The speed panels' colour scale (km/h), the one of the SR-99 contour figures.
pub const SPEED_RANGE: (f64, f64) = (0.0, 120.0);

/// Interval of the contour cells (s).
pub const CELL_S: u32 = 300;

/// Cell centres along an axis of station positions (km): the positions if they are strictly
/// increasing, else the station order (1 = most upstream), with the axis label.
fn axis(line: &[Placed]) -> (Vec<f64>, String) {
    let km: Vec<f64> = line.iter().map(|p| p.x_m / 1000.0).collect();
    if km.windows(2).all(|w| w[1] > w[0]) && km.iter().all(|v| v.is_finite()) {
        (km, "Position (km)".into())
    } else {
        (
            (1..=line.len()).map(|j| j as f64).collect(),
            "Station (1 = most upstream)".into(),
        )
    }
}

/// Speeds at `CELL_S` intervals: `z[i][j]` at interval `i` from `from_s`, station `line[j]`.
fn grid(obs: &[Obs], line: &[Placed], window: (u32, u32)) -> Vec<Vec<f64>> {
    let n = ((window.1.saturating_sub(window.0)) / CELL_S) as usize;
    let col: BTreeMap<&str, usize> = line
        .iter()
        .enumerate()
        .map(|(j, p)| (p.station.as_str(), j))
        .collect();
    let mut z = vec![vec![f64::NAN; line.len()]; n];
    for o in obs.iter().filter(|o| o.interval_s == CELL_S) {
        let (Some(&j), true) = (col.get(o.station.as_str()), o.start_s >= window.0) else {
            continue;
        };
        let i = ((o.start_s - window.0) / CELL_S) as usize;
        if i < n {
            z[i][j] = bottleneck::rule_speed(o).unwrap_or(f64::NAN);
        }
    }
    z
}

/// A station line sorted by position: each panel draws its stations in its own
/// upstream-to-downstream order.
fn sorted(line: &[Placed]) -> Vec<Placed> {
    let mut v = line.to_vec();
    v.sort_by(|a, b| a.x_m.total_cmp(&b.x_m).then(a.station.cmp(&b.station)));
    v
}

/// The three panels. `sim_line` and `field_line` are the same stations placed on each side.
pub fn panels(
    sim: &[Obs],
    field: &[Obs],
    sim_line: &[Placed],
    field_line: &[Placed],
    window: (u32, u32),
) -> Vec<Heatmap> {
    let (sim_line, field_line) = (sorted(sim_line), sorted(field_line));
    let times: Vec<f64> = (0..(window.1.saturating_sub(window.0) / CELL_S))
        .map(|i| f64::from(window.0 + i * CELL_S + CELL_S / 2) / 3600.0)
        .collect();
    let zs = grid(sim, &sim_line, window);
    let zf = grid(field, &field_line, window);
    // The difference on the simulated side's station order.
    let field_col: BTreeMap<&str, usize> = field_line
        .iter()
        .enumerate()
        .map(|(j, p)| (p.station.as_str(), j))
        .collect();
    let zd: Vec<Vec<f64>> = zs
        .iter()
        .zip(&zf)
        .map(|(rs, rf)| {
            sim_line
                .iter()
                .enumerate()
                .map(|(j, p)| match field_col.get(p.station.as_str()) {
                    Some(&k) if rs[j].is_finite() && rf[k].is_finite() => rs[j] - rf[k],
                    _ => f64::NAN,
                })
                .collect()
        })
        .collect();
    let largest = zd
        .iter()
        .flatten()
        .filter(|d| d.is_finite())
        .fold(0.0f64, |m, d| m.max(d.abs()));
    let half = ((largest / 10.0).ceil() * 10.0).max(10.0);
    let (ys, ys_label) = axis(&sim_line);
    let (yf, yf_label) = axis(&field_line);
    let map = |title: &str, y: Vec<f64>, y_label: String, z, z_label: &str, z_range| Heatmap {
        title: title.into(),
        x_label: "Time of day (h)".into(),
        y_label,
        x: times.clone(),
        y,
        z,
        z_label: z_label.into(),
        z_range,
    };
    vec![
        map(
            "Simulated",
            ys.clone(),
            ys_label.clone(),
            zs,
            "Speed (km/h)",
            SPEED_RANGE,
        ),
        map("Field", yf, yf_label, zf, "Speed (km/h)", SPEED_RANGE),
        map(
            "Simulated − field (red: simulation slower)",
            ys,
            ys_label,
            zd,
            "Speed difference (km/h)",
            (-half, half),
        ),
    ]
}
