//! `show` writes a complete scenario file: run as it is, it gives the run of the scenario and
//! flags it was shown with, bit for bit (summary, detectors, resolved scenario). And what a
//! corridor of the user's own gets by default: no other corridor's tables.

mod common;

use common::{platoonsim, s, scratch, stderr, summary_without_wall_time};
use std::path::Path;

/// `run` with `args` into `out`; panics unless it succeeds.
fn run(args: &[&str], out: &Path) {
    let mut all = vec!["--quiet", "run"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--out", s(out)]);
    let o = platoonsim(&all);
    assert!(o.status.success(), "{all:?}: {}", stderr(&o));
}

/// Show `scenario` with `flags` into a file, run that file as it is, run `scenario` with the
/// same flags, and require identical outputs.
fn shown_file_runs_as_the_scenario(test: &str, scenario: &str, flags: &[&str]) {
    let dir = scratch(test);
    let mut show = vec!["show", scenario];
    show.extend_from_slice(flags);
    let o = platoonsim(&show);
    assert!(o.status.success(), "{show:?}: {}", stderr(&o));
    // Elsewhere than the scenario, so that nothing in it can depend on its directory.
    let file = dir.join("shown").join("scenario.toml");
    std::fs::create_dir_all(file.parent().unwrap()).unwrap();
    std::fs::write(&file, &o.stdout).unwrap();

    let (from_file, direct) = (dir.join("from_file"), dir.join("direct"));
    run(&[s(&file)], &from_file);
    let mut args = vec![scenario];
    args.extend_from_slice(flags);
    run(&args, &direct);
    for name in ["detectors.csv", "scenario.json"] {
        let (a, b) = (
            std::fs::read(from_file.join(name)).unwrap(),
            std::fs::read(direct.join(name)).unwrap(),
        );
        assert!(a == b, "{test}: {name} differs");
    }
    let summary = summary_without_wall_time(&direct);
    assert_eq!(summary_without_wall_time(&from_file), summary, "{test}");
    assert!(
        summary["vehicles_exited"].as_u64().unwrap() > 100,
        "{summary}"
    );
    assert_eq!(summary["collisions"], 0, "{summary}");
}

#[test]
fn show_sr99_at_0_40_100_percent_runs_as_sr99() {
    for p in ["0", "0.4", "1"] {
        shown_file_runs_as_the_scenario(
            &format!("sr99-{p}"),
            "sr99",
            &["--penetration", p, "--set", "run.duration_s=900"],
        );
    }
}

#[test]
fn show_sr99_with_flow_aware_runs_as_sr99() {
    // The thresholds and the demand scale come from sr99's tables; the shown file has the
    // resolved values.
    shown_file_runs_as_the_scenario(
        "sr99-fa",
        "sr99",
        &[
            "--penetration",
            "0.4",
            "--strategy",
            "flow-aware",
            "--set",
            "run.duration_s=900",
        ],
    );
}

/// A corridor of the user's own: the lane drop, with tables of its own next to it.
fn own_corridor(dir: &Path) -> String {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenario/scenarios/lane_drop.toml"
    ))
    .unwrap();
    std::fs::create_dir_all(dir.join("tables")).unwrap();
    std::fs::write(
        dir.join("tables/scales.toml"),
        "[[penetration]]\npenetration = 0\ndemand_scale = 0.9\n\
         [[penetration]]\npenetration = 1\ndemand_scale = 1.1\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("tables/thresholds.toml"),
        "[[penetration]]\npenetration = 0.5\nflow_threshold_vphpl = 1700\nspeed_threshold_kmh = 80\n",
    )
    .unwrap();
    let text = text.replace(
        "demand_scale = 1.0",
        "demand_scale_table = \"tables/scales.toml\"",
    )
        + "\n[strategy]\nkind = \"flow-aware\"\nthresholds_table = \"tables/thresholds.toml\"\n";
    let file = dir.join("corridor.toml");
    std::fs::write(&file, text).unwrap();
    s(&file).to_string()
}

