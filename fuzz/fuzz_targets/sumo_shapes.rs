//! Structure-aware SUMO networks (issue 48 item 6): the input's bytes choose a shape (deep
//! nesting, a long chain, many connections, many attributes, a small network of many lanes)
//! with its size and extreme numbers (`platoonsim_import::sumo::synth::from_bytes`), and the
//! whole import runs on it. A panic, a 10 s timeout (a step quadratic in the network, as D2 and
//! D3 were) or 4 GiB of memory is a finding; a scenario it writes that validation accepts must
//! pass `Config::check`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use platoonsim_import::sumo::{from_texts, synth, Options};
use platoonsim_scenario::{from_toml, Overrides};
use std::path::PathBuf;

fuzz_target!(|data: &[u8]| {
    let (net, routes) = synth::from_bytes(data);
    let routes = vec![(PathBuf::from("shapes.rou.xml"), routes)];
    let opts = Options {
        net: PathBuf::from("shapes.net.xml"),
        edge_detectors: data.get(11).is_some_and(|b| b % 2 == 0),
        ..Options::default()
    };
    if let Ok(imported) = from_texts(&opts, &net, &routes, &[]) {
        if let Ok(config) = from_toml(&imported.toml, "shapes.toml", "shapes", &Overrides::default()) {
            assert!(
                config.check().is_ok(),
                "validation accepted what the engine refuses"
            );
        }
    }
});
