//! `model.preset`: which model the behaviour keys default to (docs/model-choices.md, "The
//! two presets").
//!
//! | preset | the behaviour keys default to |
//! |---|---|
//! | `platform` (default) | the engine's defaults: the paper's model with every documented extension that is on by default (the safe gap rule, automated organization with the narrow hold, the field form of the CACC, 6.21, 6.22, automated yielding) |
//! | `paper` | the paper's rules as published: the published gap rule, the PATH organization rule (manual from the desire on), the spec's CACC law, no cooperative or automated yielding, no CACC realism; plus only the engine rules without which the model cannot run (listed in docs/model-choices.md with their measured effect) |
//!
//! A preset only fills keys the scenario leaves out: a key written in the file or given with
//! `--set` wins. It acts on the document after the overrides, before the raw level reads it,
//! so a preset value is checked exactly like the same value written in the file.

use crate::error::ScenarioError;
use crate::overrides::{get, parse_key, set_path};
use serde::{Deserialize, Serialize};
use toml::{Table, Value};

/// The key that names the preset.
pub const KEY: &str = "model.preset";

/// A named set of defaults for the behaviour keys.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Preset {
    /// The paper's model as published.
    Paper,
    /// The engine's defaults.
    #[default]
    Platform,
}

impl Preset {
    /// Every preset, in the order the docs list them.
    pub const ALL: [Preset; 2] = [Preset::Paper, Preset::Platform];

    /// The scenario file's spelling.
    pub fn as_str(self) -> &'static str {
        match self {
            Preset::Paper => "paper",
            Preset::Platform => "platform",
        }
    }

    /// The preset of that spelling.
    pub fn parse(text: &str) -> Option<Preset> {
        Preset::ALL.into_iter().find(|p| p.as_str() == text)
    }

    /// The keys this preset sets and their values. `platform` sets none: its values are the
    /// parameter structs' defaults.
    pub fn keys(self) -> Vec<(&'static str, Value)> {
        match self {
            Preset::Platform => Vec::new(),
            Preset::Paper => paper(),
        }
    }
}

/// The paper's rules (docs/model-choices.md names the source of each).
fn paper() -> Vec<(&'static str, Value)> {
    let s = |t: &str| Value::String(t.into());
    vec![
        // Spec 4.3: the published gap acceptance, without the safe-gap check of spec 9.1.
        ("lane_change.gap_rule", s("published")),
        // Spec 3.1, the PATH rule: a CAV is in manual control from the moment a lane-change
        // desire arises, the organizing desire included (6.20 off).
        ("cav.organize_while_automated", Value::Boolean(false)),
        // The spec's CACC law (spec 3.4, 9.3), not its field form (docs/cacc-field.md) …
        ("cav.cacc_law", s("spec")),
        // … as written: gap closing whenever the gap is above target (6.21 off).
        ("cav.cacc_closing_only_approaching", Value::Boolean(false)),
        // Spec 4.3 as written: the move toward the PD lane keeps a_ant >= 0 (6.22 off).
        ("cav.organize_regardless_of_speed", Value::Boolean(false)),
        // The paper's CAV lane changes are manual and non-cooperative (spec 9.2 off).
        ("cav.cooperative_lane_change", Value::Boolean(false)),
        // Spec 6.5's recommendation: an automated CAV does not yield (a yield is a manual
        // brake, which disengages the automation).
        ("cav.yield_while_automated", Value::Boolean(false)),
        ("cav.yield_to_organizers", Value::Boolean(false)),
        // No CACC realism (spec 9.3): the paper's CACC has no lag, delay or loss.
        ("cav.actuator_lag_s", Value::Float(0.0)),
        ("cav.comm_delay_s", Value::Float(0.0)),
        ("cav.packet_loss", Value::Float(0.0)),
    ]
}

/// What a preset did to one document: which preset, and the keys it filled.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Applied {
    pub preset: Preset,
    /// The keys the preset set because the document left them out.
    pub filled: Vec<&'static str>,
}

/// Read `model.preset` from the document (default `platform`) and set every key of the preset
/// that the document leaves out.
pub fn apply(doc: &mut Table, origin: &str) -> Result<Applied, ScenarioError> {
    let preset = match get(doc, KEY)? {
        None => Preset::default(),
        Some(Value::String(text)) => {
            Preset::parse(text).ok_or_else(|| refused(origin, &format!("{text:?}")))?
        }
        Some(other) => return Err(refused(origin, &crate::raw::render(other))),
    };
    let mut filled = Vec::new();
    for (key, value) in preset.keys() {
        if get(doc, key)?.is_some() {
            continue;
        }
        let path = parse_key(key).expect("a preset key is well formed");
        set_path(doc, &path, value).map_err(|reason| ScenarioError::Override {
            arg: format!("{KEY} = \"{}\" sets {key}", preset.as_str()),
            reason,
        })?;
        filled.push(key);
    }
    Ok(Applied { preset, filled })
}

fn refused(origin: &str, value: &str) -> ScenarioError {
    ScenarioError::Structure {
        origin: origin.into(),
        path: KEY.into(),
        message: format!(
            "{value} is not a preset: use \"paper\" (the paper's rules as published) or \
             \"platform\" (the engine's defaults, the default)"
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(text: &str) -> Table {
        text.parse::<Table>().unwrap()
    }

    #[test]
    fn paper_fills_only_what_the_file_leaves_out() {
        let mut d = doc("[model]\npreset = \"paper\"\n[lane_change]\ngap_rule = \"safe\"\n");
        let applied = apply(&mut d, "test").unwrap();
        assert_eq!(applied.preset, Preset::Paper);
        assert!(!applied.filled.contains(&"lane_change.gap_rule"));
        assert_eq!(
            get(&d, "lane_change.gap_rule").unwrap(),
            Some(&Value::String("safe".into()))
        );
        assert!(applied.filled.contains(&"cav.organize_while_automated"));
        assert_eq!(
            get(&d, "cav.organize_while_automated").unwrap(),
            Some(&Value::Boolean(false))
        );
        assert_eq!(applied.filled.len(), paper().len() - 1);
    }

    #[test]
    fn platform_is_the_default_and_sets_nothing() {
        let mut d = doc("[run]\nseed = 3\n");
        let before = d.clone();
        assert_eq!(apply(&mut d, "test").unwrap(), Applied::default());
        assert_eq!(d, before);
    }

    #[test]
    fn an_unknown_preset_is_refused_with_the_allowed_values() {
        let e = apply(&mut doc("[model]\npreset = \"papers\"\n"), "test").unwrap_err();
        let m = e.to_string();
        assert!(m.contains("model.preset") && m.contains("papers") && m.contains("\"paper\""));
        let e = apply(&mut doc("[model]\npreset = 1\n"), "test").unwrap_err();
        assert!(e.to_string().contains("model.preset"));
    }
}
