//! `rules` (issue 43): every engine rule beyond the paper as a measured sensitivity. The
//! paper's Table 3 set-up (homogeneous road, 50 % CAV, baseline vs PD lane) at 2,000 and
//! 2,500 veh/h/lane under `model.preset = "paper"`, with one rule switched on per variant
//! (`sweeps/rules.toml`), and all of the platform's defaults last:
//!
//! | variant | switched on over the paper's model | docs/model-choices.md |
//! |---|---|---|
//! | `paper` | nothing | "The two presets" |
//! | `safe-gaps` | `lane_change.gap_rule = "safe"` | spec 9.1 |
//! | `auto-organize-*` | `cav.organize_while_automated`, with each `cav.organize_hold` | 6.20 |
//! | `closing-only-approaching` | `cav.cacc_closing_only_approaching` | 6.21 |
//! | `organize-regardless-of-speed` | `cav.organize_regardless_of_speed` | 6.22 |
//! | `cooperative` | `cav.cooperative_lane_change` | spec 9.2 |
//! | `field-cacc` | `cav.cacc_law = "field"` | docs/cacc-field.md |
//! | `platform` | `model.preset = "platform"` | |
//!
//! Per seed pair with the same variant's baseline: ΔQ = 100 (Q_PO − Q_B) / Q_B
//! (`discharge_change_pct`) and the L̄ gain L̄_PO / L̄_B (`platoon_length_ratio`); lane changes
//! per vehicle and severe brakings per 100 veh-km (spec 9.4) under PD.

use super::{checks_md, find, run_cells, Check, Done, Experiment, Part, Report, Results, Settings};
use crate::table::Col;
use crate::table::{self, decimals, md_table, pm, signed, SummaryRow};
use platoonsim_runs::design::num;
use platoonsim_runs::metric::Part as Share;
use platoonsim_runs::runner::Runner;
use platoonsim_runs::Metric;
use platoonsim_runs::{Cell, Error};
use platoonsim_scenario::StrategyKind;
use platoonsim_sim::Counted;

/// The demands where PD costs capacity in the paper's Table 3 (veh/h/lane), and its share.
pub const DEMANDS: [f64; 2] = [2000.0, 2500.0];
pub const PENETRATION: f64 = 0.5;
/// The baseline first: PD's paired metrics are against it.
pub const STRATEGIES: [StrategyKind; 2] = [StrategyKind::NONE, StrategyKind::PD];

/// The variants in the sweep file's order, with what each switches on.
pub const VARIANTS: [(&str, &str); 11] = [
    ("paper", "the paper's model (`model.preset = \"paper\"`)"),
    ("safe-gaps", "+ the safe gap rule (spec 9.1)"),
    (
        "auto-organize-no-hold",
        "+ automated organization (6.20), no hold",
    ),
    (
        "auto-organize-hold-always",
        "+ automated organization, the hold as first built",
    ),
    (
        "auto-organize-hold-leader-ahead",
        "+ automated organization, the hold released beside a leader (2026-12-03)",
    ),
    (
        "auto-organize-hold-narrow",
        "+ automated organization, the narrow hold (platform default)",
    ),
    (
        "closing-only-approaching",
        "+ CACC gap closing only while approaching (6.21)",
    ),
    (
        "organize-regardless-of-speed",
        "+ no a_ant ≥ 0 test for the PD move (6.22)",
    ),
    ("cooperative", "+ cooperative lane changes (spec 9.2)"),
    (
        "field-cacc",
        "+ the field form of the CACC (docs/cacc-field.md)",
    ),
    ("platform", "all of the platform's defaults"),
];

/// The grid: `sweeps/rules.toml` (demand × variant × strategy, the baseline of each (demand,
/// variant) first).
pub const SWEEP: &str = include_str!("../../../../sweeps/rules.toml");

