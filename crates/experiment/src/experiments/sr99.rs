//! `sr99` (issue 4 item 6): the paper's freeway experiment on the built-in `sr99` corridor
//! (SR-99 NB, 05:00-09:00). At 20, 40, 60 and 80 % CAV the baseline (no organization), the
//! PD lane and the Flow-Aware PD lane; at 0 and 100 % the baseline only. Each penetration
//! runs at its demand scale (the embedded table, the paper's 100/100/110/117/125/127 %, unless
//! a table file or one scale is given). Per seed pair with the baseline at the same
//! penetration: the changes of the network discharge, the lane changes per vehicle and L̄ (%).
//!
//! The first seed of the 40 % cells keeps its detector records (every lane): the speed
//! contours (paper Fig. 6) and the lane-by-lane CAV flow ratio and speed upstream of Florin
//! Rd (Fig. 7); see `sr99_figures.rs`.

use super::{
    checks_md, find, grid, Check, Done, Experiment, Extra, Part, Report, Results, Settings,
};
use crate::corridor::{self, Criterion};
use crate::paper;
use crate::table::Col;
use crate::table::{self, fixed, md_table, pm, signed, SummaryRow};
use platoonsim_runs::design::{self, num, Cell, Labels};
use platoonsim_runs::detectors::Scope;
use platoonsim_runs::metric::{Field, Metric};
use platoonsim_runs::runner::Runner;
use platoonsim_runs::sweep::spec::{Axis, Spec};
use platoonsim_runs::Error;
use platoonsim_scenario::{demand_scale_set, demand_scales, load_with, Overrides, StrategyKind};
use platoonsim_sim::{Config, DetectorRecord};

/// The built-in scenario.
pub const SCENARIO: &str = "sr99";
/// The paper's penetrations.
pub const PENETRATIONS: [f64; 6] = [0.0, 0.2, 0.4, 0.6, 0.8, 1.0];
/// The penetration of the contour and lane figures (paper Figs. 6 and 7).
pub const FIGURE_PENETRATION: f64 = 0.4;
/// The strategies at a penetration strictly between 0 and 1.
pub const STRATEGIES: [StrategyKind; 3] = [
    StrategyKind::NONE,
    StrategyKind::PD,
    StrategyKind::FLOW_AWARE,
];

/// Changes vs the baseline at the same penetration: (name, metric it is computed from). The
/// last is L̄ under the strict link statistic (spec 6.15: a link only while the follower keeps
/// a time gap ≤ 2 s), which the paper does not report.
pub const CHANGES: [(&str, Metric); 4] = [
    (
        "discharge_change_pct",
        Metric::Field(Field::NetworkDischarge),
    ),
    (
        "lane_changes_change_pct",
        Metric::Field(Field::LaneChangesPerVehicle),
    ),
    ("platoon_length_change_pct", Metric::AVG_PLATOON_LENGTH),
    (
        "platoon_length_tg2_change_pct",
        Metric::Field(Field::AvgPlatoonLengthTg2),
    ),
];

/// What `sr99` keeps besides the runs' metrics.
#[derive(Default)]
pub(crate) struct Data {
    /// The detector records of the figure runs: (cell, records), baseline / PD / Flow-Aware.
    pub figure_runs: Vec<(usize, Vec<DetectorRecord>)>,
    /// The seed of those runs.
    pub figure_seed: u64,
}

/// The grid: `sweeps/sr99.toml`.
pub const SWEEP: &str = include_str!("../../../../sweeps/sr99.toml");

/// Strategies planned at a penetration, in the order of [`STRATEGIES`]: what the cells hold,
/// so the sweep file's `[[skip]]` (the baseline alone without CAVs or with CAVs only) is the
/// one place that says which are run.
pub fn strategies_at(cells: &[Cell], penetration: &str) -> Vec<StrategyKind> {
    STRATEGIES
        .into_iter()
        .filter(|k| {
            find(
                cells,
                &[("penetration", penetration), ("strategy", k.as_str())],
            )
            .is_some()
        })
        .collect()
}

