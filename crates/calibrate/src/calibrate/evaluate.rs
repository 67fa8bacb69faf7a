//! One generation's runs and their objective values.
//!
//! A candidate is `replications` runs (seeds 1..=R) of its scenario, keeping the
//! cross-section detector records ([`Scope::CrossSection`]); the runs of a generation are
//! numbered candidate by candidate, seed by seed, continuing the numbering of the generations
//! before (the start point's runs are 0..R).
//!
//! **Sharding** (the same [`Shard`] as a sweep: `--shard I/N` or a scheduler's array index).
//! Every shard replays the optimizer, so every shard knows each generation's runs. Run number
//! r belongs to shard r mod N + 1. A shard computes its own runs (or reuses their files), then
//! waits for the others' run files, polling; if none of the awaited files has appeared for
//! `stale` (a shard died or is slow), it computes the missing runs itself. A run computed twice
//! is harmless: runs are deterministic and files are written atomically (each writer renames
//! its own complete temporary file). An unsharded invocation computes every run of the
//! generation at once. Either way the objective values come only from run files, so any split
//! gives the same values, trace and result.

use super::objective::{terms, Terms, Weights};
use crate::design::RunSpec;
use crate::detectors::Scope;
use crate::field_obs::{mean_over_runs, to_obs};
use crate::runner::{Outcome, Runner};
use crate::sweep::shard::Shard;
use crate::Error;
use platoonsim_field::Obs;
use platoonsim_sim::Config;
use std::time::{Duration, Instant};

/// How a generation is run.
pub struct Batch<'r, 'a> {
    /// Computes this process's runs (progress bar and lines).
    pub runner: &'r Runner<'a>,
    /// Reads run files (silent, reuse on).
    pub reader: &'r Runner<'a>,
    pub shard: Option<Shard>,
    /// Compute the awaited runs after this long without one appearing.
    pub stale: Duration,
    /// Between two looks at the awaited files.
    pub poll: Duration,
    /// Runs of other shards this one computed after a stale wait.
    pub taken_over: std::cell::Cell<usize>,
}

/// The runs of candidates `configs`, numbered from `first`.
pub fn specs(configs: &[Config], seeds: &[u64]) -> Vec<RunSpec> {
    let mut out = Vec::with_capacity(configs.len() * seeds.len());
    for (c, config) in configs.iter().enumerate() {
        for &seed in seeds {
            let mut config = config.clone();
            config.seed = seed;
            out.push(RunSpec {
                cell: c,
                seed,
                config,
                detectors: Scope::CrossSection,
            });
        }
    }
    out
}

/// How many runs of `n` runs numbered from `first` a shard owns.
pub fn owned(shard: Option<Shard>, first: usize, n: usize) -> usize {
    match shard {
        None => n,
        Some(s) => (first..first + n).filter(|&r| s.owns(r)).count(),
    }
}

/// Execute (or reuse, or await) every run; outcomes in spec order, all read from run files.
pub fn run(b: &Batch, specs: &[RunSpec], first: usize) -> Result<Vec<Outcome>, Error> {
    let Some(shard) = b.shard else {
        b.runner.run(specs)?;
        return b.reader.run(specs);
    };
    let mut mine: Vec<RunSpec> = Vec::new();
    let mut awaited: Vec<&RunSpec> = Vec::new();
    for (i, s) in specs.iter().enumerate() {
        if shard.owns(first + i) {
            mine.push(s.clone());
        } else {
            awaited.push(s);
        }
    }
    b.runner.run(&mine)?;
    let mut last_seen = Instant::now();
    loop {
        let before = awaited.len();
        awaited.retain(|s| !b.reader.is_done(s));
        if awaited.is_empty() {
            break;
        }
        if awaited.len() < before {
            last_seen = Instant::now();
        } else if last_seen.elapsed() >= b.stale {
            let missing: Vec<RunSpec> = awaited.iter().map(|s| (*s).clone()).collect();
            b.runner.run(&missing)?;
            b.taken_over.set(b.taken_over.get() + missing.len());
            break;
        }
        std::thread::sleep(b.poll);
    }
    b.reader.run(specs)
}

/// What the objective compares: the field data and where the simulation's are read.
pub struct Target<'f> {
    pub field: &'f [Obs],
    pub weights: Weights,
    /// `run.clock_start` (s after midnight).
    pub clock_start_s: u32,
    /// Simulated intervals starting before this (the warm-up) are not compared.
    pub warmup_s: f64,
}

/// The mean observations of one candidate's runs (its outcomes), warm-up excluded.
pub fn candidate_obs(reader: &Runner, runs: &[&Outcome], t: &Target) -> Result<Vec<Obs>, Error> {
    let mut per_run = Vec::with_capacity(runs.len());
    for o in runs {
        let obs: Vec<Obs> = to_obs(&reader.detectors(&o.key)?, t.clock_start_s)
            .into_iter()
            .filter(|x| f64::from(x.start_s - t.clock_start_s) >= t.warmup_s)
            .collect();
        per_run.push(obs);
    }
    Ok(mean_over_runs(&per_run))
}

/// The terms of every candidate (outcomes grouped by their `cell`, the candidate index).
pub fn objectives(
    reader: &Runner,
    outcomes: &[Outcome],
    candidates: usize,
    t: &Target,
) -> Result<Vec<Terms>, Error> {
    (0..candidates)
        .map(|c| {
            let runs: Vec<&Outcome> = outcomes.iter().filter(|o| o.cell == c).collect();
            let sim = candidate_obs(reader, &runs, t)?;
            terms(t.field, &sim, &t.weights).map_err(Error::Other)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_are_numbered_across_generations_and_split_by_shard() {
        let s = |i| Some(Shard::new(i, 2).unwrap());
        // 6 candidates x 3 seeds from run 3 (after the start's 3 runs)
        assert_eq!(owned(s(1), 3, 18) + owned(s(2), 3, 18), 18);
        assert_eq!(owned(s(1), 3, 3), 1); // runs 3, 4, 5: only 4 is shard 1's
        assert_eq!(owned(None, 3, 18), 18);
        let c = Config::homogeneous(0.5, 1000.0, 300.0, 60.0, 9);
        let sp = specs(&[c.clone(), c], &[1, 2]);
        let cs: Vec<(usize, u64)> = sp.iter().map(|s| (s.cell, s.seed)).collect();
        assert_eq!(cs, [(0, 1), (0, 2), (1, 1), (1, 2)]);
        assert!(sp
            .iter()
            .all(|s| s.config.seed == s.seed && s.detectors == Scope::CrossSection));
    }
}
