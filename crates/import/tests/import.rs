//! A whole import from files: network, routes and loops in, the scenario text out, checked
//! key by key (the mapping rules of docs/import.md).

use platoonsim_import::sumo::{import, Options};
use std::path::{Path, PathBuf};

/// m1 (2 lanes, 1000 m) → m2 (3 lanes, 250 m: on-ramp `on` feeds its right lane, which ends)
/// → m3 (2 lanes, 1000 m) → m4 (2 lanes, 500 m); off-ramp `off` leaves after m3. Internal
/// lanes of 4 m between the mainline edges.
const NET: &str = r#"<net version="1.20">
  <edge id=":B_1" function="internal"><lane id=":B_1_0" index="0" speed="33.33" length="4.00"/></edge>
  <edge id=":C_0" function="internal"><lane id=":C_0_0" index="0" speed="33.33" length="4.00"/></edge>
  <edge id=":D_0" function="internal"><lane id=":D_0_0" index="0" speed="33.33" length="4.00"/></edge>
  <edge id="m1" from="A" to="B" type="highway.motorway">
    <lane id="m1_0" index="0" speed="33.33" length="1000"/><lane id="m1_1" index="1" speed="33.33" length="1000"/>
  </edge>
  <edge id="m2" from="B" to="C" type="highway.motorway">
    <lane id="m2_0" index="0" speed="33.33" length="250"/><lane id="m2_1" index="1" speed="33.33" length="250"/>
    <lane id="m2_2" index="2" speed="33.33" length="250"/>
  </edge>
  <edge id="m3" from="C" to="D" type="highway.motorway">
    <lane id="m3_0" index="0" speed="33.33" length="1000"/><lane id="m3_1" index="1" speed="33.33" length="1000"/>
  </edge>
  <edge id="m4" from="D" to="E" type="highway.motorway">
    <lane id="m4_0" index="0" speed="33.33" length="500"/><lane id="m4_1" index="1" speed="33.33" length="500"/>
  </edge>
  <edge id="on" from="R" to="B" type="highway.motorway_link" name="First St">
    <lane id="on_0" index="0" speed="22.22" length="300"/>
  </edge>
  <edge id="off" from="D" to="X" type="highway.motorway_link"><lane id="off_0" index="0" speed="22.22" length="200"/></edge>
  <junction id="B" type="priority"/>
  <connection from="m1" to="m2" fromLane="0" toLane="1" via=":B_1_0" dir="s"/>
  <connection from="m1" to="m2" fromLane="1" toLane="2" via=":B_1_0" dir="s"/>
  <connection from="on" to="m2" fromLane="0" toLane="0" dir="s"/>
  <connection from="m2" to="m3" fromLane="1" toLane="0" via=":C_0_0" dir="s"/>
  <connection from="m2" to="m3" fromLane="2" toLane="1" via=":C_0_0" dir="s"/>
  <connection from="m3" to="m4" fromLane="0" toLane="0" via=":D_0_0" dir="s"/>
  <connection from="m3" to="m4" fromLane="1" toLane="1" via=":D_0_0" dir="s"/>
  <connection from="m3" to="off" fromLane="0" toLane="0" dir="r"/>
</net>"#;

const ROUTES: &str = r#"<routes>
  <vType id="car" length="4.5" accel="2.0" decel="4.5" sigma="0.5"/>
  <route id="through" edges="m1 m2 m3 m4"/>
  <flow id="main" type="car" route="through" begin="0" end="1800" vehsPerHour="2400"/>
  <flow id="leave" type="car" from="m1" to="off" begin="0" end="1800" period="6"/>
  <flow id="ramp" type="car" begin="900" end="1800" probability="0.25"><route edges="on m2 m3 m4"/></flow>
  <vehicle id="late" type="car" depart="1000" route="through"/>
</routes>"#;