/// The strategy of a cell, by its `strategy` label (`None` if it has none or names no
/// registered strategy).
pub fn strategy_of(cell: &Cell) -> Option<StrategyKind> {
    cell.labels.get("strategy")?.parse().ok()
}

/// How the strategies are named in tables.
pub fn strategy_name(k: StrategyKind) -> &'static str {
    match k {
        StrategyKind::NONE => "baseline",
        StrategyKind::PD => "PD",
        StrategyKind::FLOW_AWARE => "Flow-Aware PD",
        StrategyKind::DEDICATED => "dedicated lane (ours)",
        _ => "?",
    }
}

pub(super) fn cell_count(s: &Settings) -> usize {
    spec(NAME, SWEEP, s, |_| 1.0).map_or(0, |x| x.cell_count())
}

/// A sweep file of SR-99 cells (`sweeps/sr99.toml`, `sweeps/energy-sr99.toml`) with the
/// settings' penetrations, each at `scale(p)`, in place of its `penetration` bundle, and the
/// settings' duration if given.
pub(super) fn spec(
    name: &str,
    text: &str,
    s: &Settings,
    scale: impl Fn(f64) -> f64,
) -> Result<Spec, Error> {
    let mut spec = grid::spec(name, text, s)?;
    if let Some(d) = s.network_duration_s {
        grid::fix(&mut spec, "run.duration_s", grid::float(d));
    }
    let mut levels = Vec::new();
    for &p in &s.network_penetrations {
        if !(0.0..=1.0).contains(&p) {
            return Err(Error::Other(format!(
                "a CAV penetration must lie in [0, 1] (found {p})"
            )));
        }
        levels.push(penetration_level(p, scale(p)));
    }
    grid::levels(&mut spec, "penetration", levels)?;
    Ok(spec)
}

/// A level of the `penetration` bundle.
pub(super) fn penetration_level(p: f64, scale: f64) -> toml::Value {
    Axis::bundle(
        "penetration",
        vec![vec![
            ("run.penetration", grid::float(p)),
            ("network.demand_scale", grid::float(scale)),
        ]],
    )
    .levels
    .remove(0)
}

/// Where the demand scales come from.
#[derive(Clone, Debug, PartialEq)]
pub struct Scales {
    rows: Vec<demand_scales::Row>,
    fixed: Option<f64>,
    /// For the report: where they come from.
    pub source: String,
}

impl Scales {
    /// From the settings: `demand_scale`, else `demand_scale_table`, else the embedded table.
    pub fn from_settings(s: &Settings) -> Result<Scales, Error> {
        if let Some(v) = s.demand_scale {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::Other(format!(
                    "the demand scale must be a positive number (found {v})"
                )));
            }
            return Ok(Scales {
                rows: Vec::new(),
                fixed: Some(v),
                source: format!("one scale for every cell: {}", num(v)),
            });
        }
        match &s.demand_scale_table {
            Some(path) => {
                let text = platoonsim_scenario::bounded::read_text(
                    path,
                    platoonsim_scenario::limits::MAX_FILE_BYTES as u64,
                )
                .map_err(|e| Error::io(path, e))?;
                let rows = demand_scales::parse(&text).map_err(|message| Error::Io {
                    path: path.display().to_string(),
                    message: message.to_string(),
                })?;
                if rows.is_empty() {
                    return Err(Error::Other(format!(
                        "{} has no usable [[penetration]] row",
                        path.display()
                    )));
                }
                Ok(Scales {
                    rows,
                    fixed: None,
                    source: format!("the table file `{}`", path.display()),
                })
            }
            None => Ok(Scales {
                rows: demand_scales::embedded(),
                fixed: None,
                source: format!(
                    "the embedded table `{}` (interpolated in the penetration)",
                    demand_scales::TABLE_PATH
                ),
            }),
        }
    }

    /// The scale at a penetration, rounded to 4 decimals (it is a cell label).
    pub fn at(&self, penetration: f64) -> f64 {
        let v = self
            .fixed
            .unwrap_or_else(|| demand_scales::at(&self.rows, penetration, demand_scales::FALLBACK));
        (v * 1e4).round() / 1e4
    }
}

