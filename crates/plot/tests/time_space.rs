//! `time_space` writes a PNG and an SVG with one polyline per vehicle stay in the lane.
//!
//! Files go to a fresh directory under the system temp dir, removed at the end unless
//! `PLATOONSIM_PLOT_KEEP` is set.

use std::fs;
use std::path::PathBuf;

use platoonsim_plot::{time_space, TimeSpace, Track, TrackSample};

struct Dir(PathBuf);

impl Dir {
    fn new(test: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("platoonsim-tsd-{}-{test}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        Dir(dir)
    }
}

impl Drop for Dir {
    fn drop(&mut self) {
        if std::env::var_os("PLATOONSIM_PLOT_KEEP").is_none() {
            let _ = fs::remove_dir_all(&self.0);
        }
    }
}

/// A vehicle at constant speed `v` (m/s) from `x0`, sampled every second for `n` s; `lane(k)`
/// gives its lane at sample `k`.
fn track(cav: bool, x0: f64, v: f64, n: usize, lane: impl Fn(usize) -> u32) -> Track {
    Track {
        cav,
        samples: (0..n)
            .map(|k| TrackSample {
                t_s: k as f64,
                lane: lane(k),
                x_m: x0 + v * k as f64,
                v_mps: v,
            })
            .collect(),
    }
}

/// Track polylines in the SVG: plotters writes each path as a `<polyline`; the track lines
/// are the ones with a non-black stroke (axes and the line-width key are black).
fn track_polylines(svg: &str) -> usize {
    svg.split("<polyline")
        .skip(1)
        .filter(|p| {
            let tag = &p[..p.find('>').unwrap()];
            !tag.contains("stroke=\"#000000\"")
        })
        .count()
}

#[test]
fn one_polyline_per_stay_in_the_lane() {
    let dir = Dir::new("split");
    let ts = TimeSpace {
        title: "Time-space diagram, lane 1".into(),
        lane: 1,
        tracks: vec![
            // A CAV at 25 m/s that is in lane 2 for samples 10..20: two lines in lane 1.
            track(true, 0.0, 25.0, 40, |k| {
                if (10..20).contains(&k) {
                    2
                } else {
                    1
                }
            }),
            // A human at 15 m/s always in lane 1: one line.
            track(false, 100.0, 15.0, 40, |_| 1),
            // A human always in lane 2: nothing in lane 1.
            track(false, 50.0, 30.0, 40, |_| 2),
        ],
    };
    let stem = dir.0.join("tsd");
    let files = time_space(&ts, &stem).unwrap();
    assert_eq!(files, [dir.0.join("tsd.png"), dir.0.join("tsd.svg")]);
    let png = fs::read(&files[0]).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert!(png.len() > 5_000, "PNG of {} bytes", png.len());
    let svg = fs::read_to_string(&files[1]).unwrap();
    assert!(svg.trim_end().ends_with("</svg>"));
    assert_eq!(
        track_polylines(&svg),
        3,
        "2 stays of the CAV + 1 of the human"
    );
    for label in [
        "Time (s)",
        "Position (m)",
        "Speed (km/h)",
        "lane 1",
        "CAV (thick)",
        "human (thin)",
    ] {
        assert!(svg.contains(label), "{label} missing");
    }
    // Lane 2: the CAV's one stay and the second human.
    let ts2 = TimeSpace { lane: 2, ..ts };
    let files = time_space(&ts2, &dir.0.join("tsd2")).unwrap();
    let svg = fs::read_to_string(&files[1]).unwrap();
    assert_eq!(track_polylines(&svg), 2);
    // No temporary files are left behind.
    for entry in fs::read_dir(&dir.0).unwrap() {
        let name = entry.unwrap().file_name();
        assert!(!name.to_string_lossy().ends_with(".tmp"), "{name:?} left");
    }
}

#[test]
fn empty_and_odd_input_draws_a_frame() {
    let dir = Dir::new("empty");
    let files = time_space(&TimeSpace::default(), &dir.0.join("empty")).unwrap();
    let svg = fs::read_to_string(&files[1]).unwrap();
    assert_eq!(track_polylines(&svg), 0);
    // A lone sample, NaNs and one vehicle: no panic.
    let mut t = track(true, 0.0, 10.0, 3, |_| 1);
    t.samples[1].x_m = f64::NAN;
    let ts = TimeSpace {
        title: String::new(),
        lane: 1,
        tracks: vec![t],
    };
    let files = time_space(&ts, &dir.0.join("odd")).unwrap();
    assert!(fs::metadata(&files[0]).unwrap().len() > 0);
}
