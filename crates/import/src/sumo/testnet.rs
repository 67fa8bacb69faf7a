//! Networks for unit tests, built as data: edges with a lane count and length, and lane
//! connections (internal lanes of 0 m).

use super::net::{Conn, Edge, Lane, Net};

pub struct Build {
    pub net: Net,
}

impl Build {
    pub fn new() -> Self {
        Build {
            net: Net::default(),
        }
    }

    /// An edge `id` from node `from` to node `to`.
    pub fn edge(mut self, id: &str, from: &str, to: &str, lanes: usize, length: f64) -> Self {
        self.net.by_id.insert(id.into(), self.net.edges.len());
        self.net.edges.push(Edge {
            id: id.into(),
            from: from.into(),
            to: to.into(),
            kind: String::new(),
            name: None,
            lanes: (0..lanes)
                .map(|index| Lane {
                    index,
                    speed: 33.33,
                    length,
                })
                .collect(),
        });
        self
    }

    /// Lane connections `a_i → b_j` for each (i, j).
    pub fn conn(mut self, a: &str, b: &str, lanes: &[(usize, usize)]) -> Self {
        let (a, b) = (self.net.by_id[a], self.net.by_id[b]);
        for &(from_lane, to_lane) in lanes {
            self.net.conns.push(Conn {
                from: a,
                to: b,
                from_lane,
                to_lane,
                turnaround: false,
                internal_m: 0.0,
            });
        }
        self
    }

    pub fn done(mut self) -> Net {
        self.net.index();
        self.net
    }
}