pub(super) const EXPERIMENT: Experiment = Experiment {
    name: "rules",
    title: "Engine rules beyond the paper, one at a time over the paper's model",
    help: "The paper's Table 3 set-up at 2,000 and 2,500 veh/h/lane under model.preset = \
           paper, with one engine rule switched on per variant (issue 43): the discharge \
           change and L̄ gain of PD, its lane changes and severe brakings.",
    part: Part::Rules,
    default_seeds: 10,
    own_period: false,
    safety_group: Some(&["demand_vphpl", "variant"]),
    reuse_from: &[],
    total_runs: |s| s.seeds as usize * super::grid::cell_count(EXPERIMENT.name, SWEEP),
    run,
    report,
    quick: super::unchanged,
};

fn report(r: &Results<'_>) -> Result<Report, Error> {
    let (body, checks) = markdown(r.settings, r.cells, r.rows);
    Ok(Report {
        body,
        checks,
        ..Report::default()
    })
}

pub(super) fn run(s: &Settings, runner: &Runner<'_>, seeds: &[u64]) -> Result<Done, Error> {
    let cells = super::grid::cells(EXPERIMENT.name, SWEEP, s)?;
    let mut outcomes = run_cells(runner, &cells, seeds, 0)?;
    let n = STRATEGIES.len();
    for b in (0..cells.len()).step_by(n) {
        table::add_paired(
            &mut outcomes,
            b,
            b + 1,
            Metric::DISCHARGE_FLOW,
            "discharge_change_pct",
            true,
        );
        table::add_ratio(
            &mut outcomes,
            b,
            b + 1,
            Metric::AVG_PLATOON_LENGTH,
            "platoon_length_ratio",
        );
    }
    Ok(Done::new(cells, outcomes))
}

const DQ: Col = Col::Derived("discharge_change_pct");
const RATIO: Col = Col::Derived("platoon_length_ratio");
const LC: Col = Col::Metric(Metric::LANE_CHANGES_PER_VEHICLE);
const SEVERE: Col = Col::Metric(Metric::Counted(Counted::SevereBrakings, Share::Rate));

/// The paper's Table 3 at 2,000 and 2,500 veh/h/lane: ΔQ (%), L̄ PO / L̄ B, LC/veh under PD.
const PAPER_DQ: [f64; 2] = [-1.89, -9.54];
const PAPER_RATIO: [f64; 2] = [5.1 / 2.8, 5.4 / 3.3];
const PAPER_LC: [f64; 2] = [0.53, 0.56];

pub(super) fn markdown(s: &Settings, cells: &[Cell], rows: &[SummaryRow]) -> (String, Vec<Check>) {
    let mut md = format!(
        "Every engine rule beyond the paper, measured one at a time over the paper's model \
         (`model.preset = \"paper\"`: the published gap rule, the PATH organization rule, the \
         spec's CACC law; docs/model-choices.md, \"The two presets\"). The paper's Table 3 \
         set-up: homogeneous road, {} % CAV, {} s with the first {} s as warm-up, baseline (B) \
         against the PD lane (PO). {} seeds per cell; mean ± half-width of the 95 % confidence \
         interval; ΔQ and L̄ PO / L̄ B per seed pair with the same variant's baseline. Severe \
         brakings: episodes peaking at 6 m/s² or more (spec 9.4), per 100 veh-km, under PD. \
         Paper (Table 3) at 2,000 / 2,500 veh/h/lane: ΔQ {} / {} %, L̄ PO / L̄ B ×{:.2} / ×{:.2}, \
         LC/veh {} / {}.\n\n",
        num(100.0 * PENETRATION),
        num(s.duration_s),
        num(s.warmup_s),
        s.seeds,
        signed(PAPER_DQ[0], 2),
        signed(PAPER_DQ[1], 2),
        PAPER_RATIO[0],
        PAPER_RATIO[1],
        PAPER_LC[0],
        PAPER_LC[1],
    );
    let stat = |demand: f64, variant: &str, metric: Col| {
        find(
            cells,
            &[
                ("demand_vphpl", &num(demand)),
                ("variant", variant),
                ("strategy", StrategyKind::PD.as_str()),
            ],
        )
        .and_then(|c| {
            rows.iter()
                .find(|r| r.cell == c && r.metric == metric.name())
        })
    };
    let mut header = vec!["Variant".to_string()];
    for (title, _) in COLUMNS {
        for d in DEMANDS {
            header.push(format!("{title} at {}", num(d)));
        }
    }
    let mut trs = Vec::new();
    for (variant, what) in VARIANTS {
        let mut r = vec![format!("`{variant}`: {what}")];
        for (_, metric) in COLUMNS {
            for d in DEMANDS {
                r.push(
                    stat(d, variant, metric)
                        .map_or("–".into(), |x| pm(&x.stats, decimals(&metric.name()))),
                );
            }
        }
        trs.push(r);
    }
    md.push_str(&md_table(&header, &trs));
    let mean = |d: f64, v: &str, m: Col| stat(d, v, m).map_or(f64::NAN, |r| r.stats.mean);
    let dq = mean(2500.0, "paper", DQ);
    let checks = vec![Check {
        statement: format!(
            "under the paper's model PD costs discharge at 2,500 veh/h/lane (paper −9.54 %): \
             {} %",
            signed(dq, 2)
        ),
        passed: dq < 0.0,
    }];
    md.push_str("\n## Checks\n\n");
    md.push_str(&checks_md(&checks));
    (md, checks)
}

