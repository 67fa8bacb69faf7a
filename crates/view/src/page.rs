//! The page: `assets/viewer.html` with the stylesheet, the script, the JSON block and the
//! base64 block put in at their markers.

use crate::road::Road;
use crate::tables::{Collision, DetectorSeries, Trips};
use crate::tracks::{Packed, ACCEL_UNIT, SPEED_UNIT_KMH};
use anyhow::{Context, Result};
use serde::Serialize;

const HTML: &str = include_str!("../assets/viewer.html");
const CSS: &str = include_str!("../assets/viewer.css");
const JS: &str = include_str!("../assets/viewer.js");

pub struct Meta<'a> {
    pub road: &'a Road,
    pub packed: &'a Packed,
    pub detectors: &'a [DetectorSeries],
    pub trips: &'a Trips,
    pub collisions: &'a [Collision],
}

#[derive(Serialize)]
struct Json<'a> {
    road: &'a Road,
    frames: &'a [f64],
    x_res_m: f64,
    speed_unit_kmh: f64,
    accel_unit: f64,
    kinds: &'a [String],
    modes: &'a [String],
    regimes: &'a [String],
    platoon_column: bool,
    accel_column: bool,
    rows: usize,
    tracks: usize,
    sections: &'a [crate::pack::Section],
    contour: ContourJson,
    detectors: &'a [DetectorSeries],
    trips: &'a Trips,
    collisions: &'a [Collision],
}

#[derive(Serialize)]
struct ContourJson {
    nt: usize,
    nx: usize,
    t0_s: f64,
    t1_s: f64,
    x0_m: f64,
    x1_m: f64,
}

pub fn render(m: &Meta) -> Result<String> {
    let p = m.packed;
    let c = &p.contour;
    let json = serde_json::to_string(&Json {
        road: m.road,
        frames: &p.frames,
        x_res_m: p.x_res_m,
        speed_unit_kmh: SPEED_UNIT_KMH,
        accel_unit: ACCEL_UNIT,
        kinds: &p.kinds,
        modes: &p.modes,
        regimes: &p.regimes,
        platoon_column: p.platoon_column,
        accel_column: p.accel_column,
        rows: p.rows,
        tracks: p.tracks,
        sections: &p.blob.sections,
        contour: ContourJson {
            nt: c.nt,
            nx: c.nx,
            t0_s: c.t0_s,
            t1_s: c.t1_s,
            x0_m: c.x0_m,
            x1_m: c.x1_m,
        },
        detectors: m.detectors,
        trips: m.trips,
        collisions: m.collisions,
    })
    .context("cannot encode the viewer's data")?;
    // Inside <script>, "</" could close the element; JSON allows the escaped form.
    let json = json.replace('<', "\\u003c");
    let title = format!("platoonsim view: {}", escape(&m.road.name));
    let data = p.blob.encode();
    Ok(fill(
        HTML,
        &[
            ("{{TITLE}}", &title),
            ("/*{{CSS}}*/", CSS),
            ("{{META}}", &json),
            ("{{DATA}}", &data),
            ("/*{{JS}}*/", JS),
        ],
    ))
}

/// Puts each value at its marker, the markers found in order in the template only (never in
/// an inserted value).
fn fill(template: &str, parts: &[(&str, &str)]) -> String {
    let extra: usize = parts.iter().map(|p| p.1.len()).sum();
    let mut out = String::with_capacity(template.len() + extra);
    let mut rest = template;
    for (marker, value) in parts {
        let at = rest
            .find(marker)
            .expect("the template holds every marker, in order");
        out.push_str(&rest[..at]);
        out.push_str(value);
        rest = &rest[at + marker.len()..];
    }
    out.push_str(rest);
    out
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markers_are_filled_once_and_values_are_not_scanned() {
        let out = fill("a{{X}}b{{Y}}c", &[("{{X}}", "{{Y}}"), ("{{Y}}", "2")]);
        assert_eq!(out, "a{{Y}}b2c");
    }

    #[test]
    fn the_page_loads_nothing_from_outside() {
        for (name, text) in [("html", HTML), ("css", CSS), ("js", JS)] {
            for bad in [
                "http:",
                "https:",
                "//cdn",
                "@import",
                "url(",
                "fetch(",
                "XMLHttpRequest",
            ] {
                assert!(!text.contains(bad), "{name} contains {bad}");
            }
        }
    }
}
