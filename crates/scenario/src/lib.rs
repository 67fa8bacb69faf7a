//! # platoonsim-scenario: scenario files
//!
//! A scenario is a TOML file read in two levels: [`raw::RawScenario`] (serde, unknown keys
//! rejected, numbers as written) and then [`validate::validate`] into the engine's
//! [`platoonsim_sim::Config`]. Command-line [`Overrides`] act on the parsed document before
//! either level, so an overridden value is checked exactly like one written in the file.
//! Errors ([`ScenarioError`]) name the key path, the value and what is allowed; nothing here
//! panics on user input.
//!
//! A `[network]` section makes the scenario a freeway corridor with ramps and time-varying
//! demand (issue 4; format in `docs/network-scenarios.md`, helpers in [`network`], default
//! demand scales in [`demand_scales`]); the built-in `sr99` is one.
//!
//! Principal entry points: [`load`] / [`load_with`] (a built-in name or a file path),
//! [`from_toml`] (text), [`BUILTINS`], and [`to_toml`] (a resolved config back to a complete
//! scenario file).
//!
//! ```toml
//! name = "example"
//! [run]          # all optional: seed = 1, dt_s = 0.1, duration_s = 3600, warmup_s = 1200, penetration = 0.5
//! penetration = 0.25
//! [road]         # required
//! lanes = 3
//! length_m = 6500
//! control_start_m = 5000
//! control_end_m = 6000
//! [demand]       # required
//! vph_per_lane = 2000
//! [[detectors]]  # at least one
//! name = "discharge"
//! position_m = 6100
//! [measurement]  # detector required if there is more than one; aggregation_s = 300
//! detector = "discharge"
//! [strategy]     # kind = "none" | "pd" | "flow-aware"; zone, time window and thresholds optional
//! kind = "pd"
//! [human]        # [human], [cav], [lane_change]: model parameters, every key optional
//! buffer_s = 0.2
//! ```

pub mod bounded;
pub mod clock;
pub mod demand_scales;
pub mod error;
pub mod format;
pub mod limits;
pub mod network;
pub mod overrides;
mod pen_table;
pub mod preset;
pub mod raw;
pub mod sweep_spec;
pub mod tables;
pub mod thresholds;
pub mod validate;

pub use error::{Problem, ScenarioError, TableError};
pub use overrides::{demand_scale_set, Overrides, StrategyKind};
pub use preset::Preset;
pub use raw::RawScenario;

use platoonsim_sim::Config;
use std::path::{Path, PathBuf};

/// A scenario shipped inside the binary.
#[derive(Clone, Copy, Debug)]
pub struct Builtin {
    pub name: &'static str,
    pub description: &'static str,
    /// The scenario file's text.
    pub toml: &'static str,
}

/// The built-in scenarios.
pub const BUILTINS: &[Builtin] = &[
    Builtin {
        name: "homogeneous",
        description: "the paper's 3-lane homogeneous freeway: 5 km approach, 1 km control section \
                  (5000-6000 m), detectors at 4900/5500/6100 m, 60 min with a 20 min warm-up, \
                  50 % CAV, 2500 veh/h/lane",
        toml: include_str!("../scenarios/homogeneous.toml"),
    },
    Builtin {
        name: "sr99",
        description:
            "SR-99 northbound, Sacramento, Elk Grove Blvd to 12th Ave (the paper's freeway \
                  experiment): 17.7 km, 3-5 lanes (HOV lane open to all), 16 on-ramps, 11 \
                  off-ramps, 15-min demand 05:00-09:00, detectors around every ramp, 0 % CAV",
        toml: include_str!("../scenarios/sr99.toml"),
    },
    Builtin {
        name: "sr99-field",
        description: "SR-99 northbound as sr99, calibrated to PeMS of 2014-09-18 05:00-10:00 \
                  (demand from the counts, driver parameters from the speeds; no time shift): \
                  a detector at every PeMS station, named by its ID, 0 % CAV",
        toml: include_str!("../scenarios/sr99-field.toml"),
    },
];

/// The built-in scenario of that name.
pub fn builtin(name: &str) -> Option<&'static Builtin> {
    BUILTINS.iter().find(|b| b.name == name)
}

/// Where a scenario's text came from, resolved from a name or a path.
#[derive(Clone, Debug)]
pub struct Source {
    /// For messages: `built-in scenario 'homogeneous'` or the file path.
    pub origin: String,
    /// The name used when the file sets none (the built-in name or the file stem).
    pub default_name: String,
    /// The scenario file's text.
    pub text: String,
    /// The scenario file's directory, from which the relative table paths it names are read
    /// (`None` for a built-in: from the current directory).
    pub dir: Option<PathBuf>,
}

/// Find a scenario: an argument with a path separator or ending in `.toml` is a file; any
/// other is a built-in name, or, failing that, a file.
pub fn resolve(name_or_path: &str) -> Result<Source, ScenarioError> {
    let looks_like_path = name_or_path.contains(['/', '\\']) || name_or_path.ends_with(".toml");
    if !looks_like_path {
        if let Some(b) = builtin(name_or_path) {
            return Ok(Source {
                origin: format!("built-in scenario '{}'", b.name),
                default_name: b.name.to_string(),
                text: b.toml.to_string(),
                dir: None,
            });
        }
    }
    let path = Path::new(name_or_path);
    let builtins = || {
        BUILTINS
            .iter()
            .map(|b| b.name)
            .collect::<Vec<_>>()
            .join(", ")
    };
    if path.is_dir() {
        return Err(ScenarioError::Directory {
            path: path.to_path_buf(),
            builtins: builtins(),
        });
    }
    if path.exists() {
        // A device, FIFO or socket: say so (it exists), and never open it.
        if let Err(cause) = bounded::regular_file(path) {
            return Err(ScenarioError::Io {
                path: path.to_path_buf(),
                cause,
            });
        }
    } else {
        return Err(ScenarioError::UnknownScenario {
            name: name_or_path.to_string(),
            builtins: builtins(),
        });
    }
    let text = read_limited(path)?;
    let default_name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scenario".to_string());
    Ok(Source {
        origin: path.display().to_string(),
        default_name,
        text,
        dir: path.parent().map(Path::to_path_buf),
    })
}

