//! A run's output files and its one-paragraph summary. Files are written with
//! [`crate::atomic::write_atomic`].
//!
//! | file | content |
//! |---|---|
//! | `summary.json` | [`Summary`], pretty JSON |
//! | `detectors.csv` | one row per detector, lane (1 = rightmost, `all`) and interval |
//! | `scenario.json` | the resolved [`Config`] |
//! | `scenario.toml` | the same as a complete scenario file (`platoonsim run DIR/scenario.toml` reruns it) |

use crate::atomic::write_atomic;
use anyhow::{Context, Result};
use platoonsim_experiment::detectors::Scope;
use platoonsim_sim::{Config, DetectorRecord, Output, Summary};
use std::path::{Path, PathBuf};

/// Write every output file of a run into `dir` (which must exist); returns the paths written.
pub fn write_run(dir: &Path, config: &Config, output: &Output) -> Result<Vec<PathBuf>> {
    let files: [(&str, Vec<u8>); 4] = [
        ("summary.json", json(&output.summary)?),
        ("detectors.csv", detectors_csv(&output.detectors)?),
        ("scenario.json", json(config)?),
        (
            "scenario.toml",
            platoonsim_scenario::to_toml(config).into_bytes(),
        ),
    ];
    let mut written = Vec::with_capacity(files.len());
    for (name, bytes) in files {
        let path = dir.join(name);
        write_atomic(&path, &bytes).with_context(|| format!("cannot write {}", path.display()))?;
        written.push(path);
    }
    Ok(written)
}

/// Pretty JSON with a final newline.
pub fn json<T: serde::Serialize + ?Sized>(value: &T) -> Result<Vec<u8>> {
    let mut bytes = serde_json::to_vec_pretty(value).context("cannot encode JSON")?;
    bytes.push(b'\n');
    Ok(bytes)
}

/// `detectors.csv`: the header, then one row per record; an interval without vehicles has an
/// empty `speed_kmh` cell.
pub fn detectors_csv(records: &[DetectorRecord]) -> Result<Vec<u8>> {
    // One writer for the run files and the experiment runner's kept detector files.
    let (bytes, _) = platoonsim_experiment::detectors::to_csv(records, Scope::All)
        .map_err(anyhow::Error::msg)?;
    Ok(bytes)
}

/// The one-paragraph human summary printed after a run.
pub fn paragraph(config: &Config, s: &Summary, dir: &Path) -> String {
    let detector = config
        .detectors
        .get(config.measurement_detector)
        .map_or("?", |d| d.name.as_str());
    let rate = if s.wall_seconds > 0.0 {
        format!(
            " ({} per second)",
            si(s.vehicle_updates as f64 / s.wall_seconds)
        )
    } else {
        String::new()
    };
    // A network's demand is its series times a scale; it also reports the discharge through
    // every exit.
    let (demand, network) = match &config.road.network {
        Some(n) => (
            format!("the network's demand x {:.3}", n.demand_scale),
            format!(
                " Network discharge (off-ramps and the end): {} veh/h; {} missed exits.",
                s.network_discharge_vph
                    .map_or("-".to_string(), |q| format!("{q:.0}")),
                s.missed_exits
            ),
        ),
        None => (
            format!("{} veh/h/lane demand", s.demand_vphpl),
            String::new(),
        ),
    };
    let text = format!(
        "{name}: {dur} s simulated in steps of {dt} s (measured after the {warm} s warm-up) with \
         {pen} % CAV, {demand}, strategy {strategy}, seed {seed}. \
         Vehicles: {entered} entered, {exited} exited, {inside} still on the road, {waiting} \
         waiting at the entrance. Discharge at detector '{detector}': {q:.1} veh/h/lane over \
         the measurement window; highest {agg} s flow {qmax:.1} veh/h/lane.{network} Lane changes per \
         vehicle {lc:.3} ({counted} vehicles; per CAV {lc_cav:.3}, per human {lc_human:.3}); \
         average platoon length {lbar:.2} and platooning probability {pp:.3} ({cavs} CAVs). \
         Collisions: {collisions}. {updates} vehicle updates in {wall:.2} s{rate}. \
         Files in {dir}: summary.json, detectors.csv, scenario.json, scenario.toml.",
        name = s.scenario,
        dur = s.duration_s,
        dt = s.dt_s,
        warm = s.warmup_s,
        pen = s.penetration * 100.0,
        strategy = s.strategy,
        seed = s.seed,
        entered = s.vehicles_entered,
        exited = s.vehicles_exited,
        inside = s.vehicles_in_network,
        waiting = s.vehicles_waiting,
        q = s.discharge_flow_vphpl,
        agg = config.aggregation_s,
        qmax = s.max_sustained_flow_vphpl,
        lc = s.lane_changes_per_vehicle,
        lc_cav = s.lane_changes_per_cav,
        lc_human = s.lane_changes_per_human,
        counted = s.vehicles_counted,
        lbar = s.avg_platoon_length,
        pp = s.platooning_probability,
        cavs = s.cavs_counted,
        collisions = s.collisions,
        updates = s.vehicle_updates,
        wall = s.wall_seconds,
        dir = dir.display(),
    );
    wrap(&text, 96)
}

