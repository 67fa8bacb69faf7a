//! `--set KEY=VALUE` arguments on built-in scenarios: the first byte picks the scenario (the
//! homogeneous road or the lane-drop corridor), the rest, split at line breaks, are the
//! arguments.
#![no_main]

use libfuzzer_sys::fuzz_target;
use platoonsim_scenario::{from_toml, Overrides};

const SCENARIOS: [&str; 2] = [
    include_str!("../../crates/scenario/scenarios/homogeneous.toml"),
    include_str!("../../crates/scenario/scenarios/lane_drop.toml"),
];

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let overrides = Overrides {
        set: text.lines().take(8).map(str::to_string).collect(),
        ..Overrides::default()
    };
    let base = SCENARIOS[usize::from(pick) % SCENARIOS.len()];
    if let Ok(config) = from_toml(base, "fuzz.toml", "fuzz", &overrides) {
        assert!(
            config.check().is_ok(),
            "validation accepted what the engine refuses"
        );
    }
});
