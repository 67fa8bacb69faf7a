//! The run plan of every experiment is pinned: which runs (run key = hash of the resolved
//! configuration, seed, kept detector records) `reproduce` and `reproduce --quick` make, as a
//! digest per experiment. A change of how an experiment is described (code, sweep file, the
//! registry) that keeps the digests keeps every per-run result byte for byte, because a run's
//! file is a function of its configuration and seed only.
//!
//! The runs are not simulated: a stand-in executor returns one short real run's output with
//! its metrics perturbed by the run key, so the adaptive procedures (capacity's second stage,
//! the demand-scale search) take deterministic decisions; the plan is then pinned as a
//! function of those results. Set `PLATOONSIM_PLAN_DIR` to write each plan as text.

use platoonsim_experiment::experiments::{self, run_experiment_with};
use platoonsim_experiment::{ExperimentName, Settings};
use platoonsim_runs::hash::{config_key, fnv1a64};
use platoonsim_sim::{Config, Output, SimError};
use std::path::PathBuf;
use std::sync::{Mutex, OnceLock};

fn sample() -> &'static Output {
    static OUT: OnceLock<Output> = OnceLock::new();
    OUT.get_or_init(|| {
        platoonsim_runs::runner::simulate(&Config::homogeneous(0.5, 1500.0, 600.0, 0.0, 1)).unwrap()
    })
}

/// One run's stand-in output: the sample's, with the flows moved by the key.
fn fake(config: &Config) -> Output {
    let mut out = sample().clone();
    let h = fnv1a64(config_key(config).as_bytes());
    let s = &mut out.summary;
    s.seed = config.seed;
    s.max_sustained_flow_vphpl = 1800.0 + (h % 400) as f64;
    s.discharge_flow_vphpl = 1700.0 + (h / 400 % 300) as f64;
    s.avg_platoon_length = Some(1.0 + (h / 7 % 100) as f64 / 50.0);
    s.platooning_probability = Some((h / 11 % 100) as f64 / 100.0);
    out
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("platoonsim-plan-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// The runs one experiment asks for with these settings: one line per unique run,
/// `key seed detectors`, sorted.
fn plan(name: ExperimentName, s: &Settings, mode: &str) -> Vec<String> {
    let seen: Mutex<Vec<(String, u64)>> = Mutex::new(Vec::new());
    let exec = |c: &Config| -> Result<Output, SimError> {
        seen.lock().unwrap().push((config_key(c), c.seed));
        Ok(fake(c))
    };
    let dir = scratch(&format!("{name}-{mode}"));
    let s = Settings {
        out: dir.clone(),
        jobs: Some(1),
        ..s.clone()
    };
    // The report may fail on the stand-in results (figures from the sample's detectors); the
    // plan is what was executed.
    let _ = run_experiment_with(name, &s, &exec);
    let runs = s.dir(name.as_str()).join("runs");
    let mut lines: Vec<String> = seen
        .into_inner()
        .unwrap()
        .into_iter()
        .map(|(k, seed)| {
            let det = std::fs::read(runs.join(format!("{k}.json")))
                .ok()
                .and_then(|b| serde_json::from_slice::<serde_json::Value>(&b).ok())
                .and_then(|v| v.get("detectors").and_then(|d| d.get("scope")).cloned())
                .map_or("none".to_string(), |v| v.to_string());
            format!("{k} {seed} {det}")
        })
        .collect();
    lines.sort();
    let _ = std::fs::remove_dir_all(&dir);
    lines
}

/// `reproduce`'s experiments and settings.
fn reproduce(quick: bool) -> Vec<(ExperimentName, Settings)> {
    let base = Settings {
        seeds: if quick { 3 } else { 10 },
        ..Settings::default()
    };
    experiments::reproduction(&base, quick, None, None)
}

fn digests(quick: bool) -> Vec<String> {
    let mut out = Vec::new();
    for (name, s) in reproduce(quick) {
        let lines = plan(name, &s, if quick { "quick" } else { "full" });
        let text = lines.join("\n");
        if let Ok(d) = std::env::var("PLATOONSIM_PLAN_DIR") {
            let file = format!(
                "{}-{}.txt",
                name.as_str(),
                if quick { "quick" } else { "full" }
            );
            std::fs::write(PathBuf::from(d).join(file), &text).unwrap();
        }
        out.push(format!(
            "{}{} {} {:016x}",
            match s.preset {
                platoonsim_scenario::Preset::Paper => "paper/",
                platoonsim_scenario::Preset::Platform => "",
            },
            name.as_str(),
            lines.len(),
            fnv1a64(text.as_bytes())
        ));
    }
    out
}

#[test]
fn quick_reproduction_plan() {
    assert_eq!(
        digests(true),
        [
            "paper/capacity 39 ed06e69e5cd2d42c",
            "paper/sensitivity 36 e3370bea6aa5f51f",
            "paper/flow-aware 9 5de774217094744d",
            "paper/sr99 4 b0eb33e635700f58",
            "rules 132 97d31656907f977f",
            "capacity 39 396e8a06dd34aa88",
            "sensitivity 36 56d66ec324985097",
            "flow-aware 9 04672a019d734710",
            "sr99 4 5c0bef189432ff6b",
            "sr99-demand 2 8f3f890413b050bc",
            "behaviour 72 183fbfb21483514b",
            "energy 24 c0d69109d0e4ee15",
        ]
    );
}

#[test]
fn full_reproduction_plan() {
    assert_eq!(
        digests(false),
        [
            "paper/capacity 130 292e7a33012165e5",
            "paper/sensitivity 120 b8e3851f0a9125fb",
            "paper/flow-aware 30 cc349612d6dd6e56",
            "paper/sr99 140 06d74c2bf00ac549",
            "rules 440 f6ce2f108717d5fc",
            "capacity 130 7760193f3e325a2b",
            "sensitivity 120 26446aa8afa83a28",
            "flow-aware 30 8ed6de6a70a240e4",
            "sr99 140 7a6295686e4cd10b",
            "sr99-demand 660 4bb43ba10342c3fe",
            "behaviour 240 b51f94e919b2937d",
            "energy 320 c72f2af98160a2f0",
        ]
    );
}

#[test]
fn calibrate_flow_aware_plan() {
    let s = Settings {
        seeds: 3,
        ..Settings::default()
    };
    let lines = plan(experiments::get("calibrate-flow-aware"), &s, "default");
    let d = format!(
        "{} {:016x}",
        lines.len(),
        fnv1a64(lines.join("\n").as_bytes())
    );
    assert_eq!(d, "756 801c388f273c49b9");
}
