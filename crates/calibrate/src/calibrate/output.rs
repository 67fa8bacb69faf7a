//! The files of a calibration, all written atomically into its output directory:
//!
//! | file | content |
//! |---|---|
//! | `trace.csv` | one row per evaluated candidate: `generation` (0 = the start point), `candidate`, each fitted key, `objective`, each term (empty where it has no value or is not computed: `compare` unweighted), `pairs` (matched station intervals) |
//! | `calibrated.toml` | the scenario with the fixed keys and the best candidate's values, every key resolved (`platoonsim show` format); it loads and validates as it is |
//! | `convergence.png` / `.svg` | the objective of every candidate and the best so far, by evaluation |
//! | `fit-before.md` / `fit-after.md` | the fit of the start point and of the best candidate: the values and terms, then `platoonsim compare`'s report of the mean of its replications (criteria, measures, stations, bottlenecks) |
//! | `demand.csv` | with `[demand]`: the estimated entrance flows and exit fractions per interval (set in `calibrated.toml`) |
//! | `run.json` | provenance: version, engine, command line, scenario, the parameters file's text, the field files with their FNV-1a 64 hashes, seeds, runs, the start and the best point |

use super::evaluate::{candidate_obs, specs, Target};
use super::objective::TERMS;
use super::params::Params;
use super::space::Space;
use super::{Done, Field, Options, Row};
use crate::atomic::write_atomic;
use crate::runner::Runner;
use crate::{Error, VERSION};
use platoonsim_field::{Obs, Placed};
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// A number for messages: 4 significant digits.
pub fn short(v: f64) -> String {
    format!("{v:.4}")
}

