//! Runner and experiment tests on the SR-99 corridor, with runs shortened to a few simulated
//! minutes (`run.duration_s` overridden): detector files kept beside the run files and
//! reused like them.

use platoonsim_experiment::design::{keep_detectors, runs, seeds};
use platoonsim_experiment::detectors::Scope;
use platoonsim_experiment::runner::{bar, simulate};
use platoonsim_experiment::{Cell, Labels, Runner};
use platoonsim_scenario::{demand_scale_set, load_with, Overrides, StrategyKind};
use platoonsim_sim::{Config, Output};
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("platoonsim-net-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// SR-99 at 40 % CAV under PD, 600 s.
fn short_sr99() -> Cell {
    let o = Overrides {
        penetration: Some(0.4),
        strategy: Some(StrategyKind::Pd),
        seed: Some(1),
        set: vec![demand_scale_set(1.1), "run.duration_s=600".into()],
        ..Overrides::default()
    };
    Cell {
        labels: Labels::new().with("strategy", "pd"),
        config: load_with("sr99", &o).unwrap(),
    }
}

fn names(dir: &Path, suffix: &str) -> usize {
    fs::read_dir(dir)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .ends_with(suffix)
        })
        .count()
}

#[test]
fn detector_files_are_kept_for_the_selected_runs_and_reused() {
    let dir = scratch("detectors").join("runs");
    let count = AtomicUsize::new(0);
    let exec = |c: &Config| -> Result<Output, String> {
        count.fetch_add(1, Ordering::SeqCst);
        simulate(c)
    };
    let cells = vec![short_sr99()];
    let mut specs = runs(&cells, &seeds(2));
    keep_detectors(&mut specs, Scope::All, |_, seed| seed == 1);
    let runner = || Runner::new(dir.clone(), Some(2), bar(2, false, "t"), &exec);
    let (k1, k2) = (specs[0].key(), specs[1].key());

    runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 2);
    assert_eq!(
        (names(&dir, ".json"), names(&dir, ".detectors.csv")),
        (2, 1)
    );
    let recs = runner().detectors(&k1).unwrap();
    assert!(recs.iter().any(|r| r.lane == "1") && recs.iter().any(|r| r.lane == "all"));
    assert!(recs.iter().any(|r| r.detector == "OR11-up"));
    // The same records as the engine's.
    assert_eq!(recs, simulate(&specs[0].config).unwrap().detectors);
    assert!(runner().detectors(&k2).is_err());

    // Everything reused.
    let r = runner();
    r.run(&specs).unwrap();
    assert_eq!((count.swap(0, Ordering::SeqCst), r.reused()), (0, 2));

    // Seed 2 now wants its cross-section: only it is recomputed.
    keep_detectors(&mut specs, Scope::CrossSection, |_, seed| seed == 2);
    runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 1);
    let cross = runner().detectors(&k2).unwrap();
    assert!(!cross.is_empty() && cross.iter().all(|r| r.lane == "all"));
    // A narrower wish is covered by a wider file.
    keep_detectors(&mut specs, Scope::CrossSection, |_, seed| seed == 1);
    runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 0);

    // A changed or missing detector file makes its run recompute.
    let f1 = dir.join(format!("{k1}.detectors.csv"));
    let mut bytes = fs::read(&f1).unwrap();
    bytes.push(b'\n');
    fs::write(&f1, &bytes).unwrap();
    runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 1);
    fs::remove_file(&f1).unwrap();
    runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 1);
    assert_eq!(runner().detectors(&k1).unwrap(), recs);

    // A run recomputed without detectors leaves its old detector file behind; the new run
    // file names none, so the old file is not used.
    let plain = runs(&cells, &seeds(2));
    let mut r = runner();
    r.reuse = false;
    r.run(&plain).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 2);
    assert_eq!(names(&dir, ".detectors.csv"), 2);
    runner().run(&specs).unwrap();
    assert_eq!(count.swap(0, Ordering::SeqCst), 2);
}
