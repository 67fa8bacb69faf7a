//! SUMO networks for the import tests (issue 31): finding SUMO's `netconvert` and the installed
//! package's `SUMO_HOME`, small freeways written as SUMO plain node/edge/connection files and
//! built by `netconvert`, their demand as a routes file of flows, and the few facts of a
//! `.net.xml` a test needs to check an import independently (lane and internal-lane lengths).
//!
//! `.ci/python-deps` installs the `eclipse-sumo` package. Outside CI a machine without SUMO
//! skips these tests with a message; under CI (`CI=true`) a missing SUMO fails them.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

/// How to install what is missing (the message of a skip or of a CI failure).
const INSTALL: &str = "install it with `python3 -m pip install eclipse-sumo==1.28.0` \
                       (.ci/python-deps does), or set NETCONVERT to a netconvert binary";

fn under_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true" || v == "1")
}

/// SUMO is missing: under CI the test fails; otherwise it prints why it is skipped (the caller
/// then returns).
fn missing(test: &str, why: &str) {
    assert!(!under_ci(), "CI=true but SUMO is missing: {why}; {INSTALL}");
    eprintln!("skipped: {test}: {why}; {INSTALL}");
}

/// Whether `program --version` runs.
fn runs(program: &Path) -> bool {
    Command::new(program)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

/// `SUMO_HOME` of the `sumo` Python package (`eclipse-sumo` from PyPI), if it is installed.
fn python_sumo_home() -> Result<PathBuf, String> {
    match Command::new("python3")
        .args(["-c", "import sumo; print(sumo.SUMO_HOME)"])
        .output()
    {
        Ok(o) if o.status.success() => Ok(PathBuf::from(
            String::from_utf8_lossy(&o.stdout).trim().to_string(),
        )),
        Ok(o) => Err(format!(
            "python3 cannot import sumo ({})",
            String::from_utf8_lossy(&o.stderr)
                .trim()
                .lines()
                .last()
                .unwrap_or("")
        )),
        Err(e) => Err(format!("cannot start python3: {e}")),
    }
}

/// Where netconvert is, or why it was not found: the environment variable `NETCONVERT`, then
/// `netconvert` on the PATH, then `bin/netconvert` of the Python package's SUMO_HOME.
pub fn find_netconvert() -> Result<PathBuf, String> {
    if let Some(path) = std::env::var_os("NETCONVERT") {
        let path = PathBuf::from(path);
        return if runs(&path) {
            Ok(path)
        } else {
            Err(format!(
                "NETCONVERT = {} does not run (`--version` failed)",
                path.display()
            ))
        };
    }
    let on_path = PathBuf::from("netconvert");
    if runs(&on_path) {
        return Ok(on_path);
    }
    let home = python_sumo_home().map_err(|e| format!("no netconvert on the PATH and {e}"))?;
    let bin = home.join("bin").join("netconvert");
    if runs(&bin) {
        Ok(bin)
    } else {
        Err(format!(
            "no netconvert on the PATH, and {} does not run",
            bin.display()
        ))
    }
}

/// netconvert for `test`, or `None` when the test is to be skipped (a CI run fails instead).
pub fn netconvert(test: &str) -> Option<PathBuf> {
    match find_netconvert() {
        Ok(p) => Some(p),
        Err(why) => {
            missing(test, &why);
            None
        }
    }
}

/// The SUMO installation's home (the environment variable `SUMO_HOME`, else the Python
/// package's) for `test`, or `None` when the test is to be skipped (a CI run fails instead).
pub fn sumo_home(test: &str) -> Option<PathBuf> {
    let home = match std::env::var_os("SUMO_HOME") {
        Some(h) => Ok(PathBuf::from(h)),
        None => python_sumo_home(),
    };
    match home {
        // The shipped freeway examples the tests import.
        Ok(h) if h.join("tools/game").is_dir() => Some(h),
        Ok(h) => {
            missing(
                test,
                &format!("SUMO_HOME = {} has no tools/game/", h.display()),
            );
            None
        }
        Err(why) => {
            missing(test, &why);
            None
        }
    }
}

/// One road of a plain network: a SUMO edge between two nodes.
pub struct Road {
    pub id: &'static str,
    pub from: &'static str,
    pub to: &'static str,
    pub lanes: u32,
    /// A ramp (`highway.motorway_link`, 80 km/h) rather than the motorway (120 km/h).
    pub link: bool,
    pub name: Option<&'static str>,
}

pub const fn motorway(id: &'static str, from: &'static str, to: &'static str, lanes: u32) -> Road {
    Road {
        id,
        from,
        to,
        lanes,
        link: false,
        name: None,
    }
}

pub const fn link(id: &'static str, from: &'static str, to: &'static str) -> Road {
    Road {
        id,
        from,
        to,
        lanes: 1,
        link: true,
        name: None,
    }
}

/// A flow of the routes file: `vph` vehicles per hour over [begin_s, end_s) along `route` (edge
/// ids of the built network).
pub struct Flow {
    pub id: &'static str,
    pub route: &'static [&'static str],
    pub begin_s: u32,
    pub end_s: u32,
    pub vph: f64,
}

