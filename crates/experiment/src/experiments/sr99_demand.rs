//! `sr99-demand` (issue 4 item 6): the paper's procedure for the SR-99 demand scale. For each
//! penetration, the baseline (no organization) runs at increasing demand scales (a grid,
//! 0.90 to 1.40 in steps of 0.05 by default) until the speed contour shows the corridor's
//! recurrent bottlenecks; the scale found is the smallest at which both are active in the
//! majority of the seeds, and the grid stops there for that penetration.
//!
//! **Criterion** ([`crate::corridor`]): a detector is congested in a 5-min interval whose
//! cross-section mean speed is below 60 km/h; a bottleneck is active if a watched detector
//! stays congested for at least 30 consecutive minutes. Watched: `OR11-up` (50 m upstream of
//! the second Florin Rd on-ramp, the paper's bottleneck "upstream of the second on-ramp at
//! Florin Road") and every mainline detector from `OR1-down` to `OR5-up` (downstream of Elk
//! Grove Blvd, the 3-lane section up to the Sheldon Rd ramps where the queue of the paper's
//! bottleneck "downstream of Elk Grove Boulevard" forms); for the second, any one of them.
//!
//! Without a grid (quick mode), nothing is searched: the criterion is evaluated at the scale
//! of the table (embedded or given) at each penetration.
//!
//! Files besides the usual ones: `demand_scales.toml` (the scales found, in the format of
//! `crates/scenario/scenarios/sr99_demand_scales.toml`; also written to
//! [`Settings::write_table`] if given), `demand_scales.png`/`.svg` and
//! `demand_contours.png`/`.svg` (the baseline's contour at the scale found, first seed).

use super::sr99::{self, Scales};
use super::{checks_md, Check, Done, Experiment, Extra, Figure, Part, Report, Results, Settings};
use crate::corridor;
use crate::paper;
use crate::table::Col;
use crate::table::{fixed, md_table, signed, SummaryRow};
use platoonsim_plot::{heatmap_panels, line_chart, Chart, Heatmap, Series, Style};
use platoonsim_runs::design::{self, num};
use platoonsim_runs::detectors::Scope;
use platoonsim_runs::runner::{Outcome, Runner};
use platoonsim_runs::Metric;
use platoonsim_runs::{Cell, Error, VERSION};
use platoonsim_scenario::{demand_scales, StrategyKind};
use platoonsim_sim::DetectorRecord;
use std::path::{Path, PathBuf};

/// The default grid of demand scales.
pub const SCALE_GRID: [f64; 11] = [
    0.90, 0.95, 1.00, 1.05, 1.10, 1.15, 1.20, 1.25, 1.30, 1.35, 1.40,
];
/// Congested below this 5-min mean speed (km/h).
pub const BOTTLENECK_SPEED_KMH: f64 = 60.0;
/// Active when congested this long (min).
pub const BOTTLENECK_MINUTES: f64 = 30.0;

/// One scale tried at one penetration.
#[derive(Clone, Debug, PartialEq)]
pub struct Try {
    pub scale: f64,
    pub cell: usize,
    /// Seeds in which both bottlenecks were active, of `seeds`.
    pub active: usize,
    pub seeds: usize,
}

/// One penetration's search.
#[derive(Clone, Debug, PartialEq)]
pub struct Search {
    pub penetration: f64,
    /// The scale of the table `sr99` uses.
    pub table_scale: f64,
    pub tried: Vec<Try>,
    /// The smallest scale tried at which both bottlenecks are active in most seeds.
    pub found: Option<f64>,
}

/// What `sr99-demand` keeps besides the runs' metrics.
#[derive(Default)]
pub(crate) struct Data {
    pub searches: Vec<Search>,
    /// Whether a grid was searched (false: only the table's scales were checked).
    pub grid: bool,
    /// The first seed's records at the scale found (or the last tried), per search.
    pub contours: Vec<Vec<DetectorRecord>>,
    pub first_seed: u64,
}

