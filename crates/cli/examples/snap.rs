//! Diagnostic: run a scenario to time T and print the vehicles of every lane in [x_lo, x_hi].
//! `snap SCENARIO T X_LO X_HI [--set KEY=VALUE ...]`
mod common;

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let name = a.first().cloned().unwrap_or_else(|| "sr99".into());
    let f = |i: usize, d: f64| a.get(i).and_then(|s| s.parse().ok()).unwrap_or(d);
    let (t, x_lo, x_hi) = (f(1, 7200.0), f(2, 0.0), f(3, 1e9));
    let mut sim = common::simulation(&name, &a[4.min(a.len())..]);
    while sim.time_s() < t && !sim.finished() {
        sim.step().expect("step");
    }
    for lane in 0..sim.config().road.lanes as usize {
        println!("-- lane {lane}");
        let mut prev: Option<f64> = None;
        for v in sim
            .lane_vehicles(lane)
            .filter(|v| v.x >= x_lo && v.x <= x_hi)
        {
            let gap = prev.map(|r| r - v.x).unwrap_or(f64::NAN);
            println!(
                "{:>6} {:?} x {:>8.1} v {:>5.1} a {:>5.2} gap {:>6.1} exit {} {:?} {:?} lcs {}",
                v.id,
                v.kind,
                v.x,
                v.v * 3.6,
                v.a,
                gap,
                v.exit as i64,
                v.mode,
                v.relax,
                v.lane_changes
            );
            prev = Some(v.x - v.human.length_m);
        }
    }
}
