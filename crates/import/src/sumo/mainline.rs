//! The mainline: the chain of edges the corridor follows.
//!
//! Without `--mainline`, the longest chain in the travel direction of the freeway edges: those
//! of type `highway.motorway` or `highway.trunk` if the network has types (netconvert sets them
//! from OpenStreetMap) and untyped edges among them (added by hand in netedit), else every
//! edge that is not a `*_link`. "Longest" weighs each edge by
//! length × lanes, so that where a ramp and the freeway meet, the chain with more lanes wins
//! even on an untyped network. Turnaround connections (`dir="t"`) do not link edges: they join
//! the two carriageways. A chain that returns to itself is refused.

use super::net::Net;
use crate::ImportError;

fn is_freeway(kind: &str) -> bool {
    matches!(kind.rsplit('.').next(), Some("motorway") | Some("trunk"))
}

/// The candidate edges of the mainline.
fn candidates(net: &Net) -> Vec<bool> {
    let typed = net.edges.iter().any(|e| is_freeway(&e.kind));
    net.edges
        .iter()
        .map(|e| {
            // An untyped edge in a typed network is one added by hand (netedit): admitted.
            !e.lanes.is_empty()
                && if typed {
                    is_freeway(&e.kind) || e.kind.is_empty()
                } else {
                    !e.is_link()
                }
        })
        .collect()
}

/// Successors among candidates, without turnarounds.
fn next(net: &Net, cand: &[bool], a: usize) -> Vec<usize> {
    let mut v: Vec<usize> = net
        .leaving(a)
        .filter(|c| !c.turnaround && cand[c.to] && c.to != a)
        .map(|c| c.to)
        .collect();
    v.sort_unstable();
    v.dedup();
    v
}

/// The longest chain of candidate edges (by length × lanes).
pub fn find(net: &Net) -> Result<Vec<usize>, ImportError> {
    let cand = candidates(net);
    let n = net.edges.len();
    let succ: Vec<Vec<usize>> = (0..n)
        .map(|a| {
            if cand[a] {
                next(net, &cand, a)
            } else {
                Vec::new()
            }
        })
        .collect();
    // Longest path in a DAG by depth-first search with memo; a back edge is a loop.
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        New,
        Open,
        Done,
    }
    let mut mark = vec![Mark::New; n];
    let mut best = vec![0.0f64; n];
    let mut via: Vec<Option<usize>> = vec![None; n];
    for s in (0..n).filter(|&a| cand[a]) {
        if mark[s] != Mark::New {
            continue;
        }
        // Iterative DFS: (edge, next successor index).
        let mut stack = vec![(s, 0usize)];
        mark[s] = Mark::Open;
        while let Some(&mut (a, ref mut i)) = stack.last_mut() {
            if let Some(&b) = succ[a].get(*i) {
                *i += 1;
                match mark[b] {
                    Mark::New => {
                        mark[b] = Mark::Open;
                        stack.push((b, 0));
                    }
                    Mark::Open => {
                        return Err(ImportError::NotCorridor(format!(
                            "the freeway edges form a loop through edge \"{}\" (from \"{}\"); \
                             a corridor runs one way: give the mainline with --mainline",
                            net.edges[b].id, net.edges[a].id
                        )))
                    }
                    Mark::Done => {}
                }
            } else {
                let e = &net.edges[a];
                let own = e.length() * e.lanes.len() as f64;
                let (mut b_best, mut b_via) = (0.0, None);
                for &b in &succ[a] {
                    if best[b] > b_best {
                        (b_best, b_via) = (best[b], Some(b));
                    }
                }
                best[a] = own + b_best;
                via[a] = b_via;
                mark[a] = Mark::Done;
                stack.pop();
            }
        }
    }
    let start = (0..n)
        .filter(|&a| cand[a])
        .fold(None, |acc: Option<usize>, a| match acc {
            Some(b) if best[b] >= best[a] => Some(b),
            _ => Some(a),
        })
        .ok_or_else(|| {
            ImportError::NotCorridor(
                "no edge with car lanes could start a mainline (no motorway/trunk edges, \
                 or only *_link edges)"
                    .into(),
            )
        })?;
    let mut chain = vec![start];
    let mut at = start;
    while let Some(b) = via[at] {
        chain.push(b);
        at = b;
    }
    Ok(chain)
}

/// The mainline given as edge ids: each edge known, with car lanes, connected to the next, no
/// edge twice.
pub fn given(net: &Net, ids: &[String]) -> Result<Vec<usize>, ImportError> {
    let flag = |value: &str, problem: String| ImportError::Flag {
        flag: "--mainline",
        value: value.to_string(),
        problem,
    };
    let mut chain: Vec<usize> = Vec::with_capacity(ids.len());
    let mut listed = vec![false; net.edges.len()];
    for id in ids {
        let e = net
            .edge(id)
            .ok_or_else(|| flag(id, "the network has no edge with this id".into()))?;
        if net.edges[e].lanes.is_empty() {
            return Err(flag(id, "this edge has no lane that cars may use".into()));
        }
        if std::mem::replace(&mut listed[e], true) {
            return Err(flag(
                id,
                "this edge is listed twice; a corridor runs one way".into(),
            ));
        }
        if let Some(&a) = chain.last() {
            if net.between(a, e).next().is_none() {
                return Err(flag(
                    id,
                    format!(
                        "no lane of the edge before it, \"{}\", connects to it",
                        net.edges[a].id
                    ),
                ));
            }
        }
        chain.push(e);
    }
    if chain.is_empty() {
        return Err(flag("", "give at least one edge id".into()));
    }
    Ok(chain)
}
