//! SUMO in: a network (`.net.xml`), routes (`.rou.xml`) and additional files (`.add.xml`) as a
//! corridor scenario file. docs/import.md describes every rule; the steps are one file each:
//! [`net`] reads the network, [`mainline`] picks the corridor's edges, [`corridor`] turns
//! them into lane stretches and ramps, [`routes`] and [`demand`] turn the routes into the
//! series per interval, [`additional`] places the induction loops, [`vtypes`] maps the vehicle
//! types, [`scenario`] writes the file.

pub mod additional;
pub mod corridor;
pub mod demand;
pub mod mainline;
pub mod net;
mod router;
pub mod routes;
pub mod scenario;
pub mod synth;
#[cfg(test)]
mod testnet;
pub mod vtypes;
mod xml;

use crate::{ImportError, Notes};
use std::path::PathBuf;

/// What `platoonsim import sumo` was asked.
#[derive(Clone, Debug, Default)]
pub struct Options {
    pub net: PathBuf,
    pub routes: Vec<PathBuf>,
    pub additional: Vec<PathBuf>,
    /// The mainline's edges in order; found by [`mainline::find`] without it.
    pub mainline: Option<Vec<String>>,
    /// A detector at the downstream end of each mainline edge, named by the edge.
    pub edge_detectors: bool,
    pub interval_s: Option<f64>,
    pub duration_s: Option<f64>,
    /// The scenario's name (default: the network file's stem).
    pub name: Option<String>,
}

/// An import: the scenario file's text and what was kept, reduced and dropped.
#[derive(Clone, Debug)]
pub struct Imported {
    pub toml: String,
    pub notes: Notes,
}

/// Where an edge detector sits: this far before the edge's downstream end (m).
pub const EDGE_DETECTOR_BEFORE_END_M: f64 = 1.0;
/// Where vehicles leave the road at an edge's end (the road end, an off-ramp's diverge), its
/// detector sits this far before the end instead, as the scenario's `end` detector does: a
/// vehicle leaves in the step its front passes the end or the diverge, before the detectors
/// look, so a detector within one step's travel of that point (up to 8.9 m at 160 km/h and
/// Δt = 0.2 s) would miss the vehicles that cross it in that step.
pub const EXIT_EDGE_DETECTOR_BEFORE_END_M: f64 = 10.0;
/// The interval when the flows' times give none (s).
pub const DEFAULT_INTERVAL_S: f64 = 900.0;
/// The shortest interval derived from the flows' times (s); a finer grid falls back to
/// [`DEFAULT_INTERVAL_S`].
pub const MIN_INTERVAL_S: f64 = 60.0;
/// The run's duration without routes (s).
pub const DEFAULT_DURATION_S: f64 = 3600.0;
/// The most intervals a series may have.
pub const MAX_INTERVALS: usize = 10_000;
/// The most (demand route, interval) pairs an import spreads: a routes file of a million
/// single vehicles over 100 intervals.
pub const MAX_DEMAND_WORK: u64 = 100_000_000;
/// The longest run an import writes (s): 7 days.
pub const MAX_DURATION_S: f64 = 7.0 * 86_400.0;

fn positive(flag: &'static str, v: Option<f64>, max: f64) -> Result<Option<f64>, ImportError> {
    match v {
        Some(x) if !(x.is_finite() && x > 0.0 && x <= max) => Err(ImportError::Flag {
            flag,
            value: x.to_string(),
            problem: format!("must be a number of seconds in (0, {max}]"),
        }),
        v => Ok(v),
    }
}