const ADD: &str = r#"<additional>
  <inductionLoop id="L_0" lane="m3_0" pos="-100" freq="300" file="x"/>
  <inductionLoop id="L_1" lane="m3_1" pos="-100" freq="300" file="x"/>
  <inductionLoop id="R" lane="on_0" pos="150" freq="300" file="x"/>
  <laneAreaDetector id="E2" lane="m1_0" pos="10" length="50" freq="300" file="x"/>
</additional>"#;

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("platoonsim-import-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn doc(toml: &str) -> toml::Table {
    toml.parse().unwrap()
}

#[test]
fn a_corridor_with_its_demand_and_loops() {
    let dir = tmp("whole");
    let opts = Options {
        net: write(&dir, "c.net.xml", NET),
        routes: vec![write(&dir, "c.rou.xml", ROUTES)],
        additional: vec![write(&dir, "c.add.xml", ADD)],
        edge_detectors: true,
        ..Options::default()
    };
    let out = import(&opts).unwrap();
    let d = doc(&out.toml);
    assert_eq!(d["name"].as_str(), Some("c"));
    // The file's name, not where the importing user kept it (issue 48).
    assert_eq!(
        d["description"].as_str(),
        Some("Imported from SUMO: 4 edges of c.net.xml (2762 m), 1 on-ramps, 1 off-ramps")
    );
    let net = d["network"].as_table().unwrap();
    // 1000 + 4 + 250 + 4 + 1000 + 4 + 500
    assert_eq!(net["end_m"].as_float(), Some(2762.0));
    // The flows change at 900 s and the run ends at 1800 s: two 900-s intervals.
    assert_eq!(net["interval_s"].as_float(), Some(900.0));
    assert_eq!(d["run"]["duration_s"].as_float(), Some(1800.0));
    // 2400 + 600 (period 6 s) veh/h; one extra vehicle in the second interval (4 veh/h).
    let ml: Vec<f64> = net["mainline_vph"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_float().unwrap())
        .collect();
    assert_eq!(ml, vec![3000.0, 3004.0]);
    let lanes = net["lanes"].as_array().unwrap();
    assert_eq!(lanes.len(), 1);
    assert_eq!(lanes[0]["count"].as_integer(), Some(2));
    let on = &net["on_ramps"].as_array().unwrap()[0];
    assert_eq!(on["id"].as_str(), Some("on"));
    assert_eq!(on["name"].as_str(), Some("First St"));
    assert_eq!(on["x_m"].as_float(), Some(1004.0));
    assert_eq!(on["accel_lane_m"].as_float(), Some(250.0));
    assert_eq!(on["station"].as_str(), Some("R"));
    let ramp: Vec<f64> = on["demand_vph"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_float().unwrap())
        .collect();
    assert_eq!(ramp, vec![0.0, 900.0]); // probability 0.25 per second from 900 s
    let off = &net["off_ramps"].as_array().unwrap()[0];
    assert_eq!(off["x_m"].as_float(), Some(2258.0));
    let frac: Vec<f64> = off["exit_fraction"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_float().unwrap())
        .collect();
    // Of the traffic passing the diverge, the share routed off: 600 / 3000, then 600 / 3904.
    assert_eq!(frac, vec![0.2, (600.0f64 / 3904.0 * 1e6).round() / 1e6]);
    assert_eq!(net["ramp_speed_kmh"].as_float(), Some(80.0));
    // Detectors: the two lane loops of m3 as one cross-section, then one per mainline edge.
    let dets: Vec<(String, f64)> = d["detectors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| {
            (
                t["name"].as_str().unwrap().to_string(),
                t["position_m"].as_float().unwrap(),
            )
        })
        .collect();
    assert_eq!(
        dets,
        vec![
            ("L_0".into(), 2158.0),
            ("m1".into(), 999.0),
            ("m2".into(), 1253.0),
            // Where vehicles leave at the edge's end, 10 m before it: the off-ramp's diverge
            // (2258 m), the road end (2762 m).
            ("m3".into(), 2248.0),
            ("m4".into(), 2752.0)
        ]
    );
    let human = d["human"].as_table().unwrap();
    assert_eq!(human["length_m"]["mean"].as_float(), Some(4.5));
    assert_eq!(human["max_decel"]["mean"].as_float(), Some(-4.5));
    assert!(
        out.notes.dropped.iter().any(|n| n.contains("sigma")),
        "{}",
        out.notes
    );
    assert!(
        out.notes
            .dropped
            .iter()
            .any(|n| n.contains("<laneAreaDetector>")),
        "{}",
        out.notes
    );
    // The header says what was done, as comments, and the file loads as a scenario.
    assert!(out
        .toml
        .starts_with("# Imported by `platoonsim import sumo`"));
    platoonsim_scenario::from_toml(&out.toml, "c.toml", "c", &Default::default()).unwrap();
}