/// 12.3 M, 456.7 k, 89.
pub fn si(v: f64) -> String {
    if v >= 1e9 {
        format!("{:.2} G", v / 1e9)
    } else if v >= 1e6 {
        format!("{:.2} M", v / 1e6)
    } else if v >= 1e3 {
        format!("{:.1} k", v / 1e3)
    } else {
        format!("{v:.0}")
    }
}

/// Greedy word wrap.
pub fn wrap(text: &str, width: usize) -> String {
    let mut out = String::new();
    let mut line = 0;
    for word in text.split_whitespace() {
        if line > 0 && line + 1 + word.len() > width {
            out.push('\n');
            line = 0;
        } else if line > 0 {
            out.push(' ');
            line += 1;
        }
        out.push_str(word);
        line += word.len();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(speed: Option<f64>) -> DetectorRecord {
        DetectorRecord {
            detector: "discharge".into(),
            kind: "mainline".into(),
            position_m: 6100.0,
            lane: "all".into(),
            interval_start_s: 1200.0,
            interval_s: 300.0,
            count: 180,
            cav_count: 90,
            flow_vph: 2160.0,
            speed_kmh: speed,
            occupancy: 0.125,
        }
    }

    #[test]
    fn detectors_csv_has_the_columns_and_empty_speed_cells() {
        let bytes = detectors_csv(&[record(Some(97.25)), record(None)]).unwrap();
        let text = String::from_utf8(bytes).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(
            lines,
            vec![
                "detector,kind,position_m,lane,interval_start_s,interval_s,count,cav_count,flow_vph,speed_kmh,occupancy",
                "discharge,mainline,6100,all,1200,300,180,90,2160,97.25,0.125",
                "discharge,mainline,6100,all,1200,300,180,90,2160,,0.125",
            ]
        );
    }

    /// A real five-minute run of the homogeneous road.
    fn short_run() -> (Config, Output) {
        let o = platoonsim_scenario::Overrides {
            duration_s: Some(300.0),
            warmup_s: Some(60.0),
            ..Default::default()
        };
        let config = platoonsim_scenario::load_with("homogeneous", &o).unwrap();
        let out = platoonsim_sim::run(&config, None).unwrap();
        (config, out)
    }

    #[test]
    fn write_run_writes_every_file_atomically() {
        let dir = std::env::temp_dir().join(format!("platoonsim-output-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let (config, out) = short_run();
        let written = write_run(&dir, &config, &out).unwrap();
        assert_eq!(written.len(), 4);
        let mut names: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names,
            [
                "detectors.csv",
                "scenario.json",
                "scenario.toml",
                "summary.json"
            ]
        );
        let s: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join("summary.json")).unwrap()).unwrap();
        assert_eq!(s["vehicle_updates"], out.summary.vehicle_updates);
        let csv = std::fs::read(dir.join("detectors.csv")).unwrap();
        assert_eq!(csv, detectors_csv(&out.detectors).unwrap());
        let c: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.join("scenario.json")).unwrap()).unwrap();
        assert_eq!(c["road"]["length_m"], 6500.0);
        let back = platoonsim_scenario::load(dir.join("scenario.toml").to_str().unwrap()).unwrap();
        assert_eq!(back, config);
    }

    #[test]
    fn paragraph_mentions_the_key_figures() {
        let (config, out) = short_run();
        let s = &out.summary;
        let p = paragraph(&config, s, Path::new("out/run"));
        let flat = p.replace('\n', " ");
        let discharge = format!("{:.1} veh/h/lane", s.discharge_flow_vphpl);
        let entered = format!("{} entered", s.vehicles_entered);
        for part in [
            "homogeneous:",
            "50 % CAV",
            "2500 veh/h/lane demand",
            "detector 'discharge'",
            &discharge,
            &entered,
            "out/run",
        ] {
            assert!(flat.contains(part), "{part} missing in:\n{p}");
        }
        assert!(p.lines().all(|l| l.len() <= 96), "{p}");
    }

    #[test]
    fn paragraph_of_a_network_run_gives_its_demand_scale_and_exits() {
        let o = platoonsim_scenario::Overrides {
            duration_s: Some(60.0),
            penetration: Some(0.4),
            ..Default::default()
        };
        let config = platoonsim_scenario::load_with("sr99", &o).unwrap();
        let out = platoonsim_sim::run(&config, None).unwrap();
        let p = paragraph(&config, &out.summary, Path::new("out/run")).replace('\n', " ");
        for part in [
            "sr99:",
            "40 % CAV, the network's demand x 1.210,",
            "Network discharge (off-ramps and the end):",
            "missed exits",
        ] {
            assert!(p.contains(part), "{part} missing in:\n{p}");
        }
        assert!(!p.contains("veh/h/lane demand"), "{p}");
    }

    #[test]
    fn wrap_keeps_words_and_width() {
        let w = wrap("aaa bbb ccc ddd", 7);
        assert_eq!(w, "aaa bbb\nccc ddd");
        assert_eq!(si(12_345_678.0), "12.35 M");
        assert_eq!(si(950.0), "950");
    }
}
