//! Merge capacity of the toy corridor (tests/network.rs): mainline `Q` veh/h over three lanes
//! and 1,200 veh/h on ramp A, above what the merge can carry; prints the discharge downstream
//! of the merge (F-up) and upstream (A-up) after the first 1,200 s.
//! `mergecap PEN Q SEED [yield 0|1] [w_follower]`
#[path = "../tests/network.rs"]
#[allow(dead_code, unused_imports)]
mod network;
fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let f = |i: usize, d: f64| a.get(i).and_then(|s| s.parse().ok()).unwrap_or(d);
    let (pen, q, seed) = (f(0, 0.5), f(1, 6000.0), f(2, 11.0) as u64);
    let mut cfg = network::toy(pen, vec![q], seed);
    cfg.duration_s = std::env::var("MC_DUR")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3600.0);
    cfg.cav.yield_while_automated = f(3, 0.0) > 0.5;
    cfg.lane_change.cav_weight_follower = f(4, 0.0);
    let net = cfg.road.network.as_mut().unwrap();
    net.on_ramps[0].demand_vph = vec![f(5, 1200.0)];
    net.on_ramps[1].demand_vph = vec![0.0];
    net.on_ramps[2].demand_vph = vec![0.0];
    if let Some(t) = a.get(6).and_then(|s| s.parse::<f64>().ok()) {
        let mut sim = platoonsim_sim::Simulation::new(cfg).unwrap();
        while sim.time_s() < t {
            sim.step().unwrap();
        }
        let (lo, hi) = (f(7, 600.0), f(8, 1500.0));
        for l in 0..5 {
            let mut prev: Option<f64> = None;
            for v in sim.lane_vehicles(l).filter(|v| v.x >= lo && v.x <= hi) {
                let gap = prev.map(|r| r - v.x).unwrap_or(f64::NAN);
                println!(
                    "lane {l} {:>5} {} x {:7.1} v {:5.1} a {:5.2} gap {:5.1} {:?} {:?} exit {} {:?} tg {:.2}",
                    v.id,
                    if v.is_cav() { "C" } else { "H" },
                    v.x,
                    v.v * 3.6,
                    v.a,
                    gap,
                    v.mode,
                    v.relax,
                    v.exit as i64,
                    v.family,
                    v.time_gap_s
                );
                prev = Some(v.rear());
            }
        }
        return;
    }
    let out = platoonsim_sim::run(&cfg, None).unwrap();
    let flow = |d: &str| {
        let rows: Vec<_> = out
            .detectors
            .iter()
            .filter(|r| r.detector == d && r.lane == "all" && r.interval_start_s >= 1200.0)
            .collect();
        let n: u64 = rows.iter().map(|r| r.count).sum();
        let s: f64 = rows.iter().map(|r| r.interval_s).sum();
        n as f64 * 3600.0 / s
    };
    println!(
        "pen {pen} q {q} seed {seed} yield {} wf {}: A-up {:.0} F-up {:.0} waiting {} collisions {}",
        cfg.cav.yield_while_automated,
        cfg.lane_change.cav_weight_follower,
        flow("A-up"),
        flow("F-up"),
        out.summary.vehicles_waiting,
        out.summary.collisions
    );
}
