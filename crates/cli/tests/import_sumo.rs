//! `platoonsim import sumo` on real SUMO networks (issue 31): small freeways that `netconvert`
//! builds from plain files written here (an on-ramp, an off-ramp, a lane drop, a weaving
//! section, ramps made by `--ramps.guess`) and the freeway examples of the installed SUMO
//! package (`tools/game`: highway, ramp, corridor). Each import must keep the network's mainline
//! length (within 1 %), its ramps and lane counts, run without a collision at 0 % CAV, and
//! carry the routes' demand (hourly flow per mainline edge within GEH 5 of the demand, below
//! capacity). Bad inputs give an error that names them; an imported scenario shown and run
//! again runs identically.
//!
//! Without SUMO the tests are skipped with a message (under `CI=true` they fail instead).

mod common;

use common::sumo::{self, Built, Freeway, FREEWAYS, POSITION_TOLERANCE_M};
use common::{platoonsim, read_csv, s, scratch, stderr, stdout, summary_without_wall_time};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// `platoonsim import sumo NET args… --out OUT`; panics unless it succeeds.
fn import(net: &Path, args: &[&str], out: &Path) -> String {
    let mut all = vec!["import", "sumo", s(net)];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--out", s(out)]);
    let o = platoonsim(&all);
    assert!(
        o.status.success(),
        "{all:?} failed:\n{}{}",
        stdout(&o),
        stderr(&o)
    );
    assert!(out.is_file(), "{all:?} wrote no {}", out.display());
    stdout(&o) + &stderr(&o)
}

/// The resolved engine configuration of a scenario file (`show --format json`).
fn resolved(scenario: &Path) -> Value {
    let o = platoonsim(&["show", s(scenario), "--format", "json"]);
    assert!(
        o.status.success(),
        "show {}: {}",
        scenario.display(),
        stderr(&o)
    );
    serde_json::from_slice(&o.stdout).unwrap()
}

/// `run SCENARIO --penetration 0 --out OUT args…`; panics unless it succeeds without a collision.
fn run(scenario: &Path, out: &Path, args: &[&str]) -> Value {
    let mut all = vec![
        "-q",
        "run",
        s(scenario),
        "--penetration",
        "0",
        "--out",
        s(out),
    ];
    all.extend_from_slice(args);
    let o = platoonsim(&all);
    assert!(o.status.success(), "{all:?}: {}", stderr(&o));
    let summary = summary_without_wall_time(out);
    assert_eq!(summary["collisions"], 0, "{summary}");
    summary
}

/// A ramp's id in the engine's name `"{id}: {name}"` (or just `id`).
fn ramp_id(ramp: &Value) -> String {
    let name = ramp["name"].as_str().unwrap();
    name.split(": ").next().unwrap().to_string()
}

/// Through lanes open at engine position `x`.
fn lanes_at(network: &Value, x: f64) -> usize {
    network["through_lanes"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|l| l["from_m"].as_f64().unwrap() <= x && x < l["to_m"].as_f64().unwrap())
        .count()
}

/// The corridor of an import must have the network's mainline length (within 1 %), start at
/// corridor 0, and have the ramps (ids, positions) and lane counts the network has.
fn check_geometry(name: &str, json: &Value, net_xml: &str, expect: &sumo::Expect) {
    let network = &json["road"]["network"];
    assert_eq!(network["origin_m"], 0.0, "{name}: start_m");
    let length = json["road"]["length_m"].as_f64().unwrap();
    let want = sumo::mainline_length(net_xml, expect.mainline);
    assert!(
        (length - want).abs() <= 0.01 * want,
        "{name}: corridor length {length} m, the network's mainline {want} m"
    );
    for (kind, ramps, want) in [
        ("on_ramps", &network["on_ramps"], expect.on_ramps),
        ("off_ramps", &network["off_ramps"], expect.off_ramps),
    ] {
        let got: Vec<(String, f64)> = ramps
            .as_array()
            .unwrap()
            .iter()
            .map(|r| (ramp_id(r), r["x_m"].as_f64().unwrap()))
            .collect();
        assert_eq!(
            got.iter().map(|g| g.0.as_str()).collect::<Vec<_>>(),
            want.iter().map(|w| w.0).collect::<Vec<_>>(),
            "{name}: {kind} {got:?}"
        );
        for ((id, x), (_, x_near)) in got.iter().zip(want) {
            // Near the node (the drawing), and exactly where the network's lanes put it.
            assert!(
                (x - x_near).abs() <= POSITION_TOLERANCE_M,
                "{name}: {kind} {id} at {x} m, its node at {x_near} m"
            );
            let exact = sumo::ramp_position(net_xml, expect.mainline, id, kind == "on_ramps");
            assert!(
                (x - exact).abs() < 0.01,
                "{name}: {kind} {id} at {x} m, the network has it at {exact} m"
            );
        }
    }
    for &(x, n) in expect.lanes_at {
        assert_eq!(lanes_at(network, x), n, "{name}: lanes at {x} m: {network}");
    }
}