/// (column title, metric) of the table, each at both demands.
const COLUMNS: [(&str, Col); 4] = [
    ("ΔQ (%)", DQ),
    ("L̄ PO / L̄ B (ratio)", RATIO),
    ("LC/veh PO (1/veh)", LC),
    ("severe brakings PO (per 100 veh-km)", SEVERE),
];

#[cfg(test)]
mod tests {
    use super::*;
    use platoonsim_model::cav::OrganizeHold;
    use platoonsim_model::safegap::GapRule;

    #[test]
    fn each_variant_is_the_paper_model_with_its_rule_on() {
        let cells = super::super::grid::cells("rules", SWEEP, &Settings::default()).unwrap();
        assert_eq!(
            cells.len(),
            DEMANDS.len() * VARIANTS.len() * STRATEGIES.len()
        );
        let paper = &cells[0].config;
        assert_eq!(cells[0].labels.get("variant"), Some("paper"));
        assert_eq!(paper.lane_change.gap_rule, GapRule::Published);
        assert!(!paper.cav.organize_while_automated);
        assert!(!paper.cav.cacc_closing_only_approaching);
        assert!(!paper.cav.organize_regardless_of_speed);
        assert!(!paper.cav.yield_while_automated);
        assert_eq!(paper.cav.cacc_law, platoonsim_model::cav::CaccLaw::Spec);
        for (i, (variant, _)) in VARIANTS.iter().enumerate() {
            // The first demand's baseline of each variant.
            let c = &cells[i * STRATEGIES.len()];
            assert_eq!(c.labels.get("variant"), Some(*variant));
            assert_eq!(c.labels.get("strategy"), Some("none"));
            let mut back = c.config.clone();
            match *variant {
                "paper" => {}
                "safe-gaps" => back.lane_change.gap_rule = GapRule::Published,
                v if v.starts_with("auto-organize") => {
                    back.cav.organize_while_automated = false;
                    back.cav.organize_hold = OrganizeHold::Narrow;
                }
                "closing-only-approaching" => back.cav.cacc_closing_only_approaching = false,
                "organize-regardless-of-speed" => back.cav.organize_regardless_of_speed = false,
                "cooperative" => back.cav.cooperative_lane_change = false,
                "field-cacc" => back.cav.cacc_law = platoonsim_model::cav::CaccLaw::Spec,
                "platform" => continue,
                other => panic!("unknown variant {other}"),
            }
            // One rule on: switched back, the variant is the paper's model.
            assert_eq!(&back, paper, "{variant}");
        }
    }
}
