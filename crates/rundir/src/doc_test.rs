//! docs/outputs.md is held to this crate: for every file, each column (for `road.json`, each
//! field) has a row in that file's table on the page, and the typed word cells list every word.

use crate::*;

const DOC: &str = include_str!("../../../docs/outputs.md");

/// The names in the first cell of each table row of `file`'s section: from the paragraph that
/// starts with `` `file` `` to the next paragraph that starts with another file's name (or a
/// heading).
fn documented_columns(doc: &str, file: &str) -> Vec<(String, String)> {
    let start = format!("`{file}`");
    let mut rows = Vec::new();
    let mut inside = false;
    for line in doc.lines() {
        let begins_file = line.starts_with('`')
            && RUN_FILES
                .iter()
                .any(|f| line.starts_with(&format!("`{f}`")));
        if line.starts_with(&start) {
            inside = true;
        } else if begins_file || line.starts_with('#') {
            inside = false;
        }
        if !inside || !line.starts_with("| `") {
            continue;
        }
        let mut cells = line.split('|').skip(1);
        let (Some(first), Some(meaning)) = (cells.next(), cells.next()) else {
            continue;
        };
        for name in first.split('`').skip(1).step_by(2) {
            rows.push((name.to_string(), meaning.to_string()));
        }
    }
    rows
}

fn missing(file: &str, columns: &[&str]) -> Vec<String> {
    let documented = documented_columns(DOC, file);
    columns
        .iter()
        .filter(|c| !documented.iter().any(|(name, _)| name == *c))
        .map(|c| format!("{file}: {c}"))
        .collect()
}

#[test]
fn every_column_has_a_row_in_docs_outputs_md() {
    let mut trips: Vec<&str> = TRIP_COLUMNS.to_vec();
    trips.extend(TRIP_ENERGY_COLUMNS);
    trips.push(TRIP_ARRIVAL_COLUMN);
    trips.extend(TRIP_CLOCK_COLUMNS);
    let mut detectors = DETECTOR_COLUMNS.to_vec();
    detectors.push("clock");
    let mut gaps = missing(DETECTORS.csv, &detectors);
    gaps.extend(missing(TRIPS.csv, &trips));
    gaps.extend(missing(TRAJECTORIES.csv, &TRAJECTORY_COLUMNS));
    gaps.extend(missing(COLLISIONS, &COLLISION_COLUMNS));
    assert!(gaps.is_empty(), "not in docs/outputs.md: {gaps:?}");
}

/// The fields of a JSON value, a list's elements' as `list[].field`.
fn json_fields(v: &serde_json::Value, prefix: &str, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Object(m) => {
            for (k, v) in m {
                let path = format!("{prefix}{k}");
                out.push(path.clone());
                json_fields(v, &format!("{path}."), out);
            }
        }
        serde_json::Value::Array(items) => {
            for item in items.iter().filter(|i| i.is_object()) {
                json_fields(item, &format!("{}[].", prefix.trim_end_matches('.')), out);
            }
        }
        _ => {}
    }
}

#[test]
fn every_road_json_field_has_a_row_in_docs_outputs_md() {
    let json = serde_json::to_value(crate::road::sample()).unwrap();
    let mut fields = Vec::new();
    json_fields(&json, "", &mut fields);
    fields.sort();
    fields.dedup();
    assert!(
        fields.contains(&"segments[].ends".to_string()),
        "{fields:?}"
    );
    let fields: Vec<&str> = fields.iter().map(String::as_str).collect();
    let gaps = missing(ROAD_JSON, &fields);
    assert!(gaps.is_empty(), "not in docs/outputs.md: {gaps:?}");
}

#[test]
fn the_word_cells_are_listed_in_docs_outputs_md() {
    let rows = documented_columns(DOC, DETECTORS.csv);
    let meaning = |column: &str| {
        rows.iter()
            .find(|(name, _)| name == column)
            .map(|(_, m)| m.clone())
            .unwrap_or_default()
    };
    let road = documented_columns(DOC, ROAD_JSON);
    let road_kind = road
        .iter()
        .find(|(name, _)| name == "detectors[].kind")
        .map(|(_, m)| m.clone())
        .unwrap_or_default();
    for kind in DetectorKind::ALL {
        let word = format!("`{kind}`");
        assert!(
            meaning("kind").contains(&word),
            "{word} not in the kind row"
        );
        assert!(
            road_kind.contains(&word),
            "{word} not in road.json's detectors[].kind row"
        );
    }
    assert!(meaning("lane").contains(&format!("`{}`", Lane::ALL)));
}

#[test]
fn a_section_ends_where_the_next_file_begins() {
    let doc = "`trips.csv`: x\n\n| `id` | a |\n\n`trajectories.csv`: y\n\n| `t_s` | b |\n";
    let names = |file| {
        documented_columns(doc, file)
            .into_iter()
            .map(|(n, _)| n)
            .collect::<Vec<_>>()
    };
    assert_eq!(names("trips.csv"), ["id"]);
    assert_eq!(names("trajectories.csv"), ["t_s"]);
    assert_eq!(missing("view.html", &["x"]), ["view.html: x"]);
}
