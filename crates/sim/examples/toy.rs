//! Debug run of the toy corridor of tests/network.rs.
#[path = "../tests/network.rs"]
#[allow(dead_code, unused_imports)]
mod network;
fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let pen: f64 = a.first().and_then(|s| s.parse().ok()).unwrap_or(0.5);
    let q: f64 = a.get(1).and_then(|s| s.parse().ok()).unwrap_or(3000.0);
    let seed: u64 = a.get(2).and_then(|s| s.parse().ok()).unwrap_or(3);
    if let Some(t) = a.get(3).and_then(|s| s.parse::<f64>().ok()) {
        let mut sim = platoonsim_sim::Simulation::new(network::toy(pen, vec![q], seed)).unwrap();
        while sim.time_s() < t {
            sim.step().unwrap();
        }
        let lo: f64 = a.get(4).and_then(|s| s.parse().ok()).unwrap_or(0.0);
        let hi: f64 = a.get(5).and_then(|s| s.parse().ok()).unwrap_or(1e9);
        for l in 0..5 {
            for v in sim.lane_vehicles(l) {
                if v.x >= lo && v.x <= hi {
                    println!(
                        "lane {l} id {} x {:.1} v {:.1} a {:.2} exit {} mode {:?} cav {}",
                        v.id,
                        v.x,
                        v.v,
                        v.a,
                        v.exit as i64,
                        v.mode,
                        v.is_cav()
                    );
                }
            }
        }
        return;
    }
    let out = platoonsim_sim::run(&network::toy(pen, vec![q], seed), None).unwrap();
    println!("{:?}", out.summary);
    for r in out.detectors.iter().filter(|r| r.lane == "all") {
        println!(
            "{:8} t={:5} q={:6} v={:?}",
            r.detector,
            r.interval_start_s,
            r.flow_vph,
            r.speed_kmh.map(|v| v.round())
        );
    }
}
#[allow(dead_code)]
fn dump() {}