/// The `sr99` scenario at a penetration, strategy and demand scale, resolved exactly as
/// `platoonsim run sr99 --penetration P --strategy K --demand-scale F` with the `[set]` keys
/// of `sweeps/sr99.toml` (seed 1; the duration from the settings if given): the configuration
/// of the sweep's cells, so that `sr99-demand` reuses `sr99`'s runs.
pub fn config(s: &Settings, p: f64, k: StrategyKind, scale: f64) -> Result<Config, Error> {
    let o = Overrides {
        penetration: Some(p),
        seed: Some(1),
        strategy: Some(k),
        duration_s: s.network_duration_s,
        // The sweep file's fixed keys (`[set]`, with the settings' preset): one source for
        // what every SR-99 run measures.
        set: std::iter::once(demand_scale_set(scale))
            .chain(
                grid::spec(NAME, SWEEP, s)?
                    .set
                    .iter()
                    .map(|(k, v)| platoonsim_scenario::sweep_spec::set_arg(k, v)),
            )
            .collect(),
        ..Overrides::default()
    };
    Ok(load_with(SCENARIO, &o)?)
}

/// A cell with the labels `penetration`, `demand_scale`, `strategy`.
pub fn cell(s: &Settings, p: f64, k: StrategyKind, scale: f64) -> Result<Cell, Error> {
    Ok(Cell {
        labels: Labels::new()
            .with("penetration", num(p))
            .with("demand_scale", num(scale))
            .with("strategy", k.as_str()),
        config: config(s, p, k, scale)?,
    })
}

/// The cells: `sweeps/sr99.toml` with the settings' penetrations, each at its scale.
pub fn cells(s: &Settings) -> Result<Vec<Cell>, Error> {
    let scales = Scales::from_settings(s)?;
    grid::cells_of(&spec(NAME, SWEEP, s, |p| scales.at(p))?)
}

/// The corridor's base demand multiplier: the engine's total scale over the cell's.
pub fn base_multiplier(c: &Cell) -> Option<f64> {
    let scale: f64 = c.labels.get("demand_scale")?.parse().ok()?;
    let n = c.config.road.network.as_ref()?;
    (scale > 0.0).then(|| n.demand_scale / scale)
}

fn is_figure_cell(c: &Cell) -> bool {
    c.labels.get("penetration") == Some(num(FIGURE_PENETRATION).as_str())
}

pub(crate) const NAME: &str = "sr99";

pub(super) const EXPERIMENT: Experiment = Experiment {
    name: NAME,
    title: "SR-99 corridor: baseline, PD lane and Flow-Aware PD lane (paper Table 4, Figs. 6-8)",
    help: "Table 4 and Figs. 6-8 on the SR-99 corridor (4 h from 05:00): baseline, PD and \
           Flow-Aware PD at 20-80 % CAV, the baseline at 0 and 100 %, each penetration at its \
           demand scale (the embedded table unless --demand-scale-table or --demand-scale).",
    part: Part::Network,
    default_seeds: 10,
    own_period: true,
    safety_group: Some(&["penetration"]),
    // sr99's baselines are sr99-demand's cells at the table's scales.
    reuse_from: &["sr99-demand"],
    total_runs: |s| s.seeds as usize * cell_count(s),
    run,
    report,
    quick: quick_penetrations,
};

/// `--quick`: the figures' 40 % (baseline, PD, Flow-Aware) and the 0 % baseline.
pub(super) fn quick_penetrations(s: &mut Settings) {
    s.network_penetrations = QUICK_PENETRATIONS.to_vec();
}

/// The penetrations of `reproduce --quick`.
pub const QUICK_PENETRATIONS: [f64; 2] = [0.0, FIGURE_PENETRATION];

fn report(r: &Results<'_>) -> Result<Report, Error> {
    let (body, checks) = markdown(r.settings, r.cells, r.rows);
    let figures = super::sr99_figures::all(r.dir, r.cells, r.rows, r.extra, r.settings.preset)?;
    Ok(Report {
        body,
        checks,
        figures,
        ..Report::default()
    })
}