/// The run's duration: given, else the end of the demand.
fn duration(
    opts: &Options,
    demands: &[routes::Demand],
    notes: &mut Notes,
) -> Result<f64, ImportError> {
    if let Some(d) = positive("--duration-s", opts.duration_s, MAX_DURATION_S)? {
        return Ok(d);
    }
    let mut end: f64 = 0.0;
    for d in demands {
        end = end.max(match d.when {
            routes::When::Rate { end, .. } => end,
            routes::When::At(t) => (t / 60.0).floor() * 60.0 + 60.0,
        });
    }
    if end <= 0.0 {
        return Ok(DEFAULT_DURATION_S);
    }
    if end > MAX_DURATION_S {
        return Err(ImportError::Flag {
            flag: "--duration-s",
            value: "(not given)".into(),
            problem: format!(
                "the demand runs to {end} s, longer than an import writes ({MAX_DURATION_S} s); \
                 give --duration-s"
            ),
        });
    }
    if end > 4.0 * 3600.0 {
        notes.reduce(format!(
            "the run lasts to the end of the demand, {end} s (give --duration-s for a shorter run)"
        ));
    }
    Ok(end)
}

/// The demand interval: given, else the greatest common divisor of the flows' begin and end
/// times inside the run (whole seconds) and the run's length, if at least
/// [`MIN_INTERVAL_S`]; else [`DEFAULT_INTERVAL_S`].
fn interval(
    opts: &Options,
    demands: &[routes::Demand],
    duration: f64,
    notes: &mut Notes,
) -> Result<f64, ImportError> {
    if let Some(i) = positive("--interval-s", opts.interval_s, MAX_DURATION_S)? {
        if (duration / i).ceil() as usize > MAX_INTERVALS {
            return Err(ImportError::Flag {
                flag: "--interval-s",
                value: i.to_string(),
                problem: format!("gives more than {MAX_INTERVALS} intervals over {duration} s"),
            });
        }
        return Ok(i);
    }
    let mut times = vec![duration];
    let mut any_flow = false;
    for d in demands {
        if let routes::When::Rate { begin, end, .. } = d.when {
            any_flow = true;
            times.extend(
                [begin, end]
                    .into_iter()
                    .filter(|&t| t > 0.0 && t < duration),
            );
        }
    }
    if !any_flow {
        return Ok(DEFAULT_INTERVAL_S.min(duration));
    }
    let whole = times.iter().all(|t| (t - t.round()).abs() < 1e-9);
    let g = if whole {
        times.iter().map(|t| t.round() as u64).fold(0, gcd) as f64
    } else {
        0.0
    };
    if g >= MIN_INTERVAL_S && (duration / g).ceil() as usize <= MAX_INTERVALS {
        Ok(g)
    } else {
        notes.reduce(format!(
            "the flows begin and end off a {MIN_INTERVAL_S}-s grid: demand averaged over \
             {DEFAULT_INTERVAL_S}-s intervals (give --interval-s to choose)"
        ));
        Ok(DEFAULT_INTERVAL_S.min(duration))
    }
}

