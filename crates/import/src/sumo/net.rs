//! A SUMO network file (`.net.xml`, SUMO's "net" format, as netconvert writes it) read into the
//! parts a corridor needs: the normal edges with their lanes (usable by cars), the connections
//! between them with the length of their internal junction lanes, and the junction types.
//!
//! Sidewalks, bike lanes and other lanes that passenger cars may not use are left out of an
//! edge's lanes; internal, crossing and walking-area edges are not edges here.

use super::xml::{self, At};
use crate::ImportError;
use std::collections::HashMap;
use std::path::Path;

#[derive(Clone, Debug, PartialEq)]
pub struct Lane {
    pub index: usize,
    /// Speed limit (m/s).
    pub speed: f64,
    pub length: f64,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Edge {
    pub id: String,
    pub from: String,
    pub to: String,
    /// The edge type, e.g. `highway.motorway` (empty when the network has none).
    pub kind: String,
    /// The street name, if the network has one.
    pub name: Option<String>,
    /// Lanes that passenger cars may use, by index from the right.
    pub lanes: Vec<Lane>,
}

impl Edge {
    /// The edge's length: its longest car lane (SUMO gives all lanes of an edge one length
    /// unless the geometry is kept per lane).
    pub fn length(&self) -> f64 {
        self.lanes.iter().map(|l| l.length).fold(0.0, f64::max)
    }

    pub fn speed(&self) -> f64 {
        self.lanes.iter().map(|l| l.speed).fold(0.0, f64::max)
    }

