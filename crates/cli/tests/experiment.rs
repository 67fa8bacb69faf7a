//! `platoonsim experiment` and `platoonsim reproduce` end to end, on short runs.

mod common;

use common::{platoonsim, s, scratch, stdout};

#[test]
fn help_lists_the_experiment_commands() {
    let o = platoonsim(&["--help"]);
    let text = stdout(&o);
    for cmd in ["experiment", "reproduce"] {
        assert!(text.contains(cmd), "{cmd} missing from --help:\n{text}");
    }
    let o = platoonsim(&["experiment", "--help"]);
    let text = stdout(&o);
    for part in [
        "capacity",
        "sensitivity",
        "flow-aware",
        "sr99",
        "sr99-demand",
        "--penetrations <LIST>",
        "--scales <LIST>",
        "--write-table",
        "--demand-scale-table <FILE>",
        "--seeds <N>",
        "--out <DIR>",
        "--jobs <N>",
        "--fresh",
    ] {
        assert!(
            text.contains(part),
            "{part} missing from experiment --help:\n{text}"
        );
    }
    let o = platoonsim(&["reproduce", "--help"]);
    let text = stdout(&o);
    for part in ["--quick", "--seeds <N>", "--out <DIR>", "--jobs <N>"] {
        assert!(
            text.contains(part),
            "{part} missing from reproduce --help:\n{text}"
        );
    }
    assert!(
        !text.contains("--duration") && !text.contains("--network-duration"),
        "test-only flag shown:\n{text}"
    );
}

#[test]
fn experiment_writes_its_files_and_a_rerun_reuses_every_run() {
    let out = scratch("fa");
    let args = [
        "experiment",
        "flow-aware",
        "--seeds",
        "2",
        "--jobs",
        "2",
        "--duration",
        "600",
        "--warmup",
        "300",
        "--out",
        s(&out),
        "--quiet",
    ];
    let o = platoonsim(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = stdout(&o);
    assert!(text.contains("6 runs (6 computed, 0 reused)"), "{text}");
    let dir = out.join("flow-aware");
    for f in ["runs.csv", "summary.csv", "summary.md", "run.json"] {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    assert_eq!(std::fs::read_dir(dir.join("runs")).unwrap().count(), 6);
    let runs = std::fs::read(dir.join("runs.csv")).unwrap();

    let o = platoonsim(&args);
    assert!(o.status.success());
    assert!(
        stdout(&o).contains("6 runs (0 computed, 6 reused)"),
        "{}",
        stdout(&o)
    );
    assert_eq!(std::fs::read(dir.join("runs.csv")).unwrap(), runs);

    let prov: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("run.json")).unwrap()).unwrap();
    assert_eq!(prov["arguments"][1], "experiment");
    assert_eq!(prov["reused"], 6);
}

/// `experiment NAME --quick` takes reproduce --quick's settings: 3 seeds per cell here.
#[test]
fn experiment_quick_takes_the_quick_reproductions_settings() {
    let out = scratch("quick");
    let o = platoonsim(&[
        "experiment",
        "flow-aware",
        "--quick",
        "--duration",
        "400",
        "--warmup",
        "100",
        "--out",
        s(&out),
        "-q",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout(&o).contains("9 runs (9 computed, 0 reused)"),
        "{}",
        stdout(&o)
    );
    let prov: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("flow-aware").join("run.json")).unwrap())
            .unwrap();
    assert_eq!(prov["seeds"], serde_json::json!([1, 2, 3]));
}

