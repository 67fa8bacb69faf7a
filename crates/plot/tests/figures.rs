//! Every figure kind writes a PNG and an SVG; odd input (empty, NaN) does not panic.
//!
//! Files go to a fresh directory under the system temp dir, removed at the end of each test
//! unless `PLATOONSIM_PLOT_KEEP` is set (to look at the figures).

use std::fs;
use std::path::{Path, PathBuf};

use platoonsim_plot::{
    bar_chart, bar_panels, heatmap, heatmap_panels, heatmap_row, line_chart, panels, Bars, Chart,
    Heatmap, PlotError, Series, Style,
};

/// A fresh, empty directory for one test.
struct Dir(PathBuf);

impl Dir {
    fn new(test: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("platoonsim-plot-{}-{test}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        Dir(dir)
    }

    fn stem(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for Dir {
    fn drop(&mut self) {
        if std::env::var_os("PLATOONSIM_PLOT_KEEP").is_none() {
            let _ = fs::remove_dir_all(&self.0);
        }
    }
}

/// Checks the returned paths, the PNG signature and size, and returns the SVG text.
fn check_files(files: &[PathBuf], stem: &Path) -> String {
    check_files_min(files, stem, 5_000)
}

/// [`check_files`] with a smaller PNG size bound (a blank 1000 × 700 PNG is about 3.5 kB).
fn check_files_min(files: &[PathBuf], stem: &Path, min_png: usize) -> String {
    let png = PathBuf::from(format!("{}.png", stem.display()));
    let svg = PathBuf::from(format!("{}.svg", stem.display()));
    assert_eq!(files, [png.clone(), svg.clone()]);
    let bytes = fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    assert!(bytes.len() > min_png, "PNG of {} bytes", bytes.len());
    let text = fs::read_to_string(&svg).unwrap();
    assert!(text.trim_start().starts_with("<svg"), "SVG start");
    assert!(text.trim_end().ends_with("</svg>"), "SVG end");
    assert_eq!(text.matches("<svg").count(), 1);
    // No temporary files are left behind.
    let dir = stem.parent().unwrap();
    for entry in fs::read_dir(dir).unwrap() {
        let name = entry.unwrap().file_name();
        assert!(!name.to_string_lossy().ends_with(".tmp"), "{name:?} left");
    }
    text
}

fn capacity_chart() -> Chart {
    let x: Vec<f64> = (0..=10).map(|i| i as f64 * 10.0).collect();
    let y: Vec<f64> = x.iter().map(|p| 2000.0 + 0.16 * p * p).collect();
    Chart {
        title: "Capacity vs penetration".into(),
        x_label: "Penetration (%)".into(),
        y_label: "Capacity (veh/h/lane)".into(),
        series: vec![
            Series {
                name: "simulated".into(),
                x: x.clone(),
                band: Some((
                    y.iter().map(|v| v - 60.0).collect(),
                    y.iter().map(|v| v + 60.0).collect(),
                )),
                y: y.clone(),
                style: Style::Line,
            },
            Series {
                name: "ACC only".into(),
                x: x.clone(),
                y: x.iter().map(|p| 2000.0 - 2.0 * p).collect(),
                band: None,
                style: Style::Dashed,
            },
            Series {
                name: "paper".into(),
                x: vec![0.0, 20.0, 40.0, 60.0, 80.0, 100.0],
                y: vec![2040.0, 2090.0, 2280.0, 2560.0, 3000.0, 3650.0],
                band: None,
                style: Style::Markers,
            },
        ],
        y_range: None,
    }
}

#[test]
fn line_chart_writes_png_and_svg() {
    let dir = Dir::new("line");
    let stem = dir.stem("capacity");
    let files = line_chart(&capacity_chart(), &stem).unwrap();
    let svg = check_files(&files, &stem);
    for text in [
        "Capacity vs penetration",
        "Penetration (%)",
        "Capacity (veh/h/lane)",
        "simulated",
        "ACC only",
        "paper",
    ] {
        assert!(svg.contains(text), "SVG lacks {text:?}");
    }
}

#[test]
fn line_chart_survives_empty_and_nan_input() {
    let dir = Dir::new("odd-lines");
    let nan = f64::NAN;
    let odd = Chart {
        title: "Odd <input> & NaN".into(),
        x_label: "Time (s)".into(),
        y_label: "Speed (m/s)".into(),
        series: vec![
            Series {
                name: "empty".into(),
                ..Series::default()
            },
            Series {
                name: "all NaN".into(),
                x: vec![nan, nan],
                y: vec![nan, 1.0],
                band: Some((vec![nan], vec![])),
                style: Style::Dashed,
            },
            Series {
                name: "gaps".into(),
                x: vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0, f64::INFINITY],
                y: vec![10.0, nan, 12.0, 40.0, 11.0, 10.0, 3.0],
                band: Some((vec![9.0, 9.0, nan, 35.0], vec![11.0, 11.0, nan, 45.0, 5.0])),
                style: Style::Line,
            },
            Series {
                name: "one point".into(),
                x: vec![2.5],
                y: vec![30.0],
                band: Some((vec![25.0], vec![50.0])),
                style: Style::Markers,
            },
            Series {
                name: String::new(),
                x: vec![0.0, 5.0],
                y: vec![-100.0, 100.0],
                band: None,
                style: Style::Line,
            },
        ],
        // Clips the 40 peak and the unnamed line.
        y_range: Some((20.0, 5.0)),
    };
    let stem = dir.stem("odd");
    let svg = check_files(&line_chart(&odd, &stem).unwrap(), &stem);
    assert!(svg.contains("Odd &lt;input&gt; &amp; NaN"));
    assert!(svg.contains("gaps") && svg.contains("all NaN"));

    let nothing = Chart::default();
    let stem = dir.stem("nothing");
    check_files(&line_chart(&nothing, &stem).unwrap(), &stem);

    let flat = Chart {
        series: vec![Series {
            name: "flat".into(),
            x: vec![1.0, 1.0],
            y: vec![0.0, 0.0],
            ..Series::default()
        }],
        y_range: Some((f64::NAN, 1.0)),
        ..Chart::default()
    };
    let stem = dir.stem("flat.v2");
    check_files(&line_chart(&flat, &stem).unwrap(), &stem);
}

#[test]
fn panels_draw_a_grid_of_charts() {
    let dir = Dir::new("panels");
    let mut charts = vec![];
    for (k, lanes) in ["1 lane", "2 lanes", "3 lanes"].iter().enumerate() {
        let mut c = capacity_chart();
        c.title = format!("Panel {lanes}");
        c.series[0]
            .y
            .iter_mut()
            .for_each(|v| *v -= 100.0 * k as f64);
        charts.push(c);
    }
    charts.push(Chart::default());
    let stem = dir.stem("grid");
    let svg = check_files(
        &panels(&charts, 2, "Capacity by lane count", &stem).unwrap(),
        &stem,
    );
    for text in [
        "Capacity by lane count",
        "Panel 1 lane",
        "Panel 3 lanes",
        "paper",
    ] {
        assert!(svg.contains(text), "SVG lacks {text:?}");
    }

    let stem = dir.stem("none");
    // No charts and no title: a blank figure.
    check_files_min(&panels(&[], 0, "", &stem).unwrap(), &stem, 1_000);
    let stem = dir.stem("wide");
    check_files(&panels(&charts[..1], 9, "One", &stem).unwrap(), &stem);
}

fn contour() -> Heatmap {
    let x: Vec<f64> = (0..90).map(|i| i as f64 * 0.5).collect();
    let y: Vec<f64> = (0..16).map(|j| j as f64 * 0.5).collect();
    let z = x
        .iter()
        .map(|&t| {
            y.iter()
                .map(|&s| {
                    // A jam wave moving upstream, one broken detector.
                    if (s - 3.0).abs() < 0.1 && (10.0..15.0).contains(&t) {
                        return f64::NAN;
                    }
                    let front = 6.0 - (t - 15.0) * 0.15;
                    let d = (s - front).abs();
                    if t > 15.0 && d < 1.2 {
                        20.0 + 40.0 * d
                    } else {
                        110.0
                    }
                })
                .collect()
        })
        .collect();
    Heatmap {
        title: "Speed contour, 40 % CACC".into(),
        x_label: "Time (min)".into(),
        y_label: "Position (km)".into(),
        x,
        y,
        z,
        z_label: "Speed (km/h)".into(),
        z_range: (0.0, 120.0),
    }
}

#[test]
fn heatmap_writes_png_and_svg() {
    let dir = Dir::new("heat");
    let stem = dir.stem("contour");
    let svg = check_files(&heatmap(&contour(), &stem).unwrap(), &stem);
    for text in [
        "Speed contour, 40 % CACC",
        "Time (min)",
        "Position (km)",
        "Speed (km/h)",
        "no data",
    ] {
        assert!(svg.contains(text), "SVG lacks {text:?}");
    }
}

#[test]
fn heatmap_survives_empty_nan_and_rejects_bad_shapes() {
    let dir = Dir::new("odd-heat");
    let stem = dir.stem("empty");
    check_files(&heatmap(&Heatmap::default(), &stem).unwrap(), &stem);

    let all_nan = Heatmap {
        x: vec![0.0],
        y: vec![1.0, 2.0],
        z: vec![vec![f64::NAN, f64::NAN]],
        z_range: (5.0, 5.0),
        ..Heatmap::default()
    };
    let stem = dir.stem("nan");
    check_files(&heatmap(&all_nan, &stem).unwrap(), &stem);

    let ragged = Heatmap {
        x: vec![0.0, 1.0],
        y: vec![0.0, 1.0],
        z: vec![vec![1.0, 2.0], vec![3.0]],
        ..Heatmap::default()
    };
    let stem = dir.stem("ragged");
    let err = heatmap(&ragged, &stem).unwrap_err();
    assert!(matches!(err, PlotError::Invalid { .. }));
    let message = err.to_string();
    assert!(
        message.contains("ragged.png") && message.contains("z[1]"),
        "{message}"
    );
    assert!(!dir.stem("ragged.png").exists());
}

fn fig8() -> Bars {
    Bars {
        y_include: Vec::new(),
        title: "Lane changes per vehicle".into(),
        y_label: "Lane changes (1/veh)".into(),
        groups: vec!["0 %".into(), "40 %".into(), "80 %".into(), "100 %".into()],
        series: vec![
            (
                "human".into(),
                vec![0.9, 0.8, 0.7, f64::NAN],
                Some(vec![0.05, 0.04, 0.06, 0.0]),
            ),
            (
                "CACC".into(),
                vec![f64::NAN, 0.3, 0.25, 0.2],
                Some(vec![0.0, 0.03, 0.02, 0.02]),
            ),
            ("paper".into(), vec![0.85, 0.7, 0.6, 0.25], None),
        ],
    }
}

#[test]
fn bar_chart_writes_png_and_svg() {
    let dir = Dir::new("bars");
    let stem = dir.stem("fig8");
    let svg = check_files(&bar_chart(&fig8(), &stem).unwrap(), &stem);
    for text in [
        "Lane changes per vehicle",
        "Lane changes (1/veh)",
        "40 %",
        "100 %",
        "human",
        "CACC",
        "paper",
    ] {
        assert!(svg.contains(text), "SVG lacks {text:?}");
    }
}

#[test]
fn heatmap_panels_share_one_colour_bar() {
    let dir = Dir::new("heat-panels");
    let stem = dir.stem("contours");
    let mut maps = vec![contour(), contour(), contour()];
    for (m, name) in maps.iter_mut().zip(["Baseline", "PD lane", "Flow-Aware"]) {
        m.title = name.into();
    }
    // Only the first map's range counts: the others' are ignored.
    maps[1].z_range = (50.0, 60.0);
    let svg = check_files(
        &heatmap_panels(&maps, 3, "Speed contours, 40 % CAV", &stem).unwrap(),
        &stem,
    );
    for text in [
        "Speed contours, 40 % CAV",
        "Baseline",
        "PD lane",
        "Flow-Aware",
        "Speed (km/h)",
        "no data",
    ] {
        assert!(svg.contains(text), "SVG lacks {text:?}");
    }
    assert_eq!(svg.matches("Speed (km/h)").count(), 1, "one colour bar");

    // A bad panel is named; no panels draws an empty figure.
    maps[2].z.pop();
    let err = heatmap_panels(&maps, 3, "", &stem).unwrap_err().to_string();
    assert!(err.contains("panel 3"), "{err}");
    let stem = dir.stem("none");
    check_files_min(&heatmap_panels(&[], 2, "", &stem).unwrap(), &stem, 1_000);
}

#[test]
fn heatmap_row_gives_each_panel_its_own_colour_bar() {
    let dir = Dir::new("heat-row");
    let stem = dir.stem("compare");
    let mut diff = contour();
    diff.title = "Difference".into();
    diff.z_label = "Speed difference (km/h)".into();
    diff.z_range = (-60.0, 60.0);
    let mut sim = contour();
    sim.title = "Simulated".into();
    let svg = check_files(
        &heatmap_row(&[sim, contour(), diff.clone()], "Speeds", &stem).unwrap(),
        &stem,
    );
    assert_eq!(
        svg.matches("Speed (km/h)").count(),
        2,
        "a bar per speed panel"
    );
    assert_eq!(svg.matches("Speed difference (km/h)").count(), 1);
    // The difference bar is labelled on its own scale.
    assert!(svg.contains("\n-60\n"), "no -60 tick");
    diff.z.pop();
    let err = heatmap_row(&[contour(), diff], "", &stem)
        .unwrap_err()
        .to_string();
    assert!(err.contains("panel 2"), "{err}");
}

#[test]
fn bar_panels_draw_a_grid_of_bar_charts() {
    let dir = Dir::new("bar-panels");
    let stem = dir.stem("fig8");
    let mut b = fig8();
    b.title = "Average platoon length".into();
    let svg = check_files(
        &bar_panels(&[fig8(), b, Bars::default()], 3, "Paper Fig. 8", &stem).unwrap(),
        &stem,
    );
    for text in [
        "Paper Fig. 8",
        "Lane changes per vehicle",
        "Average platoon length",
        "100 %",
    ] {
        assert!(svg.contains(text), "SVG lacks {text:?}");
    }
}

#[test]
fn bar_chart_survives_empty_nan_and_negative_input() {
    let dir = Dir::new("odd-bars");
    let stem = dir.stem("empty");
    check_files(&bar_chart(&Bars::default(), &stem).unwrap(), &stem);

    let odd = Bars {
        y_include: Vec::new(),
        title: "Change in delay".into(),
        y_label: "Δ delay (s/veh)".into(),
        groups: vec!["a".into(), "b".into()],
        series: vec![
            ("short".into(), vec![-3.0], Some(vec![f64::NAN, 1.0, 2.0])),
            ("long".into(), vec![2.0, -1.0, 7.0, 8.0], Some(vec![-0.5])),
            ("nan".into(), vec![f64::NAN, f64::INFINITY], None),
            (String::new(), vec![], None),
        ],
    };
    let stem = dir.stem("odd");
    check_files(&bar_chart(&odd, &stem).unwrap(), &stem);

    let groups_only = Bars {
        y_include: Vec::new(),
        groups: vec!["x".into()],
        ..Bars::default()
    };
    let stem = dir.stem("groups-only");
    check_files(&bar_chart(&groups_only, &stem).unwrap(), &stem);
}

#[test]
fn errors_name_the_file() {
    let dir = Dir::new("errors");
    let blocker = dir.stem("not-a-dir");
    fs::write(&blocker, b"x").unwrap();
    let err = line_chart(&capacity_chart(), &blocker.join("fig")).unwrap_err();
    assert!(matches!(err, PlotError::Io { .. }));
    assert!(err.to_string().contains("not-a-dir"), "{err}");
}

#[test]
fn missing_directories_are_created() {
    let dir = Dir::new("nested");
    let stem = dir.stem("a/b/fig");
    check_files(&line_chart(&capacity_chart(), &stem).unwrap(), &stem);
}

#[test]
fn extreme_values_do_not_panic() {
    let dir = Dir::new("extreme");
    for (k, (xs, ys)) in [
        (vec![0.0, 1.0], vec![-1e300, 1e300]),
        (vec![-f64::MAX, f64::MAX], vec![1e-300, 2e-300]),
        (vec![1e15, 1e15 + 1.0], vec![f64::MIN_POSITIVE, 0.0]),
    ]
    .into_iter()
    .enumerate()
    {
        let chart = Chart {
            title: format!("extreme {k}"),
            series: vec![Series {
                name: "s".into(),
                x: xs.clone(),
                y: ys.clone(),
                band: Some((ys.clone(), ys.clone())),
                style: Style::Line,
            }],
            ..Chart::default()
        };
        let stem = dir.stem(&format!("line{k}"));
        check_files_min(&line_chart(&chart, &stem).unwrap(), &stem, 1_000);

        let bars = Bars {
            y_include: Vec::new(),
            groups: vec!["g".into(), "h".into()],
            series: vec![("s".into(), ys.clone(), Some(ys.clone()))],
            ..Bars::default()
        };
        let stem = dir.stem(&format!("bars{k}"));
        check_files_min(&bar_chart(&bars, &stem).unwrap(), &stem, 1_000);

        let h = Heatmap {
            x: xs.clone(),
            y: vec![0.0],
            z: ys.iter().map(|&v| vec![v]).collect(),
            ..Heatmap::default()
        };
        let stem = dir.stem(&format!("heat{k}"));
        // Either drawn or refused with a message; never a panic.
        if let Ok(files) = heatmap(&h, &stem) {
            check_files_min(&files, &stem, 1_000);
        }
    }
}
