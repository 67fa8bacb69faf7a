//! Runs in parallel, resumable.
//!
//! Each run is executed single-threaded by the engine; rayon spreads the runs over
//! `jobs` threads. A finished run is written at once to `<runs_dir>/<key>.json` through
//! [`write_atomic`] (temporary file, fsync, rename), so the directory only ever holds
//! complete run files. Before anything is executed, the run files already there are read:
//! a run whose file is present and valid (same key, same seed) is reused, not recomputed.
//! Results come back in the order of the specs, whatever the number of threads and the
//! order in which runs finish.
//!
//! A spec may ask to keep detector records ([`RunSpec::detectors`], a [`Scope`]): they are
//! written to `<runs_dir>/<key>.detectors.csv` (atomically, before the run file, which names
//! the file's scope and hash). Such a run is reused only if its run file is valid, names a
//! scope that covers the one asked for, and the detector file has the named hash; otherwise
//! it is computed again (and both files rewritten). [`Runner::detectors`] reads them back.

use crate::atomic::write_atomic;
use crate::design::RunSpec;
use crate::detectors::{self, DetectorsRef, Scope};
use crate::record::{self, Fields};
use crate::Error;
use indicatif::{ProgressBar, ProgressStyle};
use platoonsim_sim::{Config, DetectorRecord, Output, SimError};
use rayon::prelude::*;
use std::collections::HashMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// What executes one run: the engine ([`simulate`]) or, in tests, a counting wrapper.
pub type Executor<'a> = &'a (dyn Fn(&Config) -> Result<Output, SimError> + Sync);

/// The engine, without a progress callback.
pub fn simulate(config: &Config) -> Result<Output, SimError> {
    platoonsim_sim::run(config, None)
}

/// A run's metrics and whether it was computed (rather than read from its file).
type RunResult = Result<(Fields, bool), Error>;

/// One finished run.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    pub cell: usize,
    pub seed: u64,
    pub key: String,
    pub fields: Fields,
    /// False if it was read from an existing run file.
    pub computed: bool,
}

/// A progress bar counting runs (done / total, with ETA); hidden unless `show`.
pub fn bar(total: usize, show: bool, label: &str) -> ProgressBar {
    if !show {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(total as u64);
    let style = ProgressStyle::with_template(
        "{prefix} [{elapsed_precise}] {bar:40.cyan/blue} {pos}/{len} runs (eta {eta})",
    )
    .unwrap_or_else(|_| ProgressStyle::default_bar())
    .progress_chars("=> ");
    bar.set_style(style);
    bar.set_prefix(label.to_string());
    bar
}

/// Executes run specs; see the module documentation.
pub struct Runner<'a> {
    /// Where run files live (created if missing).
    pub runs_dir: PathBuf,
    /// Worker threads; `None` = one per core.
    pub jobs: Option<usize>,
    /// Read existing run files instead of recomputing (false: recompute and overwrite).
    pub reuse: bool,
    /// Reuse only run files computed by this engine build ([`record::engine_id`]); `None`
    /// accepts any.
    pub engine: Option<String>,
    /// Other experiments' run directories: a run missing here but valid there is copied
    /// here and reused (e.g. `sr99-demand` reusing the baseline runs of `sr99`).
    pub reuse_from: Vec<PathBuf>,
    /// Advanced by one per run, reused or computed.
    pub bar: ProgressBar,
    /// Progress lines for logs (no terminal), advanced with the bar.
    pub log: Option<std::sync::Arc<crate::progress::Lines>>,
    pub exec: Executor<'a>,
    computed: AtomicUsize,
    reused: AtomicUsize,
}

impl<'a> Runner<'a> {
    pub fn new(
        runs_dir: PathBuf,
        jobs: Option<usize>,
        bar: ProgressBar,
        exec: Executor<'a>,
    ) -> Self {
        Runner {
            runs_dir,
            jobs,
            reuse: true,
            engine: Some(record::engine_id().to_string()),
            reuse_from: Vec::new(),
            bar,
            log: None,
            exec,
            computed: AtomicUsize::new(0),
            reused: AtomicUsize::new(0),
        }
    }

    /// Runs executed so far by this runner.
    pub fn computed(&self) -> usize {
        self.computed.load(Ordering::Relaxed)
    }

    /// Runs read from existing files so far by this runner.
    pub fn reused(&self) -> usize {
        self.reused.load(Ordering::Relaxed)
    }