/// The scales tried at each penetration, in order.
pub fn candidates(s: &Settings) -> Result<Vec<Vec<f64>>, Error> {
    let scales = Scales::from_settings(s)?;
    if let Some(bad) = s.scale_grid.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
        return Err(Error::Other(format!(
            "sr99-demand: every demand scale of the grid must be positive (found {bad})"
        )));
    }
    let mut grid = s.scale_grid.clone();
    grid.sort_by(f64::total_cmp);
    grid.dedup();
    Ok(s.network_penetrations
        .iter()
        .map(|&p| {
            if grid.is_empty() {
                vec![scales.at(p)]
            } else {
                grid.clone()
            }
        })
        .collect())
}

pub(super) fn max_cells(s: &Settings) -> usize {
    s.network_penetrations.len() * s.scale_grid.len().max(1)
}

fn majority(active: usize, n: usize) -> bool {
    2 * active > n
}

pub(super) const EXPERIMENT: Experiment = Experiment {
    name: "sr99-demand",
    title: "SR-99 demand scale by penetration: the search for the recurrent bottlenecks",
    help: "The SR-99 demand-scale search: per penetration, the smallest scale of --scales at \
           which the baseline shows both recurrent bottlenecks (see --bottleneck-speed); writes \
           demand_scales.toml (and the embedded table with --write-table).",
    part: Part::Network,
    default_seeds: 3,
    own_period: true,
    safety_group: Some(&["penetration", "demand_scale"]),
    reuse_from: &["sr99"],
    total_runs: |s| s.seeds as usize * max_cells(s),
    run,
    report,
    // No search: the criterion at the table's scales, on the runs `sr99` made.
    quick: |s| {
        super::sr99::quick_penetrations(s);
        s.scale_grid = Vec::new();
    },
};

fn report(r: &Results<'_>) -> Result<Report, Error> {
    let (body, checks) = markdown(r.settings, r.cells, r.rows, r.extra);
    Ok(Report {
        body,
        checks,
        figures: figures(r.dir, r.extra)?,
        files: files(r.settings, r.dir, r.extra),
    })
}

