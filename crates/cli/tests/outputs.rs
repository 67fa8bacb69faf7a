//! Issue 48 item 1: no output ever removes or replaces something that is not a regular file at
//! its name. For every file name a command may write or remove (the run directory's list, the
//! sweep's tables), a FIFO, a device node (when the test may make one) and a symbolic link sit
//! at that name: the special files are refused before any work and left as they were; a link
//! stays a link and its target holds the new content (or, for a stale output the command
//! removes, is removed). An output that is one of the command's inputs is refused (D14), and
//! an unwritable output directory fails before the simulation (D13).

mod common;

use common::{platoonsim, s, scratch, stderr};
use std::fs;
use std::path::{Path, PathBuf};

/// Every name `run` writes or removes (`output::RUN_FILES`).
const RUN_FILES: [&str; 12] = [
    "summary.json",
    "scenario.json",
    "scenario.toml",
    "road.json",
    "detectors.csv",
    "detectors.parquet",
    "trips.csv",
    "trips.parquet",
    "trajectories.csv",
    "trajectories.parquet",
    "collisions.csv",
    "view.html",
];

fn mkfifo(p: &Path) {
    let ok = std::process::Command::new("mkfifo")
        .arg(p)
        .status()
        .unwrap();
    assert!(ok.success());
}

