//! The one checked path for outputs (issue 48 item 1): every file a command writes or removes
//! goes through this module, so that no output ever removes or replaces what is not a regular
//! file at one of its names.
//!
//! * [`write_atomic`] (and [`write_atomic_with`], [`write_atomic_file`] for contents written
//!   piecewise): a reader (or a rerun after an interruption) sees either the old file or the
//!   complete new one, never a half-written one. The rename replaces the directory entry, so
//!   only a regular file (or a new path) may be its target: a device, FIFO, directory or socket
//!   is refused with an error naming the path (as root, renaming over `/dev/null` would replace
//!   the device node for every other process), and a symbolic link is followed, its final
//!   target written atomically and the link kept.
//! * [`remove_output`]: a stale output of an earlier invocation is removed under the same
//!   rule: a regular file is removed, a link is followed and its final target removed (the link
//!   stays, dangling until the next write through it), anything else is refused.
//! * [`check_output`]: the same test without touching anything, for the commands that check
//!   every name they may write before any work.
//! * [`same_file`] and [`refuse_input`]: an output that is one of the command's inputs (the
//!   same file, through any link or path spelling) is refused.
//! * [`check_writable_dir`]: an output directory that cannot take a new file is refused before
//!   any work.

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
                crate::describe(&kind)
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

/// Refuse an output path that is not absent, a regular file or a link to one (see
/// [`output_target`]); nothing is touched.
pub fn check_output(path: &Path) -> io::Result<()> {
    output_target(path).map(|_| ())
}

/// Remove an output of an earlier invocation at `path`: nothing if there is none; a regular
/// file is removed; a symbolic link is followed and its final target removed, the link kept
/// (the next write through it makes the target again); a device, FIFO, directory or socket is
/// refused (never unlinked), the error naming `path` and what it is.
pub fn remove_output(path: &Path) -> io::Result<()> {
    let target = output_target(path)?;
    match fs::remove_file(&target) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(io::Error::new(
            e.kind(),
            format!("cannot remove {}: {e}", path.display()),
        )),
        Ok(()) => Ok(()),
    }
}

/// Whether `a` and `b` name the same existing file (links followed; device and inode on Unix,
/// the canonical paths elsewhere). A missing path is no file.
pub fn same_file(a: &Path, b: &Path) -> bool {
    let (Ok(ma), Ok(mb)) = (fs::metadata(a), fs::metadata(b)) else {
        return false;
    };
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        ma.dev() == mb.dev() && ma.ino() == mb.ino()
    }
    #[cfg(not(unix))]
    {
        let _ = (ma, mb);
        matches!((fs::canonicalize(a), fs::canonicalize(b)), (Ok(x), Ok(y)) if x == y)
    }
}

/// Refuse writing `output` when it is one of `inputs` (the same file): the write would replace
/// the input with the output. The error names both and says what `output` is for.
pub fn refuse_input(output: &Path, inputs: &[&Path]) -> io::Result<()> {
    for input in inputs {
        if same_file(output, input) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!(
                    "cannot write {}: it is the input {}; choose another output path",
                    output.display(),
                    input.display()
                ),
            ));
        }
    }
    Ok(())
}

/// Refuse a directory that cannot take a new file (read-only, not a directory, no room for an
/// entry), before any work: a probe file `.platoonsim-probe.PID-N.tmp` is created and removed.
pub fn check_writable_dir(dir: &Path) -> io::Result<()> {
    let probe = tmp_path(&dir.join(".platoonsim-probe"))?;
    match fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
    {
        Ok(f) => {
            drop(f);
            let _ = fs::remove_file(&probe);
            Ok(())
        }
        Err(e) => Err(io::Error::new(
            e.kind(),
            format!(
                "cannot write into the output directory {}: {e}",
                dir.display()
            ),
        )),
    }
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

    #[cfg(unix)]
    #[test]
    fn removal_never_unlinks_a_fifo_and_follows_a_link() {
        // Issue 48 D6: the stale-output removal unlinked a FIFO, a device or a link at an
        // output's name; a link then became a regular file and its target kept the old content.
        let dir = scratch("remove");
        let fifo = dir.join("summary.json");
        assert!(std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success());
        let err = remove_output(&fifo).unwrap_err().to_string();
        assert!(err.contains("not a regular file (a FIFO)"), "{err}");
        use std::os::unix::fs::FileTypeExt;
        assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
        // A link: its regular target is removed, the link stays.
        let real = dir.join("real.csv");
        fs::write(&real, b"old").unwrap();
        std::os::unix::fs::symlink("real.csv", dir.join("trips.csv")).unwrap();
        remove_output(&dir.join("trips.csv")).unwrap();
        assert!(!real.exists());
        assert!(fs::symlink_metadata(dir.join("trips.csv"))
            .unwrap()
            .is_symlink());
        // A regular file is removed; an absent one is no error (the dangling link neither).
        fs::write(dir.join("x.csv"), b"x").unwrap();
        remove_output(&dir.join("x.csv")).unwrap();
        assert!(!dir.join("x.csv").exists());
        remove_output(&dir.join("x.csv")).unwrap();
        remove_output(&dir.join("trips.csv")).unwrap();
        check_output(&dir.join("trips.csv")).unwrap();
        assert!(check_output(&fifo).is_err());
    }

    #[cfg(unix)]
    #[test]
    fn an_output_that_is_an_input_is_refused() {
        // Issue 48 D14: `import sumo NET --out NET` replaced the network.
        let dir = scratch("same");
        let net = dir.join("a.net.xml");
        fs::write(&net, b"<net/>").unwrap();
        std::os::unix::fs::symlink("a.net.xml", dir.join("alias")).unwrap();
        for out in [
            net.clone(),
            dir.join("alias"),
            dir.join(".").join("a.net.xml"),
        ] {
            let err = refuse_input(&out, &[Path::new("/nonexistent"), &net])
                .unwrap_err()
                .to_string();
            assert_eq!(
                err,
                format!(
                    "cannot write {}: it is the input {}; choose another output path",
                    out.display(),
                    net.display()
                )
            );
        }
        refuse_input(&dir.join("new.toml"), &[&net]).unwrap();
        assert!(!same_file(&dir.join("new.toml"), &dir.join("new.toml")));
    }

    #[test]
    fn a_writable_directory_passes_the_probe_and_keeps_no_file() {
        let dir = scratch("probe");
        check_writable_dir(&dir).unwrap();
        assert_eq!(fs::read_dir(&dir).unwrap().count(), 0);
        let err = check_writable_dir(&dir.join("missing"))
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("cannot write into the output directory"),
            "{err}"
        );
    }
}