    pub fn file(&self, key: &str) -> PathBuf {
        self.runs_dir.join(format!("{key}.json"))
    }

    /// The detector file of a run that keeps its detector records.
    pub fn detectors_file(&self, key: &str) -> PathBuf {
        self.runs_dir.join(platoonsim_rundir::kept_detectors(key))
    }

    /// The detector records kept by a run (after [`Runner::run`] computed or reused it).
    pub fn detectors(&self, key: &str) -> Result<Vec<DetectorRecord>, Error> {
        let path = self.detectors_file(key);
        let bytes = fs::read(&path).map_err(|e| Error::io(&path, e))?;
        detectors::from_csv(&bytes).map_err(|e| Error::Io {
            path: path.display().to_string(),
            message: e.0,
        })
    }

    /// Execute (or reuse) every spec; results in the order of `specs`. Runs with the same
    /// key are executed once. If runs fail, the others still finish and are saved; the first
    /// failure (in spec order) is returned.
    pub fn run(&self, specs: &[RunSpec]) -> Result<Vec<Outcome>, Error> {
        fs::create_dir_all(&self.runs_dir).map_err(|e| Error::io(&self.runs_dir, e))?;
        remove_stale_tmp(&self.runs_dir);

        // Unique runs in first-appearance order, with how many specs share each and the
        // widest detector scope any of them asks for.
        let keys: Vec<String> = specs.iter().map(RunSpec::key).collect();
        let mut index: HashMap<&str, usize> = HashMap::new();
        let mut unique: Vec<(usize, usize)> = Vec::new(); // (spec index, multiplicity)
        let mut scope: Vec<Scope> = Vec::new();
        for (i, k) in keys.iter().enumerate() {
            match index.get(k.as_str()) {
                Some(&u) => {
                    unique[u].1 += 1;
                    scope[u] = scope[u].max(specs[i].detectors);
                }
                None => {
                    index.insert(k, unique.len());
                    unique.push((i, 1));
                    scope.push(specs[i].detectors);
                }
            }
        }

        let mut results: Vec<Option<RunResult>> = (0..unique.len()).map(|_| None).collect();
        let mut todo = Vec::new();
        for (u, &(i, mult)) in unique.iter().enumerate() {
            let loaded = if self.reuse {
                self.load(&keys[i], specs[i].seed, scope[u])
            } else {
                None
            };
            match loaded {
                Some(fields) => {
                    results[u] = Some(Ok((fields, false)));
                    self.reused.fetch_add(mult, Ordering::Relaxed);
                    self.advance(mult, false);
                }
                None => todo.push(u),
            }
        }

        let work = || -> Vec<(usize, RunResult)> {
            todo.par_iter()
                .map(|&u| {
                    let (i, mult) = unique[u];
                    let r = self.compute(&specs[i], &keys[i], scope[u]);
                    if r.is_ok() {
                        self.computed.fetch_add(mult, Ordering::Relaxed);
                    }
                    self.advance(mult, true);
                    (u, r.map(|f| (f, true)))
                })
                .collect()
        };
        let done = match self.jobs {
            Some(n) => rayon::ThreadPoolBuilder::new()
                .num_threads(n.max(1))
                .build()
                .map_err(|e| Error::Threads(e.to_string()))?
                .install(work),
            None => work(),
        };
        for (u, r) in done {
            results[u] = Some(r);
        }

        let mut out = Vec::with_capacity(specs.len());
        let mut first_error = None;
        for (i, spec) in specs.iter().enumerate() {
            let u = index[keys[i].as_str()];
            match results[u].as_ref().expect("every unique run has a result") {
                Ok((fields, computed)) => out.push(Outcome {
                    cell: spec.cell,
                    seed: spec.seed,
                    key: keys[i].clone(),
                    fields: fields.clone(),
                    // Only the first spec of a shared key counts as computed.
                    computed: *computed && unique[u].0 == i,
                }),
                Err(e) => {
                    if first_error.is_none() {
                        first_error = Some(e.clone());
                    }
                }
            }
        }
        match first_error {
            Some(e) => Err(e),
            None => Ok(out),
        }
    }

    fn advance(&self, n: usize, computed: bool) {
        self.bar.inc(n as u64);
        if let Some(log) = &self.log {
            log.advance(n, computed);
        }
    }