pub(super) fn run(s: &Settings, runner: &Runner<'_>, seeds: &[u64]) -> Result<Done, Error> {
    let cells = cells(s)?;
    let figure_seed = seeds[0];
    let mut specs = design::runs(&cells, seeds);
    design::keep_detectors(&mut specs, Scope::CrossSection, |c, _| {
        cells[c].labels.get("strategy") == Some(StrategyKind::NONE.as_str())
    });
    design::keep_detectors(&mut specs, Scope::All, |c, seed| {
        seed == figure_seed && is_figure_cell(&cells[c])
    });
    let mut outcomes = runner.run(&specs)?;
    for (i, c) in cells.iter().enumerate() {
        let k = c.labels.get("strategy").unwrap_or("");
        if k == StrategyKind::NONE.as_str() {
            continue;
        }
        let base = find(
            &cells,
            &[
                ("penetration", c.labels.get("penetration").unwrap_or("")),
                ("strategy", StrategyKind::NONE.as_str()),
            ],
        );
        if let Some(base) = base {
            for (name, metric) in CHANGES {
                table::add_paired(&mut outcomes, base, i, metric, name, true);
            }
        }
    }
    let mut data = Data {
        figure_runs: Vec::new(),
        figure_seed,
    };
    let crit = criterion(s);
    for (o, spec) in outcomes.iter_mut().zip(&specs) {
        if spec.detectors == Scope::None {
            continue;
        }
        let recs = runner.detectors(&o.key)?;
        let b = corridor::bottlenecks(&recs, &crit);
        o.fields.set("florin_congested_min", b.florin_min);
        o.fields.set("south_congested_min", b.south_min);
        o.fields
            .set("bottlenecks_active", f64::from(u8::from(b.active(&crit))));
        if o.seed == figure_seed && is_figure_cell(&cells[o.cell]) {
            data.figure_runs.push((o.cell, recs));
        }
    }
    Ok(Done {
        cells,
        outcomes,
        extra: Extra::Sr99(data),
    })
}

/// The bottleneck criterion of the settings.
pub fn criterion(s: &Settings) -> Criterion {
    Criterion {
        speed_kmh: s.bottleneck_speed_kmh,
        minutes: s.bottleneck_minutes,
    }
}

fn row<'a>(
    cells: &[Cell],
    rows: &'a [SummaryRow],
    p: &str,
    k: StrategyKind,
    metric: Col,
) -> Option<&'a SummaryRow> {
    let c = find(cells, &[("penetration", p), ("strategy", k.as_str())])?;
    rows.iter()
        .find(|r| r.cell == c && r.metric == metric.name())
}

/// Ours with its 95 % interval (half-width), the paper's value, and ours − paper in % of the
/// paper's value.
fn triple(r: Option<&SummaryRow>, dec: usize, skip: bool) -> [String; 3] {
    let Some(r) = r.filter(|_| !skip) else {
        return ["–".into(), "–".into(), "–".into()];
    };
    let paper = r.paper.map_or("–".into(), |p| fixed(p.value, dec));
    let rel = r.relative_difference_pct() / 100.0;
    let diff = if rel.is_finite() {
        format!("{} %", signed(100.0 * rel, 1))
    } else {
        "–".into()
    };
    [pm(&r.stats, dec), paper, diff]
}

