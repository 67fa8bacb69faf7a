//! Diagnostic: print one lane's vehicles at a given time. `trace PEN DEMAND T LANE`
use platoonsim_sim::{Config, Simulation};

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let f = |i: usize, d: f64| a.get(i).and_then(|s| s.parse().ok()).unwrap_or(d);
    let mut cfg = Config::homogeneous(f(0, 1.0), f(1, 3000.0), f(2, 600.0), 0.0, 1);
    if std::env::var("NOLC").is_ok() {
        cfg.lane_change.forbid_zone_m = 1e9;
    }
    let lane = f(3, 0.0) as usize;
    let (x_lo, x_hi) = (f(4, 0.0), f(5, 1e9));
    if std::env::var("PD").is_ok() {
        cfg.warmup_s = 1200.0;
        cfg = cfg.with_pd();
    }
    let mut sim = Simulation::new(cfg).unwrap();
    while !sim.finished() {
        sim.step().unwrap();
    }
    let mut prev: Option<(f64, f64)> = None;
    for v in sim
        .lane_vehicles(lane)
        .filter(|v| v.x >= x_lo && v.x <= x_hi)
    {
        let gap = prev.map(|(x, l)| x - l - v.x).unwrap_or(f64::NAN);
        println!(
            "{:>5} {:?} x {:>8.1} v {:>5.1} a {:>5.2} gap {:>6.1} tc {:.1} vdes {:.1} {:?} {:?} {:?}",
            v.id, v.kind, v.x, v.v * 3.6, v.a, gap, v.cacc_gap_s, v.human.desired_speed * 3.6, v.family, v.mode, v.relax
        );
        prev = Some((v.x, v.human.length_m));
    }
}
