//! The files of a run directory as `platoonsim view` reads them: the first byte picks the file
//! the rest replaces (trajectories.csv, detectors.csv, trips.csv or road.json); the others are
//! those of a short valid run (seeds/run/). The page is built in memory, never written.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::path::PathBuf;
use std::sync::OnceLock;

const FILES: [&str; 4] = [
    "trajectories.csv",
    "detectors.csv",
    "trips.csv",
    "road.json",
];
const RUN: [(&str, &[u8]); 4] = [
    ("road.json", include_bytes!("../seeds/run/road.json")),
    (
        "trajectories.csv",
        include_bytes!("../seeds/run/trajectories.csv"),
    ),
    (
        "detectors.csv",
        include_bytes!("../seeds/run/detectors.csv"),
    ),
    ("trips.csv", include_bytes!("../seeds/run/trips.csv")),
];

/// A scratch run directory of this process, filled with the valid run once (under $TMPDIR:
/// scripts/fuzz.sh points it at a RAM disk where there is one).
fn dir() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("platoonsim-fuzz-run-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        for (name, bytes) in RUN {
            std::fs::write(d.join(name), bytes).unwrap();
        }
        d
    })
}

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let d = dir();
    let name = FILES[usize::from(pick) % FILES.len()];
    std::fs::write(d.join(name), rest).unwrap();
    let _ = platoonsim_view::build(d);
    // Put the valid file back for the next input.
    let valid = RUN.iter().find(|(n, _)| *n == name).unwrap().1;
    std::fs::write(d.join(name), valid).unwrap();
});
