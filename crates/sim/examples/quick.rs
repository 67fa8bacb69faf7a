//! Quick engine run for calibration: `cargo run --release -p platoonsim-sim --example quick --
//! PEN DEMAND [DURATION] [WARMUP] [SEED] [STRATEGY]` prints the summary as JSON-ish lines.

use platoonsim_sim::{run, Config};

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let f = |i: usize, d: f64| a.get(i).and_then(|s| s.parse().ok()).unwrap_or(d);
    let mut cfg = Config::homogeneous(
        f(0, 0.5),
        f(1, 2500.0),
        f(2, 3600.0),
        f(3, 1200.0),
        f(4, 1.0) as u64,
    );
    if let Some(s) = a.get(5) {
        if s == "pd" {
            cfg = cfg.with_pd();
        }
    }
    if let Ok(theta) = std::env::var("THETA") {
        cfg.human.buffer_s = theta.parse().unwrap();
    }
    if std::env::var("HOMOG").is_ok() {
        cfg.human.desired_speed_kmh = platoonsim_model::dist::Dist::fixed(110.0);
        cfg.cav.time_gap_shares = vec![(0.6, 1.0)];
    }
    if let Ok(r) = std::env::var("RAMP") {
        cfg.cav.time_gap_ramp_per_s = r.parse().unwrap();
    }
    if let Ok(m) = std::env::var("MAXP") {
        cfg.cav.max_platoon = m.parse().unwrap();
    }
    if let Ok(t) = std::env::var("THR") {
        let v: Vec<f64> = t.split(',').map(|x| x.parse().unwrap()).collect();
        cfg.lane_change.threshold = platoonsim_model::dist::Dist::clamped(v[0], v[1], v[2], v[3]);
    }
    if let Ok(t) = std::env::var("SCAN") {
        cfg.lane_change.scan_distance_m = t.parse().unwrap();
    }
    if let Ok(t) = std::env::var("GAIN") {
        cfg.lane_change.min_speed_gain_mps = t.parse().unwrap();
    }
    if std::env::var("NOLC").is_ok() {
        cfg.lane_change.forbid_zone_m = 1e9;
    }
    let out = run(&cfg, None).unwrap();
    let s = &out.summary;
    println!(
        "pen {} dem {} | entered {} exited {} net {} wait {} | lc/veh {:.3} (cav {:.2} hum {:.2}) Lbar {:.2} Pp {:.3} (tg2 {:.2} {:.3}) | Q {:.0} Qmax {:.0} | coll {} | upd {} in {:.2}s = {:.2} M/s",
        s.penetration,
        s.demand_vphpl,
        s.vehicles_entered,
        s.vehicles_exited,
        s.vehicles_in_network,
        s.vehicles_waiting,
        s.lane_changes_per_vehicle,
        s.lane_changes_per_cav,
        s.lane_changes_per_human,
        s.avg_platoon_length,
        s.platooning_probability,
        s.avg_platoon_length_tg2,
        s.platooning_probability_tg2,
        s.discharge_flow_vphpl,
        s.max_sustained_flow_vphpl,
        s.collisions,
        s.vehicle_updates,
        s.wall_seconds,
        s.vehicle_updates as f64 / s.wall_seconds / 1e6
    );
    if std::env::var("DET").is_ok() {
        for r in out.detectors.iter().filter(|r| r.lane == "all") {
            println!(
                "{} {:>6} {:>5.0} {:>7.0} {:?}",
                r.detector,
                r.interval_start_s,
                r.count,
                r.flow_vph / 3.0,
                r.speed_kmh.map(|v| v.round())
            );
        }
    }
}
