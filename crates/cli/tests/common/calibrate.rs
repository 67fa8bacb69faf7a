//! The calibration tests' corridor and its "field" data, made by platoonsim itself with known
//! parameter values (shared by `tests/calibrate.rs` and `tests/hyperqueue.rs`).

use super::{platoonsim, s, stderr};
use platoonsim_calibrate::field_obs::{mean_over_runs, to_obs};
use std::path::{Path, PathBuf};

pub fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/calibrate")
}

pub fn scenario() -> String {
    dir().join("corridor.toml").display().to_string()
}

/// The field's parameter values.
pub const BUFFER_S: f64 = 0.4;
pub const SPEED_KMH: f64 = 100.0;

/// "Field" data: the mean of six runs of the corridor with the field's values, at seeds
/// 101..=106 (none of the calibration's seeds 1..=3, so the fit meets noise it has not seen),
/// stations s1..s4, as tidy CSV.
pub fn field(dir: &Path) -> PathBuf {
    field_of(dir, &|station| station.starts_with('s'))
}

/// [`field`] with every detector of the corridor that `keep` selects as a station.
pub fn field_of(dir: &Path, keep: &dyn Fn(&str) -> bool) -> PathBuf {
    let mut runs = Vec::new();
    for seed in 101..=106 {
        let out = dir.join(format!("field-run-{seed}"));
        let o = platoonsim(&[
            "-q",
            "run",
            &scenario(),
            "--set",
            &format!("human.buffer_s={BUFFER_S}"),
            "--set",
            &format!("human.desired_speed_kmh.mean={SPEED_KMH}"),
            "--seed",
            &seed.to_string(),
            "--out",
            s(&out),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let bytes = std::fs::read(out.join("detectors.csv")).unwrap();
        let records = platoonsim_runs::detectors::from_csv(&bytes).unwrap();
        runs.push(to_obs(&records, 7 * 3600));
    }
    let mut csv = String::from("station,time,flow_vph,speed_kmh,occupancy\n");
    for o in mean_over_runs(&runs) {
        if !keep(&o.station) {
            continue;
        }
        let t = o.start_s;
        csv.push_str(&format!(
            "{},{:02}:{:02}:{:02},{},{},{}\n",
            o.station,
            t / 3600,
            t / 60 % 60,
            t % 60,
            o.flow_vph,
            o.speed_kmh.map_or(String::new(), |v| v.to_string()),
            o.occupancy.map_or(String::new(), |v| v.to_string()),
        ));
    }
    let path = dir.join("field.csv");
    std::fs::write(&path, csv).unwrap();
    path
}
