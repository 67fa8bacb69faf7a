//! The corridor along a mainline: positions, through lanes per stretch, on-ramps with their
//! acceleration lanes, off-ramps. docs/import.md ("Network") gives the rules; in short:
//!
//! * x = 0 at the upstream end of the first mainline edge; each edge starts where the one
//!   before ends plus the internal junction lanes between them (the through connection's).
//! * At each junction of the mainline, the other edges with a connection into the next
//!   mainline edge are on-ramps (merge point: the start of that edge); the other edges that
//!   the previous mainline edge connects to are off-ramps (diverge point: its end).
//! * Lanes are followed by count. A lane that appears where an on-ramp's lanes feed it, and
//!   ends further on without an exit, is that ramp's acceleration lane (its length: from
//!   appearing to ending); one that runs to an off-ramp is an auxiliary lane, modelled as the
//!   on-ramp's acceleration lane up to the diverge (a weaving section, reduced); one that never
//!   ends is a lane add fed by the ramp. A lane that appears without a ramp and ends at an
//!   off-ramp is a deceleration lane: not modelled (reduced). Any other change is a lane add
//!   or drop of the through lanes; the model adds and drops lanes on the right, so one on the
//!   left in SUMO is noted as reduced.

use super::net::Net;
use crate::{ImportError, Notes};

/// An acceleration lane given to an on-ramp that merges without one in SUMO (a priority or
/// zipper merge): SUMO's own default ramp length for `--ramps.guess` (netconvert's
/// `ramps.ramp-length`, 100 m).
pub const NO_ACCEL_LANE_M: f64 = 100.0;
/// The model's most lanes per stretch.
pub const MAX_LANES: usize = 7;
/// Ramps of one kind closer than this are merged into one: two merge or diverge points a car
/// length apart are one place for the model (and leave no room for a vehicle between them).
pub const MERGE_RAMPS_WITHIN_M: f64 = 20.0;
/// How far upstream a ramp's own length is followed over single-predecessor edges.
const MAX_RAMP_M: f64 = 5_000.0;

#[derive(Clone, Debug, PartialEq)]
pub struct OnRamp {
    pub id: String,
    pub name: String,
    /// The ramp edges that join the mainline here (one unless merged).
    pub edges: Vec<usize>,
    pub x: f64,
    /// The acceleration lane (m); `None` where the ramp feeds a lane add.
    pub accel_lane_m: Option<f64>,
    pub ramp_length_m: f64,
    /// Speed limit of the ramp edge (m/s).
    pub speed: f64,
}