/// What an import of the network must give.
pub struct Expect {
    /// The mainline edges of the built network, upstream first.
    pub mainline: &'static [&'static str],
    /// On-ramps: id and merge point (corridor m, within [`POSITION_TOLERANCE_M`]).
    pub on_ramps: &'static [(&'static str, f64)],
    /// Off-ramps: id and diverge point.
    pub off_ramps: &'static [(&'static str, f64)],
    /// Through lanes at corridor positions: (x, lanes).
    pub lanes_at: &'static [(f64, usize)],
}

/// How far a ramp may be from its node in the drawing: SUMO shortens edges at junctions (a few
/// metres) and an edge ends where its junction begins.
pub const POSITION_TOLERANCE_M: f64 = 15.0;

/// A small freeway: nodes, roads, optional lane connections, built with or without
/// `--ramps.guess`, and its flows.
pub struct Freeway {
    pub name: &'static str,
    pub nodes: &'static [(&'static str, f64, f64)],
    pub roads: &'static [Road],
    /// (from edge, from lane, to edge, to lane); none: netconvert guesses them.
    pub connections: &'static [(&'static str, u32, &'static str, u32)],
    pub ramps_guess: bool,
    pub flows: &'static [Flow],
    pub expect: Expect,
}

/// A built freeway: the network and routes files.
pub struct Built {
    pub net: PathBuf,
    pub routes: PathBuf,
}

/// Two 30-min intervals per hour, two hours: the demand changes every 30 min and the test
/// compares hourly counts.
pub const DEMAND_END_S: u32 = 7200;

