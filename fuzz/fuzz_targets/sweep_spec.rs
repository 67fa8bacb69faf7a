//! A sweep file: parsing and checking of the spec (scenario, seeds, axes, set, compare).
#![no_main]

use libfuzzer_sys::fuzz_target;
use platoonsim_scenario::sweep_spec::Spec;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = Spec::from_toml(text, "fuzz.toml", "fuzz");
});