/// `key = value` pairs of a point, for messages.
pub fn point(space: &Space, values: &[f64]) -> String {
    space
        .params
        .iter()
        .zip(values)
        .map(|(q, v)| format!("{} = {}", q.key, short(*v)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Write every output file of a finished (unsharded) calibration.
#[allow(clippy::too_many_arguments)]
pub fn write_all(
    p: &Params,
    field: &Field,
    opts: &Options,
    space: &Space,
    reader: &Runner,
    target: &Target,
    done: &Done,
    demand: Option<&super::demand::Demand>,
) -> Result<(), Error> {
    let write = |name: &str, bytes: &[u8]| {
        let path = opts.out.join(name);
        write_atomic(&path, bytes).map_err(|e| Error::io(&path, e))
    };
    write("trace.csv", &trace_csv(space, &done.trace)?)?;
    if let Some(d) = demand {
        write("demand.csv", &super::demand::csv(d).map_err(Error::Other)?)?;
    }
    let best = &done.trace[done.best];
    write(
        "calibrated.toml",
        calibrated_toml(p, opts, space, best)?.as_bytes(),
    )?;
    convergence(&opts.out, &done.trace)?;
    for (name, row, title) in [
        ("fit-before.md", &done.trace[0], "the start point"),
        ("fit-after.md", best, "the best candidate"),
    ] {
        let config = space.config(&row.values)?;
        let outcomes = reader.run(&specs(&[config], &p.seeds()))?;
        let runs: Vec<&crate::runner::Outcome> = outcomes.iter().collect();
        let sim = candidate_obs(reader, &runs, target)?;
        let places = crate::compare::runs::places(&reader.detectors(&outcomes[0].key)?);
        let keys: Vec<String> = outcomes.iter().map(|o| o.key.clone()).collect();
        let md = fit_md(p, space, row, title, field, &sim, &places, &keys);
        write(name, md.as_bytes())?;
    }
    write("run.json", &provenance(p, field, opts, space, done)?)
}

fn csv_error(e: impl std::fmt::Display) -> Error {
    Error::Other(format!("cannot encode CSV: {e}"))
}

/// `trace.csv` (numbers in their shortest round-trip form, so equal values give equal bytes).
pub fn trace_csv(space: &Space, trace: &[Row]) -> Result<Vec<u8>, Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut header = vec!["generation".to_string(), "candidate".to_string()];
    header.extend(space.params.iter().map(|q| q.key.clone()));
    header.push("objective".into());
    header.extend(TERMS.iter().map(|t| t.to_string()));
    header.push("pairs".into());
    w.write_record(&header).map_err(csv_error)?;
    for r in trace {
        let mut row = vec![r.generation.to_string(), r.candidate.to_string()];
        row.extend(r.values.iter().map(|v| format!("{v}")));
        row.push(format!("{}", r.objective));
        row.extend(
            r.terms
                .values
                .iter()
                .map(|v| v.map_or(String::new(), |v| format!("{v}"))),
        );
        row.push(r.terms.pairs.to_string());
        w.write_record(&row).map_err(csv_error)?;
    }
    w.into_inner().map_err(csv_error)
}

/// The calibrated scenario: a comment naming the fit, then the resolved scenario.
pub fn calibrated_toml(
    p: &Params,
    opts: &Options,
    space: &Space,
    best: &Row,
) -> Result<String, Error> {
    let config = space.config(&best.values)?;
    let mut out = format!(
        "# Calibrated by `platoonsim calibrate` ({}) from {} to the field data in run.json:\n\
         # objective {} (generation {}, candidate {}). Fitted keys:\n",
        p.origin, opts.scenario, best.objective, best.generation, best.candidate
    );
    for (q, v) in space.params.iter().zip(&best.values) {
        let _ = writeln!(out, "#   {} = {v}   (bounds [{}, {}])", q.key, q.min, q.max);
    }
    for (k, v) in &p.set {
        let _ = writeln!(out, "# fixed: {k} = {v}");
    }
    out.push('\n');
    out.push_str(&platoonsim_scenario::to_toml(&config));
    Ok(out)
}

fn convergence(dir: &std::path::Path, trace: &[Row]) -> Result<(), Error> {
    use platoonsim_plot::{Chart, Series, Style};
    let x: Vec<f64> = (0..trace.len()).map(|i| i as f64).collect();
    let each: Vec<f64> = trace.iter().map(|r| r.objective).collect();
    let mut best = Vec::with_capacity(each.len());
    for v in &each {
        let b: f64 = best.last().copied().unwrap_or(f64::INFINITY);
        best.push(b.min(*v));
    }
    let chart = Chart {
        title: "Calibration: objective by evaluation (0 = the start point)".into(),
        x_label: "Evaluation (candidate)".into(),
        y_label: "Objective (weighted fit terms)".into(),
        series: vec![
            Series {
                name: "each candidate".into(),
                x: x.clone(),
                y: each,
                style: Style::Markers,
                ..Series::default()
            },
            Series {
                name: "best so far".into(),
                x,
                y: best,
                style: Style::Line,
                ..Series::default()
            },
        ],
        y_range: None,
    };
    platoonsim_plot::line_chart(&chart, &dir.join("convergence"))
        .map_err(|e| Error::Other(format!("cannot draw convergence: {e}")))?;
    Ok(())
}

/// Per station: (field flow, sim flow, field speed, sim speed, GEH < 5 share, intervals).
fn by_station(field: &[Obs], sim: &[Obs]) -> BTreeMap<String, [f64; 6]> {
    let sims: BTreeMap<(&str, u32, u32), &Obs> = sim
        .iter()
        .map(|o| ((o.station.as_str(), o.start_s, o.interval_s), o))
        .collect();
    let mut acc: BTreeMap<String, ([f64; 6], f64)> = BTreeMap::new();
    for f in field {
        let Some(s) = sims.get(&(f.station.as_str(), f.start_s, f.interval_s)) else {
            continue;
        };
        let (a, speeds) = acc.entry(f.station.clone()).or_default();
        a[0] += f.flow_vph;
        a[1] += s.flow_vph;
        if let Some(v) = f.speed_kmh {
            a[2] += v;
            a[3] += s.speed_kmh.unwrap_or(0.0);
            *speeds += 1.0;
        }
        let geh = platoonsim_field::fit::geh(s.flow_vph, f.flow_vph);
        a[4] += f64::from(u8::from(geh < platoonsim_field::fit::GEH_LIMIT));
        a[5] += 1.0;
    }
    acc.into_iter()
        .map(|(k, (a, speeds))| {
            let n = a[5];
            let sp = |v: f64| if speeds > 0.0 { v / speeds } else { f64::NAN };
            (k, [a[0] / n, a[1] / n, sp(a[2]), sp(a[3]), a[4] / n, n])
        })
        .collect()
}

/// The fit report of one candidate: its values and terms, then `platoonsim compare`'s report
/// of the mean of its replications against the field (criteria, measures, stations,
/// bottlenecks).
#[allow(clippy::too_many_arguments)]
fn fit_md(
    p: &Params,
    space: &Space,
    row: &Row,
    title: &str,
    field: &Field,
    sim: &[Obs],
    sim_places: &[Placed],
    keys: &[String],
) -> String {
    let mut md = format!(
        "# Fit of {title}\n\n{} against the field data, {}; generation {}, candidate {}.\n\n\
         | key | value |\n|---|---|\n",
        space.scenario,
        match p.replications {
            1 => "one run (seed 1)".to_string(),
            r => format!("mean of {r} replications (seeds 1..={r})"),
        },
        row.generation,
        row.candidate
    );
    for (q, v) in space.params.iter().zip(&row.values) {
        let _ = writeln!(md, "| `{}` | {v} |", q.key);
    }
    md.push_str("\n| term | value | weight |\n|---|---|---|\n");
    for (i, t) in TERMS.iter().enumerate() {
        let _ = writeln!(
            md,
            "| {t} | {} | {} |",
            row.terms.values[i].map_or("–".to_string(), short),
            p.weights.0[i]
        );
    }
    let _ = writeln!(
        md,
        "| **objective** | **{}** | |\n\n{} station intervals matched.\n",
        short(row.objective),
        row.terms.pairs
    );
    md.push_str(
        "At the data's own interval:\n\n| station | intervals | field flow (veh/h) | simulated flow \
         (veh/h) | field speed (km/h) | simulated speed (km/h) | GEH < 5 |\n|---|---|---|---|---|---|---|\n",
    );
    for (st, a) in by_station(&field.obs, sim) {
        let _ = writeln!(
            md,
            "| {st} | {} | {:.0} | {:.0} | {:.1} | {:.1} | {:.0} % |",
            a[5],
            a[0],
            a[1],
            a[2],
            a[3],
            100.0 * a[4]
        );
    }
    md.push('\n');
    let opts = crate::compare::Options {
        window: crate::compare::sim_span(sim),
        ..crate::compare::Options::default()
    };
    let eval = crate::compare::evaluate(sim, &field.obs, sim_places, &field.places, &opts);
    let runs: Vec<String> = keys.iter().map(|k| format!("runs/{k}")).collect();
    let files: Vec<String> = field.files.iter().map(|(f, _)| f.clone()).collect();
    let report = platoonsim_field::report::markdown(&platoonsim_field::report::Report {
        runs: &runs,
        field_files: &files,
        window: eval.window,
        fit: &eval.fit,
        criteria: &eval.criteria,
        ramps: Some((&eval.ramp_fit, &eval.ramp_criteria)),
        bottlenecks: &eval.bottlenecks,
        figure: None,
        notes: &field.notes,
    });
    // The compare report's title becomes a section of this one.
    md.push_str("## platoonsim compare\n\n");
    for line in report.lines() {
        if line.starts_with('#') {
            md.push('#');
        }
        md.push_str(line);
        md.push('\n');
    }
    md
}

#[derive(Serialize)]
struct Point<'a> {
    generation: usize,
    candidate: usize,
    values: BTreeMap<&'a str, f64>,
    objective: f64,
    terms: BTreeMap<&'a str, f64>,
}

fn point_json<'a>(space: &'a Space, r: &Row) -> Point<'a> {
    Point {
        generation: r.generation,
        candidate: r.candidate,
        values: space
            .params
            .iter()
            .map(|q| q.key.as_str())
            .zip(r.values.iter().copied())
            .collect(),
        objective: r.objective,
        terms: TERMS
            .iter()
            .copied()
            .zip(r.terms.values)
            .filter_map(|(t, v)| Some((t, v?)))
            .collect(),
    }
}

fn provenance(
    p: &Params,
    field: &Field,
    opts: &Options,
    space: &Space,
    done: &Done,
) -> Result<Vec<u8>, Error> {
    let json = serde_json::json!({
        "calibrate": p.name,
        "version": VERSION,
        "engine": crate::record::engine_id(),
        "arguments": opts.arguments,
        "scenario": opts.scenario,
        "params_file": p.origin,
        "params": p.text,
        "field_files": field.files.iter().map(|(f, h)| serde_json::json!({"path": f, "fnv1a64": h})).collect::<Vec<_>>(),
        "seeds": p.seeds(),
        "population": p.population,
        "budget": p.budget,
        "evaluations": done.trace.len() - 1,
        "stopped": done.stopped,
        "runs": done.handled,
        "computed": done.computed,
        "reused": done.reused,
        "wall_seconds": done.wall_seconds,
        "finished_unix_s": std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs()),
        "start": point_json(space, &done.trace[0]),
        "best": point_json(space, &done.trace[done.best]),
    });
    let mut bytes = serde_json::to_vec_pretty(&json)
        .map_err(|e| Error::Other(format!("cannot encode run.json: {e}")))?;
    bytes.push(b'\n');
    Ok(bytes)
}
