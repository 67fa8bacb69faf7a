//! Diagnostic: print one vehicle's state every step between two times.
//! `follow SCENARIO ID T0 T1 [KEY=VALUE ...]`
mod common;

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let name = a.first().cloned().unwrap_or_else(|| "sr99".into());
    let id: u64 = a.get(1).and_then(|s| s.parse().ok()).unwrap_or(0);
    let t0: f64 = a.get(2).and_then(|s| s.parse().ok()).unwrap_or(0.0);
    let t1: f64 = a.get(3).and_then(|s| s.parse().ok()).unwrap_or(60.0);
    let mut sim = common::simulation(&name, &a[4.min(a.len())..]);
    while sim.time_s() < t1 && !sim.finished() {
        sim.step().expect("step");
        if sim.time_s() < t0 {
            continue;
        }
        for lane in 0..sim.config().road.lanes as usize {
            let vs: Vec<_> = sim.lane_vehicles(lane).collect();
            for (k, v) in vs.iter().enumerate() {
                if v.id != id {
                    continue;
                }
                let gap = k
                    .checked_sub(1)
                    .map(|j| vs[j].rear() - v.x)
                    .unwrap_or(f64::NAN);
                println!(
                    "t {:>7.1} lane {lane} x {:>8.2} v {:>5.2} a {:>6.2} gap {:>6.2} {:?} {:?} lcs {}",
                    sim.time_s(),
                    v.x,
                    v.v,
                    v.a,
                    gap,
                    v.mode,
                    v.relax,
                    v.lane_changes
                );
            }
        }
    }
}