/// A character device like /dev/null (1, 3) at `p`, if this process may make one (root).
fn mknod_null(p: &Path) -> bool {
    std::process::Command::new("mknod")
        .arg(p)
        .args(["c", "1", "3"])
        .stderr(std::process::Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

fn kind(p: &Path) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    match fs::symlink_metadata(p) {
        Err(_) => "absent",
        Ok(m) if m.file_type().is_symlink() => "link",
        Ok(m) if m.file_type().is_fifo() => "FIFO",
        Ok(m) if m.file_type().is_char_device() => "device",
        Ok(m) if m.is_file() => "file",
        Ok(_) => "other",
    }
}

fn run(out: &Path) -> std::process::Output {
    platoonsim(&[
        "run",
        "homogeneous",
        "--duration",
        "30",
        "--warmup",
        "0",
        "-q",
        "--out",
        s(out),
    ])
}

/// Makes a special file at a path; false if it may not.
type Maker = fn(&Path) -> bool;

#[test]
fn run_never_removes_or_replaces_a_fifo_a_device_or_a_link_at_any_of_its_names() {
    let dir = scratch("run_special");
    let may_mknod = mknod_null(&dir.join("probe"));
    for (i, name) in RUN_FILES.iter().enumerate() {
        // A FIFO (and a device): refused before the simulation, naming the file, left alone.
        let mut specials: Vec<(&str, Maker)> = vec![("FIFO", |p| {
            mkfifo(p);
            true
        })];
        if may_mknod {
            specials.push(("device", mknod_null));
        }
        for (what, make) in specials {
            let out = dir.join(format!("{what}-{i}"));
            fs::create_dir_all(&out).unwrap();
            let at = out.join(name);
            assert!(make(&at));
            let o = run(&out);
            let err = stderr(&o);
            assert_eq!(o.status.code(), Some(1), "{name} as a {what}: {err}");
            assert!(
                err.contains(&format!("{}: not a regular file", at.display())),
                "{name} as a {what}: {err}"
            );
            assert_eq!(kind(&at), what, "{name}");
            // Nothing else was written: the refusal came before the simulation.
            let others: Vec<_> = fs::read_dir(&out).unwrap().flatten().collect();
            assert_eq!(others.len(), 1, "{name} as a {what}: {others:?}");
        }
        // A link to a regular file elsewhere: the link stays a link; the target is the new
        // file when the run writes the name (summary.json, scenario.*, road.json,
        // detectors.csv), and is
        // removed when the run removes a stale output there (the other tables).
        let out = dir.join(format!("link-{i}"));
        let elsewhere = dir.join(format!("elsewhere-{i}"));
        fs::create_dir_all(&out).unwrap();
        fs::create_dir_all(&elsewhere).unwrap();
        let target = elsewhere.join(name);
        fs::write(&target, b"old").unwrap();
        std::os::unix::fs::symlink(&target, out.join(name)).unwrap();
        let o = run(&out);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        assert_eq!(kind(&out.join(name)), "link", "{name}");
        let written = matches!(
            *name,
            "summary.json" | "scenario.json" | "scenario.toml" | "road.json" | "detectors.csv"
        );
        if written {
            let new = fs::read(&target).unwrap();
            assert_ne!(new, b"old", "{name}");
            assert!(!new.is_empty(), "{name}");
        } else if *name == "view.html" {
            // A run without --view neither writes nor removes the page.
            assert_eq!(fs::read(&target).unwrap(), b"old");
        } else {
            assert_eq!(kind(&target), "absent", "{name}: a stale output stays");
        }
    }
}

#[test]
fn an_unwritable_output_directory_fails_before_the_simulation() {
    // As root a mode of 0555 does not stop a write; /sys is read-only for everyone.
    let dir = scratch("unwritable");
    let ro = dir.join("ro");
    fs::create_dir_all(&ro).unwrap();
    use std::os::unix::fs::PermissionsExt;
    fs::set_permissions(&ro, fs::Permissions::from_mode(0o555)).unwrap();
    let candidates = [ro.clone(), PathBuf::from("/sys/kernel")];
    let Some(out) = candidates.iter().find(|d| {
        let probe = d.join(".probe-outputs-test");
        let writable = fs::write(&probe, b"").is_ok();
        let _ = fs::remove_file(&probe);
        d.is_dir() && !writable
    }) else {
        eprintln!("skipped: no unwritable directory here");
        return;
    };
    // A run of a simulated week would take minutes: the refusal must come at once.
    let started = std::time::Instant::now();
    let o = platoonsim(&[
        "run",
        "homogeneous",
        "--duration",
        "604800",
        "-q",
        "--out",
        s(out),
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains(&format!(
            "cannot write into the output directory {}",
            out.display()
        )),
        "{err}"
    );
    assert!(started.elapsed().as_secs_f64() < 5.0, "{err}");
    fs::set_permissions(&ro, fs::Permissions::from_mode(0o755)).unwrap();
}

#[test]
fn sweep_never_removes_a_fifo_at_its_table_names() {
    let dir = scratch("sweep_special");
    let spec = dir.join("tiny.toml");
    fs::write(
        &spec,
        "scenario = \"homogeneous\"\nseeds = 1\nmetrics = [\"discharge_flow_vphpl\"]\n\
         [set]\n\"run.duration_s\" = 30\n\"run.warmup_s\" = 0\n\
         [axes]\n\"run.penetration\" = [0.2]\n",
    )
    .unwrap();
    for (i, name) in [
        "runs.csv",
        "runs.parquet",
        "summary.csv",
        "summary.parquet",
        "summary.md",
        "run.json",
    ]
    .iter()
    .enumerate()
    {
        let out = dir.join(format!("out-{i}"));
        fs::create_dir_all(&out).unwrap();
        let at = out.join(name);
        mkfifo(&at);
        let o = platoonsim(&["-q", "sweep", s(&spec), "--out", s(&out)]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{name}: {err}");
        assert!(err.contains("not a regular file (a FIFO)"), "{name}: {err}");
        assert_eq!(kind(&at), "FIFO", "{name}");
        assert!(!out.join("runs").exists(), "{name}: ran before refusing");
    }
}

/// A motorway of two edges: enough for `import sumo` to write a scenario.
const NET: &str = r#"<net version="1.20">
  <edge id="a" from="A" to="B" type="highway.motorway">
    <lane id="a_0" index="0" speed="33.33" length="1000"/><lane id="a_1" index="1" speed="33.33" length="1000"/>
  </edge>
  <edge id="b" from="B" to="C" type="highway.motorway">
    <lane id="b_0" index="0" speed="33.33" length="1000"/><lane id="b_1" index="1" speed="33.33" length="1000"/>
  </edge>
  <connection from="a" to="b" fromLane="0" toLane="0" dir="s"/>
  <connection from="a" to="b" fromLane="1" toLane="1" dir="s"/>
</net>"#;

#[test]
fn an_output_that_is_an_input_is_refused() {
    let dir = scratch("input_output");
    // import sumo NET --out NET, directly and through a link.
    let net = dir.join("a.net.xml");
    fs::write(&net, NET).unwrap();
    let ok = platoonsim(&["import", "sumo", s(&net), "--out", s(&dir.join("a.toml"))]);
    assert!(ok.status.success(), "{}", stderr(&ok));
    std::os::unix::fs::symlink(&net, dir.join("alias.toml")).unwrap();
    for out in [
        net.clone(),
        dir.join("alias.toml"),
        dir.join(".").join("a.net.xml"),
    ] {
        let o = platoonsim(&["import", "sumo", s(&net), "--out", s(&out)]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(
            err.contains(&format!(
                "cannot write {}: it is the input {}",
                out.display(),
                net.display()
            )),
            "{err}"
        );
        assert_eq!(fs::read_to_string(&net).unwrap(), NET);
    }
    // view RUN --out RUN/trajectories.csv (and every other file of the run).
    let run_dir = dir.join("run");
    let o = platoonsim(&[
        "run",
        "homogeneous",
        "--duration",
        "30",
        "--warmup",
        "0",
        "-q",
        "--trajectories",
        "1",
        "--trips",
        "--out",
        s(&run_dir),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    for name in [
        "trajectories.csv",
        "summary.json",
        "scenario.json",
        "road.json",
        "detectors.csv",
        "trips.csv",
    ] {
        let input = run_dir.join(name);
        let before = fs::read(&input).unwrap();
        let o = platoonsim(&["view", s(&run_dir), "--out", s(&input)]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{name}: {err}");
        assert!(err.contains("it is the input"), "{name}: {err}");
        assert_eq!(fs::read(&input).unwrap(), before, "{name}");
    }
}
