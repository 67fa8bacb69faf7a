//! A scenario file: TOML parsing, validation (with the geometry's room rules) and the
//! warnings. Whatever validation accepts must pass the engine's own `Config::check`.
#![no_main]

use libfuzzer_sys::fuzz_target;
use platoonsim_scenario::{from_toml, validate::warnings, Overrides};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(config) = from_toml(text, "fuzz.toml", "fuzz", &Overrides::default()) {
        assert!(
            config.check().is_ok(),
            "validation accepted what the engine refuses"
        );
        let _ = warnings(&config);
    }
});