#[test]
fn bad_inputs_name_the_file_and_the_problem() {
    let dir = tmp("bad");
    let net = write(&dir, "c.net.xml", NET);
    let err = |opts: Options| import(&opts).unwrap_err().to_string();
    let notxml = write(&dir, "x.net.xml", "this is not XML");
    let e = err(Options {
        net: notxml,
        ..Options::default()
    });
    assert!(e.contains("x.net.xml: not XML"), "{e}");
    let routes = write(
        &dir,
        "r.rou.xml",
        r#"<routes><route id="a" edges="m1 nowhere"/></routes>"#,
    );
    let e = err(Options {
        net: net.clone(),
        routes: vec![routes],
        ..Options::default()
    });
    assert!(
        e.contains("r.rou.xml:1:") && e.contains("names edge \"nowhere\""),
        "{e}"
    );
    let e = err(Options {
        net: net.clone(),
        mainline: Some(vec!["m1".into(), "m3".into()]),
        ..Options::default()
    });
    assert_eq!(
        e,
        "--mainline m3: no lane of the edge before it, \"m1\", connects to it"
    );
    let e = err(Options {
        net: dir.clone(),
        ..Options::default()
    });
    assert!(e.contains("not a regular file (a directory)"), "{e}");
    let e = err(Options {
        net: net.clone(),
        duration_s: Some(-5.0),
        ..Options::default()
    });
    assert!(
        e.contains("--duration-s -5: must be a number of seconds"),
        "{e}"
    );
    let routes = write(
        &dir,
        "n.rou.xml",
        r#"<routes><flow id="f" from="m1" to="m4" begin="0" end="60"/></routes>"#,
    );
    let e = err(Options {
        net,
        routes: vec![routes],
        ..Options::default()
    });
    assert!(e.contains("<flow id=\"f\"> has no rate"), "{e}");
}

#[test]
fn gzip_networks_read_as_plain_ones() {
    use std::io::Write;
    let dir = tmp("gz");
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    gz.write_all(NET.as_bytes()).unwrap();
    let path = dir.join("c.net.xml.gz");
    std::fs::write(&path, gz.finish().unwrap()).unwrap();
    let a = import(&Options {
        net: path,
        name: Some("c".into()),
        ..Options::default()
    })
    .unwrap();
    let b = import(&Options {
        net: write(&dir, "c.net.xml", NET),
        ..Options::default()
    })
    .unwrap();
    assert_eq!(doc(&a.toml)["network"], doc(&b.toml)["network"]);
}

