//! SUMO routes files (`.rou.xml`): flows, vehicles, trips, routes, route distributions and
//! vehicle types, read into departures over edge paths. Trips and flows given by `from`/`to`
//! edges are routed on the network by shortest length (`via` edges in order).
//!
//! A flow's rate: `vehsPerHour` (or `perHour`), `period` (`exp(r)`: r vehicles per second,
//! Poisson), `probability` p (a vehicle each second with probability p: 3600 p veh/h) or
//! `number` spread over [`begin`, `end`). `end` defaults to 24 h, SUMO's default.

use super::net::Net;
use super::xml::{self, At};
use crate::{ImportError, Notes};
use roxmltree::Node;
use std::collections::{BTreeMap, HashMap};

/// SUMO's default end of a flow without `end` or `number` (s).
pub const FLOW_END_DEFAULT_S: f64 = 86_400.0;

#[derive(Clone, Debug, PartialEq)]
pub enum When {
    /// A constant rate (veh/h) over [begin, end).
    Rate { begin: f64, end: f64, vph: f64 },
    /// One vehicle departing at t.
    At(f64),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Demand {
    /// `flow "x"`, for notes.
    pub what: String,
    /// Edge paths with their shares (summing to 1).
    pub paths: Vec<(Vec<usize>, f64)>,
    pub when: When,
    pub vtype: String,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct VType {
    /// Attributes as written.
    pub attrs: BTreeMap<String, String>,
}

#[derive(Clone, Debug, Default)]
pub struct Routes {
    pub demands: Vec<Demand>,
    pub vtypes: HashMap<String, VType>,
    /// Distribution id → (type id, probability).
    pub vtype_dists: HashMap<String, Vec<(String, f64)>>,
}

/// SUMO time: seconds, or `h:m:s` / `d:h:m:s`.
pub fn time(s: &str) -> Option<f64> {
    let parts: Vec<&str> = s.trim().split(':').collect();
    let mult = [86_400.0, 3_600.0, 60.0, 1.0];
    if parts.len() > 4 {
        return None;
    }
    let mut t = 0.0;
    for (i, (p, m)) in parts.iter().zip(&mult[4 - parts.len()..]).enumerate() {
        let v: f64 = p.parse().ok()?;
        if !v.is_finite() || v < 0.0 {
            return None;
        }
        // After the first part, a clock: hours below 24, minutes and seconds below 60
        // (`99:99:99` was 4 days of seconds; issue 48 D16).
        let unit = *m;
        if i > 0 && ((unit == 3_600.0 && v >= 24.0) || (unit < 3_600.0 && v >= 60.0)) {
            return None;
        }
        t += v * unit;
    }
    Some(t)
}

fn time_attr(at: &At, name: &str) -> Result<Option<f64>, ImportError> {
    match at.node.attribute(name) {
        None => Ok(None),
        Some(s) => time(s).map(Some).ok_or_else(|| {
            at.invalid(
                format!("attribute {name}=\"{s}\""),
                "must be a time: seconds >= 0, or h:m:s",
            )
        }),
    }
}

pub fn read(
    paths: &[std::path::PathBuf],
    net: &Net,
    notes: &mut Notes,
) -> Result<Routes, ImportError> {
    parse(&crate::read::texts(paths)?, net, notes)
}

/// [`read`] for texts already read: (the path for messages, the text), in order.
pub fn parse(
    texts: &[(std::path::PathBuf, String)],
    net: &Net,
    notes: &mut Notes,
) -> Result<Routes, ImportError> {
    let mut routes = Routes::default();
    // Named routes and route distributions of every file, so that a vehicle may use one
    // defined in an earlier file.
    let mut named: HashMap<String, Vec<(Vec<usize>, f64)>> = HashMap::new();
    let mut dropped: BTreeMap<&'static str, usize> = BTreeMap::new();
    for (path, text) in texts {
        let path = path.as_path();
        let doc = xml::parse(path, text)?;
        let root = xml::root(path, &doc, &["routes", "additional"], "SUMO routes file")?;
        for node in root.children().filter(|n| n.is_element()) {
            let at = At::new(path, node);
            match node.tag_name().name() {
                "vType" => {
                    add_vtype(&mut routes, &at)?;
                }
                "vTypeDistribution" => {
                    let id = at.req("id")?;
                    let mut members = Vec::new();
                    for t in node.children().filter(|n| n.has_tag_name("vType")) {
                        let ta = At::new(path, t);
                        let p = ta.num("probability", 0.0, 1e9)?.unwrap_or(1.0);
                        members.push((add_vtype(&mut routes, &ta)?, p));
                    }
                    if let Some(list) = node.attribute("vTypes") {
                        for t in list.split_whitespace() {
                            members.push((t.to_string(), 1.0));
                        }
                    }
                    routes
                        .vtype_dists
                        .insert(id.to_string(), normalize(&at, "vType", members)?);
                }
                "route" => {
                    let id = at.req("id")?;
                    let edges = edges_of(net, &at)?;
                    named.insert(id.to_string(), vec![(edges, 1.0)]);
                }
                "routeDistribution" => {
                    let id = at.req("id")?;
                    let mut members = Vec::new();
                    for r in node.children().filter(|n| n.has_tag_name("route")) {
                        let ra = At::new(path, r);
                        let p = ra.num("probability", 0.0, 1e9)?.unwrap_or(1.0);
                        let edges = match r.attribute("refId") {
                            Some(rid) => named
                                .get(rid)
                                .and_then(|v| v.first())
                                .map(|v| v.0.clone())
                                .ok_or_else(|| {
                                    ra.invalid(
                                        format!("refId=\"{rid}\""),
                                        "names no route defined before it",
                                    )
                                })?,
                            None => edges_of(net, &ra)?,
                        };
                        if let Some(rid) = r.attribute("id") {
                            named.insert(rid.to_string(), vec![(edges.clone(), 1.0)]);
                        }
                        members.push((edges, p));
                    }
                    named.insert(id.to_string(), normalize(&at, "route", members)?);
                }
                tag @ ("vehicle" | "trip" | "flow") => {
                    let paths = path_of(net, &at, &named)?;
                    let vtype = node
                        .attribute("type")
                        .unwrap_or("DEFAULT_VEHTYPE")
                        .to_string();
                    let what = format!("{tag} \"{}\"", node.attribute("id").unwrap_or("?"));
                    let when = if tag == "flow" {
                        flow_rate(&at)?
                    } else {
                        match node.attribute("depart") {
                            Some(s) => match time(s) {
                                Some(t) => When::At(t),
                                None => {
                                    *dropped.entry("vehicles with a non-numeric depart (triggered, containerTriggered, begin, now)").or_default() += 1;
                                    continue;
                                }
                            },
                            None => {
                                return Err(at.invalid("has no attribute depart", "it is required"))
                            }
                        }
                    };
                    if let When::Rate { vph, .. } = when {
                        if vph == 0.0 {
                            continue;
                        }
                    }
                    routes.demands.push(Demand {
                        what,
                        paths,
                        when,
                        vtype,
                    });
                }
                "person" | "personFlow" | "container" | "containerFlow" => {
                    *dropped.entry("persons and containers").or_default() += 1;
                }
                "interval" => {
                    *dropped
                        .entry("<interval> blocks (edge-based demand; use flows or routes)")
                        .or_default() += 1;
                }
                _ => {}
            }
        }
    }
    for (what, count) in dropped {
        notes.drop(format!("{count} {what}"));
    }
    Ok(routes)
}

/// A distribution's probabilities as shares. One without members, or whose probabilities sum
/// to 0, would silently drop the demand that uses it (issue 48 D7: 2,400 of 3,000 veh/h): it
/// is an error naming the element.
fn normalize<T>(
    at: &At,
    member: &str,
    members: Vec<(T, f64)>,
) -> Result<Vec<(T, f64)>, ImportError> {
    if members.is_empty() {
        return Err(at.invalid(
            format!("has no <{member}>"),
            format!("a distribution needs at least one {member}; its demand would be lost"),
        ));
    }
    let total: f64 = members.iter().map(|m| m.1).sum();
    if !(total > 0.0 && total.is_finite()) {
        return Err(at.invalid(
            format!("has probabilities that sum to {total}"),
            format!("some {member} needs a probability > 0; its demand would be lost"),
        ));
    }
    Ok(members.into_iter().map(|(m, p)| (m, p / total)).collect())
}

/// The mapped attributes of a vType and their ranges: each must be a number in (0, max] (a
/// NaN, 0 or negative value was left out of the mean but kept its type's demand weight,
/// issue 48 D8).
const VTYPE_RANGES: [(&str, f64); 4] = [
    ("length", 50.0),
    ("accel", 20.0),
    ("decel", 20.0),
    ("maxSpeed", 100.0),
];

fn add_vtype(routes: &mut Routes, at: &At) -> Result<String, ImportError> {
    let id = at.req("id")?.to_string();
    for (name, max) in VTYPE_RANGES {
        if let Some(s) = at.node.attribute(name) {
            match s.trim().parse::<f64>() {
                Ok(v) if v > 0.0 && v <= max => {}
                _ => {
                    return Err(at.invalid(
                        format!("attribute {name}=\"{s}\""),
                        format!("must be a number in (0, {max}]"),
                    ))
                }
            }
        }
    }
    let attrs = at
        .node
        .attributes()
        .map(|a| (a.name().to_string(), a.value().to_string()))
        .collect();
    routes.vtypes.insert(id.clone(), VType { attrs });
    Ok(id)
}

/// The edges of a `<route edges="...">`.
fn edges_of(net: &Net, at: &At) -> Result<Vec<usize>, ImportError> {
    let list = at.req("edges")?;
    let edges = list
        .split_whitespace()
        .map(|id| {
            net.edge(id).ok_or_else(|| {
                at.invalid(
                    format!("edges=\"...{id}...\""),
                    format!("names edge \"{id}\", which the network does not have"),
                )
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    if edges.is_empty() {
        return Err(at.invalid("edges=\"\"", "a route needs at least one edge"));
    }
    Ok(edges)
}

/// The paths of a vehicle, trip or flow: its `route` (a route or a distribution), an embedded
/// `<route>` or `<routeDistribution>`, or `from`/`to` (and `via`) routed on the network.
fn path_of(
    net: &Net,
    at: &At,
    named: &HashMap<String, Vec<(Vec<usize>, f64)>>,
) -> Result<Vec<(Vec<usize>, f64)>, ImportError> {
    if let Some(r) = at.node.attribute("route") {
        return named.get(r).cloned().ok_or_else(|| {
            at.invalid(
                format!("route=\"{r}\""),
                "names no route or routeDistribution defined before it",
            )
        });
    }
    if let Some(child) = at.node.children().find(|n| n.has_tag_name("route")) {
        return Ok(vec![(edges_of(net, &At::new(at.path, child))?, 1.0)]);
    }
    if let Some(dist) = at
        .node
        .children()
        .find(|n| n.has_tag_name("routeDistribution"))
    {
        let mut members = Vec::new();
        for r in dist.children().filter(|n: &Node| n.has_tag_name("route")) {
            let ra = At::new(at.path, r);
            let p = ra.num("probability", 0.0, 1e9)?.unwrap_or(1.0);
            members.push((edges_of(net, &ra)?, p));
        }
        return normalize(&At::new(at.path, dist), "route", members);
    }
    match (at.node.attribute("from"), at.node.attribute("to")) {
        (Some(from), Some(to)) => {
            let mut stops = vec![from];
            if let Some(via) = at.node.attribute("via") {
                stops.extend(via.split_whitespace());
            }
            stops.push(to);
            let ids = stops
                .iter()
                .map(|id| {
                    net.edge(id).ok_or_else(|| {
                        at.invalid(
                            format!("edge \"{id}\""),
                            "the network does not have this edge",
                        )
                    })
                })
                .collect::<Result<Vec<_>, _>>()?;
            let mut path = vec![ids[0]];
            for w in ids.windows(2) {
                let leg = super::router::shortest(net, w[0], w[1]).ok_or_else(|| {
                    at.invalid(
                        format!(
                            "from \"{}\" to \"{}\"",
                            net.edges[w[0]].id, net.edges[w[1]].id
                        ),
                        "no path on the network's connections",
                    )
                })?;
                path.extend_from_slice(&leg[1..]);
            }
            Ok(vec![(path, 1.0)])
        }
        _ => Err(at.invalid(
            "has no route",
            "give route=\"ID\", an embedded <route edges=...>, or from and to edges",
        )),
    }
}

fn flow_rate(at: &At) -> Result<When, ImportError> {
    let begin = time_attr(at, "begin")?.unwrap_or(0.0);
    let end = time_attr(at, "end")?;
    let number = at.num("number", 0.0, 1e12)?;
    let period = at.node.attribute("period");
    let rate = if let Some(v) = at.num("vehsPerHour", 0.0, 1e7)? {
        Some(v)
    } else if let Some(v) = at.num("perHour", 0.0, 1e7)? {
        Some(v)
    } else if let Some(p) = period {
        let bad = || {
            at.invalid(
                format!("attribute period=\"{p}\""),
                "must be seconds > 0 or exp(RATE) with RATE > 0 vehicles per second",
            )
        };
        let p = p.trim();
        if let Some(r) = p.strip_prefix("exp(").and_then(|s| s.strip_suffix(')')) {
            match r.trim().parse::<f64>() {
                Ok(r) if r.is_finite() && r > 0.0 => Some(3600.0 * r),
                _ => return Err(bad()),
            }
        } else {
            match p.parse::<f64>() {
                Ok(s) if s.is_finite() && s > 0.0 => Some(3600.0 / s),
                _ => return Err(bad()),
            }
        }
    } else {
        at.num("probability", 0.0, 1.0)?.map(|p| 3600.0 * p)
    };
    let (end, vph) = match (rate, number, end) {
        (Some(v), Some(n), None) if v > 0.0 => (begin + n / v * 3600.0, v),
        (Some(v), _, end) => (end.unwrap_or(FLOW_END_DEFAULT_S), v),
        (None, Some(n), Some(end)) if end > begin => (end, n / (end - begin) * 3600.0),
        (None, Some(_), _) => {
            return Err(at.invalid(
                "has number but no rate and no end after begin",
                "give vehsPerHour, period or probability, or an end after begin",
            ))
        }
        (None, None, _) => {
            return Err(at.invalid(
                "has no rate",
                "give vehsPerHour, perHour, period, probability or number",
            ))
        }
    };
    if end < begin {
        return Err(at.invalid(
            format!("end {end} s before begin {begin} s"),
            "a flow ends after it begins",
        ));
    }
    Ok(When::Rate { begin, end, vph })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sumo_times() {
        assert_eq!(time("90"), Some(90.0));
        assert_eq!(time("1:00:30"), Some(3630.0));
        assert_eq!(time("1:0:0:0"), Some(86_400.0));
        assert_eq!(time("-3"), None);
        assert_eq!(time("soon"), None);
        // Issue 48 D16: a clock's minutes and seconds are below 60, its hours (after days)
        // below 24; the first part may be any size.
        assert_eq!(time("99:99:99"), None);
        assert_eq!(time("1:60:00"), None);
        assert_eq!(time("1:24:00:00"), None);
        assert_eq!(time("25:59:59.5"), Some(25.0 * 3600.0 + 59.0 * 60.0 + 59.5));
        assert_eq!(time("1:23:59:59"), Some(86_400.0 + 86_399.0));
    }

    #[test]
    fn an_openstreetmap_file_points_to_netconvert() {
        let e = super::super::net::parse(
            std::path::Path::new("x.osm"),
            "<?xml version='1.0'?>\n<osm version=\"0.6\"><node id=\"1\" lat=\"0\" lon=\"0\"/></osm>",
        )
        .unwrap_err()
        .to_string();
        assert_eq!(
            e,
            "x.osm:2: an OpenStreetMap file (<osm>): import sumo reads SUMO networks: convert it \
             with netconvert first, e.g. scripts/osm_to_corridor.sh (docs/import.md, \"From \
             OpenStreetMap\")"
        );
    }
}
