//! `platoonsim bench`: vehicle updates per second on the homogeneous road at 50 % CAV and
//! 2,500 veh/h/lane (the figure compared with SUMO in issue 2).

use crate::args::BenchArgs;
use crate::output::si;
use crate::progress;
use anyhow::{Context, Result};
use platoonsim_scenario::{load_with, Overrides, StrategyKind};
use serde::Serialize;
use std::time::Instant;

/// The benchmark's fixed operating point.
pub const PENETRATION: f64 = 0.5;
pub const DEMAND_VPHPL: f64 = 2500.0;
pub const SCENARIO: &str = "homogeneous";

#[derive(Debug, Serialize)]
struct Repetition {
    wall_seconds: f64,
    vehicle_updates: u64,
    updates_per_second: f64,
    steps: u64,
    vehicles_entered: u64,
}

#[derive(Debug, Serialize)]
struct Report {
    scenario: &'static str,
    version: &'static str,
    penetration: f64,
    demand_vphpl: f64,
    lanes: u32,
    length_m: f64,
    duration_s: f64,
    dt_s: f64,
    seed: u64,
    repetitions: Vec<Repetition>,
    best_updates_per_second: f64,
    median_updates_per_second: f64,
}

pub fn bench(args: &BenchArgs, quiet: bool) -> Result<()> {
    let overrides = Overrides {
        penetration: Some(PENETRATION),
        demand_vphpl: Some(DEMAND_VPHPL),
        duration_s: Some(args.duration),
        warmup_s: Some((args.duration / 3.0).min(1200.0)),
        seed: Some(args.seed),
        strategy: Some(StrategyKind::NONE),
        set: Vec::new(),
    };
    let config = load_with(SCENARIO, &overrides).context("cannot set up the benchmark")?;
    if !args.json {
        outln!(
            "bench: {} road, {} lanes x {} m, {} % CAV, {} veh/h/lane, {} s at dt {} s, {} repetition(s)",
            SCENARIO,
            config.road.lanes,
            config.road.length_m,
            PENETRATION * 100.0,
            DEMAND_VPHPL,
            config.duration_s,
            config.dt_s,
            args.repeat
        )?;
    }
    let mut reps = Vec::new();
    for i in 0..args.repeat {
        let bar = progress::sim_bar(
            config.duration_s,
            progress::wanted(quiet),
            &format!("run {}/{}", i + 1, args.repeat),
        );
        let start = Instant::now();
        let out = progress::run_with_bar(&config, &bar)
            .map_err(anyhow::Error::msg)
            .context("benchmark simulation failed")?;
        let wall = start.elapsed().as_secs_f64();
        let s = &out.summary;
        let rep = Repetition {
            wall_seconds: wall,
            vehicle_updates: s.vehicle_updates,
            updates_per_second: if wall > 0.0 {
                s.vehicle_updates as f64 / wall
            } else {
                0.0
            },
            steps: s.steps,
            vehicles_entered: s.vehicles_entered,
        };
        if !args.json {
            outln!(
                "run {}: {} vehicle updates/s ({} updates, {} steps, {} vehicles entered, {:.3} s wall)",
                i + 1,
                si(rep.updates_per_second),
                rep.vehicle_updates,
                rep.steps,
                rep.vehicles_entered,
                rep.wall_seconds
            )?;
        }
        reps.push(rep);
    }
    let mut rates: Vec<f64> = reps.iter().map(|r| r.updates_per_second).collect();
    rates.sort_by(f64::total_cmp);
    let best = rates.last().copied().unwrap_or(0.0);
    let median = median_sorted(&rates);
    if args.json {
        let report = Report {
            scenario: SCENARIO,
            version: env!("CARGO_PKG_VERSION"),
            penetration: PENETRATION,
            demand_vphpl: DEMAND_VPHPL,
            lanes: config.road.lanes,
            length_m: config.road.length_m,
            duration_s: config.duration_s,
            dt_s: config.dt_s,
            seed: config.seed,
            repetitions: reps,
            best_updates_per_second: best,
            median_updates_per_second: median,
        };
        outln!("{}", serde_json::to_string_pretty(&report)?)?;
    } else {
        outln!(
            "vehicle updates per second: best {}, median {}",
            si(best),
            si(median)
        )?;
    }
    Ok(())
}

fn median_sorted(v: &[f64]) -> f64 {
    match v.len() {
        0 => 0.0,
        n if n % 2 == 1 => v[n / 2],
        n => (v[n / 2 - 1] + v[n / 2]) / 2.0,
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn median() {
        assert_eq!(super::median_sorted(&[]), 0.0);
        assert_eq!(super::median_sorted(&[1.0, 2.0, 9.0]), 2.0);
        assert_eq!(super::median_sorted(&[1.0, 2.0, 3.0, 9.0]), 2.5);
    }
}
