//! Issue 48 item 2: the importer's cost grows linearly with the network (D1-D4). The networks
//! are made here as `scripts/sumo_scale.py` makes them; docs/import.md ("Scaling") has the
//! benchmark of 10⁴ to 10⁶ elements. The bounds are generous (the imports take 0.1-0.3 s in a
//! release build); main's importer took 277 s for the 10,000-edge chain and 49 s for the
//! 40,000 connections.

use platoonsim_import::sumo::{from_texts, synth, Options};
use std::path::PathBuf;
use std::time::Instant;

/// A motorway of `n` edges of `len` m (the fuzz target's generator).
fn chain(n: usize, lanes: usize, len: f64, fanout: bool) -> String {
    synth::chain(n, lanes, &len.to_string(), "33.33", fanout, "")
}

fn opts(mainline: Option<Vec<String>>) -> Options {
    Options {
        net: PathBuf::from("scale.net.xml"),
        routes: vec![PathBuf::from("scale.rou.xml")],
        additional: Vec::new(),
        mainline,
        edge_detectors: false,
        interval_s: None,
        duration_s: None,
        name: Some("scale".into()),
    }
}

fn routes(last: usize) -> Vec<(PathBuf, String)> {
    vec![(
        PathBuf::from("scale.rou.xml"),
        format!(
            "<routes><flow id=\"f\" begin=\"0\" end=\"3600\" vehsPerHour=\"1800\" from=\"e0\" \
             to=\"e{last}\"/></routes>"
        ),
    )]
}

#[test]
fn a_chain_of_10000_edges_with_a_routed_flow_imports_in_seconds() {
    // D3: the corridor was cubic in mainline edges (crossings and chain membership scanned
    // the chain per connection), the router scanned every connection per trip.
    let n = 10_000;
    let net = chain(n, 2, 1.0, false);
    let started = Instant::now();
    let imported = from_texts(&opts(None), &net, &routes(n - 1), &[]).unwrap();
    let found = started.elapsed().as_secs_f64();
    assert!(
        imported.toml.contains("mainline_vph = [1800.0]"),
        "{}",
        &imported.toml[..2000]
    );
    // The mainline given by hand: the list's duplicate check was quadratic too.
    let ids: Vec<String> = (0..n).map(|k| format!("e{k}")).collect();
    let given = from_texts(&opts(Some(ids)), &net, &routes(n - 1), &[]).unwrap();
    assert_eq!(given.toml, imported.toml);
    let total = started.elapsed().as_secs_f64();
    assert!(total < 10.0, "found in {found:.2} s, both in {total:.2} s");
}

#[test]
fn forty_thousand_connections_import_in_seconds() {
    // D2: a line number counted from the file's start for every connection.
    let net = chain(2_501, 4, 10.0, true);
    assert_eq!(net.matches("<connection").count(), 40_000);
    let started = Instant::now();
    from_texts(&opts(None), &net, &routes(2_500), &[]).unwrap();
    let s = started.elapsed().as_secs_f64();
    assert!(s < 10.0, "{s:.2} s");
}

#[test]
fn a_corridor_longer_than_a_scenario_may_be_is_refused_early() {
    let net = chain(3_000, 1, 100.0, false);
    let e = from_texts(&opts(None), &net, &[], &[])
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "not a corridor: the mainline (3000 edges from \"e0\" to \"e2999\") is 300000 m long; a \
         corridor may be at most 200000 m (docs/robustness.md): give a shorter one with --mainline"
    );
}

#[test]
fn structured_networks_never_panic_and_what_is_accepted_validates() {
    // Issue 48 item 6: the fuzz target `sumo_shapes`'s generator on a fixed sequence of inputs
    // (sizes below 4,096 here to keep the test short; the fuzz target reaches 20,000).
    let mut state: u64 = 48;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 33) as u8
    };
    let started = Instant::now();
    let mut accepted = 0;
    for case in 0..200 {
        let mut bytes: Vec<u8> = (0..12).map(|_| next()).collect();
        bytes[2] %= 16;
        let (net, routes) = synth::from_bytes(&bytes);
        let routes = vec![(PathBuf::from("s.rou.xml"), routes)];
        let result = std::panic::catch_unwind(|| from_texts(&opts(None), &net, &routes, &[]));
        let Ok(result) = result else {
            panic!("case {case}: {bytes:?} panicked");
        };
        if let Ok(imported) = result {
            if let Ok(config) = platoonsim_scenario::from_toml(
                &imported.toml,
                "s.toml",
                "s",
                &platoonsim_scenario::Overrides::default(),
            ) {
                config.check().unwrap();
                accepted += 1;
            }
        }
    }
    assert!(accepted > 10, "{accepted} of 200 accepted");
    let s = started.elapsed().as_secs_f64();
    assert!(s < 20.0, "{s:.1} s");
}

#[test]
fn edge_detectors_on_a_long_chain_are_refused_at_once() {
    // Found by the fuzz target sumo_shapes (its first seed, a 10,000-edge chain with
    // --edge-detectors): validation of 10,000 detectors was quadratic, past libFuzzer's 10 s
    // in the instrumented build.
    let net = chain(10_000, 2, 1.0, false);
    let mut o = opts(None);
    o.edge_detectors = true;
    let started = Instant::now();
    let e = from_texts(&o, &net, &routes(9_999), &[])
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "--edge-detectors given: the mainline has 10000 edges (and 0 loop detectors): a detector per \
         edge would be more than the 1000 a scenario may have; leave the flag out or give a \
         shorter --mainline"
    );
    assert!(started.elapsed().as_secs_f64() < 5.0);
}
