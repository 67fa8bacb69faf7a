//! `platoonsim show`: a scenario with every key resolved.

use crate::args::{ShowArgs, ShowFormat};
use crate::output;
use anyhow::Result;

pub fn show(args: &ShowArgs) -> Result<()> {
    let config = args.scenario.load()?;
    let text = match args.format {
        ShowFormat::Toml => format!(
            "# Scenario '{}' with every key resolved (`platoonsim show {}`).\n\
             # Save it to a .toml file, edit it, and run it with `platoonsim run FILE.toml`.\n\n{}",
            crate::messages::printable(&config.name),
            crate::messages::printable(&args.scenario.scenario),
            platoonsim_scenario::to_toml(&config)
        ),
        ShowFormat::Json => String::from_utf8(output::json(&config)?)?,
    };
    Ok(crate::stdout::print(&text)?)
}