impl Freeway {
    /// Writes the plain files and the routes file into `dir` and runs `netconvert`.
    pub fn build(&self, netconvert: &Path, dir: &Path) -> Built {
        std::fs::create_dir_all(dir).unwrap();
        let stem = dir.join(self.name);
        let file = |ext: &str| PathBuf::from(format!("{}.{ext}", stem.display()));
        let mut types = String::from("<types>\n");
        types.push_str(
            "  <type id=\"highway.motorway\" priority=\"13\" numLanes=\"2\" speed=\"33.33\" \
             oneway=\"true\"/>\n  <type id=\"highway.motorway_link\" priority=\"12\" \
             numLanes=\"1\" speed=\"22.22\" oneway=\"true\"/>\n</types>\n",
        );
        std::fs::write(file("typ.xml"), types).unwrap();
        let mut nodes = String::from("<nodes>\n");
        for (id, x, y) in self.nodes {
            writeln!(nodes, "  <node id=\"{id}\" x=\"{x}\" y=\"{y}\"/>").unwrap();
        }
        nodes.push_str("</nodes>\n");
        std::fs::write(file("nod.xml"), nodes).unwrap();
        let mut edges = String::from("<edges>\n");
        for r in self.roads {
            let kind = if r.link { "motorway_link" } else { "motorway" };
            let name = r.name.map(|n| format!(" name=\"{n}\"")).unwrap_or_default();
            writeln!(
                edges,
                "  <edge id=\"{}\" from=\"{}\" to=\"{}\" type=\"highway.{kind}\" numLanes=\"{}\"{name}/>",
                r.id, r.from, r.to, r.lanes
            )
            .unwrap();
        }
        edges.push_str("</edges>\n");
        std::fs::write(file("edg.xml"), edges).unwrap();
        let net = file("net.xml");
        let mut cmd = Command::new(netconvert);
        cmd.arg("--type-files")
            .arg(file("typ.xml"))
            .arg("--node-files")
            .arg(file("nod.xml"))
            .arg("--edge-files")
            .arg(file("edg.xml"))
            .args(["--no-turnarounds", "--output.street-names"])
            .arg("--output-file")
            .arg(&net);
        if !self.connections.is_empty() {
            let mut con = String::from("<connections>\n");
            for (from, fl, to, tl) in self.connections {
                writeln!(
                    con,
                    "  <connection from=\"{from}\" to=\"{to}\" fromLane=\"{fl}\" toLane=\"{tl}\"/>"
                )
                .unwrap();
            }
            con.push_str("</connections>\n");
            std::fs::write(file("con.xml"), con).unwrap();
            cmd.arg("--connection-files").arg(file("con.xml"));
        }
        if self.ramps_guess {
            cmd.arg("--ramps.guess");
        }
        let o = cmd.output().expect("cannot start netconvert");
        assert!(
            o.status.success(),
            "netconvert failed for {}:\n{}",
            self.name,
            String::from_utf8_lossy(&o.stderr)
        );
        let routes = file("rou.xml");
        std::fs::write(&routes, self.routes_xml()).unwrap();
        Built { net, routes }
    }

    fn routes_xml(&self) -> String {
        // SUMO reads a routes file in departure order.
        let mut flows: Vec<&Flow> = self.flows.iter().collect();
        flows.sort_by_key(|f| f.begin_s);
        let mut xml = String::from("<routes>\n");
        for f in flows {
            writeln!(
                xml,
                "  <flow id=\"{}\" begin=\"{}\" end=\"{}\" vehsPerHour=\"{}\" departLane=\"best\" \
                 departSpeed=\"max\">\n    <route edges=\"{}\"/>\n  </flow>",
                f.id,
                f.begin_s,
                f.end_s,
                f.vph,
                f.route.join(" ")
            )
            .unwrap();
        }
        xml.push_str("</routes>\n");
        xml
    }

    /// The demand (veh/h) of the flows that pass `edge` at time `t_s` (s).
    pub fn demand_through(&self, edge: &str, t_s: f64) -> f64 {
        self.flows
            .iter()
            .filter(|f| f.route.contains(&edge))
            .filter(|f| f64::from(f.begin_s) <= t_s && t_s < f64::from(f.end_s))
            .map(|f| f.vph)
            .sum()
    }
}

/// The value of attribute `name` in the XML start tag `tag` (the text from `<` to `>`).
fn attr<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    let len = tag[start..].find('"')?;
    Some(&tag[start..start + len])
}

/// The start tags named `element` in a SUMO XML file (SUMO writes one per line; enough for the
/// networks netconvert writes, which is all the tests read with it).
fn tags<'a>(xml: &'a str, element: &'a str) -> impl Iterator<Item = &'a str> + 'a {
    let open = format!("<{element} ");
    xml.lines()
        .map(str::trim_start)
        .filter(move |l| l.starts_with(&open))
}

/// Length of lane `lane` (id) in the network text.
pub fn lane_length(net_xml: &str, lane: &str) -> f64 {
    tags(net_xml, "lane")
        .find(|t| attr(t, "id") == Some(lane))
        .and_then(|t| attr(t, "length"))
        .unwrap_or_else(|| panic!("no lane {lane} with a length"))
        .parse()
        .unwrap()
}

