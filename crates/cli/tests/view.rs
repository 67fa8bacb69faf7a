//! `platoonsim view` and `run --view` end to end: the page is written where asked, holds the
//! run's samples and nothing that loads from the network; bad input fails with a clear error.
//! (What the page shows is tested in a browser: tests/browser.)

mod common;

use common::{platoonsim, s, scratch, stderr};

/// The value of a top-level number in the page's JSON block.
fn meta_number(html: &str, key: &str) -> f64 {
    let at = html.find(&format!("\"{key}\":")).expect(key) + key.len() + 3;
    let end = html[at..].find([',', '}']).unwrap() + at;
    html[at..end].parse().unwrap()
}

#[test]
fn run_with_view_writes_a_self_contained_page_of_every_sample() {
    let dir = scratch("view_run");
    let o = platoonsim(&[
        "run",
        "homogeneous",
        "--duration",
        "120",
        "--warmup",
        "30",
        "--trajectories",
        "1",
        "--trips",
        "--view",
        "--quiet",
        "--out",
        s(&dir),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let html = std::fs::read_to_string(dir.join("view.html")).unwrap();
    let rows = std::fs::read_to_string(dir.join("trajectories.csv"))
        .unwrap()
        .lines()
        .count()
        - 1;
    assert_eq!(meta_number(&html, "rows") as usize, rows);
    // 1 s to 120 s.
    assert!(html.contains("\"frames\":[1.0,2.0,3.0,"));
    assert!(html.contains("\"platoon_column\":true"));
    for bad in ["http:", "https:", "src=", "href="] {
        assert!(!html.contains(bad), "the page contains {bad}");
    }
    // `view` writes the same page (the build is deterministic) to --out.
    let other = dir.join("again.html");
    let o = platoonsim(&["view", s(&dir), "--out", s(&other)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&other).unwrap(), html);
    assert!(stderr(&o).contains(&format!("view: {rows} samples")));
}

#[test]
fn view_refuses_a_run_without_trajectories_and_a_bad_file() {
    let dir = scratch("view_bad");
    let o = platoonsim(&[
        "run",
        "homogeneous",
        "--duration",
        "30",
        "--warmup",
        "0",
        "--quiet",
        "--out",
        s(&dir),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = platoonsim(&["view", s(&dir)]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("trajectories.csv not found") && e.contains("--trajectories"),
        "{e}"
    );
    std::fs::write(
        dir.join("trajectories.csv"),
        "t_s,id,kind,lane,x_m,v_mps\n0,1,cav,1,abc,3\n",
    )
    .unwrap();
    let o = platoonsim(&["view", s(&dir)]);
    let e = stderr(&o);
    assert!(
        e.contains("line 2, column x_m: 'abc' is not a finite number"),
        "{e}"
    );
    assert!(!dir.join("view.html").exists());
    // --view needs --trajectories.
    let o = platoonsim(&["run", "homogeneous", "--view", "--out", s(&dir)]);
    assert_eq!(o.status.code(), Some(2));
}

/// Files that no run writes (issue 35 item 7): an unknown vehicle kind, a lane the run's road
/// does not have (trajectories from another run), a truncated detectors.csv and a missing
/// road.json (a run directory older than it).
#[test]
fn view_refuses_unknown_kinds_a_mismatched_scenario_and_a_truncated_table() {
    let dir = scratch("view_mismatch");
    let o = platoonsim(&[
        "run",
        "homogeneous",
        "--duration",
        "300",
        "--warmup",
        "0",
        "--trajectories",
        "1",
        "--quiet",
        "--out",
        s(&dir),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let traj = dir.join("trajectories.csv");
    let good = std::fs::read_to_string(&traj).unwrap();
    let header = good.lines().next().unwrap();
    let first = good.lines().nth(1).unwrap();
    let cells: Vec<&str> = first.split(',').collect();
    let with = |col: usize, v: &str| {
        let mut c = cells.clone();
        c[col] = v;
        format!("{header}\n{}\n", c.join(","))
    };
    let col = |name: &str| header.split(',').position(|h| h == name).unwrap();
    for (text, want) in [
        (
            with(col("kind"), "truck"),
            "line 2, column kind: 'truck' is not a vehicle kind (cav or human)",
        ),
        (
            with(col("lane"), "9"),
            "line 2, column lane: '9' is not a lane of the road in road.json (1 to 3): \
             trajectories.csv and road.json are not from the same run",
        ),
    ] {
        std::fs::write(&traj, text).unwrap();
        let o = platoonsim(&["view", s(&dir)]);
        assert_eq!(o.status.code(), Some(1));
        assert!(stderr(&o).contains(want), "{}", stderr(&o));
    }
    std::fs::write(&traj, good).unwrap();
    let det = dir.join("detectors.csv");
    let table = std::fs::read_to_string(&det).unwrap();
    std::fs::write(&det, &table[..table.len() - 3]).unwrap();
    let o = platoonsim(&["view", s(&dir)]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("detectors.csv is truncated (its last line has no line break)"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.join("view.html").exists());
    std::fs::write(&det, table).unwrap();
    assert!(platoonsim(&["view", s(&dir)]).status.success());
    // A run directory from before road.json: the error names the file and the way out.
    std::fs::remove_file(dir.join("road.json")).unwrap();
    let o = platoonsim(&["view", s(&dir)]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("road.json not found: the run directory predates road.json")
            && e.contains("platoonsim run ... --trajectories"),
        "{e}"
    );
}
