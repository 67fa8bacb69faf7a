//! `platoonsim show`: a scenario with every key resolved, its model preset named and the keys
//! the preset set marked.

use crate::args::{ShowArgs, ShowFormat};
use anyhow::Result;
use platoonsim_scenario::preset::{self, Applied};

pub fn show(args: &ShowArgs) -> Result<()> {
    let config = args.scenario.load()?;
    let applied =
        platoonsim_scenario::preset_of(&args.scenario.scenario, &args.scenario.overrides())?;
    let text = match args.format {
        ShowFormat::Toml => format!(
            "# Scenario '{}' with every key resolved (`platoonsim show {}`).\n\
             # Save it to a .toml file, edit it, and run it with `platoonsim run FILE.toml`.\n\n{}",
            crate::messages::printable(&config.name),
            crate::messages::printable(&args.scenario.scenario),
            mark_preset(&platoonsim_scenario::to_toml(&config), &applied)
        ),
        ShowFormat::Json => String::from_utf8(platoonsim_runs::run_dir::json(&config)?)?,
    };
    Ok(crate::stdout::print(&text)?)
}

/// The scenario file with a `[model]` section naming the preset before its first table (after
/// the top-level keys, which a table header would otherwise capture), and `# preset` after
/// every key whose value the preset set (the scenario left it out).
fn mark_preset(toml: &str, applied: &Applied) -> String {
    let name = applied.preset.as_str();
    let mut model = Some(format!(
        "[model]\npreset = \"{name}\"  # the behaviour keys below default to the {name} model; \
         marked: set by it\n\n"
    ));
    let mut out = String::new();
    let mut section = String::new();
    for line in toml.lines() {
        if let Some(head) = line.strip_prefix('[') {
            if let Some(block) = model.take() {
                out.push_str(&block);
            }
            section = head.trim_matches(|c| c == '[' || c == ']').to_string();
            out.push_str(line);
        } else {
            out.push_str(line);
            if let Some((key, _)) = line.split_once(" = ") {
                let path = format!("{section}.{}", key.trim());
                if applied.filled.iter().any(|k| *k == path) {
                    out.push_str(&format!("  # {} = \"{name}\"", preset::KEY));
                }
            }
        }
        out.push('\n');
    }
    if let Some(block) = model {
        out.push_str(&block);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use platoonsim_scenario::Preset;

    #[test]
    fn the_keys_a_preset_set_are_marked_and_no_others() {
        let applied = Applied {
            preset: Preset::Paper,
            filled: vec!["lane_change.gap_rule"],
        };
        let text = mark_preset(
            "name = \"x\"\n\n[cav]\ngap_rule = \"safe\"\n\n[lane_change]\ngap_rule = \"published\"\n",
            &applied,
        );
        assert!(text.starts_with("name = \"x\"\n\n[model]\npreset = \"paper\""));
        assert!(text.contains("[cav]\ngap_rule = \"safe\"\n"));
        assert!(text.contains("gap_rule = \"published\"  # model.preset = \"paper\"\n"));
    }
}