/// Number of lanes of edge `edge`.
pub fn lane_count(net_xml: &str, edge: &str) -> usize {
    let prefix = format!("{edge}_");
    tags(net_xml, "lane")
        .filter_map(|t| attr(t, "id"))
        .filter(|id| {
            id.strip_prefix(&prefix)
                .is_some_and(|i| i.chars().all(|c| c.is_ascii_digit()))
        })
        .count()
}

/// Where each mainline edge starts along the mainline (m): the lane lengths of the edges before
/// it and the internal lanes of the connections between them (as [`mainline_length`]).
pub fn mainline_starts(net_xml: &str, edges: &[&str]) -> Vec<f64> {
    (0..edges.len())
        .map(|k| {
            if k == 0 {
                0.0
            } else {
                let before = mainline_length(net_xml, &edges[..k]);
                let via = tags(net_xml, "connection")
                    .find(|t| {
                        attr(t, "from") == Some(edges[k - 1]) && attr(t, "to") == Some(edges[k])
                    })
                    .and_then(|t| attr(t, "via"))
                    .map_or(0.0, |v| lane_length(net_xml, v));
                before + via
            }
        })
        .collect()
}

/// Where the network has a ramp edge meet the mainline: an on-ramp at the start of the mainline
/// edge it connects to, an off-ramp at the end of the mainline edge that connects to it.
pub fn ramp_position(net_xml: &str, edges: &[&str], ramp: &str, on: bool) -> f64 {
    let starts = mainline_starts(net_xml, edges);
    let (from, to) = if on {
        (Some(ramp), None)
    } else {
        (None, Some(ramp))
    };
    let conn = tags(net_xml, "connection")
        .find(|t| {
            let (f, g) = (attr(t, "from").unwrap_or(""), attr(t, "to").unwrap_or(""));
            match (from, to) {
                (Some(r), _) => f == r && edges.contains(&g),
                (_, Some(r)) => g == r && edges.contains(&f),
                _ => false,
            }
        })
        .unwrap_or_else(|| panic!("no connection between ramp {ramp} and the mainline"));
    if on {
        let b = edges
            .iter()
            .position(|e| Some(*e) == attr(conn, "to"))
            .unwrap();
        starts[b]
    } else {
        let a = edges
            .iter()
            .position(|e| Some(*e) == attr(conn, "from"))
            .unwrap();
        starts[a] + lane_length(net_xml, &format!("{}_0", edges[a]))
    }
}

/// The mainline's length as the network has it: the lane lengths of `edges` plus, between two
/// consecutive edges, the internal junction lane of a connection from one to the other
/// (computed here with its own reading of the file, independently of the importer).
pub fn mainline_length(net_xml: &str, edges: &[&str]) -> f64 {
    let mut total = 0.0;
    for (i, e) in edges.iter().enumerate() {
        total += lane_length(net_xml, &format!("{e}_0"));
        if let Some(next) = edges.get(i + 1) {
            let via = tags(net_xml, "connection")
                .find(|t| attr(t, "from") == Some(e) && attr(t, "to") == Some(next))
                .unwrap_or_else(|| panic!("no connection {e} -> {next}"));
            if let Some(via) = attr(via, "via") {
                total += lane_length(net_xml, via);
            }
        }
    }
    total
}

/// Four 30-min intervals of a flow along `route`, with the demands `vph`.
macro_rules! flows {
    ($($id:literal: [$($e:literal),+] => [$a:expr, $b:expr, $c:expr, $d:expr]);+ $(;)?) => {
        &[$(
            Flow { id: concat!($id, "_0"), route: &[$($e),+], begin_s: 0, end_s: 1800, vph: $a },
            Flow { id: concat!($id, "_1"), route: &[$($e),+], begin_s: 1800, end_s: 3600, vph: $b },
            Flow { id: concat!($id, "_2"), route: &[$($e),+], begin_s: 3600, end_s: 5400, vph: $c },
            Flow { id: concat!($id, "_3"), route: &[$($e),+], begin_s: 5400, end_s: 7200, vph: $d },
        )+]
    };
}