/// GEH of a modelled hourly flow against a counted one.
fn geh(model: f64, count: f64) -> f64 {
    if model + count == 0.0 {
        return 0.0;
    }
    ((model - count).powi(2) / ((model + count) / 2.0)).sqrt()
}

/// Vehicles per hour window counted by each detector (cross-section rows), with its position.
fn hourly_counts(detectors_csv: &Path) -> BTreeMap<String, (f64, Vec<f64>)> {
    let mut out: BTreeMap<String, (f64, Vec<f64>)> = BTreeMap::new();
    for row in read_csv(detectors_csv) {
        if row["lane"] != "all" {
            continue;
        }
        let hour = (common::num(&row, "interval_start_s") / 3600.0).floor() as usize;
        let entry = out
            .entry(row["detector"].clone())
            .or_insert((common::num(&row, "position_m"), Vec::new()));
        if entry.1.len() <= hour {
            entry.1.resize(hour + 1, 0.0);
        }
        entry.1[hour] += common::num(&row, "count");
    }
    out
}

/// Free-flow speed for the demand's travel lag to a detector (m/s): about the mean desired
/// speed of the default drivers (110 km/h).
const LAG_SPEED_MPS: f64 = 30.0;

/// Every mainline edge's detector (`--edge-detectors`) counts, per hour, the demand of the
/// flows that pass the edge (delayed by the free-flow travel time to it) within GEH 5.
fn check_edge_flows(
    name: &str,
    detectors_csv: &Path,
    edges: &[&str],
    demand: &dyn Fn(&str, f64) -> f64,
    hours: usize,
) {
    let counts = hourly_counts(detectors_csv);
    for edge in edges {
        let det = sanitize(edge);
        let (x, per_hour) = counts
            .get(&det)
            .unwrap_or_else(|| panic!("{name}: no detector {det}: {:?}", counts.keys()));
        let lag = x / LAG_SPEED_MPS;
        for (h, counted) in per_hour.iter().take(hours).enumerate() {
            let model: f64 = (0..3600)
                .map(|s| demand(edge, (h * 3600 + s) as f64 + 0.5 - lag) / 3600.0)
                .sum();
            let g = geh(model, *counted);
            assert!(
                g < 5.0,
                "{name}: edge {edge}, hour {h}: counted {counted}, demand {model:.0}, GEH {g:.2}"
            );
        }
        assert!(
            per_hour.len() >= hours,
            "{name}: {det} has {} hours",
            per_hour.len()
        );
    }
}