pub(super) fn markdown(s: &Settings, cells: &[Cell], rows: &[SummaryRow]) -> (String, Vec<Check>) {
    let duration = cells.first().map_or(14400.0, |c| c.config.duration_s);
    let source = Scales::from_settings(s).map_or_else(|e| e.to_string(), |x| x.source);
    let mut md = format!(
        "The built-in `sr99` corridor (SR-99 NB, Elk Grove Blvd to 12th Ave, 16 on-ramps, 11 \
         off-ramps), {} s simulated from 05:00 ({} per cell). Demand scale per \
         penetration from {source}, on top of the corridor's base demand multiplier ({}; the \
         entrance demands are multiplied by both). Network discharge = mean flow through every exit detector \
         (off-ramps and the mainline end) over the whole run, veh/h; lane changes per vehicle \
         and L̄ over every vehicle / CAV that entered. Ours: mean ± half-width of the 95 % \
         confidence interval over the seeds; the paper gives single values. \"vs paper\" is \
         (ours − paper) / paper.\n\n",
        num(duration),
        seeds_text(s.seeds),
        cells
            .first()
            .and_then(base_multiplier)
            .map_or("?".into(), |b| fixed(b, 3))
    );
    md.push_str("## Table 4: ours vs the paper\n\n");
    let header: Vec<String> = [
        "CAV (%)",
        "Demand scale, ours / paper (×)",
        "Strategy",
        "Network discharge (veh/h)",
        "paper (veh/h)",
        "vs paper (%)",
        "Lane changes (1/veh)",
        "paper (1/veh)",
        "vs paper (%)",
        "L̄ (veh)",
        "paper (veh)",
        "vs paper (%)",
    ]
    .iter()
    .map(|h| h.to_string())
    .collect();
    let mut trs = Vec::new();
    let pens: Vec<f64> = s.network_penetrations.clone();
    for &p in &pens {
        let ps = num(p);
        // A strategy the sweep file skips at this penetration has no cell.
        for k in STRATEGIES {
            let ks = k.as_str();
            let Some(c) = find(cells, &[("penetration", &ps), ("strategy", ks)]) else {
                continue;
            };
            let scale = cells[c]
                .labels
                .get("demand_scale")
                .and_then(|v| v.parse::<f64>().ok())
                .map_or("?".into(), |v| fixed(v, 2));
            let paper_scale = paper::sr99_demand_scale(p).map_or("–".into(), |v| fixed(v, 2));
            let mut r = vec![
                format!("{} %", num(100.0 * p)),
                format!("{scale} / {paper_scale}"),
                strategy_name(k).to_string(),
            ];
            r.extend(triple(
                row(cells, rows, &ps, k, Metric::NETWORK_DISCHARGE.into()),
                1,
                false,
            ));
            r.extend(triple(
                row(cells, rows, &ps, k, Metric::LANE_CHANGES_PER_VEHICLE.into()),
                2,
                false,
            ));
            r.extend(triple(
                row(cells, rows, &ps, k, Metric::AVG_PLATOON_LENGTH.into()),
                2,
                p == 0.0,
            ));
            trs.push(r);
        }
    }
    md.push_str(&md_table(&header, &trs));
    md.push_str(&plain(cells, rows, &pens));

    md.push_str(
        "\n## Change vs the baseline at the same penetration (%)\n\n\
         Per seed pair with the baseline (same seed, same demand); the paper's values are the \
         percentages in parentheses in its Table 4. The strict L̄ counts a CAV as linked only \
         while it keeps a time gap of at most 2 s to the CAV ahead (the paper does not define \
         its link further; see the notes).\n\n",
    );
    let header: Vec<String> = [
        "CAV (%)",
        "Strategy",
        "Network discharge: ours (%)",
        "paper (%)",
        "Lane changes / veh: ours (%)",
        "paper (%)",
        "L̄: ours (%)",
        "paper (%)",
        "L̄ strict (time gap ≤ 2 s): ours (%)",
        "paper (%)",
    ]
    .iter()
    .map(|h| h.to_string())
    .collect();
    let mut trs = Vec::new();
    let mid: Vec<f64> = pens
        .iter()
        .copied()
        .filter(|&p| strategies_at(cells, &num(p)).len() > 1)
        .collect();
    for &p in &mid {
        let ps = num(p);
        for k in [StrategyKind::PD, StrategyKind::FLOW_AWARE] {
            let mut r = vec![format!("{} %", num(100.0 * p)), strategy_name(k).into()];
            for (name, _) in CHANGES {
                let x = row(cells, rows, &ps, k, Col::Derived(name));
                r.push(x.map_or("–".into(), |x| signed_pm(x, 1)));
                r.push(
                    x.and_then(|x| x.paper)
                        .map_or("–".into(), |v| signed(v.value, 1)),
                );
            }
            trs.push(r);
        }
    }
    if trs.is_empty() {
        md.push_str("No penetration between 0 and 100 % was run.\n");
    } else {
        md.push_str(&md_table(&header, &trs));
    }

    if !mid.is_empty() {
        md.push_str("\n## The organizing strategies' mechanism\n\n");
        md.push_str(&super::mechanism::legend(
            "the whole corridor (the PD zone)",
        ));
        let keys: Vec<(String, String)> = mid
            .iter()
            .map(|&p| (num(p), format!("{} % CAV", num(100.0 * p))))
            .collect();
        for k in [StrategyKind::PD, StrategyKind::FLOW_AWARE] {
            md.push_str(&format!("{}:\n\n", strategy_name(k)));
            md.push_str(&super::mechanism::table(
                &keys,
                k,
                Col::Derived(CHANGES[0].0),
                false,
                &|key: &str, st, c| row(cells, rows, key, st, c),
            ));
            md.push('\n');
        }
    }

    md.push_str(&bottleneck_section(s, cells, rows));

    let checks = checks(cells, rows, &mid);
    if !checks.is_empty() {
        md.push_str("\n## Checks (the paper's findings)\n\n");
        md.push_str(&checks_md(&checks));
    }
    (md, checks)
}