pub(super) fn run(s: &Settings, runner: &Runner<'_>, seeds: &[u64]) -> Result<Done, Error> {
    let cands = candidates(s)?;
    let scales = Scales::from_settings(s)?;
    let crit = sr99::criterion(s);
    let mut searches: Vec<Search> = s
        .network_penetrations
        .iter()
        .map(|&p| Search {
            penetration: p,
            table_scale: scales.at(p),
            tried: Vec::new(),
            found: None,
        })
        .collect();
    let mut cells: Vec<Cell> = Vec::new();
    let mut outcomes: Vec<Outcome> = Vec::new();
    let steps = cands.iter().map(Vec::len).max().unwrap_or(0);
    for step in 0..steps {
        let open: Vec<usize> = (0..searches.len())
            .filter(|&i| searches[i].found.is_none() && step < cands[i].len())
            .collect();
        if open.is_empty() {
            break;
        }
        let mut new = Vec::new();
        for &i in &open {
            let p = searches[i].penetration;
            new.push(sr99::cell(s, p, StrategyKind::NONE, cands[i][step])?);
        }
        let mut specs = design::runs(&new, seeds);
        design::keep_detectors(&mut specs, Scope::CrossSection, |_, _| true);
        let offset = cells.len();
        let mut done = runner.run(&specs)?;
        for o in done.iter_mut() {
            o.cell += offset;
            let b = corridor::bottlenecks(&runner.detectors(&o.key)?, &crit);
            o.fields.set("florin_congested_min", b.florin_min);
            o.fields.set("south_congested_min", b.south_min);
            o.fields
                .set("bottlenecks_active", f64::from(u8::from(b.active(&crit))));
        }
        for (j, &i) in open.iter().enumerate() {
            let cell = offset + j;
            let active = done
                .iter()
                .filter(|o| o.cell == cell && o.fields.get("bottlenecks_active") == Some(1.0))
                .count();
            let scale = cands[i][step];
            searches[i].tried.push(Try {
                scale,
                cell,
                active,
                seeds: seeds.len(),
            });
            if majority(active, seeds.len()) {
                searches[i].found = Some(scale);
            }
        }
        cells.extend(new);
        outcomes.extend(done);
        // The bar's length: what is done plus the most that can still come.
        let left: usize = (0..searches.len())
            .filter(|&i| searches[i].found.is_none())
            .map(|i| cands[i].len().saturating_sub(step + 1) * seeds.len())
            .sum();
        runner.bar.set_length(runner.bar.position() + left as u64);
    }

    // Cells in (penetration, scale) order, as every other experiment's tables.
    let mut order: Vec<usize> = (0..cells.len()).collect();
    let key = |c: &Cell| {
        let f = |k: &str| c.labels.get(k).and_then(|v| v.parse::<f64>().ok());
        (f("penetration"), f("demand_scale"))
    };
    order.sort_by(|&a, &b| {
        let (ka, kb) = (key(&cells[a]), key(&cells[b]));
        ka.0.partial_cmp(&kb.0)
            .unwrap_or(std::cmp::Ordering::Equal)
            .then(ka.1.partial_cmp(&kb.1).unwrap_or(std::cmp::Ordering::Equal))
    });
    let mut new_index = vec![0; cells.len()];
    for (n, &old) in order.iter().enumerate() {
        new_index[old] = n;
    }
    let cells: Vec<Cell> = order.iter().map(|&i| cells[i].clone()).collect();
    for o in outcomes.iter_mut() {
        o.cell = new_index[o.cell];
    }
    outcomes.sort_by_key(|o| (o.cell, o.seed));
    for t in searches.iter_mut().flat_map(|x| x.tried.iter_mut()) {
        t.cell = new_index[t.cell];
    }

    let first_seed = seeds[0];
    let mut contours = Vec::new();
    for x in &searches {
        let shown = x
            .tried
            .iter()
            .find(|t| Some(t.scale) == x.found)
            .or(x.tried.last());
        let recs = match shown.and_then(|t| {
            outcomes
                .iter()
                .find(|o| o.cell == t.cell && o.seed == first_seed)
        }) {
            Some(o) => runner.detectors(&o.key)?,
            None => Vec::new(),
        };
        contours.push(recs);
    }
    Ok(Done {
        cells,
        outcomes,
        extra: Extra::Demand(Data {
            searches,
            grid: !s.scale_grid.is_empty(),
            contours,
            first_seed,
        }),
    })
}

fn criterion_text(s: &Settings) -> String {
    format!(
        "A mainline detector is *congested* in a 5-min interval whose cross-section mean speed \
         is below {} km/h (an interval in which nobody crossed counts as congested only if the \
         detector was occupied more than half of it); a bottleneck is *active* if a watched \
         detector stays congested for at least {} consecutive minutes. The bottleneck upstream \
         of the second Florin Rd on-ramp is watched at `{}`; the one downstream of Elk Grove \
         Blvd at every mainline detector from `{}` to `{}` (any one of them). The scale found \
         is the smallest at which both are active in the majority of the seeds.",
        num(s.bottleneck_speed_kmh),
        num(s.bottleneck_minutes),
        corridor::FLORIN_DETECTOR,
        corridor::SOUTH_FIRST,
        corridor::SOUTH_LAST
    )
}