/// m/s to km/h, to 0.1 km/h: SUMO writes limits as m/s rounded to 0.01 (80 km/h is 22.22).
fn kmh(mps: f64) -> f64 {
    (mps * 36.0).round() / 10.0
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// Imports a SUMO network with its routes and loops.
pub fn import(opts: &Options) -> Result<Imported, ImportError> {
    let net_text = crate::read::text(&opts.net)?;
    let routes = crate::read::texts(&opts.routes)?;
    let additional = crate::read::texts(&opts.additional)?;
    from_texts(opts, &net_text, &routes, &additional)
}

/// [`import`] for texts already read (`opts`' paths then only name the files in messages):
/// the network's, and the routes and additional files' with their paths, in order.
pub fn from_texts(
    opts: &Options,
    net_text: &str,
    routes_texts: &[(PathBuf, String)],
    additional_texts: &[(PathBuf, String)],
) -> Result<Imported, ImportError> {
    let mut notes = Notes::default();
    let net = net::parse(&opts.net, net_text)?;
    let chain = match &opts.mainline {
        Some(ids) => mainline::given(&net, ids)?,
        None => mainline::find(&net)?,
    };
    let on_chain = chain.len();
    let c = corridor::build(&net, chain, &mut notes)?;
    let others = net
        .edges
        .iter()
        .enumerate()
        .filter(|(i, e)| {
            c.position(*i).is_none()
                && c.on_ramp_of(*i).is_none()
                && c.off_ramp_of(*i).is_none()
                && !e.lanes.is_empty()
        })
        .count();
    if others > 0 {
        notes.drop(format!(
            "{others} edges that are neither the mainline ({on_chain} edges) nor the last edge of \
             a ramp (ramp roads upstream and downstream, the other carriageway, other roads)"
        ));
    }
    notes.keep(format!(
        "{} on-ramps, {} off-ramps",
        c.on_ramps.len(),
        c.off_ramps.len()
    ));

    let routes = routes::parse(routes_texts, &net, &mut notes)?;
    let duration = duration(opts, &routes.demands, &mut notes)?;
    let interval = interval(opts, &routes.demands, duration, &mut notes)?;
    if routes_texts.is_empty() {
        notes.reduce(
            "no routes file: every demand is 0 (edit mainline_vph and the ramps' demand_vph)",
        );
    }
    // Each demand is spread over every interval: bound the work before doing it.
    let count = (duration / interval).ceil() as u64;
    let paths: u64 = routes.demands.iter().map(|d| d.paths.len() as u64).sum();
    if paths.saturating_mul(count) > MAX_DEMAND_WORK {
        return Err(ImportError::Flag {
            flag: "--routes",
            value: format!("({paths} routes of flows and vehicles)"),
            problem: format!(
                "{paths} routes over {count} intervals is more than this import spreads \
                 ({MAX_DEMAND_WORK}); give a longer --interval-s or fewer vehicles (flows)"
            ),
        });
    }
    let names = |i: usize| net.edges[i].id.clone();
    let series = demand::series(&c, &routes.demands, interval, duration, &names, &mut notes);

    let (loops, other_add) = additional::parse(additional_texts, &net)?;
    let placed = additional::place(&loops, &net, &c, &mut notes);
    for (tag, n) in other_add {
        notes.drop(format!("{n} {tag} elements of the additional files"));
    }
    let max = platoonsim_scenario::limits::MAX_DETECTORS;
    if opts.edge_detectors && c.chain.len() + placed.mainline.len() > max {
        return Err(ImportError::Flag {
            flag: "--edge-detectors",
            value: "given".into(),
            problem: format!(
                "the mainline has {} edges (and {} loop detectors): a detector per edge would \
                 be more than the {max} a scenario may have; leave the flag out or give a \
                 shorter --mainline",
                c.chain.len(),
                placed.mainline.len()
            ),
        });
    }
    let edge_detectors: Vec<(String, f64)> = if opts.edge_detectors {
        c.chain
            .iter()
            .enumerate()
            .map(|(k, &e)| {
                let end = c.start[k] + net.edges[e].length();
                let exits_here = k + 1 == c.chain.len() || c.off_ramps.iter().any(|r| r.x == end);
                let before = if exits_here {
                    EXIT_EDGE_DETECTOR_BEFORE_END_M
                } else {
                    EDGE_DETECTOR_BEFORE_END_M
                };
                (
                    corridor::sanitize(&net.edges[e].id),
                    additional::inside((end - before).max(c.start[k]), c.length),
                )
            })
            .collect()
    } else {
        Vec::new()
    };
    // An edge detector is named by its edge, a loop by its id: SUMO allows a loop and an edge
    // of one id, a scenario not two detectors of one name (issue 48 D15).
    let mut edge_detectors = edge_detectors;
    let mut renamed = Vec::new();
    {
        let mut taken: std::collections::HashSet<String> =
            placed.mainline.iter().map(|p| p.name.clone()).collect();
        for (name, _) in edge_detectors.iter_mut() {
            if taken.contains(name.as_str()) {
                let mut n = 1;
                let mut new = format!("{name}_end");
                while taken.contains(&new) {
                    n += 1;
                    new = format!("{name}_end{n}");
                }
                renamed.push(format!("{name} -> {new}"));
                *name = new;
            }
            taken.insert(name.clone());
        }
    }
    if !renamed.is_empty() {
        notes.reduce(format!(
            "{} edge detector(s) renamed, a loop has the edge's id: {}",
            renamed.len(),
            renamed.join(", ")
        ));
    }

    // Speed limits: the ramps' as ramp_speed_kmh (their median), the mainline's as a cap when
    // it is one value.
    let mut ramp_speeds: Vec<f64> = c.on_ramps.iter().map(|r| kmh(r.speed)).collect();
    ramp_speeds.sort_by(f64::total_cmp);
    let ramp_speed_kmh = ramp_speeds.get(ramp_speeds.len() / 2).copied();
    if ramp_speeds.len() > 1 && ramp_speeds[0] != ramp_speeds[ramp_speeds.len() - 1] {
        notes.reduce(format!(
            "on-ramp speed limits {:.0}-{:.0} km/h: one ramp speed for all, the median {:.0} km/h",
            ramp_speeds[0],
            ramp_speeds[ramp_speeds.len() - 1],
            ramp_speed_kmh.unwrap_or(0.0)
        ));
    }
    let limits: Vec<f64> = c.chain.iter().map(|&e| kmh(net.edges[e].speed())).collect();
    let max_limit = limits.iter().copied().fold(0.0, f64::max);
    let uniform = limits.iter().all(|&v| (v - max_limit).abs() < 0.05);
    let speed_data: Vec<String> = c
        .chain
        .iter()
        .zip(&limits)
        .enumerate()
        // Only where the limit changes: a line per edge made the file of a long chain of
        // short edges larger than a scenario may be (issue 48, 100,000 edges: 3.4 MB).
        .filter(|&(k, (_, v))| k == 0 || (v - limits[k - 1]).abs() >= 0.05)
        .map(|(k, (&e, v))| format!("{} at x = {:.1} m: {v:.1}", net.edges[e].id, c.start[k]))
        .collect();
    if !uniform {
        notes.reduce(format!(
            "mainline speed limits vary along the corridor ({:.0}-{max_limit:.0} km/h): the \
             model has one, the highest, as the desired-speed cap (the others are in the header)",
            limits.iter().copied().fold(f64::INFINITY, f64::min)
        ));
    }
    let human_defaults = platoonsim_scenario::raw::RawScenario::default().human;
    let d = human_defaults.desired_speed_kmh;
    // A cap at or above every desired speed changes nothing: leave the key out then.
    let lane_speed_limit_kmh = (max_limit < d.max).then_some(max_limit);
    if let Some(v) = lane_speed_limit_kmh {
        notes.keep(format!(
            "mainline speed limit {v:.1} km/h as network.lane_speed_limits_kmh"
        ));
    }
    let human = vtypes::human(
        &routes,
        &series.by_type,
        (d.mean, d.sd, d.min, d.max),
        &mut notes,
    );

    let stem = opts
        .net
        .file_name()
        .and_then(|s| s.to_str())
        .map(|s| {
            s.trim_end_matches(".gz")
                .trim_end_matches(".xml")
                .trim_end_matches(".net")
        })
        .unwrap_or("imported")
        .to_string();
    let name = opts.name.clone().unwrap_or(stem);
    let description = format!(
        "Imported from SUMO: {} edges of {} ({:.0} m), {} on-ramps, {} off-ramps",
        c.chain.len(),
        // The file's name only: the description travels with the scenario (an absolute path
        // told where the importing user kept their files).
        opts.net.file_name().map_or_else(
            || opts.net.display().to_string(),
            |n| n.to_string_lossy().into_owned()
        ),
        c.length,
        c.on_ramps.len(),
        c.off_ramps.len()
    );
    let parts = scenario::Parts {
        name: &name,
        description,
        corridor: &c,
        series: &series,
        duration_s: duration,
        detectors: &placed,
        edge_detectors: &edge_detectors,
        ramp_speed_kmh,
        lane_speed_limit_kmh,
        human,
    };
    let mut sources = vec![format!("network {}", opts.net.display())];
    sources.extend(
        opts.routes
            .iter()
            .map(|p| format!("routes {}", p.display())),
    );
    sources.extend(
        opts.additional
            .iter()
            .map(|p| format!("additional {}", p.display())),
    );
    let body = platoonsim_scenario::format::pretty(&scenario::table(&parts));
    let toml = scenario::header(&sources, &notes, &speed_data) + &body;
    Ok(Imported { toml, notes })
}
