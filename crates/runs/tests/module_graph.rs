//! The modules of `platoonsim-runs` must not import each other in a circle of more than
//! three: the graph and the check are the engine's (`crates/sim/tests/support/module_graph.rs`,
//! included by path), applied to this crate's `src/`.

#[path = "../../sim/tests/support/module_graph.rs"]
mod graph;

use std::collections::BTreeSet;
use std::path::Path;

/// The largest strongly connected component allowed, as in the engine.
const MAX_SCC: usize = 3;
/// Edges the graph has at least (fewer: the parser lost its way).
const MIN_EDGES: usize = 30;

#[test]
fn no_import_circle_of_more_than_three_modules() {
    let graph = graph::check_circles(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"), MAX_SCC);
    // The bound is not met by a graph the parser failed to see.
    let edges: usize = graph.values().map(BTreeSet::len).sum();
    assert!(edges >= MIN_EDGES, "only {edges} edges found");
}