/// A scenario file's text, refused without reading further once it passes
/// [`limits::MAX_FILE_BYTES`] (a file that grows while read is caught too).
pub(crate) fn read_limited(path: &Path) -> Result<String, ScenarioError> {
    use std::io::Read;
    let io = |cause| ScenarioError::Io {
        path: path.to_path_buf(),
        cause,
    };
    // Never open what is not a regular file: a FIFO blocks the open, a device never ends.
    bounded::regular_file(path).map_err(io)?;
    let file = std::fs::File::open(path).map_err(io)?;
    let size = file.metadata().map_err(io)?.len();
    let too_large = |bytes: u64| ScenarioError::TooLarge {
        origin: path.display().to_string(),
        bytes,
        limit: limits::MAX_FILE_BYTES,
    };
    if size > limits::MAX_FILE_BYTES as u64 {
        return Err(too_large(size));
    }
    let mut bytes = Vec::new();
    file.take(limits::MAX_FILE_BYTES as u64 + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() > limits::MAX_FILE_BYTES {
        return Err(too_large(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|e| {
        io(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("not UTF-8 text ({e})"),
        ))
    })
}

/// Load a built-in scenario or a scenario file, as written.
pub fn load(name_or_path: &str) -> Result<Config, ScenarioError> {
    load_with(name_or_path, &Overrides::default())
}

/// Load a built-in scenario or a scenario file with command-line overrides.
pub fn load_with(name_or_path: &str, overrides: &Overrides) -> Result<Config, ScenarioError> {
    let source = resolve(name_or_path)?;
    from_toml_in(
        &source.text,
        &source.origin,
        &source.default_name,
        overrides,
        source.dir.as_deref(),
    )
    .map_err(|e| match e {
        // A JSON object is never valid TOML: say what the file is rather than where the TOML
        // parser gave up.
        ScenarioError::Syntax { origin, .. } if looks_like_json(name_or_path, &source.text) => {
            ScenarioError::NotToml { origin }
        }
        e => e,
    })
}

/// A `.json` name, or text that opens with a JSON object (a TOML file cannot start with `{`).
fn looks_like_json(name: &str, text: &str) -> bool {
    name.to_ascii_lowercase().ends_with(".json") || text.trim_start().starts_with('{')
}

/// Read scenario text: parse, apply overrides, read the raw level, validate. Relative table
/// paths are read from the current directory.
pub fn from_toml(
    text: &str,
    origin: &str,
    default_name: &str,
    overrides: &Overrides,
) -> Result<Config, ScenarioError> {
    from_toml_in(text, origin, default_name, overrides, None)
}

/// [`from_toml`] for the text of a file in `base_dir`, from which the relative table paths it
/// names are read.
pub fn from_toml_in(
    text: &str,
    origin: &str,
    default_name: &str,
    overrides: &Overrides,
    base_dir: Option<&Path>,
) -> Result<Config, ScenarioError> {
    let raw = raw_from_toml(text, origin, overrides)?;
    validate::validate_in(&raw, default_name, origin, base_dir)
}

/// The first level only: parse and apply overrides, read into a [`RawScenario`].
pub fn raw_from_toml(
    text: &str,
    origin: &str,
    overrides: &Overrides,
) -> Result<RawScenario, ScenarioError> {
    // The same bound as for files, for text from any other source.
    if text.len() > limits::MAX_FILE_BYTES {
        return Err(ScenarioError::TooLarge {
            origin: origin.to_string(),
            bytes: text.len() as u64,
            limit: limits::MAX_FILE_BYTES,
        });
    }
    Ok(raw_and_preset(text, origin, overrides)?.0)
}

/// [`raw_from_toml`], and what `model.preset` filled in (the preset acts after the overrides,
/// on the keys that neither the file nor an override sets).
pub fn raw_and_preset(
    text: &str,
    origin: &str,
    overrides: &Overrides,
) -> Result<(RawScenario, preset::Applied), ScenarioError> {
    let mut doc = raw::parse_document(text, origin)?;
    overrides.apply(&mut doc)?;
    let applied = preset::apply(&mut doc, origin)?;
    Ok((raw::from_document(&doc, origin)?, applied))
}

/// The preset a scenario with these overrides runs under, and the keys it fills.
pub fn preset_of(
    name_or_path: &str,
    overrides: &Overrides,
) -> Result<preset::Applied, ScenarioError> {
    let source = resolve(name_or_path)?;
    Ok(raw_and_preset(&source.text, &source.origin, overrides)?.1)
}

/// The description of a scenario (the file's `description` key), if it has one.
pub fn description(name_or_path: &str) -> Result<Option<String>, ScenarioError> {
    let source = resolve(name_or_path)?;
    Ok(raw_from_toml(&source.text, &source.origin, &Overrides::default())?.description)
}

/// A resolved config as a complete scenario file that loads back to the same config.
pub fn to_toml(config: &Config) -> String {
    format::to_toml(config, None)
}
