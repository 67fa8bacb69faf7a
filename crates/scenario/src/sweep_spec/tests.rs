//! Tests of the sweep file's validation.

use super::*;

fn parse(text: &str) -> Result<Spec, SpecError> {
    Spec::from_toml(text, "s.toml", "s")
}

#[test]
fn a_full_spec() {
    let s = parse(
        r#"
        scenario = "homogeneous"
        seeds = 3
        [set]
        "run.duration_s" = 600
        [axes]
        "run.penetration" = [0.2, 0.4]
        "strategy.kind" = ["none", "pd", "flow-aware"]
        [compare]
        "strategy.kind" = "none"
        "#,
    )
    .unwrap();
    assert_eq!(s.name, "s");
    assert_eq!(s.seeds, [1, 2, 3]);
    assert_eq!(s.set, [("run.duration_s".to_string(), Value::Integer(600))]);
    assert_eq!(s.axes.len(), 2);
    assert_eq!(s.cell_count(), 6);
    assert_eq!(s.compare, Some((1, 0)));
    assert_eq!(label(&s.axes[0].levels[1]), "0.4");
    assert_eq!(
        set_arg("strategy.kind", &s.axes[1].levels[2]),
        "strategy.kind=\"flow-aware\""
    );
}

#[test]
fn labels_name_keys_of_set_or_axes_in_file_order() {
    let head = "scenario = \"homogeneous\"\nseeds = 1\n[set]\n\"run.penetration\" = 0.5\n\
                [axes]\n\"strategy.kind\" = [\"none\", \"pd\"]\n[labels]\n";
    let s = parse(&format!(
        "{head}strategy = \"strategy.kind\"\npenetration = \"run.penetration\"\n"
    ))
    .unwrap();
    assert_eq!(
        s.labels,
        [
            ("strategy".to_string(), "strategy.kind".to_string()),
            ("penetration".to_string(), "run.penetration".to_string())
        ]
    );
    for (bad, key) in [
        ("demand = \"demand.vph_per_lane\"", "labels.demand"),
        ("demand = 2", "labels.demand"),
        ("\"a b\" = \"strategy.kind\"", "labels.a b"),
    ] {
        let e = parse(&format!("{head}{bad}\n")).unwrap_err();
        assert_eq!(e.key, key, "{bad}: {e}");
    }
    assert_eq!(parse(head).unwrap().labels, []);
}

#[test]
fn errors_name_the_spec_key() {
    let cases = [
        ("seeds = 2", "scenario"),
        ("scenario = \"x\"\nseeds = 0", "seeds"),
        ("scenario = \"x\"\nseeds = [1, 1]", "seeds"),
        ("scenario = \"x\"\nseeds = 1\nbogus = 2", "bogus"),
        (
            "scenario = \"x\"\nseeds = 1\n[axes]\n\"run.penetration\" = []",
            "axes.\"run.penetration\"",
        ),
        (
            "scenario = \"x\"\nseeds = 1\n[axes]\n\"a b\" = [1]",
            "axes.\"a b\"",
        ),
        (
            "scenario = \"x\"\nseeds = 1\n[set]\n\"run.seed\" = 1",
            "set.\"run.seed\"",
        ),
        (
            "scenario = \"x\"\nseeds = 1\n[axes]\n\"a\" = [1, 1.0]",
            "axes.\"a\"",
        ),
        (
            "scenario = \"x\"\nseeds = 1\n[axes]\n\"a\" = [1]\n[compare]\n\"b\" = 1",
            "compare.\"b\"",
        ),
        (
            "scenario = \"x\"\nseeds = 1\n[axes]\n\"a\" = [1]\n[compare]\n\"a\" = 2",
            "compare.\"a\"",
        ),
        ("scenario = \"x\"\nseeds = 1\nname = \"../up\"", "name"),
    ];
    for (text, key) in cases {
        let e = parse(text).unwrap_err();
        assert_eq!(e.key, key, "{text}: {e}");
        assert!(e.to_string().contains(key), "{e}");
    }
}

const HEAD: &str = "scenario = \"homogeneous\"\nseeds = 1\n";