fn bottleneck_section(s: &Settings, cells: &[Cell], rows: &[SummaryRow]) -> String {
    let crit = criterion(s);
    let get = |c: usize, m: &str| rows.iter().find(|r| r.cell == c && r.metric == m);
    let mut trs = Vec::new();
    for (c, cell) in cells.iter().enumerate() {
        let Some(active) = get(c, "bottlenecks_active") else {
            continue;
        };
        let p: f64 = cell
            .labels
            .get("penetration")
            .and_then(|v| v.parse().ok())
            .unwrap_or(f64::NAN);
        let mean = |m: &str| get(c, m).map_or("–".into(), |r| fixed(r.stats.mean, 0));
        trs.push(vec![
            format!("{} %", num(100.0 * p)),
            strategy_of(cell).map_or("?", strategy_name).into(),
            cell.labels
                .get("demand_scale")
                .and_then(|v| v.parse::<f64>().ok())
                .map_or("?".into(), |v| fixed(v, 2)),
            format!(
                "{}/{}",
                (active.stats.mean * active.stats.n as f64).round(),
                active.stats.n
            ),
            mean("florin_congested_min"),
            mean("south_congested_min"),
        ]);
    }
    if trs.is_empty() {
        return String::new();
    }
    let mut md = format!(
        "\n## Recurrent bottlenecks\n\n\
         Every baseline run, and the PD and Flow-Aware PD runs of the figures: runs with both \
         recurrent bottlenecks active, and the means of the longest stretch of consecutive \
         5-min intervals with a cross-section mean speed below {} km/h at `{}` (upstream of the \
         second Florin Rd on-ramp) and at any mainline detector from `{}` to `{}` (downstream \
         of Elk Grove Blvd). A bottleneck counts as active from {} min on (the criterion of \
         `sr99-demand`, which the paper's demand scales are meant to meet in the baseline).\n\n",
        num(crit.speed_kmh),
        corridor::FLORIN_DETECTOR,
        corridor::SOUTH_FIRST,
        corridor::SOUTH_LAST,
        num(crit.minutes)
    );
    let header: Vec<String> = [
        "CAV (%)",
        "Strategy",
        "Demand scale (×)",
        "Runs with both active (runs)",
        "Florin Rd (min)",
        "Elk Grove Blvd stretch (min)",
    ]
    .iter()
    .map(|h| h.to_string())
    .collect();
    md.push_str(&md_table(&header, &trs));
    md
}

