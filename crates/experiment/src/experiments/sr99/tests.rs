//! Unit tests of the SR-99 experiment: its cells and its figure data.

use super::*;

#[test]
fn cells_follow_the_paper_design() {
    let s = Settings {
        network_duration_s: Some(600.0),
        ..Settings::default()
    };
    let c = cells(&s).unwrap();
    assert_eq!(c.len(), 14);
    assert_eq!(cell_count(&s), 14);
    let labels: Vec<String> = c
        .iter()
        .map(|c| {
            c.labels
                .0
                .iter()
                .map(|(_, v)| v.as_str())
                .collect::<Vec<_>>()
                .join("/")
        })
        .collect();
    assert_eq!(labels[0], "0/1/none");
    assert_eq!(labels[1..4], ["0.2/1/none", "0.2/1/pd", "0.2/1/flow-aware"]);
    assert_eq!(
        labels[4..7],
        ["0.4/1.1/none", "0.4/1.1/pd", "0.4/1.1/flow-aware"]
    );
    assert_eq!(labels[7], "0.6/1.17/none");
    assert_eq!(labels[10], "0.8/1.25/none");
    assert_eq!(labels[13], "1/1.27/none");
    // The engine's scale is the corridor's base multiplier times the cell's.
    let base = base_multiplier(&c[0]).unwrap();
    assert!(base > 0.5 && base < 2.0, "{base}");
    for cell in &c {
        assert!((base_multiplier(cell).unwrap() - base).abs() < 1e-9);
        assert_eq!(cell.config.duration_s, 600.0);
    }
    assert_eq!(c[5].config.strategy.kind, StrategyKind::PD);
    // The tables read which strategies run from the planned cells (the file's `[[skip]]`).
    assert_eq!(strategies_at(&c, "0"), [StrategyKind::NONE]);
    assert_eq!(strategies_at(&c, "1"), [StrategyKind::NONE]);
    assert_eq!(strategies_at(&c, "0.4"), STRATEGIES);
    assert!(strategies_at(&c, "0.5").is_empty());

    // One scale for all, or a table file.
    let fixed = Settings {
        demand_scale: Some(1.2),
        network_penetrations: vec![0.5],
        ..s.clone()
    };
    let c = cells(&fixed).unwrap();
    assert_eq!(c.len(), 3);
    assert!(c
        .iter()
        .all(|c| c.labels.get("demand_scale") == Some("1.2")));
    let dir = std::env::temp_dir().join(format!("platoonsim-scales-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("t.toml");
    std::fs::write(
        &path,
        "[[penetration]]\npenetration = 0\ndemand_scale = 1.3\n\
         [[penetration]]\npenetration = 1\ndemand_scale = 1.5\n",
    )
    .unwrap();
    let table = Settings {
        demand_scale_table: Some(path.clone()),
        network_penetrations: vec![0.0, 0.25],
        ..s.clone()
    };
    let c = cells(&table).unwrap();
    let scales: Vec<&str> = c
        .iter()
        .map(|c| c.labels.get("demand_scale").unwrap())
        .collect();
    assert_eq!(scales, ["1.3", "1.35", "1.35", "1.35"]);
    std::fs::write(&path, "# nothing\n").unwrap();
    assert!(cells(&table).is_err());
    let bad = Settings {
        network_penetrations: vec![1.5],
        ..s
    };
    assert!(cells(&bad).is_err());
}
