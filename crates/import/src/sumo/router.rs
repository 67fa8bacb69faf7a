//! Shortest paths by length over the network's connections, for trips and flows given by
//! `from` and `to` edges (SUMO's duarouter would use travel times; on a freeway corridor the
//! two agree).

use super::net::Net;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

#[derive(PartialEq)]
struct Item(f64, usize);
impl Eq for Item {}
impl Ord for Item {
    fn cmp(&self, o: &Self) -> Ordering {
        o.0.total_cmp(&self.0).then(o.1.cmp(&self.1))
    }
}
impl PartialOrd for Item {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// The edges from `a` to `b` (both included), shortest by the lengths of the edges after `a`.
pub fn shortest(net: &Net, a: usize, b: usize) -> Option<Vec<usize>> {
    let n = net.edges.len();
    let mut dist = vec![f64::INFINITY; n];
    let mut prev = vec![usize::MAX; n];
    let mut heap = BinaryHeap::new();
    dist[a] = 0.0;
    heap.push(Item(0.0, a));
    while let Some(Item(d, u)) = heap.pop() {
        if u == b {
            break;
        }
        if d > dist[u] {
            continue;
        }
        for v in net.successors(u) {
            let nd = d + net.edges[v].length();
            if nd < dist[v] {
                dist[v] = nd;
                prev[v] = u;
                heap.push(Item(nd, v));
            }
        }
    }
    if !dist[b].is_finite() {
        return None;
    }
    let mut path = vec![b];
    let mut at = b;
    while at != a {
        at = prev[at];
        path.push(at);
    }
    path.reverse();
    Some(path)
}