    pub fn is_link(&self) -> bool {
        self.kind.ends_with("_link")
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Conn {
    pub from: usize,
    pub to: usize,
    pub from_lane: usize,
    pub to_lane: usize,
    /// A turnaround (`dir="t"`): from one carriageway onto the other.
    pub turnaround: bool,
    /// Length of the internal lanes the connection drives through (m); 0 without them
    /// (`--no-internal-links`).
    pub internal_m: f64,
}

#[derive(Clone, Debug, Default)]
pub struct Net {
    pub edges: Vec<Edge>,
    pub by_id: HashMap<String, usize>,
    pub conns: Vec<Conn>,
    /// Junction id → type (`priority`, `traffic_light`, `dead_end`, ...).
    pub junctions: HashMap<String, String>,
    /// Indices into `conns` by the edge they leave and by the edge they enter, made by
    /// [`Net::index`] (issue 48 D2/D3: every query scanned all connections, which made an import
    /// quadratic and the corridor cubic in the network's size).
    out_conns: Vec<Vec<u32>>,
    in_conns: Vec<Vec<u32>>,
}

impl Net {
    pub fn edge(&self, id: &str) -> Option<usize> {
        self.by_id.get(id).copied()
    }

    /// Index the connections by edge; called once after `conns` is complete.
    pub fn index(&mut self) {
        let n = self.edges.len();
        self.out_conns = vec![Vec::new(); n];
        self.in_conns = vec![Vec::new(); n];
        for (i, c) in self.conns.iter().enumerate() {
            self.out_conns[c.from].push(i as u32);
            self.in_conns[c.to].push(i as u32);
        }
    }

    /// Connections leaving edge `a`.
    pub fn leaving(&self, a: usize) -> impl Iterator<Item = &Conn> {
        self.out_conns
            .get(a)
            .into_iter()
            .flatten()
            .map(|&i| &self.conns[i as usize])
    }

    /// Connections entering edge `b`.
    pub fn entering(&self, b: usize) -> impl Iterator<Item = &Conn> {
        self.in_conns
            .get(b)
            .into_iter()
            .flatten()
            .map(|&i| &self.conns[i as usize])
    }

    /// Connections from edge `a` to edge `b`.
    pub fn between(&self, a: usize, b: usize) -> impl Iterator<Item = &Conn> {
        self.leaving(a).filter(move |c| c.to == b)
    }

    /// Edges that edge `a` has a connection to.
    pub fn successors(&self, a: usize) -> Vec<usize> {
        let mut v: Vec<usize> = self.leaving(a).map(|c| c.to).collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    pub fn predecessors(&self, b: usize) -> Vec<usize> {
        let mut v: Vec<usize> = self.entering(b).map(|c| c.from).collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// Length of the junction's internal lanes between edges `a` and `b` (the longest of the
    /// connections, which is the through lanes' on a straight freeway).
    pub fn internal_m(&self, a: usize, b: usize) -> f64 {
        self.between(a, b).map(|c| c.internal_m).fold(0.0, f64::max)
    }
}

/// Whether a lane's permissions let passenger cars drive on it.
fn for_cars(allow: Option<&str>, disallow: Option<&str>) -> bool {
    let has = |list: &str, c: &str| list.split_whitespace().any(|w| w == c);
    match (allow, disallow) {
        (Some(a), _) => has(a, "passenger") || has(a, "all") || a.trim().is_empty(),
        (None, Some(d)) => !(has(d, "passenger") || has(d, "all")),
        (None, None) => true,
    }
}

pub fn read(path: &Path) -> Result<Net, ImportError> {
    let text = crate::read::text(path)?;
    parse(path, &text)
}

pub fn parse(path: &Path, text: &str) -> Result<Net, ImportError> {
    let doc = xml::parse(path, text)?;
    if doc.root_element().has_tag_name("osm") {
        return Err(ImportError::Invalid {
            path: path.to_path_buf(),
            line: Some(doc.text_pos_at(doc.root_element().range().start).row),
            what: "an OpenStreetMap file (<osm>)".into(),
            problem: "import sumo reads SUMO networks: convert it with netconvert first, \
                      e.g. scripts/osm_to_corridor.sh (docs/import.md, \"From OpenStreetMap\")"
                .into(),
        });
    }
    let root = xml::root(path, &doc, &["net"], "SUMO network (.net.xml)")?;
    let mut net = Net::default();
    // Internal lanes: id → length, and the connections that go on from one (internal
    // junctions split a connection into two internal lanes).
    let mut internal_len: HashMap<&str, f64> = HashMap::new();
    let mut internal_next: HashMap<(String, usize), &str> = HashMap::new();
    let mut raw_conns = Vec::new();
    for node in root.children().filter(|n| n.is_element()) {
        let at = At::new(path, node);
        match node.tag_name().name() {
            "edge" => {
                let id = at.req("id")?;
                let function = node.attribute("function").unwrap_or("normal");
                if function == "internal" {
                    for lane in node.children().filter(|n| n.has_tag_name("lane")) {
                        let la = At::new(path, lane);
                        internal_len.insert(la.req("id")?, la.req_num("length", 0.0, 1e7)?);
                    }
                    continue;
                }
                if function != "normal" {
                    continue;
                }
                let mut lanes = Vec::new();
                for lane in node.children().filter(|n| n.has_tag_name("lane")) {
                    let la = At::new(path, lane);
                    let index = la
                        .index("index", 1000)?
                        .ok_or_else(|| la.invalid("has no attribute index", "it is required"))?;
                    let speed = la.req_num("speed", 0.0, 1e4)?;
                    let length = la.req_num("length", 0.0, 1e7)?;
                    if for_cars(lane.attribute("allow"), lane.attribute("disallow")) {
                        lanes.push(Lane {
                            index,
                            speed,
                            length,
                        });
                    }
                }
                lanes.sort_by_key(|l| l.index);
                if net.by_id.contains_key(id) {
                    return Err(at.invalid("", "a second edge with this id"));
                }
                net.by_id.insert(id.to_string(), net.edges.len());
                net.edges.push(Edge {
                    id: id.to_string(),
                    from: at.req("from")?.to_string(),
                    to: at.req("to")?.to_string(),
                    kind: node.attribute("type").unwrap_or("").to_string(),
                    name: node.attribute("name").map(str::to_string),
                    lanes,
                });
            }
            "junction" => {
                let id = at.req("id")?;
                let kind = node.attribute("type").unwrap_or("unknown");
                net.junctions.insert(id.to_string(), kind.to_string());
            }
            "connection" => {
                let from = at.req("from")?;
                let from_lane = at
                    .index("fromLane", 1000)?
                    .ok_or_else(|| at.invalid("has no attribute fromLane", "it is required"))?;
                let via = node.attribute("via");
                if from.starts_with(':') {
                    if let Some(v) = via {
                        internal_next.insert((from.to_string(), from_lane), v);
                    }
                    continue;
                }
                let to = at.req("to")?;
                let to_lane = at
                    .index("toLane", 1000)?
                    .ok_or_else(|| at.invalid("has no attribute toLane", "it is required"))?;
                let turnaround = node.attribute("dir") == Some("t");
                // The position, not the line: a line is counted only for an error.
                raw_conns.push((node, from, to, from_lane, to_lane, via, turnaround));
            }
            _ => {}
        }
    }
    if net.edges.is_empty() {
        return Err(ImportError::NotCorridor(format!(
            "{} has no edges",
            path.display()
        )));
    }
    for (node, from, to, from_lane, to_lane, via, turnaround) in raw_conns {
        let edge = |id: &str| {
            net.edge(id).ok_or_else(|| ImportError::Invalid {
                path: path.to_path_buf(),
                line: Some(At::new(path, node).line()),
                what: format!("<connection from=\"{from}\" to=\"{to}\">"),
                problem: format!("names edge \"{id}\", which the network does not have"),
            })
        };
        let (a, b) = (edge(from)?, edge(to)?);
        // Follow the internal lanes: via, then the internal lane it continues on, ...
        let mut internal_m = 0.0;
        let mut lane = via;
        let mut hops = 0;
        while let Some(l) = lane {
            internal_m += internal_len.get(l).copied().unwrap_or(0.0);
            hops += 1;
            if hops > 16 {
                break;
            }
            lane = l.rsplit_once('_').and_then(|(edge, idx)| {
                idx.parse::<usize>()
                    .ok()
                    .and_then(|i| internal_next.get(&(edge.to_string(), i)).copied())
            });
        }
        net.conns.push(Conn {
            from: a,
            to: b,
            from_lane,
            to_lane,
            turnaround,
            internal_m,
        });
    }
    net.index();
    Ok(net)
}

#[cfg(test)]
mod tests {
    use super::*;

    pub const SMALL: &str = r#"<net version="1.20">
  <edge id=":B_0" function="internal"><lane id=":B_0_0" index="0" speed="10" length="3.71"/></edge>
  <edge id=":B_1" function="internal">
    <lane id=":B_1_0" index="0" speed="33.33" length="3.76"/><lane id=":B_1_1" index="1" speed="33.33" length="3.76"/>
  </edge>
  <edge id="m1" from="A" to="B" priority="-1" type="highway.motorway">
    <lane id="m1_0" index="0" speed="33.33" length="985.70"/>
    <lane id="m1_1" index="1" speed="33.33" length="985.70"/>
    <lane id="m1_s" index="2" speed="2" length="985.70" allow="pedestrian"/>
  </edge>
  <edge id="m2" from="B" to="C"><lane id="m2_0" index="0" speed="33.33" length="256.54"/></edge>
  <edge id="on" from="R" to="B"><lane id="on_0" index="0" speed="22.22" length="318.84"/></edge>
  <junction id="B" type="priority"/>
  <connection from="m1" to="m2" fromLane="0" toLane="0" via=":B_1_0"/>
  <connection from="on" to="m2" fromLane="0" toLane="0" via=":B_0_0"/>
  <connection from=":B_1" to="m2" fromLane="0" toLane="0"/>
</net>"#;

    #[test]
    fn reads_edges_lanes_connections_and_internal_lengths() {
        let net = parse(Path::new("t.net.xml"), SMALL).unwrap();
        assert_eq!(net.edges.len(), 3);
        let m1 = &net.edges[net.edge("m1").unwrap()];
        assert_eq!(m1.lanes.len(), 2, "the sidewalk is not a car lane");
        assert_eq!(m1.kind, "highway.motorway");
        assert_eq!(m1.length(), 985.70);
        let (a, b) = (net.edge("m1").unwrap(), net.edge("m2").unwrap());
        assert_eq!(net.internal_m(a, b), 3.76);
        assert_eq!(net.successors(a), vec![b]);
        assert_eq!(net.predecessors(b).len(), 2);
        assert_eq!(net.junctions["B"], "priority");
    }

    #[test]
    fn errors_name_file_line_element_and_attribute() {
        let bad = SMALL.replace("length=\"256.54\"", "length=\"long\"");
        let e = parse(Path::new("t.net.xml"), &bad).unwrap_err().to_string();
        assert_eq!(
            e,
            "t.net.xml:11: <lane id=\"m2_0\"> attribute length=\"long\": must be a number in [0, 10000000]"
        );
        let e = parse(Path::new("r.xml"), "<routes/>")
            .unwrap_err()
            .to_string();
        assert!(e.contains("the root element is <routes>"), "{e}");
        let e = parse(Path::new("x.xml"), "not xml")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("x.xml: not XML:"), "{e}");
        let unknown = SMALL.replace("from=\"on\" to=\"m2\"", "from=\"nowhere\" to=\"m2\"");
        let e = parse(Path::new("t.net.xml"), &unknown)
            .unwrap_err()
            .to_string();
        assert!(e.contains("names edge \"nowhere\""), "{e}");
    }

    #[test]
    fn lane_permissions() {
        assert!(for_cars(None, None));
        assert!(for_cars(Some("passenger bus"), None));
        assert!(!for_cars(Some("pedestrian"), None));
        assert!(!for_cars(None, Some("passenger truck")));
        assert!(for_cars(None, Some("pedestrian bicycle")));
    }
}