/// "x % higher / lower than the paper's" for a row with a paper value.
fn versus(r: Option<&SummaryRow>, dec: usize) -> String {
    let Some(r) = r else { return "–".into() };
    let rel = r.relative_difference_pct();
    if !rel.is_finite() {
        return "no paper value".into();
    }
    format!(
        "{} % {} than the paper's {}",
        fixed(rel.abs(), 1),
        if rel >= 0.0 { "higher" } else { "lower" },
        r.paper.map_or("?".into(), |p| fixed(p.value, dec))
    )
}

/// The differences to the paper in words, one line per penetration.
fn plain(cells: &[Cell], rows: &[SummaryRow], pens: &[f64]) -> String {
    let mut md = String::from("\nIn words:\n\n");
    for &p in pens {
        let ps = num(p);
        let r = |k: StrategyKind, m: Col| row(cells, rows, &ps, k, m);
        let mean = |k: StrategyKind, m: Col| r(k, m).map_or(f64::NAN, |x| x.stats.mean);
        let paper =
            |k: StrategyKind, m: Col| r(k, m).and_then(|x| x.paper).map_or(f64::NAN, |v| v.value);
        let mut line =
            format!(
            "- **{} % CAV**: baseline network discharge {} veh/h, {}; lane changes per vehicle \
             {}, {}",
            num(100.0 * p),
            fixed(mean(StrategyKind::NONE, Metric::NETWORK_DISCHARGE.into()), 0),
            versus(r(StrategyKind::NONE, Metric::NETWORK_DISCHARGE.into()), 1),
            fixed(mean(StrategyKind::NONE, Metric::LANE_CHANGES_PER_VEHICLE.into()), 2),
            versus(r(StrategyKind::NONE, Metric::LANE_CHANGES_PER_VEHICLE.into()), 2),
        );
        if p > 0.0 {
            line.push_str(&format!(
                "; L̄ {}, {}",
                fixed(
                    mean(StrategyKind::NONE, Metric::AVG_PLATOON_LENGTH.into()),
                    2
                ),
                versus(r(StrategyKind::NONE, Metric::AVG_PLATOON_LENGTH.into()), 2)
            ));
        }
        if strategies_at(cells, &ps).len() > 1 {
            line.push_str(&format!(
                ". Against the baseline, PD changes the discharge by {} % (paper {} %) and \
                 Flow-Aware PD by {} % (paper {} %); L̄ by {} % and {} % (paper {} % and {} %)",
                signed(
                    mean(StrategyKind::PD, Col::Derived("discharge_change_pct")),
                    1
                ),
                signed(
                    paper(StrategyKind::PD, Col::Derived("discharge_change_pct")),
                    1
                ),
                signed(
                    mean(
                        StrategyKind::FLOW_AWARE,
                        Col::Derived("discharge_change_pct")
                    ),
                    1
                ),
                signed(
                    paper(
                        StrategyKind::FLOW_AWARE,
                        Col::Derived("discharge_change_pct")
                    ),
                    1
                ),
                signed(
                    mean(StrategyKind::PD, Col::Derived("platoon_length_change_pct")),
                    1
                ),
                signed(
                    mean(
                        StrategyKind::FLOW_AWARE,
                        Col::Derived("platoon_length_change_pct")
                    ),
                    1
                ),
                signed(
                    paper(StrategyKind::PD, Col::Derived("platoon_length_change_pct")),
                    1
                ),
                signed(
                    paper(
                        StrategyKind::FLOW_AWARE,
                        Col::Derived("platoon_length_change_pct")
                    ),
                    1
                ),
            ));
        }
        line.push_str(".\n");
        md.push_str(&line);
    }
    md
}

/// "1 seed", "10 seeds".
pub fn seeds_text(n: u32) -> String {
    if n == 1 {
        "1 seed".into()
    } else {
        format!("{n} seeds")
    }
}

/// `+mean ± half-width` (a change, with its sign).
fn signed_pm(r: &SummaryRow, dec: usize) -> String {
    let hw = r.stats.half_width();
    if hw.is_finite() {
        format!("{} ± {}", signed(r.stats.mean, dec), fixed(hw, dec))
    } else {
        signed(r.stats.mean, dec)
    }
}

mod checks;
use checks::checks;

#[cfg(test)]
mod tests;
