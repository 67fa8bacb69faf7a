//! Atomic file writes: every result file goes through [`write_atomic`] (or
//! [`write_atomic_with`] for one written piecewise), so a reader (or a rerun after an
//! interruption) sees either the old file or the complete new one, never a half-written one.
//!
//! The rename replaces the directory entry, so only a regular file (or a new path) may be its
//! target: a device, FIFO, directory or socket is refused with an error naming the path (as
//! root, renaming over `/dev/null` would replace the device node for every other process), and
//! a symbolic link is followed, its final target written atomically and the link kept.

use std::fs::{self, File};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// Write `contents` to `path` atomically: write `<name>.tmp` in the same directory, flush it
/// to disk, rename it over `path`, then flush the directory entry (best effort).
pub fn write_atomic(path: &Path, contents: &[u8]) -> io::Result<()> {
    write_atomic_with(path, |w| w.write_all(contents))
}

/// [`write_atomic`] for contents produced piecewise (a large file that should not be held in
/// memory): `fill` writes them to a buffered writer on `<name>.tmp`; an error from it leaves
/// the old file in place and no tmp file.
pub fn write_atomic_with<F>(path: &Path, fill: F) -> io::Result<()>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    write_atomic_file(path, |f| fill(f))
}

/// [`write_atomic_with`] handing `fill` the buffered file itself (a concrete, `Send` writer,
/// as the Parquet writer needs).
pub fn write_atomic_file<F>(path: &Path, fill: F) -> io::Result<()>
where
    F: FnOnce(&mut io::BufWriter<File>) -> io::Result<()>,
{
    let target = output_target(path)?;
    let path = target.as_path();
    let tmp = tmp_path(path)?;
    let result = (|| {
        let mut f = io::BufWriter::with_capacity(1 << 16, File::create(&tmp)?);
        fill(&mut f)?;
        let f = f.into_inner().map_err(io::IntoInnerError::into_error)?;
        f.sync_all()?;
        drop(f);
        fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result?;
    sync_dir(path);
    Ok(())
}

/// Links followed at most, as the kernel's own limit (`ELOOP`).
const MAX_LINKS: usize = 40;

/// The path the rename may replace: `path` itself when it is absent or a regular file, the
/// final target of a chain of symbolic links (absent or a regular file), otherwise an error
/// naming `path` and what it is.
pub fn output_target(path: &Path) -> io::Result<PathBuf> {
    let mut p = path.to_path_buf();
    for _ in 0..=MAX_LINKS {
        let meta = match fs::symlink_metadata(&p) {
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(p),
            Err(e) => {
                return Err(io::Error::new(
                    e.kind(),
                    format!("cannot write {}: {e}", path.display()),
                ))
            }
            Ok(m) => m,
        };
        let kind = meta.file_type();
        if kind.is_file() {
            return Ok(p);
        }
        if kind.is_symlink() {
            let link = fs::read_link(&p)?;
            p = match p.parent() {
                Some(dir) if link.is_relative() => dir.join(link),
                _ => link,
            };
            continue;
        }
        let via = if p == path {
            String::new()
        } else {
            format!(" (a link to {})", p.display())
        };
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "cannot write {}{via}: not a regular file (a {}); outputs are written only to \
                 regular files or new paths",
                path.display(),
                platoonsim_scenario::bounded::describe(&kind)
            ),
        ));
    }
    Err(io::Error::new(
        io::ErrorKind::InvalidInput,
        format!(
            "cannot write {}: more than {MAX_LINKS} symbolic links",
            path.display()
        ),
    ))
}

fn tmp_path(path: &Path) -> io::Result<PathBuf> {
    let name = path.file_name().ok_or_else(|| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} is not a file path", path.display()),
        )
    })?;
    // Unique per process and write: two processes (the shards of a calibration computing the
    // same run after a stale wait) or two threads may write one path at once, and each must
    // rename only its own complete file. The `.tmp` ending is what stale-file cleanup looks for.
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let mut tmp_name = name.to_os_string();
    tmp_name.push(format!(".{}-{n}.tmp", std::process::id()));
    Ok(path.with_file_name(tmp_name))
}