/// An on-ramp with a 300 m acceleration lane: the ramp feeds lane 0 of a 3-lane edge whose
/// lane 0 ends (two through lanes).
pub const ON_RAMP: Freeway = Freeway {
    name: "on_ramp",
    nodes: &[
        ("A", 0.0, 0.0),
        ("B", 1000.0, 0.0),
        ("C", 1300.0, 0.0),
        ("D", 2500.0, 0.0),
        ("R", 600.0, -150.0),
    ],
    roads: &[
        motorway("main1", "A", "B", 2),
        Road {
            name: Some("Elm St"),
            ..link("ramp", "R", "B")
        },
        motorway("accel", "B", "C", 3),
        motorway("main2", "C", "D", 2),
    ],
    connections: &[
        ("ramp", 0, "accel", 0),
        ("main1", 0, "accel", 1),
        ("main1", 1, "accel", 2),
        ("accel", 1, "main2", 0),
        ("accel", 2, "main2", 1),
    ],
    ramps_guess: false,
    flows: flows! {
        "through": ["main1", "accel", "main2"] => [2200.0, 2600.0, 2000.0, 2400.0];
        "ramp": ["ramp", "accel", "main2"] => [300.0, 500.0, 400.0, 200.0];
    },
    expect: Expect {
        mainline: &["main1", "accel", "main2"],
        on_ramps: &[("ramp", 1000.0)],
        off_ramps: &[],
        lanes_at: &[(500.0, 2), (1150.0, 2), (2000.0, 2)],
    },
};

/// An off-ramp: lane 0 of a 2-lane motorway leads on and to the ramp (netconvert's connections).
pub const OFF_RAMP: Freeway = Freeway {
    name: "off_ramp",
    nodes: &[
        ("A", 0.0, 0.0),
        ("B", 1200.0, 0.0),
        ("D", 2500.0, 0.0),
        ("X", 1600.0, -150.0),
    ],
    roads: &[
        motorway("main1", "A", "B", 2),
        motorway("main2", "B", "D", 2),
        Road {
            name: Some("Oak Ave"),
            ..link("exit", "B", "X")
        },
    ],
    connections: &[],
    ramps_guess: false,
    flows: flows! {
        "through": ["main1", "main2"] => [2400.0, 2800.0, 2000.0, 2600.0];
        "exiting": ["main1", "exit"] => [400.0, 300.0, 500.0, 200.0];
    },
    expect: Expect {
        mainline: &["main1", "main2"],
        on_ramps: &[],
        off_ramps: &[("exit", 1200.0)],
        lanes_at: &[(600.0, 2), (1800.0, 2)],
    },
};

/// A lane drop: 3 lanes, then 2 (lane 0 ends; lanes 1 and 2 go on).
pub const LANE_DROP: Freeway = Freeway {
    name: "lane_drop",
    nodes: &[("A", 0.0, 0.0), ("B", 1500.0, 0.0), ("D", 3000.0, 0.0)],
    roads: &[
        motorway("main1", "A", "B", 3),
        motorway("main2", "B", "D", 2),
    ],
    connections: &[("main1", 1, "main2", 0), ("main1", 2, "main2", 1)],
    ramps_guess: false,
    flows: flows! {
        "through": ["main1", "main2"] => [2800.0, 3200.0, 2600.0, 3000.0];
    },
    expect: Expect {
        mainline: &["main1", "main2"],
        on_ramps: &[],
        off_ramps: &[],
        lanes_at: &[(700.0, 3), (2200.0, 2)],
    },
};

