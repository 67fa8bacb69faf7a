//! The road as drawn: the run's `road.json`, the engine's sketch of the road it simulated
//! ([`platoonsim_rundir::road::RoadSketch`], written by `platoonsim run` for every run), so
//! the viewer draws the lanes, ramps and organized lane the engine used instead of deriving
//! them again. Read bounded and checked for what the page relies on (a lane count it can
//! stack, a road of some length, every lane number on the road).

use crate::bounded;
use anyhow::{bail, Context, Result};
use platoonsim_rundir::ROAD_JSON;
use std::path::Path;

pub use platoonsim_rundir::road::RoadSketch as Road;

/// The most lanes the page stacks (a corridor has a few; the trajectories' lane codes stop at
/// 254).
const MAX_LANES: u32 = 250;

/// Read `road.json` of the run in `dir`. Errors name the file.
pub fn read(dir: &Path) -> Result<Road> {
    let path = dir.join(ROAD_JSON);
    // Only a missing file is an old run directory; any other failure is reported by the read.
    let missing =
        std::fs::symlink_metadata(&path).is_err_and(|e| e.kind() == std::io::ErrorKind::NotFound);
    if missing {
        bail!(
            "{} not found: the run directory predates {ROAD_JSON} (the road as the engine built \
             it, which the viewer draws); re-run it with `platoonsim run ... --trajectories \
             PERIOD_S --out {}`",
            path.display(),
            dir.display()
        );
    }
    let text = bounded::read_text(&path, bounded::MAX_ROAD_BYTES).with_context(|| {
        format!(
            "cannot read {} (the run's road, written by `platoonsim run`)",
            path.display()
        )
    })?;
    let road: Road = serde_json::from_str(&text)
        .with_context(|| format!("{} is not a road sketch", path.display()))?;
    check(&road).with_context(|| format!("in {}", path.display()))?;
    Ok(road)
}

/// What the page relies on: 1 to [`MAX_LANES`] lanes, a road of positive length, a vehicle
/// length it can draw, and lane numbers on the road. (A run writes nothing else; a file edited
/// by hand or from another tool may.)
fn check(r: &Road) -> Result<()> {
    if !(1..=MAX_LANES).contains(&r.lanes) {
        bail!("lanes = {}: expected 1 to {MAX_LANES}", r.lanes);
    }
    if r.end_m <= r.start_m {
        bail!(
            "start_m = {}, end_m = {}: expected a road of positive length",
            r.start_m,
            r.end_m
        );
    }
    if !(r.vehicle_length_m > 0.0 && r.vehicle_length_m < 100.0) {
        bail!(
            "vehicle_length_m = {}: expected a length in (0, 100) m",
            r.vehicle_length_m
        );
    }
    let lanes = r
        .segments
        .iter()
        .map(|s| ("segments", s.lane))
        .chain(r.on_ramps.iter().map(|s| ("on_ramps", s.lane)))
        .chain(r.off_ramps.iter().map(|s| ("off_ramps", s.lane)))
        .chain(r.organized.iter().map(|s| ("organized", s.lane)));
    for (list, lane) in lanes {
        if !(1..=r.lanes).contains(&lane) {
            bail!(
                "{list}: lane {lane} is not a lane of the road (1 to {})",
                r.lanes
            );
        }
    }
    Ok(())
}

/// A road for tests: `lanes` lanes over [0, `length_m`), no ramps, no strategy.
#[cfg(test)]
pub(crate) fn plain(lanes: u32, length_m: f64) -> Road {
    use platoonsim_rundir::road::Segment;
    Road {
        name: "t".into(),
        seed: 1,
        penetration: 0.5,
        origin_m: 0.0,
        start_m: 0.0,
        end_m: length_m,
        lanes,
        segments: (1..=lanes)
            .map(|lane| Segment {
                lane,
                from_m: 0.0,
                to_m: length_m,
                accel: false,
                ends: false,
            })
            .collect(),
        on_ramps: vec![],
        off_ramps: vec![],
        detectors: vec![],
        control_m: [0.0, length_m],
        strategy: "none".into(),
        pd_zone_m: None,
        pd_window_s: None,
        organized: vec![],
        vehicle_length_m: 4.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let d = std::env::temp_dir().join(format!("platoonsim-view-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn road_json_reads_back_and_a_missing_one_says_to_rerun() {
        let dir = scratch("road");
        let e = read(&dir).unwrap_err().to_string();
        assert!(
            e.contains("road.json not found: the run directory predates road.json")
                && e.contains("platoonsim run ... --trajectories"),
            "{e}"
        );
        let road = plain(3, 1000.0);
        std::fs::write(dir.join(ROAD_JSON), serde_json::to_vec(&road).unwrap()).unwrap();
        assert_eq!(read(&dir).unwrap(), road);
        std::fs::write(dir.join(ROAD_JSON), "{\"lanes\": 3}").unwrap();
        let e = format!("{:#}", read(&dir).unwrap_err());
        assert!(e.contains("road.json is not a road sketch"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_bad_lane_count_or_lane_names_the_field() {
        let e = check(&plain(0, 100.0)).unwrap_err().to_string();
        assert!(e.contains("lanes = 0"), "{e}");
        let mut r = plain(2, 100.0);
        r.segments[1].lane = 3;
        let e = check(&r).unwrap_err().to_string();
        assert!(
            e.contains("segments: lane 3 is not a lane of the road (1 to 2)"),
            "{e}"
        );
        let e = check(&plain(2, 0.0)).unwrap_err().to_string();
        assert!(e.contains("end_m = 0"), "{e}");
    }
}
