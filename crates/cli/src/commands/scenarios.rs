//! `platoonsim scenarios`: the built-in scenarios.

use anyhow::Result;
use platoonsim_scenario::BUILTINS;

pub fn scenarios() -> Result<()> {
    let width = BUILTINS.iter().map(|b| b.name.len()).max().unwrap_or(0);
    for b in BUILTINS {
        let description = b
            .description
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
        outln!("{:width$}  {}", b.name, description)?;
    }
    outln!(
        "\nUse a name with `platoonsim run NAME`; `platoonsim show NAME` prints it as a scenario file to copy and edit."
    )?;
    Ok(())
}