/// A weaving section: an on-ramp's lane runs 500 m as an auxiliary lane into an off-ramp.
pub const WEAVING: Freeway = Freeway {
    name: "weaving",
    nodes: &[
        ("A", 0.0, 0.0),
        ("B", 1000.0, 0.0),
        ("C", 1500.0, 0.0),
        ("D", 3000.0, 0.0),
        ("R", 600.0, -150.0),
        ("X", 1900.0, -150.0),
    ],
    roads: &[
        motorway("main1", "A", "B", 2),
        Road {
            name: Some("Pine St"),
            ..link("onr", "R", "B")
        },
        motorway("weave", "B", "C", 3),
        motorway("main2", "C", "D", 2),
        Road {
            name: Some("Cedar Rd"),
            ..link("offr", "C", "X")
        },
    ],
    connections: &[
        ("onr", 0, "weave", 0),
        ("main1", 0, "weave", 1),
        ("main1", 1, "weave", 2),
        ("weave", 0, "offr", 0),
        ("weave", 1, "main2", 0),
        ("weave", 2, "main2", 1),
    ],
    ramps_guess: false,
    flows: flows! {
        "through": ["main1", "weave", "main2"] => [2000.0, 2400.0, 1800.0, 2200.0];
        "main_exit": ["main1", "weave", "offr"] => [300.0, 400.0, 200.0, 300.0];
        "ramp_main": ["onr", "weave", "main2"] => [300.0, 400.0, 300.0, 200.0];
        "ramp_exit": ["onr", "weave", "offr"] => [100.0, 100.0, 100.0, 100.0];
    },
    expect: Expect {
        mainline: &["main1", "weave", "main2"],
        on_ramps: &[("onr", 1000.0)],
        off_ramps: &[("offr", 1500.0)],
        lanes_at: &[(500.0, 2), (1250.0, 2), (2200.0, 2)],
    },
};

/// Two on-ramps and an off-ramp drawn as plain junctions; `--ramps.guess` adds the
/// acceleration and deceleration lanes (edges `…-AddedOnRampEdge`, `…-AddedOffRampEdge`).
pub const RAMPS_GUESS: Freeway = Freeway {
    name: "ramps_guess",
    nodes: &[
        ("A", 0.0, 0.0),
        ("B", 800.0, 0.0),
        ("C", 2000.0, 0.0),
        ("D", 3000.0, 0.0),
        ("F", 4000.0, 0.0),
        ("R1", 400.0, -150.0),
        ("X", 2400.0, -150.0),
        ("R2", 2600.0, -150.0),
    ],
    roads: &[
        motorway("m1", "A", "B", 2),
        motorway("m2", "B", "C", 2),
        motorway("m3", "C", "D", 2),
        motorway("m4", "D", "F", 2),
        link("on1", "R1", "B"),
        link("off1", "C", "X"),
        link("on2", "R2", "D"),
    ],
    connections: &[],
    ramps_guess: true,
    flows: flows! {
        "through": ["m1", "m2-AddedOnRampEdge", "m2", "m2-AddedOffRampEdge", "m3",
                    "m4-AddedOnRampEdge", "m4"] => [2000.0, 2400.0, 1800.0, 2200.0];
        "main_exit": ["m1", "m2-AddedOnRampEdge", "m2", "m2-AddedOffRampEdge", "off1"]
            => [300.0, 300.0, 400.0, 200.0];
        "on1_exit": ["on1", "m2-AddedOnRampEdge", "m2", "m2-AddedOffRampEdge", "off1"]
            => [100.0, 100.0, 100.0, 100.0];
        "on1_end": ["on1", "m2-AddedOnRampEdge", "m2", "m2-AddedOffRampEdge", "m3",
                    "m4-AddedOnRampEdge", "m4"] => [300.0, 400.0, 300.0, 200.0];
        "on2_end": ["on2", "m4-AddedOnRampEdge", "m4"] => [300.0, 300.0, 400.0, 200.0];
    },
    expect: Expect {
        mainline: &[
            "m1",
            "m2-AddedOnRampEdge",
            "m2",
            "m2-AddedOffRampEdge",
            "m3",
            "m4-AddedOnRampEdge",
            "m4",
        ],
        on_ramps: &[("on1", 800.0), ("on2", 3000.0)],
        off_ramps: &[("off1", 2000.0)],
        lanes_at: &[(400.0, 2), (1500.0, 2), (2500.0, 2), (3500.0, 2)],
    },
};

/// The test networks.
pub const FREEWAYS: [&Freeway; 5] = [&ON_RAMP, &OFF_RAMP, &LANE_DROP, &WEAVING, &RAMPS_GUESS];
