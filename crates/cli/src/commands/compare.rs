//! `platoonsim compare`: runs against field data (docs/compare.md). This module reads the
//! field files and the placement; `platoonsim_calibrate::compare` measures and writes.

use crate::args::{CompareArgs, FieldFlags};
use anyhow::{bail, Context, Result};
use platoonsim_calibrate::compare::{self, files, runs, Options};
use platoonsim_field::{combine, load, pems, place, Obs, Placed};

/// Names shown in a message before "…".
const SHOWN: usize = 8;

fn some_names(names: &[String]) -> String {
    let mut s = names
        .iter()
        .take(SHOWN)
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    if names.len() > SHOWN {
        s.push_str(&format!(", … ({} in all)", names.len()));
    }
    s
}

/// Where the field data come from: `--field`, `--meta`, `--origin-pm`, `--stations` (of
/// `compare` and `calibrate`).
/// The field rows (HOV stations added to their mainline station when there is metadata),
/// the placement, and notes on what was combined or left out inside `window`.
pub fn field_data(
    args: &FieldFlags,
    window: (u32, u32),
) -> Result<(Vec<Obs>, Vec<Placed>, Vec<String>)> {
    let mut obs = load::load(&args.field)?;
    let mut notes = Vec::new();
    let meta = match &args.meta {
        Some(path) => Some(pems::read_meta(path)?),
        None => None,
    };
    if let Some(meta) = &meta {
        let groups = combine::hov_groups(meta, combine::HOV_TOLERANCE_MI);
        let (combined, incomplete) = combine::combine(&obs, &groups);
        obs = combined;
        if !groups.is_empty() {
            notes.push(format!(
                "HOV stations added to the mainline station at their postmile (within {} mi): {}.",
                combine::HOV_TOLERANCE_MI,
                groups
                    .iter()
                    .map(|g| {
                        let members: Vec<&str> = g
                            .members
                            .iter()
                            .skip(1)
                            .map(|(id, _)| id.as_str())
                            .collect();
                        format!("{} + {}", g.station, members.join(" + "))
                    })
                    .collect::<Vec<_>>()
                    .join("; ")
            ));
        }
        let left_out: Vec<_> = incomplete
            .iter()
            .filter(|i| window.0 <= i.start_s && i.start_s < window.1)
            .collect();
        if let Some(first) = left_out.first() {
            notes.push(format!(
                "{} field 5-min intervals of mainline + HOV stations left out because a member \
                 had no row (the first: station {} at {}, missing {}).",
                left_out.len(),
                first.station,
                platoonsim_field::report::clock(first.start_s),
                first.missing.join(", ")
            ));
        }
    }
    let places = match (&args.stations, args.origin_pm, &meta) {
        (Some(table), _, _) => place::from_table(table)?,
        (None, Some(pm), Some(meta)) => {
            place::by_postmile(meta, pm, f64::NEG_INFINITY, f64::INFINITY)
        }
        _ => Vec::new(),
    };
    if let Some(table) = &args.stations {
        // A table of other stations placed nothing and silently changed the result (issue 48):
        // it must place at least one station of the field files; the others are noted.
        let field: std::collections::BTreeSet<&str> =
            obs.iter().map(|o| o.station.as_str()).collect();
        let (matched, unmatched): (Vec<&Placed>, Vec<&Placed>) = places
            .iter()
            .partition(|p| field.contains(p.station.as_str()));
        let ids = |v: &[&Placed]| -> Vec<String> { v.iter().map(|p| p.station.clone()).collect() };
        if matched.is_empty() {
            bail!(
                "--stations {}: none of its stations ({}) is in the field files (stations {})",
                table.display(),
                some_names(&ids(&unmatched)),
                some_names(&field.iter().map(|s| s.to_string()).collect::<Vec<_>>())
            );
        }
        if !unmatched.is_empty() {
            notes.push(format!(
                "{} station(s) of --stations not in the field files, not placed: {}.",
                unmatched.len(),
                some_names(&ids(&unmatched))
            ));
        }
    }
    Ok((obs, places, notes))
}

pub fn compare(args: &CompareArgs) -> Result<()> {
    let sim = runs::read_runs(&args.runs)?;
    let Some(span) = compare::sim_span(&sim.obs) else {
        bail!(
            "{}: {} has no cross-section rows (lane \"{}\"): nothing to compare",
            args.runs[0].display(),
            platoonsim_rundir::DETECTORS.csv,
            platoonsim_rundir::Lane::ALL
        );
    };
    let window = args.window(span)?;
    let (field, field_places, notes) = field_data(&args.source, window)?;
    let opts = Options {
        window: Some(window),
        ..Options::default()
    };
    let eval = compare::evaluate(&sim.obs, &field, &sim.places, &field_places, &opts);
    let fit = &eval.fit;
    if fit.stations_compared.is_empty() {
        bail!(
            "no simulated detector has the name of a field station, so nothing can be compared: \
             detectors {}; field stations {}. Name the scenario's detectors by station ID \
             (docs/compare.md)",
            some_names(&fit.sim_only_stations),
            some_names(&fit.field_only_stations)
        );
    }
    if let Some(x) = eval.objective().filter(|x| !x.is_finite()) {
        // Never a result file with a NaN fit (issue 48 D5); the readers' ranges should make
        // this unreachable.
        bail!(
            "the fit's objective is {x}: a field or simulated value is not a finite number in \
             range; nothing written"
        );
    }
    if !fit.sim_only_stations.is_empty() {
        errln!(
            "note: {} simulated detector(s) without field data, not compared: {}",
            fit.sim_only_stations.len(),
            some_names(&fit.sim_only_stations)
        );
    }
    let out = args.out_dir();
    let _lock = crate::out_lock::lock(&out, crate::out_lock::Share::Alone)?;
    let inputs = files::Inputs {
        runs: args.runs.iter().map(|p| p.display().to_string()).collect(),
        field_files: args
            .source
            .field
            .iter()
            .map(|p| p.display().to_string())
            .collect(),
        notes,
    };
    let written = files::write(
        &out,
        &inputs,
        &eval,
        &opts,
        &sim.obs,
        &field,
        &sim.places,
        &field_places,
    )
    .with_context(|| format!("cannot write the comparison to {}", out.display()))?;

    outln!(
        "Compared {} station(s), {}–{}: {} station-hours, {} 15-min speeds.",
        fit.stations_compared.len(),
        platoonsim_field::report::clock(window.0),
        platoonsim_field::report::clock(window.1),
        fit.hour_coverage.matched,
        fit.speed_intervals
    )?;
    for c in &eval.criteria {
        outln!(
            "{} {}: {} (threshold {})",
            if c.pass { "✓" } else { "✗" },
            c.name,
            c.measured,
            c.threshold
        )?;
    }
    let failed = eval.criteria.iter().filter(|c| !c.pass).count();
    outln!(
        "{}",
        if failed == 0 {
            "Every criterion holds.".to_string()
        } else {
            format!("{failed} of {} criteria do not hold.", eval.criteria.len())
        }
    )?;
    for p in written {
        outln!("{}", p.display())?;
    }
    Ok(())
}
