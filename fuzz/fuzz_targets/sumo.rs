//! SUMO files in (`platoonsim import sumo`): the input is a network, a routes file and an
//! additional file separated by NUL bytes; the whole import runs on them (network, mainline,
//! corridor, routes and demand, loops, vehicle types, the scenario text). Whatever it returns,
//! it must not panic, hang or run out of memory; a scenario it writes that validation accepts
//! must pass the engine's own `Config::check`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use platoonsim_import::sumo::{from_texts, Options};
use platoonsim_scenario::{from_toml, Overrides};
use std::path::PathBuf;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let mut parts = text.splitn(3, '\0');
    let net = parts.next().unwrap_or("");
    let routes: Vec<(PathBuf, String)> = parts
        .next()
        .map(|r| vec![(PathBuf::from("fuzz.rou.xml"), r.to_string())])
        .unwrap_or_default();
    let additional: Vec<(PathBuf, String)> = parts
        .next()
        .map(|a| vec![(PathBuf::from("fuzz.add.xml"), a.to_string())])
        .unwrap_or_default();
    let opts = Options {
        net: PathBuf::from("fuzz.net.xml"),
        edge_detectors: net.len() % 2 == 0,
        ..Options::default()
    };
    if let Ok(imported) = from_texts(&opts, net, &routes, &additional) {
        if let Ok(config) = from_toml(&imported.toml, "fuzz.toml", "fuzz", &Overrides::default()) {
            assert!(
                config.check().is_ok(),
                "validation accepted what the engine refuses"
            );
        }
    }
});
