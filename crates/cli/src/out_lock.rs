//! An advisory lock on an output directory, held while a command writes it: two processes
//! writing one run directory leave a mix of both runs (issue 35 item 3), which a scheduler's
//! retry of a still-running job easily does. `run`, `experiment`, `compare` and an unsharded
//! `sweep`/`calibrate` (or `--collect`) take it exclusively; the shards of a sweep or a
//! calibration (`--shard I/N`) share it, since they are meant to write one directory at once
//! (each run file is written atomically, and two shards computing the same run write the same
//! bytes).
//!
//! The lock is `flock(2)` (through `fs4`) on the directory itself, so it leaves no file
//! behind, and the kernel releases it when the process ends, however it ends. Elsewhere than
//! Unix a directory cannot be opened as a file: the lock is taken on `DIR/.platoonsim.lock`.

use anyhow::{bail, Context, Result};
use fs4::{FileExt, TryLockError};
use std::fs::File;
use std::path::Path;

/// How a writer shares its directory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Share {
    /// The only writer (a run, an unsharded sweep or calibration, a collect).
    Alone,
    /// One of the shards of a sweep or a calibration.
    Shard,
}

/// Held for as long as the command writes; dropping it (or the process ending) releases it.
#[derive(Debug)]
pub struct OutLock {
    _file: File,
}

/// Create `dir` if needed and lock it, or fail at once naming it if another platoonsim process
/// writes it.
pub fn lock(dir: &Path, share: Share) -> Result<OutLock> {
    std::fs::create_dir_all(dir)
        .with_context(|| format!("cannot create the output directory {}", dir.display()))?;
    let file =
        open(dir).with_context(|| format!("cannot open the output directory {}", dir.display()))?;
    let tried = match share {
        Share::Alone => FileExt::try_lock(&file),
        Share::Shard => FileExt::try_lock_shared(&file),
    };
    match tried {
        Ok(()) => {
            // An existing directory that cannot take a new file fails here, before any work
            // (it used to fail only when the results were written).
            platoonsim_runs::atomic::check_writable_dir(dir)?;
            Ok(OutLock { _file: file })
        }
        Err(TryLockError::WouldBlock) => bail!(
            "another platoonsim process is writing {}: wait for it to end or choose another \
             --out (only the shards of one sweep or calibration, --shard I/N, may write a \
             directory together)",
            dir.display()
        ),
        Err(TryLockError::Error(e)) => {
            Err(e).with_context(|| format!("cannot lock the output directory {}", dir.display()))
        }
    }
}

#[cfg(unix)]
fn open(dir: &Path) -> std::io::Result<File> {
    File::open(dir)
}

#[cfg(not(unix))]
fn open(dir: &Path) -> std::io::Result<File> {
    std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(dir.join(".platoonsim.lock"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writers_exclude_each_other_and_shards_share() {
        let dir = std::env::temp_dir().join(format!("platoonsim-out-lock-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let a = lock(&dir, Share::Alone).unwrap();
        let msg = format!("{:#}", lock(&dir, Share::Alone).unwrap_err());
        assert!(
            msg.starts_with(&format!(
                "another platoonsim process is writing {}:",
                dir.display()
            )),
            "{msg}"
        );
        assert!(lock(&dir, Share::Shard).is_err());
        drop(a);
        let s1 = lock(&dir, Share::Shard).unwrap();
        let s2 = lock(&dir, Share::Shard).unwrap();
        assert!(lock(&dir, Share::Alone).is_err());
        drop((s1, s2));
        drop(lock(&dir, Share::Alone).unwrap());
        // Nothing is left in the directory.
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
