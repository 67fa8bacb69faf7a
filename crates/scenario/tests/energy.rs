//! The energy keys (`[human] powertrain`, `[cav] powertrain`, `[energy]`; docs/energy.md):
//! read, checked with errors naming the key and the allowed values, written back by `show`
//! only when not the default, so that configurations without them keep their JSON.

use platoonsim_model::energy::Powertrain;
use platoonsim_scenario::{from_toml, load, load_with, to_toml, Overrides};

fn with(set: &[&str]) -> Overrides {
    Overrides {
        set: set.iter().map(|s| s.to_string()).collect(),
        ..Overrides::default()
    }
}

#[test]
fn powertrains_and_energy_keys_are_read_and_round_trip() {
    let c = load_with(
        "homogeneous",
        &with(&[
            "cav.powertrain=electric",
            "energy.enabled=true",
            "energy.humans_draft=false",
        ]),
    )
    .unwrap();
    assert_eq!(c.cav.powertrain, Powertrain::Electric);
    assert_eq!(c.human.powertrain, Powertrain::Combustion);
    assert!(c.energy.enabled && c.energy.drag_reduction && !c.energy.humans_draft);
    let text = to_toml(&c);
    assert!(text.contains("powertrain = \"electric\""), "{text}");
    assert!(text.contains("[energy]") && text.contains("humans_draft = false"));
    let back = from_toml(&text, "shown", "x", &Overrides::default()).unwrap();
    assert_eq!(back, c);
}

#[test]
fn defaults_are_not_written() {
    let c = load("homogeneous").unwrap();
    assert_eq!(c.cav.powertrain, Powertrain::Combustion);
    assert!(!c.energy.enabled);
    // The serialized configuration (scenario.json, the run keys) has neither.
    let t = toml::Value::try_from(&c).unwrap();
    assert!(t.get("energy").is_none());
    assert!(t["cav"].get("powertrain").is_none() && t["human"].get("powertrain").is_none());
    assert!(!to_toml(&c).contains("[energy]"));
}

#[test]
fn bad_values_name_the_key_and_what_is_allowed() {
    let e = load_with("homogeneous", &with(&["cav.powertrain=diesel"]))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("cav.powertrain") && e.contains("combustion") && e.contains("electric"),
        "{e}"
    );
    let e = load_with("homogeneous", &with(&["human.powertrain=3"]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("human.powertrain"), "{e}");
    let e = load_with("homogeneous", &with(&["energy.enable=true"]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("energy.enable") && e.contains("enabled"), "{e}");
    let e = load_with("homogeneous", &with(&["energy.enabled=3"]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("energy.enabled"), "{e}");
}
