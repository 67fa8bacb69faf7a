//! Additional files (`.add.xml`): induction loops (`<inductionLoop>`, or `<e1Detector>` in
//! older files) become detectors. SUMO's loops measure one lane each; the model's detectors
//! count the whole cross-section, so the loops of one mainline edge within
//! [`GROUP_WITHIN_M`] of each other are one detector, named by the first loop's id. A loop on
//! an on-ramp or off-ramp edge becomes that ramp's counter (`station`). Other detectors and
//! additional elements are listed as dropped.

use super::corridor::{sanitize, Corridor};
use super::net::Net;
use super::xml::{self, At};
use crate::{ImportError, Notes};
use std::collections::BTreeMap;
use std::path::PathBuf;

pub const GROUP_WITHIN_M: f64 = 1.0;

#[derive(Clone, Debug, PartialEq)]
pub struct Loop {
    pub id: String,
    pub edge: usize,
    /// Position on the edge from its start (m).
    pub pos: f64,
}

pub fn read(
    paths: &[PathBuf],
    net: &Net,
) -> Result<(Vec<Loop>, BTreeMap<String, usize>), ImportError> {
    parse(&crate::read::texts(paths)?, net)
}

/// [`read`] for texts already read: (the path for messages, the text), in order.
pub fn parse(
    texts: &[(PathBuf, String)],
    net: &Net,
) -> Result<(Vec<Loop>, BTreeMap<String, usize>), ImportError> {
    let mut loops = Vec::new();
    let mut other: BTreeMap<String, usize> = BTreeMap::new();
    for (path, text) in texts {
        let path = path.as_path();
        let doc = xml::parse(path, text)?;
        let root = xml::root(path, &doc, &["additional", "add"], "SUMO additional file")?;
        for node in root.children().filter(|n| n.is_element()) {
            let at = At::new(path, node);
            let tag = node.tag_name().name();
            if tag != "inductionLoop" && tag != "e1Detector" {
                *other.entry(format!("<{tag}>")).or_default() += 1;
                continue;
            }
            let id = at.req("id")?.to_string();
            let lane = at.req("lane")?;
            let edge_id = lane.rsplit_once('_').map_or(lane, |(e, _)| e);
            let edge = net.edge(edge_id).ok_or_else(|| {
                at.invalid(
                    format!("lane=\"{lane}\""),
                    format!("the network has no edge \"{edge_id}\""),
                )
            })?;
            let len = net.edges[edge].length();
            let pos = at.req_num("pos", -1e7, 1e7)?;
            let pos = if pos < 0.0 { len + pos } else { pos };
            let friendly = matches!(node.attribute("friendlyPos"), Some("true" | "1"));
            let pos = if friendly {
                pos.clamp(0.0, len)
            } else if !(0.0..=len).contains(&pos) {
                return Err(at.invalid(
                    format!("pos=\"{}\"", node.attribute("pos").unwrap_or("")),
                    format!("must lie on the lane: in [-{len}, {len}] m (or set friendlyPos)"),
                ));
            } else {
                pos
            };
            loops.push(Loop { id, edge, pos });
        }
    }
    Ok((loops, other))
}

/// A mainline detector: name and corridor position.
#[derive(Clone, Debug, PartialEq)]
pub struct Placed {
    pub name: String,
    pub x: f64,
}

/// The loops placed on the corridor: mainline cross-sections, ramp stations by ramp index.
pub struct OnCorridor {
    pub mainline: Vec<Placed>,
    pub on_station: BTreeMap<usize, String>,
    pub off_station: BTreeMap<usize, String>,
}

/// How far inside the road a detector at its very start or end is placed (m): a scenario's
/// detectors lie strictly inside the corridor, and SUMO loops at `pos="0"` are common (issue 48
/// D15).
pub const DETECTOR_INSIDE_M: f64 = 1.0;

/// `x` moved into `[DETECTOR_INSIDE_M, length - DETECTOR_INSIDE_M]` (the middle of a road
/// shorter than twice that).
pub fn inside(x: f64, length: f64) -> f64 {
    if length <= 2.0 * DETECTOR_INSIDE_M {
        return length / 2.0;
    }
    x.clamp(DETECTOR_INSIDE_M, length - DETECTOR_INSIDE_M)
}

pub fn place(loops: &[Loop], net: &Net, c: &Corridor, notes: &mut Notes) -> OnCorridor {
    let mut out = OnCorridor {
        mainline: Vec::new(),
        on_station: BTreeMap::new(),
        off_station: BTreeMap::new(),
    };
    let mut grouped: Vec<(Placed, usize)> = Vec::new(); // (detector, loops in it)
    let mut elsewhere = 0;
    let mut moved = Vec::new();
    for l in loops {
        if let Some(k) = c.position(l.edge) {
            let x = inside(c.start[k] + l.pos, c.length);
            if x != c.start[k] + l.pos {
                moved.push(l.id.clone());
            }
            match grouped
                .iter_mut()
                .find(|(g, _)| (g.x - x).abs() <= GROUP_WITHIN_M)
            {
                Some((_, n)) => *n += 1,
                None => grouped.push((
                    Placed {
                        name: sanitize(&l.id),
                        x,
                    },
                    1,
                )),
            }
        } else if let Some(r) = c.on_ramp_of(l.edge) {
            station(&mut out.on_station, r, l, net, notes);
        } else if let Some(r) = c.off_ramp_of(l.edge) {
            station(&mut out.off_station, r, l, net, notes);
        } else {
            elsewhere += 1;
        }
    }
    let multi = grouped.iter().filter(|g| g.1 > 1).count();
    if !grouped.is_empty() {
        notes.keep(format!(
            "{} induction loops on the mainline as {} detectors{}",
            grouped.iter().map(|g| g.1).sum::<usize>(),
            grouped.len(),
            if multi > 0 {
                format!(" ({multi} from several lanes' loops, named by the first loop's id)")
            } else {
                String::new()
            }
        ));
    }
    if elsewhere > 0 {
        notes.drop(format!(
            "{elsewhere} induction loops on edges that are neither the mainline nor a ramp's last edge"
        ));
    }
    if !moved.is_empty() {
        notes.reduce(format!(
            "{} loop(s) at the corridor's very start or end moved {DETECTOR_INSIDE_M} m inside \
             (a detector lies strictly inside the road): {}",
            moved.len(),
            moved.join(", ")
        ));
    }
    out.mainline = grouped.into_iter().map(|g| g.0).collect();
    out.mainline.sort_by(|a, b| a.x.total_cmp(&b.x));
    out
}

fn station(map: &mut BTreeMap<usize, String>, r: usize, l: &Loop, net: &Net, notes: &mut Notes) {
    match map.get(&r) {
        Some(first) => notes.reduce(format!(
            "loop \"{}\" on ramp edge \"{}\": the ramp is counted by \"{first}\" already",
            l.id, net.edges[l.edge].id
        )),
        None => {
            map.insert(r, sanitize(&l.id));
        }
    }
}