#[test]
fn show_of_a_corridor_of_ones_own_runs_as_the_corridor() {
    let dir = scratch("own");
    let file = own_corridor(&dir);
    shown_file_runs_as_the_scenario(
        "own-corridor",
        &file,
        &[
            "--penetration",
            "0.6",
            "--duration",
            "600",
            "--warmup",
            "120",
        ],
    );
    // The shown file carries the values of the tables, not the references.
    let o = platoonsim(&["show", &file, "--penetration", "0.5"]);
    let text = String::from_utf8(o.stdout).unwrap();
    for part in [
        "demand_scale = 1.0\n",
        "flow_threshold_vphpl = 1700.0\n",
        "speed_threshold_kmh = 80.0\n",
    ] {
        assert!(text.contains(part), "{part} missing:\n{text}");
    }
    assert!(!text.contains("_table"), "{text}");
}

#[test]
fn a_corridor_of_ones_own_gets_no_sr99_scale_and_no_thresholds() {
    let lane_drop = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../scenario/scenarios/lane_drop.toml"
    );
    let dir = scratch("defaults");
    // lane_drop.toml without its demand_scale line: 60 % CAV runs at the demand as written.
    let text = std::fs::read_to_string(lane_drop)
        .unwrap()
        .replace("demand_scale = 1.0", "");
    let file = dir.join("lane_drop.toml");
    std::fs::write(&file, text).unwrap();
    let o = platoonsim(&["show", s(&file), "--penetration", "0.6", "--format", "json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(json["road"]["network"]["demand_scale"], 1.0);
    // Flow-Aware needs thresholds it names: the error says which keys and where the tables are.
    let o = platoonsim(&[
        "run",
        s(&file),
        "--strategy",
        "flow-aware",
        "--out",
        s(&dir.join("o")),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    for part in [
        "strategy.flow_threshold_vphpl = (missing): strategy.kind = \"flow-aware\" needs both thresholds",
        "strategy.speed_threshold_kmh = (missing)",
        "strategy.thresholds_table = \"flow_aware_thresholds\"",
        "crates/scenario/scenarios/flow_aware_thresholds.toml",
    ] {
        assert!(err.contains(part), "{part} missing:\n{err}");
    }
    assert!(!dir.join("o").exists());
}

/// `model.preset = "paper"` (issue 43): `show` names the preset and marks the keys it set,
/// among them the published gap rule and the PATH organization rule; a key given with `--set`
/// wins over the preset and is not marked; the shown file runs as the scenario with the preset
/// (PD at 2,500 veh/h/lane, where the paper's rules matter).
#[test]
fn show_names_the_paper_preset_and_marks_what_it_set() {
    let o = platoonsim(&[
        "show",
        "homogeneous",
        "--set",
        "model.preset=paper",
        "--set",
        "cav.cacc_closing_only_approaching=true",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    for line in [
        "[model]\npreset = \"paper\"",
        "\ngap_rule = \"published\"  # model.preset = \"paper\"\n",
        "\norganize_while_automated = false  # model.preset = \"paper\"\n",
        "\nyield_while_automated = false  # model.preset = \"paper\"\n",
        "\ncacc_closing_only_approaching = true\n",
    ] {
        assert!(text.contains(line), "{line:?} missing:\n{text}");
    }
    let platform = platoonsim(&["show", "homogeneous"]);
    let platform = String::from_utf8(platform.stdout).unwrap();
    assert!(platform.contains("[model]\npreset = \"platform\""));
    assert!(platform.contains("\ngap_rule = \"safe\"\n"));
    assert!(!platform.contains("# model.preset"));
    shown_file_runs_as_the_scenario(
        "paper-preset",
        "homogeneous",
        &[
            "--set",
            "model.preset=paper",
            "--strategy",
            "pd",
            "--duration",
            "900",
            "--warmup",
            "300",
        ],
    );
}
