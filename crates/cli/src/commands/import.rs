//! `platoonsim import sumo`: a SUMO network with its routes and induction loops as a corridor
//! scenario file (docs/import.md). The importer lives in `platoonsim-import`; this module
//! checks that the file it made loads as a scenario, writes it and prints what was kept,
//! reduced and dropped.

use anyhow::{Context, Result};
use clap::{Args, Subcommand};
use platoonsim_import::sumo;
use platoonsim_runs::atomic::write_atomic;
use platoonsim_scenario::Overrides;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct ImportArgs {
    #[command(subcommand)]
    pub from: ImportFrom,
}

#[derive(Debug, Subcommand)]
pub enum ImportFrom {
    /// A SUMO network (.net.xml, as netconvert writes it, also from OpenStreetMap) with its
    /// routes and induction loops: the mainline as lane stretches, on- and off-ramps with
    /// their acceleration lanes, detectors, the demand per interval, and the vehicle-type
    /// parameters that map onto the model's. Prints what was kept, reduced and dropped (also
    /// written into the file's header). See docs/import.md.
    Sumo(SumoArgs),
}

#[derive(Debug, Args)]
pub struct SumoArgs {
    /// The SUMO network file (.net.xml or .net.xml.gz).
    pub net: PathBuf,
    /// Routes files (.rou.xml): flows, vehicles, trips, routes, vehicle types. Repeatable.
    #[arg(long = "routes", value_name = "FILE")]
    pub routes: Vec<PathBuf>,
    /// Additional files (.add.xml): induction loops become detectors. Repeatable.
    #[arg(long = "additional", value_name = "FILE")]
    pub additional: Vec<PathBuf>,
    /// The mainline's edges in travel order, comma-separated (default: the longest chain of
    /// motorway/trunk edges, or of non-link edges on an untyped network).
    #[arg(long, value_name = "EDGE,EDGE,...", value_delimiter = ',')]
    pub mainline: Option<Vec<String>>,
    /// Add a detector 1 m before the downstream end of every mainline edge (10 m where the
    /// road or an off-ramp leaves at that end), named by the edge.
    #[arg(long)]
    pub edge_detectors: bool,
    /// Demand interval (s); default: the common divisor of the flows' begin and end times.
    #[arg(long, value_name = "S")]
    pub interval_s: Option<f64>,
    /// Run duration (s); default: the end of the demand.
    #[arg(long, value_name = "S")]
    pub duration_s: Option<f64>,
    /// Scenario name (default: the network file's name).
    #[arg(long)]
    pub name: Option<String>,
    /// The scenario file to write.
    #[arg(long, value_name = "SCENARIO.toml")]
    pub out: PathBuf,
}

pub fn import(args: &ImportArgs) -> Result<()> {
    match &args.from {
        ImportFrom::Sumo(a) => sumo_cmd(a),
    }
}

fn sumo_cmd(a: &SumoArgs) -> Result<()> {
    let opts = sumo::Options {
        net: a.net.clone(),
        routes: a.routes.clone(),
        additional: a.additional.clone(),
        mainline: a.mainline.clone(),
        edge_detectors: a.edge_detectors,
        interval_s: a.interval_s,
        duration_s: a.duration_s,
        name: a.name.clone(),
    };
    // Before reading: the scenario must not replace one of the SUMO files (`--out NET` did),
    // nor anything that is not a regular file.
    let inputs: Vec<&std::path::Path> = std::iter::once(a.net.as_path())
        .chain(a.routes.iter().map(|p| p.as_path()))
        .chain(a.additional.iter().map(|p| p.as_path()))
        .collect();
    platoonsim_runs::atomic::refuse_input(&a.out, &inputs)?;
    platoonsim_runs::atomic::check_output(&a.out)?;
    let imported = sumo::import(&opts)?;
    // The file must load as it will be run: relative paths from its own directory.
    let dir = a.out.parent().filter(|p| !p.as_os_str().is_empty());
    platoonsim_scenario::from_toml_in(
        &imported.toml,
        &a.out.display().to_string(),
        "imported",
        &Overrides::default(),
        dir,
    )
    .context(
        "the corridor imported from the SUMO files is not a valid scenario (the importer's \
         notes above say what it made of the network)",
    )
    .inspect_err(|_| errln!("{}", imported.notes))?;
    write_atomic(&a.out, imported.toml.as_bytes())
        .with_context(|| format!("cannot write {}", a.out.display()))?;
    outln!("{}", imported.notes)?;
    outln!("wrote {}", a.out.display())?;
    Ok(())
}