#[test]
fn demand_never_disappears_silently() {
    // Issue 48 D7: a routeDistribution with zero-sum probabilities or no routes dropped its
    // flow (2,400 of 3,000 veh/h) without a note. D8: a vType with a NaN, 0 or negative
    // length, accel, decel or maxSpeed was left out of the mean but kept its demand weight.
    let dir = tmp("demand");
    let net = write(&dir, "c.net.xml", NET);
    let err = |name: &str, routes: &str| {
        let r = write(&dir, name, routes);
        import(&Options {
            net: net.clone(),
            routes: vec![r],
            ..Options::default()
        })
        .unwrap_err()
        .to_string()
        .replace(&format!("{}/", dir.display()), "")
    };
    let flow = r#"<flow id="f" route="d" begin="0" end="3600" vehsPerHour="2400"/>"#;
    let e = err(
        "zero.rou.xml",
        &format!(
            r#"<routes>
<routeDistribution id="d"><route id="a" edges="m1 m2 m3 m4" probability="0"/><route id="b" edges="m1 m2 m3 off" probability="0"/></routeDistribution>
{flow}</routes>"#
        ),
    );
    assert_eq!(
        e,
        "zero.rou.xml:2: <routeDistribution id=\"d\"> has probabilities that sum to 0: some route \
         needs a probability > 0; its demand would be lost"
    );
    let e = err(
        "empty.rou.xml",
        &format!("<routes>\n<routeDistribution id=\"d\"/>\n{flow}</routes>"),
    );
    assert_eq!(
        e,
        "empty.rou.xml:2: <routeDistribution id=\"d\"> has no <route>: a distribution needs at \
         least one route; its demand would be lost"
    );
    // Inside a flow, and a vTypeDistribution.
    let e = err(
        "inline.rou.xml",
        "<routes><flow id=\"g\" begin=\"0\" end=\"60\" vehsPerHour=\"600\">\n<routeDistribution>\
         <route edges=\"m1 m2\" probability=\"0\"/></routeDistribution></flow></routes>",
    );
    assert!(
        e.starts_with("inline.rou.xml:2: <routeDistribution> has probabilities that sum to 0"),
        "{e}"
    );
    let e = err(
        "types.rou.xml",
        "<routes>\n<vTypeDistribution id=\"t\"/></routes>",
    );
    assert!(
        e.contains("<vTypeDistribution id=\"t\"> has no <vType>"),
        "{e}"
    );
    for (attr, value) in [
        ("length", "nan"),
        ("accel", "0"),
        ("decel", "-4.5"),
        ("maxSpeed", "inf"),
        ("length", "1e300"),
    ] {
        let e = err(
            "v.rou.xml",
            &format!(
                "<routes>\n<vType id=\"car\" {attr}=\"{value}\"/>\n<flow id=\"f\" type=\"car\" \
                 from=\"m1\" to=\"m4\" begin=\"0\" end=\"60\" vehsPerHour=\"600\"/></routes>"
            ),
        );
        assert!(
            e.starts_with(&format!(
                "v.rou.xml:2: <vType id=\"car\"> attribute {attr}=\"{value}\": must be a number in (0, "
            )),
            "{e}"
        );
    }
}

#[test]
fn ordinary_loops_import() {
    // Issue 48 D15: a loop at pos 0 and a loop whose id is an edge's (with --edge-detectors)
    // made scenarios that validation refused, with messages about keys the importer wrote.
    let dir = tmp("loops");
    let net = write(&dir, "c.net.xml", NET);
    let add = write(
        &dir,
        "l.add.xml",
        r#"<additional><inductionLoop id="L0" lane="m1_0" pos="0" freq="300" file="x"/>
<inductionLoop id="m3" lane="m3_0" pos="-1" freq="300" file="x"/></additional>"#,
    );
    let out = import(&Options {
        net,
        additional: vec![add],
        edge_detectors: true,
        ..Options::default()
    })
    .unwrap();
    let d = doc(&out.toml);
    let dets: Vec<(String, f64)> = d["detectors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| {
            (
                t["name"].as_str().unwrap().to_string(),
                t["position_m"].as_float().unwrap(),
            )
        })
        .collect();
    assert!(dets.contains(&("L0".into(), 1.0)), "{dets:?}");
    assert!(dets.iter().any(|(n, _)| n == "m3"), "{dets:?}");
    assert!(dets.iter().any(|(n, _)| n == "m3_end"), "{dets:?}");
    platoonsim_scenario::from_toml_in(
        &out.toml,
        "loops.toml",
        "imported",
        &platoonsim_scenario::Overrides::default(),
        None,
    )
    .unwrap();
}
