//! The engine's modules must not import each other in a circle of more than a few.
//!
//! The graph is built from the source, a node per top-level module of `src/`, by
//! `support/module_graph.rs` (which the module-graph tests of `runs`, `scenario` and
//! `experiment` share; its head says what counts as an edge).
//!
//! The bound, [`MAX_SCC`] = 3: the phases and the records depend on the state and on the
//! public views (`view.rs`, `events::StepView`), never on the step (`sim.rs`) or on each
//! other but for shared laws and types, and the types that the state's parts hold depend on
//! none of them. Two circles are left: a knot of definitions that name each other on purpose
//! (the config names its strategy, `organize::StrategyKind`, `LaneChoice`; an organizer reads
//! the road's geometry, `network`, which is built from the config), and decide ↔ insert (the
//! entrance queue's type one way, the automated follower's law the other). Any phase,
//! observer or record that reaches back into the engine joins a circle with `sim` and `state`
//! and fails this test. Before this check existed, 22 of the 30 modules formed one circle.

#[path = "support/module_graph.rs"]
mod graph;

use graph::{check_circles, module_graph, Graph};
use std::collections::BTreeSet;
use std::path::Path;

/// The largest strongly connected component allowed in the module graph.
const MAX_SCC: usize = 3;

#[test]
fn no_import_circle_of_more_than_a_few_modules() {
    check_circles(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"), MAX_SCC);
}

#[test]
fn the_graph_sees_grouped_and_re_exported_paths() {
    // A check that its parser finds the paths it is meant to find, so that the bound above
    // is not met by a graph with no edges.
    let graph: Graph = module_graph(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"));
    // `use crate::{config::Config, …}` style groups and root re-exports (`crate::Simulation`).
    assert!(graph["sim"].contains("state"), "{:?}", graph["sim"]);
    assert!(graph["state"].contains("vehicle"), "{:?}", graph["state"]);
    let edges: usize = graph.values().map(BTreeSet::len).sum();
    assert!(edges > 50, "only {edges} edges found");
}
