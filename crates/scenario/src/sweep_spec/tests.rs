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
