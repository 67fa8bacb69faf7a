//! Shared helpers of the scenario tests.
#![allow(dead_code)]

// Scenario files: the built-in scenario's values, every error class, overrides, round trips.

use platoonsim_scenario::{from_toml, Overrides, ScenarioError};
use platoonsim_sim::Config;

pub const HOMOGENEOUS: &str = include_str!("../../scenarios/homogeneous.toml");

/// A small valid scenario; tests patch it.
pub const SMALL: &str = r#"
name = "small"
[road]
lanes = 2
length_m = 3000
control_start_m = 2000
control_end_m = 2500
[demand]
vph_per_lane = 1000
[[detectors]]
name = "a"
position_m = 1000
[[detectors]]
name = "b"
position_m = 2600
[measurement]
detector = "b"
"#;

pub fn parse(text: &str) -> Result<Config, ScenarioError> {
    from_toml(text, "test.toml", "test", &Overrides::default())
}

pub fn with_set(text: &str, sets: &[&str]) -> Result<Config, ScenarioError> {
    let o = Overrides {
        set: sets.iter().map(|s| s.to_string()).collect(),
        ..Overrides::default()
    };
    from_toml(text, "test.toml", "test", &o)
}

/// The problems of an `Invalid` error as "field = value: allowed" lines; panics otherwise.
pub fn problems(r: Result<Config, ScenarioError>) -> Vec<String> {
    match r {
        Err(e @ ScenarioError::Invalid { .. }) => {
            e.problems().iter().map(|p| p.to_string()).collect()
        }
        Err(e) => panic!("expected a validation error, got: {e}"),
        Ok(_) => panic!("expected a validation error, got a valid config"),
    }
}

pub fn has(problems: &[String], line: &str) -> bool {
    problems.iter().any(|p| p == line)
}

pub fn structure(r: Result<Config, ScenarioError>) -> (String, String) {
    match r {
        Err(ScenarioError::Structure { path, message, .. }) => (path, message),
        Err(e) => panic!("expected a structure error, got: {e}"),
        Ok(_) => panic!("expected a structure error, got a valid config"),
    }
}

/// A lane stretch of a network.
pub fn ext(lane: u32, from_m: f64, to_m: f64) -> platoonsim_sim::config::LaneExtent {
    platoonsim_sim::config::LaneExtent { lane, from_m, to_m }
}

/// The detector names of a configuration, in order.
pub fn names(c: &Config) -> Vec<&str> {
    c.detectors.iter().map(|d| d.name.as_str()).collect()
}