/// Make the rename durable (on platforms where a directory can be opened and synced).
fn sync_dir(path: &Path) {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("platoonsim-atomic-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn writes_and_replaces_without_leaving_a_tmp_file() {
        let dir = scratch("replace");
        let path = dir.join("summary.json");
        write_atomic(&path, b"first").unwrap();
        write_atomic(&path, b"second").unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"second");
        let names: Vec<_> = fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("summary.json")]);
    }

    #[test]
    fn failure_leaves_the_old_file_and_no_tmp() {
        let dir = scratch("failure");
        let path = dir.join("x.csv");
        write_atomic(&path, b"old").unwrap();
        // The rename cannot replace a non-empty directory: make the target one.
        let blocked = dir.join("blocked");
        fs::create_dir_all(blocked.join("inside")).unwrap();
        assert!(write_atomic(&blocked, b"new").is_err());
        let left: Vec<_> = fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".tmp"))
            .collect();
        assert!(left.is_empty(), "{left:?}");
        assert_eq!(fs::read(&path).unwrap(), b"old");
        // A missing directory is an error, not a panic.
        assert!(write_atomic(&dir.join("missing/x.csv"), b"x").is_err());
    }

    #[test]
    fn concurrent_writers_of_one_path_each_rename_a_complete_file() {
        // Shards that compute the same run write the same path at the same time: every write
        // succeeds and the file is one writer's whole content, never a mix.
        let dir = scratch("concurrent");
        let path = dir.join("run.json");
        let contents: Vec<Vec<u8>> = (0..8u8).map(|i| vec![b'a' + i; 200_000]).collect();
        std::thread::scope(|s| {
            for c in &contents {
                let path = &path;
                s.spawn(move || {
                    for _ in 0..20 {
                        write_atomic(path, c).unwrap();
                    }
                });
            }
        });
        let got = fs::read(&path).unwrap();
        assert!(contents.contains(&got));
        assert_eq!(fs::read_dir(&dir).unwrap().count(), 1);
    }

    #[cfg(unix)]
    #[test]
    fn never_replaces_a_fifo_a_directory_or_a_link() {
        // Issue 35 item 1: `view --out /dev/null` as root replaced the device node. A FIFO
        // stands in for the device (mknod needs root); a directory and a link chain too.
        let dir = scratch("special");
        let fifo = dir.join("pipe");
        let made = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(made.success());
        let err = write_atomic(&fifo, b"x").unwrap_err();
        assert_eq!(
            err.to_string(),
            format!(
                "cannot write {}: not a regular file (a FIFO); outputs are written only to \
                 regular files or new paths",
                fifo.display()
            )
        );
        use std::os::unix::fs::FileTypeExt;
        assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
        let empty = dir.join("empty");
        fs::create_dir(&empty).unwrap();
        let err = write_atomic(&empty, b"x").unwrap_err().to_string();
        assert!(err.contains("not a regular file (a directory)"), "{err}");
        assert!(fs::symlink_metadata(&empty).unwrap().is_dir());

        // A link to a link to a file: the file is written, both links stay links.
        let real = dir.join("real.csv");
        fs::write(&real, b"old").unwrap();
        std::os::unix::fs::symlink("real.csv", dir.join("hop")).unwrap();
        std::os::unix::fs::symlink(dir.join("hop"), dir.join("link.csv")).unwrap();
        write_atomic(&dir.join("link.csv"), b"new").unwrap();
        assert_eq!(fs::read(&real).unwrap(), b"new");
        for l in ["hop", "link.csv"] {
            assert!(fs::symlink_metadata(dir.join(l)).unwrap().is_symlink());
        }
        // A dangling link creates its target; a link to the FIFO is refused, naming both.
        std::os::unix::fs::symlink("fresh.csv", dir.join("dangling")).unwrap();
        write_atomic(&dir.join("dangling"), b"made").unwrap();
        assert_eq!(fs::read(dir.join("fresh.csv")).unwrap(), b"made");
        std::os::unix::fs::symlink("pipe", dir.join("to-pipe")).unwrap();
        let err = write_atomic(&dir.join("to-pipe"), b"x")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("to-pipe (a link to") && err.contains("(a FIFO)"),
            "{err}"
        );
        // A loop of links is an error, not a hang.
        std::os::unix::fs::symlink("loop-b", dir.join("loop-a")).unwrap();
        std::os::unix::fs::symlink("loop-a", dir.join("loop-b")).unwrap();
        let err = write_atomic(&dir.join("loop-a"), b"x")
            .unwrap_err()
            .to_string();
        assert!(err.contains("more than 40 symbolic links"), "{err}");
    }

    #[test]
    fn piecewise_writes_and_failures() {
        let dir = scratch("piecewise");
        let path = dir.join("big.csv");
        write_atomic_with(&path, |w| {
            for i in 0..100_000 {
                writeln!(w, "{i}")?;
            }
            Ok(())
        })
        .unwrap();
        let text = fs::read_to_string(&path).unwrap();
        assert_eq!(text.lines().count(), 100_000);
        assert!(text.ends_with("99999\n"));
        // A failing producer keeps the old file and leaves no tmp file.
        let err = write_atomic_with(&path, |w| {
            w.write_all(b"partial")?;
            Err(io::Error::other("producer failed"))
        })
        .unwrap_err();
        assert_eq!(err.to_string(), "producer failed");
        assert_eq!(fs::read_to_string(&path).unwrap(), text);
        assert!(!dir.join("big.csv.tmp").exists());
    }
}