pub(super) fn markdown(
    s: &Settings,
    cells: &[Cell],
    rows: &[SummaryRow],
    extra: &Extra,
) -> (String, Vec<Check>) {
    let Extra::Demand(d) = extra else {
        return (String::new(), Vec::new());
    };
    let duration = cells.first().map_or(14400.0, |c| c.config.duration_s);
    let source = Scales::from_settings(s).map_or_else(|e| e.to_string(), |x| x.source);
    let mut md = if d.grid {
        format!(
            "The paper's procedure on the `sr99` corridor ({} s from 05:00, baseline without \
             organization, {} per scale): for each penetration, the demand scale is raised \
             over the grid {} until the recurrent bottlenecks show; the grid stops there. {}\n\n",
            num(duration),
            sr99::seeds_text(s.seeds),
            s.scale_grid
                .iter()
                .map(|v| num(*v))
                .collect::<Vec<_>>()
                .join(", "),
            criterion_text(s)
        )
    } else {
        format!(
            "**No search** (quick mode, or no grid given): the criterion is evaluated only at the \
             scale of {source} at each penetration ({} s from 05:00, baseline, {}). {}\n\n",
            num(duration),
            sr99::seeds_text(s.seeds),
            criterion_text(s)
        )
    };
    md.push_str("## Demand scale by penetration\n\n");
    let header: Vec<String> = [
        "CAV (%)",
        if d.grid {
            "Found, ours (×)"
        } else {
            "Table scale (×): both bottlenecks?"
        },
        "Paper (×)",
        "Ours − paper (×)",
        "Table used by `sr99` (×)",
    ]
    .iter()
    .map(|h| h.to_string())
    .collect();
    let mut trs = Vec::new();
    for x in &d.searches {
        let paper = paper::sr99_demand_scale(x.penetration);
        let ours = if d.grid {
            x.found.map_or_else(
                || format!("not reached (≤ {})", num(last_scale(x))),
                |v| fixed(v, 2),
            )
        } else {
            format!(
                "{}: {}",
                fixed(x.table_scale, 2),
                if x.found.is_some() { "yes" } else { "no" }
            )
        };
        let diff = match (x.found, paper) {
            (Some(a), Some(b)) if d.grid => signed(a - b, 2),
            _ => "–".into(),
        };
        trs.push(vec![
            format!("{} %", num(100.0 * x.penetration)),
            ours,
            paper.map_or("–".into(), |v| fixed(v, 2)),
            diff,
            fixed(x.table_scale, 2),
        ]);
    }
    md.push_str(&md_table(&header, &trs));

    md.push_str(
        "\n## Every scale tried\n\nPer cell: seeds with both bottlenecks active, and the means \
         over the seeds of the longest congested stretch at each bottleneck (min) and of the \
         network discharge (veh/h).\n\n",
    );
    let header: Vec<String> = [
        "CAV (%)",
        "Scale (×)",
        "Both active (seeds)",
        "Florin Rd (min)",
        "Elk Grove Blvd stretch (min)",
        "Network discharge (veh/h)",
    ]
    .iter()
    .map(|h| h.to_string())
    .collect();
    let mean = |c: usize, m: Col| {
        rows.iter()
            .find(|r| r.cell == c && r.metric == m.name())
            .map_or(f64::NAN, |r| r.stats.mean)
    };
    let mut trs = Vec::new();
    for x in &d.searches {
        for t in &x.tried {
            trs.push(vec![
                format!("{} %", num(100.0 * x.penetration)),
                fixed(t.scale, 2),
                format!("{}/{}", t.active, t.seeds),
                fixed(mean(t.cell, Col::Derived("florin_congested_min")), 0),
                fixed(mean(t.cell, Col::Derived("south_congested_min")), 0),
                fixed(mean(t.cell, Metric::NETWORK_DISCHARGE.into()), 0),
            ]);
        }
    }
    md.push_str(&md_table(&header, &trs));

    let checks = checks(d);
    md.push_str("\n## Checks\n\n");
    md.push_str(&checks_md(&checks));
    (md, checks)
}

fn last_scale(x: &Search) -> f64 {
    x.tried.last().map_or(f64::NAN, |t| t.scale)
}