#[test]
fn a_bundle_moves_its_keys_together_and_skip_leaves_cells_out() {
    let s = parse(&format!(
        "{HEAD}[axes]\n\
         point = [\n\
           {{ \"run.penetration\" = 0.0, \"demand.vph_per_lane\" = 1000 }},\n\
           {{ \"run.penetration\" = 0.5, \"demand.vph_per_lane\" = 2000 }},\n\
         ]\n\
         driver = [\n\
           {{ name = \"published\", \"lane_change.gap_rule\" = \"published\" }},\n\
           {{ name = \"safe\", \"lane_change.gap_rule\" = \"safe\" }},\n\
         ]\n\
         \"strategy.kind\" = [\"none\", \"pd\"]\n\
         [[skip]]\n\
         \"run.penetration\" = 0.0\n\
         \"strategy.kind\" = \"pd\"\n\
         [labels]\n\
         road = \"scenario\"\n\
         penetration = \"run.penetration\"\n\
         driver = \"driver\"\n\
         [compare]\n\
         driver = \"published\"\n"
    ))
    .unwrap();
    assert!(s.axes[0].is_bundle() && !s.axes[2].is_bundle());
    assert_eq!(s.axes[0].keys(), ["run.penetration", "demand.vph_per_lane"]);
    assert_eq!(s.axes[1].keys(), ["lane_change.gap_rule"]);
    // A level without a name is labelled by its values; with one, by its name.
    assert_eq!(label(&s.axes[0].levels[1]), "0.5, 2000");
    assert_eq!(label(&s.axes[1].levels[1]), "safe");
    assert_eq!(s.compare, Some((1, 0)));
    // 2 x 2 x 2 less the two PD cells at 0 % CAV.
    let combos = s.combinations();
    assert_eq!(s.cell_count(), 6);
    assert_eq!(
        combos,
        [
            vec![0, 0, 0],
            vec![0, 1, 0],
            vec![1, 0, 0],
            vec![1, 0, 1],
            vec![1, 1, 0],
            vec![1, 1, 1]
        ]
    );
    let settings: Vec<String> = s
        .settings(&combos[3])
        .iter()
        .map(|(k, v)| format!("{k}={v}"))
        .collect();
    assert_eq!(
        settings,
        [
            "run.penetration=0.5",
            "demand.vph_per_lane=2000",
            "lane_change.gap_rule=\"published\"",
            "strategy.kind=\"pd\""
        ]
    );
    let labels: Vec<Option<String>> = ["scenario", "run.penetration", "driver", "run.seed"]
        .iter()
        .map(|k| s.label_of(&combos[3], k))
        .collect();
    assert_eq!(
        labels,
        [
            Some("homogeneous".into()),
            Some("0.5".into()),
            Some("published".into()),
            None
        ]
    );
}

#[test]
fn bundle_and_skip_errors_name_the_key_the_value_and_what_is_allowed() {
    let cases: [(&str, &str, &str); 11] = [
        (
            "[axes]\n\"run.point\" = [{ \"run.penetration\" = 0.5 }]",
            "axes.\"run.point\"",
            "no dot",
        ),
        (
            "[axes]\np = [{ \"run.penetration\" = 0.5 }, 0.2]",
            "axes.\"p\"",
            "the level 0.2 is not a table",
        ),
        (
            "[axes]\np = [{ \"run.penetration\" = 0.5 }, { \"demand.vph_per_lane\" = 1 }]",
            "axes.\"p\"",
            "sets demand.vph_per_lane but the first level sets run.penetration",
        ),
        (
            "[axes]\np = [{ name = \"a\", \"run.penetration\" = 0.5 }, { \"run.penetration\" = 0.2 }]",
            "axes.\"p\"",
            "give every level a name, or none",
        ),
        (
            "[axes]\np = [{ name = \"a\" }]",
            "axes.\"p\"",
            "sets no scenario key",
        ),
        (
            "[axes]\np = [{ \"run.seed\" = 2 }]",
            "axes.\"p\"",
            "the seed is set by the sweep's `seeds`",
        ),
        (
            "[set]\n\"run.penetration\" = 0.5\n[axes]\np = [{ \"run.penetration\" = 0.2 }]",
            "axes.\"p\"",
            "run.penetration is also under [set]",
        ),
        (
            "[axes]\n\"run.penetration\" = [0.2]\np = [{ \"run.penetration\" = 0.5 }]",
            "axes.\"p\"",
            "run.penetration is moved by another axis too",
        ),
        (
            "[axes]\n\"run.penetration\" = [0.2, 0.5]\n[[skip]]\n\"strategy.kind\" = \"pd\"",
            "skip[1].\"strategy.kind\"",
            "is not an axis key; the axes set run.penetration",
        ),
        (
            "[axes]\n\"run.penetration\" = [0.2, 0.5]\n[[skip]]\n\"run.penetration\" = [0.3]",
            "skip[1].\"run.penetration\"",
            "0.3 is not one of its levels (0.2, 0.5)",
        ),
        (
            "[axes]\n\"run.penetration\" = [0.2, 0.5]\n[[skip]]\n\"run.penetration\" = [0.2, 0.5]",
            "skip",
            "the rules leave out every cell",
        ),
    ];
    for (text, key, message) in cases {
        let e = parse(&format!("{HEAD}{text}\n")).unwrap_err();
        assert_eq!(e.key, key, "{text}: {e}");
        assert!(e.message.contains(message), "{text}: {e}");
    }
    // A label may name a bundle's key, its name or the scenario, nothing else.
    let e = parse(&format!(
        "{HEAD}[axes]\np = [{{ \"run.penetration\" = 0.2 }}]\n[labels]\nx = \"demand.vph_per_lane\"\n"
    ))
    .unwrap_err();
    assert_eq!(e.key, "labels.x");
    assert!(e.message.contains("\"scenario\", a key of [set]"), "{e}");
}

#[test]
fn a_file_name_that_is_no_name_is_refused_unless_the_file_names_itself() {
    // Issue 48 D12: a sweep file named `...toml` has the stem `..`, and the default output
    // directory `out/sweeps/..` was outside `out/sweeps`.
    let dir = std::env::temp_dir().join(format!("platoonsim-spec-d12-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let text = "scenario = \"homogeneous\"\nseeds = 1\n[axes]\n\"run.penetration\" = [0.2]\n";
    for file in ["...toml", "..toml", ".hidden.toml"] {
        let path = dir.join(file);
        std::fs::write(&path, text).unwrap();
        let e = Spec::from_file(&path).unwrap_err();
        assert_eq!(e.key, "name", "{file}");
        assert!(e.message.contains("which is not a name"), "{file}: {e}");
        std::fs::write(&path, format!("name = \"fine\"\n{text}")).unwrap();
        assert_eq!(Spec::from_file(&path).unwrap().name, "fine");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