    /// Whether a valid run file of `spec` is already there (or in [`Runner::reuse_from`],
    /// whose files are then copied here): it would be reused, not computed.
    pub fn is_done(&self, spec: &RunSpec) -> bool {
        self.load(&spec.key(), spec.seed, spec.detectors).is_some()
    }

    /// A valid existing run file's metrics, or `None` (missing or unusable: recompute): from
    /// this runner's directory, else from the first of [`Runner::reuse_from`] that has it,
    /// whose files are then copied here (atomically, detector file first).
    fn load(&self, key: &str, seed: u64, scope: Scope) -> Option<Fields> {
        if let Some((fields, _)) = self.load_from(&self.runs_dir, key, seed, scope) {
            return Some(fields);
        }
        self.reuse_from.iter().find_map(|dir| {
            let (fields, files) = self.load_from(dir, key, seed, scope)?;
            let (bytes, csv) = files;
            if let Some(csv) = csv {
                write_atomic(&self.detectors_file(key), &csv).ok()?;
            }
            write_atomic(&self.file(key), &bytes).ok()?;
            Some(fields)
        })
    }

    /// A valid run in `dir`: its metrics, and the bytes of its run file and (if it names one)
    /// detector file. With a detector scope, the run file must name a detector file of a
    /// covering scope, and that file must be there with the named hash.
    #[allow(clippy::type_complexity)]
    fn load_from(
        &self,
        dir: &Path,
        key: &str,
        seed: u64,
        scope: Scope,
    ) -> Option<(Fields, (Vec<u8>, Option<Vec<u8>>))> {
        let bytes = fs::read(dir.join(format!("{key}.json"))).ok()?;
        let (fields, det) = record::decode_with(&bytes, key, seed, self.engine.as_deref()).ok()?;
        let csv = match det {
            Some(det) => fs::read(dir.join(platoonsim_rundir::kept_detectors(key)))
                .ok()
                .filter(|csv| det.matches(csv) && det.scope.covers(scope)),
            None => None,
        };
        if scope != Scope::None && csv.is_none() {
            return None;
        }
        Some((fields, (bytes, csv)))
    }

    fn compute(&self, spec: &RunSpec, key: &str, scope: Scope) -> Result<Fields, Error> {
        let run_error = |message: String| Error::Run {
            key: key.to_string(),
            seed: spec.seed,
            message,
        };
        let output = (self.exec)(&spec.config).map_err(|e| run_error(e.to_string()))?;
        let det = if scope == Scope::None {
            None
        } else {
            let (csv, rows) =
                detectors::to_csv(&output.detectors, scope, None).map_err(|e| run_error(e.0))?;
            let path = self.detectors_file(key);
            write_atomic(&path, &csv).map_err(|e| Error::io(&path, e))?;
            Some(DetectorsRef::of(scope, rows, &csv))
        };
        let bytes = record::encode_with(
            key,
            spec.seed,
            record::engine_id(),
            &output.summary,
            det.as_ref(),
        );
        let path = self.file(key);
        write_atomic(&path, &bytes).map_err(|e| Error::io(&path, e))?;
        // Read back what was written, so a fresh result and a reused one are identical.
        record::decode(&bytes, key, spec.seed, None).map_err(|e| Error::Run {
            key: key.to_string(),
            seed: spec.seed,
            message: e.to_string(),
        })
    }
}

/// A temporary file untouched for this long was left by an interrupted write. Younger ones may
/// belong to another process writing into the same directory right now (the shards of a
/// sweep on a cluster share it): a run file is written in milliseconds.
const STALE_TMP: std::time::Duration = std::time::Duration::from_secs(120);

/// Temporary files left by an interrupted write are never results; remove them (only stale
/// ones: see [`STALE_TMP`]).
fn remove_stale_tmp(dir: &Path) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    let now = std::time::SystemTime::now();
    for e in entries.flatten() {
        if !e.file_name().to_string_lossy().ends_with(".tmp") {
            continue;
        }
        // Only a regular file (never a link, FIFO or device that happens to end in `.tmp`).
        if !e.file_type().is_ok_and(|t| t.is_file()) {
            continue;
        }
        let age = e
            .metadata()
            .and_then(|m| m.modified())
            .ok()
            .and_then(|t| now.duration_since(t).ok());
        if age.is_some_and(|a| a >= STALE_TMP) {
            let _ = fs::remove_file(e.path());
        }
    }
}
