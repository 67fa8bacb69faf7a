//! `platoonsim reproduce`: every experiment (the homogeneous road, then SR-99), then
//! `REPORT.md` and `report.html`.

use crate::args::ReproduceArgs;
use crate::commands::experiment::{describe, settings};
use anyhow::{Context, Result};
use platoonsim_experiment::experiments::{reproduction, QUICK_SEEDS};
use platoonsim_experiment::report::{self, Provenance, ReportInput};
use platoonsim_experiment::{run_experiment, Part, Settings};
use std::time::Instant;

/// What the SR-99 section says about the choices of this invocation.
fn network_note(args: &ReproduceArgs, sr99: &Settings) -> String {
    if args.quick {
        format!(
            "**Quick mode** (to finish within 10 minutes on 2 cores; a 4-hour SR-99 run takes \
             25-75 s of one core, the longer ones at high penetration and with PD): `sr99` runs {} seed(s) at {} % \
             CAV only (the baseline at 0 %, and baseline, PD and Flow-Aware PD at 40 %, the \
             cells of the figures), and `sr99-demand` does not search: it evaluates the \
             bottleneck criterion at the table's demand scales of those two penetrations, on \
             the baseline runs of `sr99` (no extra run). The full reproduction (`platoonsim \
             reproduce`) runs every penetration with 10 seeds and the search.",
            sr99.seeds,
            sr99.network_penetrations
                .iter()
                .map(|p| format!("{}", 100.0 * p))
                .collect::<Vec<_>>()
                .join(" and ")
        )
    } else {
        format!(
            "Every penetration of the paper with {} seeds per cell; the demand-scale search over \
             the grid with the same seeds. `sr99` uses the demand scales of the embedded table \
             (the paper's), not the ones the search finds (see the search's table).",
            sr99.seeds
        )
    }
}

/// The report's provenance: now (UTC), `git describe --always --dirty` of the working
/// directory's repository ("unknown" without git or outside a repository), and the host.
fn provenance() -> Provenance {
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let commit = std::process::Command::new("git")
        .args(["describe", "--always", "--dirty", "--tags"])
        .stderr(std::process::Stdio::null())
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "unknown".into());
    let name = std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .or_else(|| std::env::var("HOSTNAME").ok())
        .or_else(|| std::env::var("COMPUTERNAME").ok())
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "unknown".into());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    Provenance {
        date: report::utc(now),
        commit,
        host: format!(
            "{name} ({} {}, {cores} cores)",
            std::env::consts::OS,
            std::env::consts::ARCH
        ),
    }
}

pub fn reproduce(args: &ReproduceArgs, quiet: bool) -> Result<()> {
    let start = Instant::now();
    let seeds = args
        .seeds
        .unwrap_or(if args.quick { QUICK_SEEDS } else { 10 });
    let mut s = settings(&args.grid, seeds, quiet);
    s.duration_s = args.duration;
    s.warmup_s = args.warmup;
    let mut outputs = Vec::new();
    let mut network: Option<Settings> = None;
    for (name, settings) in reproduction(&s, args.quick, args.seeds, args.network_duration) {
        if name.part == Part::Network {
            network.get_or_insert_with(|| settings.clone());
        }
        let out =
            run_experiment(name, &settings).with_context(|| format!("experiment {name} failed"))?;
        crate::stdout::print(&describe(&out))?;
        outputs.push(out);
    }
    let sr99 = network.context("reproduce has no SR-99 experiment")?;
    let mut command = String::from("platoonsim reproduce");
    if args.quick {
        command.push_str(" --quick");
    }
    if let Some(n) = args.seeds {
        command.push_str(&format!(" --seeds {n}"));
    }
    if args.duration != 3600.0 || args.warmup != 1200.0 {
        command.push_str(&format!(
            " --duration {} --warmup {}",
            args.duration, args.warmup
        ));
    }
    if let Some(d) = args.network_duration {
        command.push_str(&format!(" --network-duration {d}"));
    }
    let wall = start.elapsed().as_secs_f64();
    let note = network_note(args, &sr99);
    let input = ReportInput {
        outputs: &outputs,
        provenance: provenance(),
        command: &command,
        seeds,
        network_seeds: Some(sr99.seeds),
        network_note: &note,
        jobs: s.jobs,
        wall_seconds: wall,
    };
    let (md, html) = report::write(&args.grid.out, &input).context("cannot write the report")?;
    outln!(
        "Report: {} and {}. Total wall time {:.1} s ({:.1} min).",
        md.display(),
        html.display(),
        wall,
        wall / 60.0
    )?;
    Ok(())
}