#[derive(Clone, Debug, PartialEq)]
pub struct OffRamp {
    pub id: String,
    pub name: String,
    pub edges: Vec<usize>,
    pub x: f64,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Corridor {
    pub chain: Vec<usize>,
    /// x of each mainline edge's start (m).
    pub start: Vec<f64>,
    pub length: f64,
    /// (from, to, through lanes).
    pub stretches: Vec<(f64, f64, u32)>,
    pub on_ramps: Vec<OnRamp>,
    pub off_ramps: Vec<OffRamp>,
    /// Non-mainline edges feeding the first mainline edge (their traffic enters at x = 0).
    pub feeders: Vec<usize>,
    /// Per network edge: its index in the chain, its on-ramp and off-ramp (`u32::MAX`: none),
    /// so that placing a route or a loop costs a lookup, not a scan of the chain (issue 48 D3).
    place: Vec<[u32; 3]>,
}

impl Corridor {
    /// Index in the chain of a mainline edge.
    pub fn position(&self, edge: usize) -> Option<usize> {
        self.placed(edge, 0)
    }
    pub fn on_ramp_of(&self, edge: usize) -> Option<usize> {
        self.placed(edge, 1)
    }
    pub fn off_ramp_of(&self, edge: usize) -> Option<usize> {
        self.placed(edge, 2)
    }
    fn placed(&self, edge: usize, what: usize) -> Option<usize> {
        self.place
            .get(edge)
            .map(|p| p[what])
            .filter(|&i| i != u32::MAX)
            .map(|i| i as usize)
    }
}

/// An id the scenario accepts: letters, digits, `_`, `-`, `.`; anything else becomes `_`.
pub fn sanitize(id: &str) -> String {
    let s: String = id
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.') {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() {
        "_".into()
    } else {
        s
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Origin {
    Ramp(usize), // index into the node's ramp list (global on-ramp index)
    Plain,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum End {
    Open,
    Drop,
    Exit,
}

#[derive(Clone, Copy, Debug)]
struct Extra {
    origin: Origin,
    open_k: usize,
    close_k: usize, // first mainline edge without it (chain.len() if open)
    end: End,
}

pub fn build(net: &Net, chain: Vec<usize>, notes: &mut Notes) -> Result<Corridor, ImportError> {
    let e = |k: usize| &net.edges[chain[k]];
    let n = chain.len();
    let mut start = vec![0.0; n];
    for k in 1..n {
        start[k] = start[k - 1] + e(k - 1).length() + net.internal_m(chain[k - 1], chain[k]);
    }
    let length = start[n - 1] + e(n - 1).length();
    // Refused before any ramp or lane is followed: a corridor a scenario may not have.
    let max = platoonsim_scenario::limits::MAX_LENGTH_M;
    if length > max {
        return Err(ImportError::NotCorridor(format!(
            "the mainline ({n} edges from \"{}\" to \"{}\") is {length:.0} m long; a corridor \
             may be at most {max:.0} m (docs/robustness.md): give a shorter one with --mainline",
            e(0).id,
            e(n - 1).id
        )));
    }
    if length <= 0.0 {
        return Err(ImportError::NotCorridor(format!(
            "the mainline ({} edges from \"{}\") has length 0",
            n,
            e(0).id
        )));
    }
    let end_of = |k: usize| start[k] + e(k).length(); // x of edge k's downstream end
    let mut main = vec![false; net.edges.len()];
    for &x in &chain {
        main[x] = true;
    }
    let on_main = |x: usize| main[x];
    // Edges by the junction they end at, for the crossing streams of each mainline junction.
    let mut into: std::collections::HashMap<&str, Vec<usize>> = std::collections::HashMap::new();
    for (i, edge) in net.edges.iter().enumerate() {
        into.entry(edge.to.as_str()).or_default().push(i);
    }

    // Ramps at each junction k (between edges k-1 and k).
    let mut on_ramps: Vec<OnRamp> = Vec::new();
    let mut off_ramps: Vec<OffRamp> = Vec::new();
    let mut on_at: Vec<Vec<usize>> = vec![Vec::new(); n]; // on-ramp indices by junction
    let mut off_at: Vec<bool> = vec![false; n];
    for k in 1..n {
        let (a, b) = (chain[k - 1], chain[k]);
        let junction = &e(k).from;
        match net.junctions.get(junction).map(String::as_str) {
            Some(t) if t.starts_with("traffic_light") => notes.reduce(format!(
                "junction \"{junction}\" on the mainline has a traffic light: not modelled \
                 (traffic runs through it)"
            )),
            _ => {}
        }
        for p in net
            .predecessors(b)
            .into_iter()
            .filter(|&p| p != a && !on_main(p))
        {
            let x = start[k];
            let ramp_len = ramp_length(net, p, &main);
            let pe = &net.edges[p];
            if let Some(last) = on_ramps.last_mut() {
                if x - last.x < MERGE_RAMPS_WITHIN_M {
                    notes.reduce(format!(
                        "on-ramps \"{}\" and \"{}\" join {:.1} m apart: merged into one on-ramp \
                         (demands added)",
                        net.edges[last.edges[0]].id,
                        pe.id,
                        x - last.x
                    ));
                    last.edges.push(p);
                    continue;
                }
            }
            on_at[k].push(on_ramps.len());
            on_ramps.push(OnRamp {
                id: sanitize(&pe.id),
                name: pe.name.clone().unwrap_or_else(|| pe.id.clone()),
                edges: vec![p],
                x,
                accel_lane_m: Some(NO_ACCEL_LANE_M), // set below from the lanes
                ramp_length_m: ramp_len,
                speed: pe.speed(),
            });
        }
        for s in net
            .successors(a)
            .into_iter()
            .filter(|&s| s != b && !on_main(s))
        {
            let x = end_of(k - 1);
            let se = &net.edges[s];
            off_at[k] = true;
            if let Some(last) = off_ramps.last_mut() {
                if x - last.x < MERGE_RAMPS_WITHIN_M {
                    notes.reduce(format!(
                        "off-ramps \"{}\" and \"{}\" leave {:.1} m apart: merged into one \
                         off-ramp",
                        net.edges[last.edges[0]].id,
                        se.id,
                        x - last.x
                    ));
                    last.edges.push(s);
                    continue;
                }
            }
            off_ramps.push(OffRamp {
                id: sanitize(&se.id),
                name: se.name.clone().unwrap_or_else(|| se.id.clone()),
                edges: vec![s],
                x,
            });
        }
        crossings(net, a, b, &main, &into, junction, notes);
    }

    // Follow the lanes by count (module doc).
    let lanes = |k: usize| e(k).lanes.len();
    let mut extras: Vec<Extra> = Vec::new();
    let mut open: Vec<usize> = Vec::new(); // indices into extras, rightmost last
    for k in 1..n {
        let (a, b) = (chain[k - 1], chain[k]);
        let delta = lanes(k) as i64 - lanes(k - 1) as i64;
        if delta > 0 {
            // Lanes of b fed by an on-ramp of this junction and by no lane of a.
            let from_main: Vec<usize> = net.between(a, b).map(|c| c.to_lane).collect();
            let mut fed: Vec<usize> = Vec::new(); // on-ramp index per fed lane
            for &r in &on_at[k] {
                for &p in &on_ramps[r].edges {
                    for c in net.between(p, b) {
                        if !from_main.contains(&c.to_lane) && !fed.contains(&r) {
                            fed.push(r);
                        }
                    }
                }
            }
            side_note(net, a, b, true, notes);
            for i in 0..delta as usize {
                let origin = fed.get(i).map_or(Origin::Plain, |&r| Origin::Ramp(r));
                open.push(extras.len());
                extras.push(Extra {
                    origin,
                    open_k: k,
                    close_k: n,
                    end: End::Open,
                });
            }
        } else if delta < 0 {
            side_note(net, a, b, false, notes);
            let end = if off_at[k] { End::Exit } else { End::Drop };
            for _ in 0..(-delta) {
                // None: a drop of the through lanes.
                if let Some(i) = open.pop() {
                    extras[i].close_k = k;
                    extras[i].end = end;
                }
            }
        }
    }

    // Classify the extra lanes; auxiliary ones are not through lanes.
    let mut aux = vec![0i64; n]; // auxiliary lanes on each edge
    let mut ramp_lane_used = vec![false; on_ramps.len()];
    for x in &extras {
        let span = start[x.open_k]..end_of(x.close_k - 1);
        let len = span.end - span.start;
        let auxiliary = match (x.origin, x.end) {
            (Origin::Ramp(r), End::Open) if !ramp_lane_used[r] => {
                ramp_lane_used[r] = true;
                on_ramps[r].accel_lane_m = None;
                notes.keep(format!(
                    "on-ramp \"{}\" feeds a lane added at x = {:.1} m",
                    on_ramps[r].id, span.start
                ));
                false
            }
            (Origin::Ramp(r), end @ (End::Drop | End::Exit)) if !ramp_lane_used[r] => {
                ramp_lane_used[r] = true;
                on_ramps[r].accel_lane_m = Some(len);
                if end == End::Exit {
                    notes.reduce(format!(
                        "the auxiliary lane from on-ramp \"{}\" to the off-ramp at x = {:.1} m \
                         ({len:.1} m, a weaving section) is modelled as the on-ramp's \
                         acceleration lane: exiting traffic leaves from the rightmost through \
                         lane",
                        on_ramps[r].id, span.end
                    ));
                }
                true
            }
            (Origin::Ramp(r), End::Drop | End::Exit) => {
                notes.reduce(format!(
                    "on-ramp \"{}\" adds more than one lane: modelled with one acceleration lane",
                    on_ramps[r].id
                ));
                true
            }
            (Origin::Plain, End::Exit) => {
                notes.reduce(format!(
                    "a deceleration lane of {len:.1} m before the off-ramp at x = {:.1} m is not \
                     modelled: exiting traffic leaves from the rightmost through lane",
                    span.end
                ));
                true
            }
            _ => false,
        };
        if auxiliary {
            for a in aux.iter_mut().take(x.close_k).skip(x.open_k) {
                *a += 1;
            }
        }
    }
    for (r, ramp) in on_ramps.iter().enumerate() {
        if !ramp_lane_used[r] {
            notes.reduce(format!(
                "on-ramp \"{}\" merges without an acceleration lane in the network: given one of \
                 {NO_ACCEL_LANE_M} m",
                ramp.id
            ));
        }
    }

    // Through lanes per edge, then stretches of equal count.
    let mut through_k: Vec<u32> = Vec::with_capacity(n);
    for (k, &aux_k) in aux.iter().enumerate() {
        let through = lanes(k) as i64 - aux_k;
        if through < 1 {
            return Err(ImportError::NotCorridor(format!(
                "mainline edge \"{}\" has no through lane (its {} lanes are all ramp lanes)",
                e(k).id,
                lanes(k)
            )));
        }
        let mut through = through as usize;
        if through > MAX_LANES {
            notes.reduce(format!(
                "mainline edge \"{}\" has {through} through lanes: the model runs at most \
                 {MAX_LANES}",
                e(k).id
            ));
            through = MAX_LANES;
        }
        through_k.push(through as u32);
    }
    // A lane that ends at a junction ends with its edge: the junction's internal lanes carry
    // only the lanes that go on. So a drop is at the edge's end (where an off-ramp there
    // diverges, for an exit-only lane), an add at the next edge's start.
    let mut stretches: Vec<(f64, f64, u32)> = Vec::new();
    for (k, &through) in through_k.iter().enumerate() {
        let to = match through_k.get(k + 1) {
            Some(&next) if next < through => end_of(k),
            Some(_) => start[k + 1],
            None => length,
        };
        let from = stretches.last().map_or(0.0, |s| s.1);
        match stretches.last_mut() {
            Some(s) if s.2 == through => s.1 = to,
            _ => stretches.push((from, to, through)),
        }
    }
    let feeders: Vec<usize> = net
        .predecessors(chain[0])
        .into_iter()
        .filter(|&p| !on_main(p))
        .collect();
    notes.keep(format!(
        "mainline: {} edges from \"{}\" to \"{}\", {:.1} m, {} stretch(es) of through lanes",
        n,
        e(0).id,
        e(n - 1).id,
        length,
        stretches.len()
    ));
    let mut place = vec![[u32::MAX; 3]; net.edges.len()];
    for (k, &x) in chain.iter().enumerate() {
        place[x][0] = k as u32;
    }
    for (r, ramp) in on_ramps.iter().enumerate() {
        for &x in &ramp.edges {
            if place[x][1] == u32::MAX {
                place[x][1] = r as u32;
            }
        }
    }
    for (r, ramp) in off_ramps.iter().enumerate() {
        for &x in &ramp.edges {
            if place[x][2] == u32::MAX {
                place[x][2] = r as u32;
            }
        }
    }
    Ok(Corridor {
        chain,
        start,
        length,
        stretches,
        on_ramps,
        off_ramps,
        feeders,
        place,
    })
}

/// A ramp's own length: its edge and, upstream, the edges that lead only to it.
fn ramp_length(net: &Net, p: usize, main: &[bool]) -> f64 {
    let typed = !net.edges[p].kind.is_empty();
    let mut total = net.edges[p].length();
    let mut cur = p;
    let mut seen = vec![p];
    while total < MAX_RAMP_M {
        let preds = net.predecessors(cur);
        let [q] = preds[..] else { break };
        let qe = &net.edges[q];
        if main[q] || seen.contains(&q) || (typed && !qe.is_link()) {
            break;
        }
        if net.successors(q).len() != 1 {
            break;
        }
        total += qe.length() + net.internal_m(q, cur);
        seen.push(q);
        cur = q;
    }
    total.min(MAX_RAMP_M)
}

/// Traffic across a mainline junction (not onto or off the mainline) is not modelled.
fn crossings(
    net: &Net,
    a: usize,
    b: usize,
    main: &[bool],
    into: &std::collections::HashMap<&str, Vec<usize>>,
    junction: &str,
    notes: &mut Notes,
) {
    let crossing = into
        .get(junction)
        .into_iter()
        .flatten()
        .filter(|&&from| !main[from])
        .flat_map(|&from| net.leaving(from))
        .any(|c| !main[c.to] && !c.turnaround);
    if crossing {
        notes.drop(format!(
            "traffic crossing the mainline at junction \"{junction}\" (between \"{}\" and \"{}\"): \
             a corridor has no crossing streams",
            net.edges[a].id, net.edges[b].id
        ));
    }
}

/// A lane added or dropped on the left in SUMO is added or dropped on the right in the model.
fn side_note(net: &Net, a: usize, b: usize, added: bool, notes: &mut Notes) {
    let (ea, eb) = (&net.edges[a], &net.edges[b]);
    let left = if added {
        // lanes of b with no connection from a, above the lowest connected one
        let fed: Vec<usize> = net.between(a, b).map(|c| c.to_lane).collect();
        let low = fed.iter().copied().min().unwrap_or(0);
        eb.lanes
            .iter()
            .any(|l| !fed.contains(&l.index) && l.index > low)
    } else {
        let going: Vec<usize> = net.between(a, b).map(|c| c.from_lane).collect();
        let low = going.iter().copied().min().unwrap_or(0);
        ea.lanes
            .iter()
            .any(|l| !going.contains(&l.index) && l.index > low)
    };
    if left {
        notes.reduce(format!(
            "a lane {} on the left between \"{}\" and \"{}\": the model {} lanes on the right",
            if added { "is added" } else { "ends" },
            ea.id,
            eb.id,
            if added { "adds" } else { "drops" }
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::super::mainline;
    use super::super::testnet::Build;
    use super::*;

    fn corridor(net: &Net) -> (Corridor, Notes) {
        let mut notes = Notes::default();
        let chain = mainline::find(net).unwrap();
        (build(net, chain, &mut notes).unwrap(), notes)
    }

    /// m1 (2 lanes, 1000 m) → m2 (3 lanes, 250 m) → m3 (2 lanes, 1000 m), on-ramp `on` feeding
    /// m2's right lane.
    fn accel_lane() -> Build {
        Build::new()
            .edge("m1", "A", "B", 2, 1000.0)
            .edge("m2", "B", "C", 3, 250.0)
            .edge("m3", "C", "D", 2, 1000.0)
            .edge("on", "R", "B", 1, 300.0)
            .conn("m1", "m2", &[(0, 1), (1, 2)])
            .conn("on", "m2", &[(0, 0)])
            .conn("m2", "m3", &[(1, 0), (2, 1)])
    }

    #[test]
    fn a_lane_fed_by_a_ramp_that_ends_is_its_acceleration_lane() {
        let (c, notes) = corridor(&accel_lane().done());
        assert_eq!(c.length, 2250.0);
        assert_eq!(c.stretches, vec![(0.0, 2250.0, 2)]);
        assert_eq!(c.on_ramps.len(), 1);
        let r = &c.on_ramps[0];
        assert_eq!(
            (r.id.as_str(), r.x, r.accel_lane_m),
            ("on", 1000.0, Some(250.0))
        );
        assert_eq!(r.ramp_length_m, 300.0);
        assert!(notes.reduced.is_empty(), "{notes}");
    }

    #[test]
    fn a_lane_fed_by_a_ramp_that_goes_on_is_a_lane_add() {
        let net = Build::new()
            .edge("m1", "A", "B", 2, 1000.0)
            .edge("m2", "B", "C", 3, 1500.0)
            .edge("on", "R", "B", 1, 300.0)
            .conn("m1", "m2", &[(0, 1), (1, 2)])
            .conn("on", "m2", &[(0, 0)])
            .done();
        let (c, _) = corridor(&net);
        assert_eq!(c.stretches, vec![(0.0, 1000.0, 2), (1000.0, 2500.0, 3)]);
        assert_eq!(c.on_ramps[0].accel_lane_m, None);
        assert_eq!(c.on_ramps[0].x, 1000.0);
    }

    #[test]
    fn an_auxiliary_lane_to_an_off_ramp_is_the_on_ramps_acceleration_lane() {
        let net = accel_lane()
            .edge("off", "C", "X", 1, 200.0)
            .conn("m2", "off", &[(0, 0)])
            .done();
        let (c, notes) = corridor(&net);
        assert_eq!(c.stretches, vec![(0.0, 2250.0, 2)]);
        assert_eq!(c.on_ramps[0].accel_lane_m, Some(250.0));
        assert_eq!(c.off_ramps.len(), 1);
        assert_eq!(
            (c.off_ramps[0].id.as_str(), c.off_ramps[0].x),
            ("off", 1250.0)
        );
        assert!(
            notes.reduced.iter().any(|n| n.contains("weaving section")),
            "{notes}"
        );
    }

    #[test]
    fn a_lane_that_appears_without_a_ramp_and_ends_at_an_exit_is_a_deceleration_lane() {
        let net = Build::new()
            .edge("m1", "A", "B", 2, 1000.0)
            .edge("m2", "B", "C", 3, 150.0)
            .edge("m3", "C", "D", 2, 1000.0)
            .edge("off", "C", "X", 1, 200.0)
            .conn("m1", "m2", &[(0, 0), (0, 1), (1, 2)])
            .conn("m2", "m3", &[(1, 0), (2, 1)])
            .conn("m2", "off", &[(0, 0)])
            .done();
        let (c, notes) = corridor(&net);
        assert_eq!(c.stretches, vec![(0.0, 2150.0, 2)]);
        assert!(c.on_ramps.is_empty());
        assert_eq!(c.off_ramps[0].x, 1150.0);
        assert!(
            notes
                .reduced
                .iter()
                .any(|n| n.contains("deceleration lane of 150.0 m")),
            "{notes}"
        );
    }

    #[test]
    fn an_exit_only_lane_is_a_lane_drop_at_the_off_ramp() {
        let net = Build::new()
            .edge("m1", "A", "B", 3, 1000.0)
            .edge("m2", "B", "C", 2, 1000.0)
            .edge("off", "B", "X", 1, 200.0)
            .conn("m1", "m2", &[(1, 0), (2, 1)])
            .conn("m1", "off", &[(0, 0)])
            .done();
        let (c, _) = corridor(&net);
        assert_eq!(c.stretches, vec![(0.0, 1000.0, 3), (1000.0, 2000.0, 2)]);
        assert_eq!(c.off_ramps[0].x, 1000.0);
    }

    #[test]
    fn a_merge_without_an_added_lane_gets_a_short_acceleration_lane() {
        let net = Build::new()
            .edge("m1", "A", "B", 2, 1000.0)
            .edge("m2", "B", "C", 2, 1000.0)
            .edge("on", "R", "B", 1, 300.0)
            .conn("m1", "m2", &[(0, 0), (1, 1)])
            .conn("on", "m2", &[(0, 0)])
            .done();
        let (c, notes) = corridor(&net);
        assert_eq!(c.on_ramps[0].accel_lane_m, Some(NO_ACCEL_LANE_M));
        assert!(notes
            .reduced
            .iter()
            .any(|n| n.contains("without an acceleration lane")));
    }

    #[test]
    fn the_mainline_is_the_chain_with_the_most_lane_metres() {
        // The ramp (1 lane, 900 m) is longer than the freeway upstream of the merge (2 lanes,
        // 500 m): by length alone the ramp would be the mainline.
        let net = Build::new()
            .edge("m1", "A", "B", 2, 500.0)
            .edge("m2", "B", "C", 2, 1000.0)
            .edge("on", "R", "B", 1, 900.0)
            .conn("m1", "m2", &[(0, 0), (1, 1)])
            .conn("on", "m2", &[(0, 0)])
            .done();
        let chain = mainline::find(&net).unwrap();
        assert_eq!(chain, vec![0, 1]);
    }

    #[test]
    fn a_loop_is_refused_naming_an_edge() {
        let net = Build::new()
            .edge("a", "A", "B", 2, 500.0)
            .edge("b", "B", "A", 2, 500.0)
            .conn("a", "b", &[(0, 0)])
            .conn("b", "a", &[(0, 0)])
            .done();
        let e = mainline::find(&net).unwrap_err().to_string();
        assert!(e.contains("loop through edge"), "{e}");
    }

    #[test]
    fn ids_are_made_scenario_ids() {
        assert_eq!(sanitize("-12345#3"), "-12345_3");
        assert_eq!(sanitize("gneE2"), "gneE2");
        assert_eq!(sanitize(""), "_");
    }
}