/// The importer's detector name of an edge: characters outside [A-Za-z0-9_.-] become `_`.
fn sanitize(id: &str) -> String {
    id.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "_.-".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Builds `freeway` with netconvert into `dir`, or `None` when SUMO is missing (skipped).
fn built(test: &str, freeway: &Freeway, dir: &Path) -> Option<Built> {
    let netconvert = sumo::netconvert(test)?;
    Some(freeway.build(&netconvert, dir))
}

#[test]
fn test_networks_import_with_their_length_ramps_lanes_and_demand() {
    let dir = scratch("freeways");
    for freeway in FREEWAYS {
        let Some(b) = built("test_networks_import", freeway, &dir.join(freeway.name)) else {
            return;
        };
        let scenario = dir.join(freeway.name).join("scenario.toml");
        let summary = import(
            &b.net,
            &["--routes", s(&b.routes), "--edge-detectors"],
            &scenario,
        );
        for part in ["kept", "reduced", "dropped"] {
            assert!(
                summary.contains(part),
                "{}: summary without {part}:\n{summary}",
                freeway.name
            );
        }
        let json = resolved(&scenario);
        let net_xml = std::fs::read_to_string(&b.net).unwrap();
        check_geometry(freeway.name, &json, &net_xml, &freeway.expect);
        assert_eq!(
            json["duration_s"],
            f64::from(sumo::DEMAND_END_S),
            "{}",
            freeway.name
        );

        let out = dir.join(freeway.name).join("run");
        let summary = run(&scenario, &out, &[]);
        assert!(
            summary["vehicles_exited"].as_u64().unwrap() > 1000,
            "{summary}"
        );
        check_edge_flows(
            freeway.name,
            &out.join("detectors.csv"),
            freeway.expect.mainline,
            &|edge, t| freeway.demand_through(edge, t),
            2,
        );
    }
}

/// A routes file of flows on known edges, for the shipped networks' below-capacity demand:
/// (route edges, veh/h) over [0, 3600).
fn routes_file(path: &Path, flows: &[(&[&str], f64)]) {
    let mut xml = String::from("<routes>\n");
    for (i, (route, vph)) in flows.iter().enumerate() {
        xml.push_str(&format!(
            "  <flow id=\"f{i}\" begin=\"0\" end=\"3600\" vehsPerHour=\"{vph}\">\n    \
             <route edges=\"{}\"/>\n  </flow>\n",
            route.join(" ")
        ));
    }
    xml.push_str("</routes>\n");
    std::fs::write(path, xml).unwrap();
}

/// One of SUMO's shipped freeway examples: its network and routes files in the installed
/// package, the mainline (given with `--mainline` where the network has no road types), the
/// expected corridor and a below-capacity demand of our own on its edges.
struct Shipped {
    name: &'static str,
    net: &'static str,
    routes: &'static str,
    mainline_flag: bool,
    expect: sumo::Expect,
    demand: &'static [(&'static [&'static str], f64)],
}

const HIGHWAY: Shipped = Shipped {
    name: "highway",
    net: "tools/game/highway/highway.net.xml",
    routes: "tools/game/highway/highway.rou.xml",
    // Found: its edge E0 (the on-ramp's merge, added by hand in netedit) has no road type,
    // and the importer takes untyped edges with the motorway ones.
    mainline_flag: false,
    expect: sumo::Expect {
        mainline: &[
            "145354574",
            "189597495",
            "E0",
            "191842213",
            "153177809",
            "153177820",
        ],
        on_ramps: &[("201283198.145.16", 827.1)],
        off_ramps: &[],
        lanes_at: &[(300.0, 3), (900.0, 3), (2000.0, 3)],
    },
    demand: &[
        // To the mainline's end (the shipped routes end on 191842213).
        (
            &[
                "145354574",
                "189597495",
                "E0",
                "191842213",
                "153177809",
                "153177820",
            ],
            4000.0,
        ),
        (
            &[
                "153180751",
                "201283198",
                "201283198.145",
                "201283198.145.16",
                "E0",
                "191842213",
                "153177809",
                "153177820",
            ],
            500.0,
        ),
    ],
};

const RAMP: Shipped = Shipped {
    name: "ramp",
    net: "tools/game/ramp/ramp.net.xml",
    routes: "tools/game/ramp/ramp.rou.xml",
    mainline_flag: true,
    expect: sumo::Expect {
        mainline: &["gneE2", "offramp", "gneE3", "gneE7", "gneE8", "gneE11"],
        on_ramps: &[("gneE14", 656.6)],
        off_ramps: &[("gneE4", 434.5)],
        // The third lane runs from the start into the off-ramp (an exit-only lane): a lane drop
        // where it ends, at the end of edge "offramp", which is the diverge (434.49 m), not at
        // the next edge's start after the junction (438.32 m).
        lanes_at: &[(200.0, 3), (434.0, 3), (435.0, 2), (1000.0, 2), (1500.0, 2)],
    },
    demand: &[
        (
            &["gneE2", "offramp", "gneE3", "gneE7", "gneE8", "gneE11"],
            2400.0,
        ),
        (&["gneE2", "offramp", "gneE4"], 300.0),
        (&["gneE13", "gneE14", "gneE7", "gneE8", "gneE11"], 300.0),
    ],
};

const CORRIDOR: Shipped = Shipped {
    name: "corridor",
    net: "tools/game/corridor/corridor.net.xml",
    routes: "tools/game/corridor/corridor.rou.xml",
    mainline_flag: true,
    expect: sumo::Expect {
        mainline: &["gneE28", "gneE10", "gneE11", "gneE26"],
        // An urban street with three signalized crossings: at each, the two cross streets'
        // turns onto it are one on-ramp and the turns off it one off-ramp (named by the
        // first edge of each pair); the signals and the crossing traffic are left out.
        on_ramps: &[("gneE12", 207.2), ("gneE14", 407.2), ("gneE23", 607.2)],
        off_ramps: &[("gneE13", 192.8), ("gneE15", 392.8), ("gneE16", 592.8)],
        lanes_at: &[(100.0, 1), (300.0, 1), (500.0, 1), (700.0, 1)],
    },
    demand: &[
        (&["gneE28", "gneE10", "gneE11", "gneE26"], 500.0),
        (&["gneE20", "gneE10", "gneE11", "gneE26"], 100.0),
        (&["gneE28", "gneE13"], 100.0),
    ],
};

fn shipped_network_imports(shipped: &Shipped) {
    let test = format!("shipped_{}", shipped.name);
    let Some(home) = sumo::sumo_home(&test) else {
        return;
    };
    let dir = scratch(&test);
    let net: PathBuf = home.join(shipped.net);
    let net_xml = std::fs::read_to_string(&net).unwrap();
    let mainline = shipped.expect.mainline.join(",");
    let mut flags: Vec<&str> = Vec::new();
    if shipped.mainline_flag {
        flags.extend(["--mainline", &mainline]);
    }

    // The shipped routes (hours of demand, some above capacity): imported and run for 30 min.
    let shipped_routes = home.join(shipped.routes);
    let scenario = dir.join("shipped.toml");
    let mut args = flags.clone();
    args.extend(["--routes", s(&shipped_routes), "--duration-s", "1800"]);
    import(&net, &args, &scenario);
    let json = resolved(&scenario);
    check_geometry(shipped.name, &json, &net_xml, &shipped.expect);
    let summary = run(&scenario, &dir.join("shipped-run"), &[]);
    assert!(
        summary["vehicles_exited"].as_u64().unwrap() > 100,
        "{summary}"
    );

    // Our own demand below capacity: hourly flows per mainline edge.
    let routes = dir.join("below_capacity.rou.xml");
    routes_file(&routes, shipped.demand);
    let scenario = dir.join("below.toml");
    let mut args = flags.clone();
    args.extend(["--routes", s(&routes), "--edge-detectors"]);
    import(&net, &args, &scenario);
    let out = dir.join("below-run");
    run(&scenario, &out, &[]);
    let demand = |edge: &str, t: f64| -> f64 {
        if !(0.0..3600.0).contains(&t) {
            return 0.0;
        }
        shipped
            .demand
            .iter()
            .filter(|(route, _)| route.contains(&edge))
            .map(|(_, vph)| vph)
            .sum()
    };
    check_edge_flows(
        shipped.name,
        &out.join("detectors.csv"),
        shipped.expect.mainline,
        &demand,
        1,
    );
}

#[test]
fn sumo_highway_example_imports() {
    shipped_network_imports(&HIGHWAY);
}

#[test]
fn sumo_ramp_example_imports() {
    shipped_network_imports(&RAMP);
}

#[test]
fn sumo_corridor_example_imports() {
    shipped_network_imports(&CORRIDOR);
}

/// `import` with `args` must fail with exit code 1 and a message containing every `part`.
fn fails_naming(args: &[&str], parts: &[&str]) {
    let o = platoonsim(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    for part in parts {
        assert!(err.contains(part), "{args:?}: {part:?} missing:\n{err}");
    }
}

#[test]
fn bad_inputs_give_errors_naming_them() {
    let Some(netconvert) = sumo::netconvert("bad_inputs") else {
        return;
    };
    let dir = scratch("bad");
    let out = dir.join("out.toml");
    let b = sumo::ON_RAMP.build(&netconvert, &dir.join("net"));

    // Not XML.
    let junk = dir.join("junk.net.xml");
    std::fs::write(&junk, "this is not XML\n").unwrap();
    fails_naming(
        &["import", "sumo", s(&junk), "--out", s(&out)],
        &["junk.net.xml"],
    );
    // A routes file that is not XML.
    fails_naming(
        &[
            "import",
            "sumo",
            s(&b.net),
            "--routes",
            s(&junk),
            "--out",
            s(&out),
        ],
        &["junk.net.xml"],
    );

    // A network that is not a corridor: a grid of streets without a motorway.
    let grid = dir.join("grid.net.xml");
    // netgenerate is next to netconvert (or, like it, on the PATH).
    let netgenerate = netconvert.with_file_name("netgenerate");
    let o = std::process::Command::new(&netgenerate)
        .args(["--grid", "--grid.number", "3", "--output-file", s(&grid)])
        .output()
        .expect("cannot start netgenerate");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    fails_naming(
        &["import", "sumo", s(&grid), "--out", s(&out)],
        // Its streets run both ways: the chain of freeway candidates comes back to itself.
        &["not a corridor", "loop through edge", "--mainline"],
    );
    // A mainline that is not a chain of edges in the travel direction.
    fails_naming(
        &[
            "import",
            "sumo",
            s(&b.net),
            "--mainline",
            "main2,main1",
            "--out",
            s(&out),
        ],
        &["main2", "main1"],
    );
    // A mainline edge the network does not have.
    fails_naming(
        &[
            "import",
            "sumo",
            s(&b.net),
            "--mainline",
            "main1,nosuchedge",
            "--out",
            s(&out),
        ],
        &["nosuchedge"],
    );

    // A routes file naming an edge the network does not have.
    let routes = dir.join("unknown.rou.xml");
    std::fs::write(
        &routes,
        "<routes>\n  <flow id=\"f\" begin=\"0\" end=\"900\" vehsPerHour=\"1000\">\n    \
         <route edges=\"main1 accel nosuchedge\"/>\n  </flow>\n</routes>\n",
    )
    .unwrap();
    fails_naming(
        &[
            "import",
            "sumo",
            s(&b.net),
            "--routes",
            s(&routes),
            "--out",
            s(&out),
        ],
        &["unknown.rou.xml", "nosuchedge"],
    );
    // A missing file.
    fails_naming(
        &[
            "import",
            "sumo",
            s(&dir.join("missing.net.xml")),
            "--out",
            s(&out),
        ],
        &["missing.net.xml"],
    );
    assert!(!out.exists(), "a failed import wrote {}", out.display());
}

#[test]
fn an_imported_scenario_shown_runs_as_the_imported_file() {
    let Some(netconvert) = sumo::netconvert("roundtrip") else {
        return;
    };
    let dir = scratch("roundtrip");
    let b = sumo::WEAVING.build(&netconvert, &dir.join("net"));
    let imported = dir.join("imported.toml");
    import(
        &b.net,
        &[
            "--routes",
            s(&b.routes),
            "--edge-detectors",
            "--duration-s",
            "1800",
        ],
        &imported,
    );
    let o = platoonsim(&["show", s(&imported)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let resolved = dir.join("shown").join("resolved.toml");
    std::fs::create_dir_all(resolved.parent().unwrap()).unwrap();
    std::fs::write(&resolved, &o.stdout).unwrap();
    let a = run(&imported, &dir.join("from-import"), &[]);
    let b = run(&resolved, &dir.join("from-shown"), &[]);
    assert_eq!(a, b);
    assert!(a["vehicles_exited"].as_u64().unwrap() > 100, "{a}");
    for name in ["detectors.csv", "scenario.json"] {
        assert!(
            std::fs::read(dir.join("from-import").join(name)).unwrap()
                == std::fs::read(dir.join("from-shown").join(name)).unwrap(),
            "{name} differs"
        );
    }
}

/// The edges netconvert makes of `tests/fixtures/osm_motorway.osm`: the OSM way ids, split by
/// `--ramps.guess`.
const OSM_MAINLINE: &[&str] = &[
    "100",
    "101-AddedOnRampEdge",
    "101",
    "101-AddedOffRampEdge",
    "102",
];

/// The OpenStreetMap walk-through: `scripts/osm_to_corridor.sh` runs netconvert on the
/// hand-written extract `tests/fixtures/osm_motorway.osm` (a one-direction motorway, 2 lanes,
/// with an on-ramp and an off-ramp) and imports the network with a routes file on its edges.
#[test]
fn osm_extract_becomes_a_running_corridor_through_the_script() {
    let Some(netconvert) = sumo::netconvert("osm_script") else {
        return;
    };
    let dir = scratch("osm");
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let script = root.join("scripts/osm_to_corridor.sh");
    let osm = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/osm_motorway.osm");

    let routes = dir.join("osm.rou.xml");
    routes_file(
        &routes,
        &[
            (OSM_MAINLINE, 2400.0),
            (
                &[
                    "100",
                    "101-AddedOnRampEdge",
                    "101",
                    "101-AddedOffRampEdge",
                    "300",
                ],
                300.0,
            ),
            (
                &[
                    "200",
                    "101-AddedOnRampEdge",
                    "101",
                    "101-AddedOffRampEdge",
                    "102",
                ],
                400.0,
            ),
        ],
    );
    let scenario = dir.join("corridor.toml");
    let script_run = |osm: &Path, scenario: &Path| {
        std::process::Command::new("bash")
            .arg(&script)
            .arg(osm)
            .arg(scenario)
            .args(["--routes", s(&routes), "--edge-detectors"])
            .env("NETCONVERT", &netconvert)
            .env("PLATOONSIM", env!("CARGO_BIN_EXE_platoonsim"))
            .output()
            .unwrap()
    };
    let o = script_run(&osm, &scenario);
    assert!(
        o.status.success(),
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let net_xml = std::fs::read_to_string(dir.join("corridor.net.xml")).unwrap();
    let json = resolved(&scenario);
    check_geometry(
        "osm",
        &json,
        &net_xml,
        &sumo::Expect {
            mainline: OSM_MAINLINE,
            // Nodes 2 and 4 of the extract: 0.01° and 0.03° of longitude east of node 1.
            on_ramps: &[("200", 871.0)],
            off_ramps: &[("300", 2614.0)],
            lanes_at: &[(400.0, 2), (1700.0, 2), (3200.0, 2)],
        },
    );
    // The extract's own length: 0.04° of longitude at 38.5° N (spherical Earth, R = 6371 km).
    let geodesic = 0.04_f64.to_radians() * 6_371_000.0 * 38.5_f64.to_radians().cos();
    let length = json["road"]["length_m"].as_f64().unwrap();
    assert!(
        (length - geodesic).abs() < 0.01 * geodesic,
        "{length} vs {geodesic}"
    );
    let names: Vec<&str> = ["on_ramps", "off_ramps"]
        .iter()
        .flat_map(|k| json["road"]["network"][k].as_array().unwrap())
        .map(|r| r["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        ["200: Elm Street on-ramp", "300: Oak Avenue off-ramp"]
    );

    let out = dir.join("run");
    run(&scenario, &out, &[]);
    let demand = |edge: &str, t: f64| -> f64 {
        if !(0.0..3600.0).contains(&t) {
            return 0.0;
        }
        match edge {
            "100" => 2700.0,
            "102" => 2800.0,
            _ => 3100.0,
        }
    };
    check_edge_flows("osm", &out.join("detectors.csv"), OSM_MAINLINE, &demand, 1);

    // A missing extract: exit 1, naming it.
    let o = script_run(&dir.join("nowhere.osm"), &dir.join("x.toml"));
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("nowhere.osm"));
}