#[test]
fn sr99_experiments_run_from_the_command_line() {
    let out = scratch("sr99");
    let o = platoonsim(&[
        "experiment",
        "sr99",
        "--seeds",
        "1",
        "--penetrations",
        "0.4",
        "--network-duration",
        "300",
        "--out",
        s(&out),
        "-q",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout(&o).contains("3 runs (3 computed, 0 reused)"),
        "{}",
        stdout(&o)
    );
    for f in [
        "summary.md",
        "sr99_contours.png",
        "sr99_lanes.svg",
        "sr99_bars.png",
    ] {
        assert!(out.join("sr99").join(f).is_file(), "{f} missing");
    }

    // The demand search writes its table where --write-table says.
    let table = out.join("scales.toml");
    let o = platoonsim(&[
        "experiment",
        "sr99-demand",
        "--seeds",
        "1",
        "--penetrations",
        "0",
        "--scales",
        "1",
        "--bottleneck-speed",
        "300",
        "--bottleneck-minutes",
        "5",
        "--network-duration",
        "300",
        "--write-table",
        s(&table),
        "--out",
        s(&out),
        "-q",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout(&o).contains("Wrote the demand scales found to"),
        "{}",
        stdout(&o)
    );
    let text = std::fs::read_to_string(&table).unwrap();
    assert!(
        text.contains("[[penetration]]\npenetration = 0.0\ndemand_scale = 1.0"),
        "{text}"
    );

    // --write-table needs a search.
    let o = platoonsim(&[
        "experiment",
        "sr99",
        "--write-table",
        s(&table),
        "--out",
        s(&out),
    ]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--write-table"));

    // A --write-table path that cannot be written is refused before any run.
    let o = platoonsim(&[
        "experiment",
        "calibrate-flow-aware",
        "--write-table",
        s(&out.join("no-such-dir").join("t.toml")),
        "--out",
        s(&out),
        "-q",
    ]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("no-such-dir") && err.contains("does not exist"),
        "{err}"
    );
    assert!(!out.join("calibrate-flow-aware").exists(), "a run was made");

    // The threshold calibration writes its choice where --write-table says (by default the
    // table the Flow-Aware defaults are read from).
    let thresholds = out.join("thresholds.toml");
    let o = platoonsim(&[
        "experiment",
        "calibrate-flow-aware",
        "--seeds",
        "1",
        "--duration",
        "120",
        "--warmup",
        "60",
        "--flow-thresholds",
        "2750",
        "--speed-thresholds",
        "0",
        "--tolerance",
        "100",
        "--write-table",
        s(&thresholds),
        "--out",
        s(&out),
        "-q",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout(&o).contains("Wrote the chosen Flow-Aware thresholds to"),
        "{}",
        stdout(&o)
    );
    let text = std::fs::read_to_string(&thresholds).unwrap();
    assert_eq!(
        text,
        std::fs::read_to_string(out.join("calibrate-flow-aware").join("thresholds.toml")).unwrap()
    );
    assert_eq!(text.matches("[[penetration]]").count(), 3, "{text}");
}

#[test]
fn reproduce_writes_the_report() {
    let out = scratch("reproduce");
    let o = platoonsim(&[
        "reproduce",
        "--quick",
        "--seeds",
        "2",
        "--duration",
        "600",
        "--warmup",
        "300",
        "--network-duration",
        "300",
        "--out",
        s(&out),
        "-q",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = stdout(&o);
    assert!(text.contains("Total wall time"), "{text}");
    let md = std::fs::read_to_string(out.join("REPORT.md")).unwrap();
    for part in [
        // The paper's model first (issue 43), then the rules over it, then the platform.
        "## Under the paper's model (`model.preset = \"paper\"`)",
        "### 1. Capacity",
        "### 2. Platoon organization at various demands (paper Table 3)",
        "### 3. Flow-Aware",
        "### 4. SR-99 corridor (paper Table 4, Figs. 6-8)",
        "## Every engine rule beyond the paper, as a sensitivity",
        "### 5. Engine rules beyond the paper, one at a time over the paper's model",
        "| `auto-organize-hold-narrow`: + automated organization, the narrow hold",
        "## Under the platform's defaults (`model.preset = \"platform\"`)",
        "### 6. Capacity",
        "### 9. SR-99 corridor (paper Table 4, Figs. 6-8)",
        "### 10. Driver behaviour: the published and the safe gap rule, cooperative lane changes (beyond the paper)",
        "### 11. Energy with platoon organization: fuel per vehicle-km (beyond the paper)",
        "**Beyond the paper**",
        "**Quick mode**",
        "##### Table 4: ours vs the paper",
        "##### Demand scale by penetration",
        "**No search**",
        "## Run time",
        "## Contents",
        "- [1. Capacity with and without the PD lane (paper Fig. 4)](#1-capacity-with-and-without-the-pd-lane-paper-fig-4)",
        "paper/capacity/capacity.png",
        "| Result | Experiment | Check |",
        "| Date | ",
        "`docs/reproduction-notes-sr99.md`",
        "platoonsim reproduce --quick --seeds 2",
    ] {
        assert!(md.contains(part), "{part} missing from REPORT.md");
    }
    // Only this run's figures: the reproduction notes in docs/ are linked, not printed.
    for notebook in [
        "Notes on differences",
        "Notes on the SR-99 results",
        "Session 13",
    ] {
        assert!(!md.contains(notebook), "{notebook} in REPORT.md");
    }
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>"));
    assert!(html.contains("<table>"));
    assert!(html.contains("<h3 id=\"1-capacity-with-and-without-the-pd-lane-paper-fig-4\">"));
    // Every check has a coloured verdict.
    let verdicts = html.matches("class=\"pass\"").count() + html.matches("class=\"fail\"").count();
    assert!(
        verdicts
            >= md.matches("| ✓ **holds** |").count()
                + md.matches("| ✗ **does not hold** |").count()
    );
    // capacity, sensitivity; sr99: contours, lanes, bars; sr99-demand: scales, contours;
    // energy; and the braking histogram of each of the seven experiments (issue 29); under
    // the paper's model capacity, sensitivity and sr99's three with the braking histograms of
    // its four experiments; the rules' braking histogram.
    assert_eq!(
        html.matches("src=\"data:image/png;base64,").count(),
        8 + 7 + 5 + 4 + 1
    );
    assert!(out.join("capacity/capacity.svg").is_file());
    assert!(out.join("paper/capacity/capacity.svg").is_file());
    assert!(out.join("rules/summary.csv").is_file());
    for exp in [
        "capacity",
        "sensitivity",
        "flow-aware",
        "sr99",
        "sr99-demand",
        "behaviour",
        "energy",
    ] {
        assert!(out.join(exp).join("summary.csv").is_file(), "{exp}");
    }
}

/// `experiment energy` on short runs: both roads, every strategy, the fuel and drag columns,
/// the answer, the figure.
#[test]
fn energy_experiment_runs_both_roads() {
    let out = scratch("energy-experiment");
    let o = platoonsim(&[
        "experiment",
        "energy",
        "--seeds",
        "2",
        "--duration",
        "600",
        "--warmup",
        "300",
        "--penetrations",
        "0,0.4",
        "--network-duration",
        "300",
        "--out",
        s(&out),
        "-q",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let dir = out.join("energy");
    let md = std::fs::read_to_string(dir.join("summary.md")).unwrap();
    for part in [
        "**Beyond the paper**",
        "## Fuel per 100 km",
        "homogeneous, 2500 veh/h/lane",
        "SR-99, 40 % CAV",
        "dedicated lane (ours)",
        "## Where the CAVs' energy goes: drag vs dynamics",
        "## The paper's question",
        "## Checks",
        "## Safety",
    ] {
        assert!(md.contains(part), "{part} missing from summary.md:\n{md}");
    }
    assert!(dir.join("energy.png").is_file() && dir.join("energy.svg").is_file());
    // 4 demands × 4 strategies + 1 penetration × 4 strategies, 2 seeds each.
    let runs = std::fs::read_to_string(dir.join("runs.csv")).unwrap();
    let mut lines = runs.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 40);
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (fuel, cav, drag) = (
        col("fuel_l_per_100km"),
        col("cav_fuel_change_pct"),
        col("cav_drag_reduction_pct"),
    );
    for r in &rows {
        let f: f64 = r[fuel].parse().unwrap();
        assert!((4.0..12.0).contains(&f), "{r:?}");
        let d: f64 = r[drag].parse().unwrap();
        assert!(d > 0.0 && d < 30.0, "{r:?}");
    }
    // The changes exist on the organized cells and not on the baselines.
    let strategy = col("strategy");
    for r in &rows {
        assert_eq!(r[strategy] == "none", r[cav].is_empty(), "{r:?}");
    }
}