fn checks(d: &Data) -> Vec<Check> {
    let pens = d
        .searches
        .iter()
        .map(|x| num(100.0 * x.penetration))
        .collect::<Vec<_>>()
        .join("/");
    let all_found = d.searches.iter().all(|x| x.found.is_some());
    if !d.grid {
        return vec![Check {
            statement: format!(
                "at the table's demand scales both recurrent bottlenecks show at {pens} % CAV \
                 (missing at: {})",
                missing(d)
            ),
            passed: all_found,
        }];
    }
    let found: Vec<f64> = d.searches.iter().filter_map(|x| x.found).collect();
    vec![
        Check {
            statement: format!(
                "both recurrent bottlenecks show within the grid at {pens} % CAV (not reached \
                 at: {})",
                missing(d)
            ),
            passed: all_found,
        },
        Check {
            statement: format!(
                "the scale found does not decrease with the penetration, as in the paper \
                 (100/100/110/117/125/127 %): {}",
                found
                    .iter()
                    .map(|v| fixed(*v, 2))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            passed: all_found && found.windows(2).all(|w| w[1] >= w[0]),
        },
    ]
}

fn missing(d: &Data) -> String {
    let m: Vec<String> = d
        .searches
        .iter()
        .filter(|x| x.found.is_none())
        .map(|x| format!("{} %", num(100.0 * x.penetration)))
        .collect();
    if m.is_empty() {
        "none".into()
    } else {
        m.join(", ")
    }
}

/// The table file of the scales found (penetrations without one: `feasible = false`).
pub fn table_toml(s: &Settings, searches: &[Search]) -> String {
    let header = format!(
        "Demand scale by CAV penetration found by `platoonsim experiment sr99-demand`\n\
         (platoonsim {VERSION}): the smallest scale of the grid {:?} at which the baseline shows\n\
         both recurrent bottlenecks of the sr99 corridor in most of {} seeds (5-min mean speed\n\
         below {} km/h for at least {} min at {} and at one detector from {} to {}).\n\
         Read by platoonsim_scenario::demand_scales; copy over {} and rebuild to use it.",
        s.scale_grid,
        s.seeds,
        num(s.bottleneck_speed_kmh),
        num(s.bottleneck_minutes),
        corridor::FLORIN_DETECTOR,
        corridor::SOUTH_FIRST,
        corridor::SOUTH_LAST,
        demand_scales::TABLE_PATH
    );
    let rows: Vec<demand_scales::Row> = searches
        .iter()
        .filter_map(|x| {
            x.found.map(|v| demand_scales::Row {
                penetration: x.penetration,
                demand_scale: v,
            })
        })
        .collect();
    let mut t = demand_scales::to_toml(&header, &rows);
    for x in searches.iter().filter(|x| x.found.is_none()) {
        t.push_str(&format!(
            "\n[[penetration]]\npenetration = {}\nfeasible = false  # not reached up to {}\n",
            num(x.penetration),
            num(last_scale(x))
        ));
    }
    t
}

/// `demand_scales.toml` (and the table file to write, if asked); nothing without a grid.
pub(super) fn files(s: &Settings, dir: &Path, extra: &Extra) -> Vec<(PathBuf, Vec<u8>)> {
    let Extra::Demand(d) = extra else {
        return Vec::new();
    };
    if !d.grid {
        return Vec::new();
    }
    let text = table_toml(s, &d.searches).into_bytes();
    let mut out = vec![(dir.join("demand_scales.toml"), text.clone())];
    if let Some(p) = &s.write_table {
        out.push((p.clone(), text));
    }
    out
}

pub(super) fn figures(dir: &Path, extra: &Extra) -> Result<Vec<Figure>, Error> {
    let Extra::Demand(d) = extra else {
        return Ok(Vec::new());
    };
    let err = |e: platoonsim_plot::PlotError| Error::Other(e.to_string());
    let x: Vec<f64> = d.searches.iter().map(|x| 100.0 * x.penetration).collect();
    let mut series = vec![Series {
        name: if d.grid {
            "ours: smallest scale with both bottlenecks".into()
        } else {
            "table scale where both bottlenecks show".into()
        },
        x: x.clone(),
        y: d.searches
            .iter()
            .map(|x| x.found.unwrap_or(f64::NAN))
            .collect(),
        band: None,
        style: Style::Line,
    }];
    series.push(Series {
        name: "table used by sr99".into(),
        x: x.clone(),
        y: d.searches.iter().map(|x| x.table_scale).collect(),
        band: None,
        style: Style::Dashed,
    });
    series.push(Series {
        name: "paper".into(),
        x: x.clone(),
        y: d.searches
            .iter()
            .map(|x| paper::sr99_demand_scale(x.penetration).unwrap_or(f64::NAN))
            .collect(),
        band: None,
        style: Style::Markers,
    });
    let chart = Chart {
        title: "SR-99 demand scale at which the recurrent bottlenecks show".into(),
        x_label: "CAV penetration (%)".into(),
        y_label: "Demand scale".into(),
        series,
        y_range: None,
    };
    line_chart(&chart, &dir.join("demand_scales")).map_err(err)?;
    let mut out = vec![Figure {
        title: format!(
            "Demand scale by penetration: {}; dashed: the table `sr99` uses; markers: the \
             paper's scales",
            if d.grid {
                "the smallest scale of the grid with both recurrent bottlenecks (gaps: not reached)"
            } else {
                "the table's scale where both bottlenecks show (no search)"
            }
        ),
        stem: "demand_scales".into(),
    }];

    let maps: Vec<Heatmap> = d
        .searches
        .iter()
        .zip(&d.contours)
        .filter(|(_, recs)| !recs.is_empty())
        .map(|(x, recs)| {
            let k = corridor::contour(recs);
            let scale = x.found.unwrap_or_else(|| last_scale(x));
            Heatmap {
                title: format!(
                    "{} % CAV, scale {}{}",
                    num(100.0 * x.penetration),
                    fixed(scale, 2),
                    if x.found.is_some() {
                        ""
                    } else {
                        " (not reached)"
                    }
                ),
                x_label: "Time from 05:00 (min)".into(),
                y_label: "Mainline detector".into(),
                x: k.times_min,
                y: (1..=k.detectors.len()).map(|j| j as f64).collect(),
                z: k.speed_kmh,
                z_label: "Speed (km/h)".into(),
                z_range: super::sr99_figures::SPEED_RANGE,
            }
        })
        .collect();
    if !maps.is_empty() {
        heatmap_panels(
            &maps,
            3,
            "SR-99 baseline speed contours at the demand scale found",
            &dir.join("demand_contours"),
        )
        .map_err(err)?;
        out.push(Figure {
            title: format!(
                "Baseline speed contours (seed {}) at the scale found for each penetration (or \
                 the last tried); detector index 1 = most upstream",
                d.first_seed
            ),
            stem: "demand_contours".into(),
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn candidates_are_the_grid_or_the_table() {
        let s = Settings {
            scale_grid: vec![1.1, 1.0, 1.1],
            ..Settings::default()
        };
        let c = candidates(&s).unwrap();
        assert_eq!(c.len(), 6);
        assert!(c.iter().all(|g| g == &[1.0, 1.1]));
        assert_eq!(max_cells(&s), 6 * 3);
        let quick = Settings {
            scale_grid: vec![],
            ..Settings::default()
        };
        let c = candidates(&quick).unwrap();
        assert_eq!(
            c,
            vec![
                vec![1.0],
                vec![1.0],
                vec![1.1],
                vec![1.17],
                vec![1.25],
                vec![1.27]
            ]
        );
        assert_eq!(max_cells(&quick), 6);
        let bad = Settings {
            scale_grid: vec![0.0],
            ..Settings::default()
        };
        assert!(candidates(&bad).is_err());
        assert_eq!(SCALE_GRID.len(), 11);
        assert!(majority(2, 3) && !majority(1, 2) && majority(1, 1));
    }

    #[test]
    fn the_table_file_reads_back() {
        let searches = vec![
            Search {
                penetration: 0.0,
                table_scale: 1.0,
                tried: vec![],
                found: Some(1.15),
            },
            Search {
                penetration: 0.2,
                table_scale: 1.0,
                tried: vec![Try {
                    scale: 1.4,
                    cell: 0,
                    active: 0,
                    seeds: 3,
                }],
                found: None,
            },
        ];
        let t = table_toml(&Settings::default(), &searches);
        assert!(t.starts_with("# Demand scale by CAV penetration found by"));
        assert!(t.contains("feasible = false  # not reached up to 1.4"));
        let rows = demand_scales::parse(&t).unwrap();
        assert_eq!(
            rows,
            vec![demand_scales::Row {
                penetration: 0.0,
                demand_scale: 1.15
            }]
        );
    }
}
