//! Field data files: the first byte picks the reader (PeMS station_5min, PeMS day with
//! metadata columns, tidy CSV, or the format sniffer and loader); the rest is the file, plain
//! or gzip as the readers tell apart by its first bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;
use platoonsim_field::{load, pems, tidy};
use std::path::PathBuf;
use std::sync::OnceLock;

fn file() -> &'static PathBuf {
    static FILE: OnceLock<PathBuf> = OnceLock::new();
    FILE.get_or_init(|| {
        std::env::temp_dir().join(format!("platoonsim-fuzz-field-{}.txt", std::process::id()))
    })
}

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let f = file();
    std::fs::write(f, rest).unwrap();
    match pick % 4 {
        0 => drop(pems::read_station_5min(f)),
        1 => drop(pems::read_day(f)),
        2 => drop(tidy::read(f)),
        _ => drop(load::load(std::slice::from_ref(f))),
    }
});
