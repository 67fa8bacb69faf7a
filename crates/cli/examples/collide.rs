//! Diagnostic: run a scenario and print every overlapping same-lane pair in the steps where
//! the collision count rises. `collide SCENARIO T_END [KEY=VALUE ...]`
mod common;

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let name = a.first().cloned().unwrap_or_else(|| "sr99".into());
    let t_end: f64 = a.get(1).and_then(|s| s.parse().ok()).unwrap_or(14_400.0);
    let mut sim = common::simulation(&name, &a[2.min(a.len())..]);
    let mut seen = 0;
    while sim.time_s() < t_end && !sim.finished() {
        sim.step().expect("step");
        if sim.collisions() == seen {
            continue;
        }
        seen = sim.collisions();
        println!("t = {:.1} s, collisions {seen}", sim.time_s());
        if let Some(e) = sim.collision_events().last() {
            println!("  {e:?}");
        }
        for lane in 0..sim.config().road.lanes as usize {
            let vs: Vec<_> = sim.lane_vehicles(lane).collect();
            for w in vs.windows(2) {
                let (l, f) = (w[0], w[1]);
                if f.x > l.x - l.human.length_m {
                    for v in [l, f] {
                        println!(
                            "  lane {lane} {:>6} {:?} x {:>8.1} v {:>5.1} a {:>5.2} {:?} {:?} {:?} lcs {}",
                            v.id, v.kind, v.x, v.v * 3.6, v.a, v.mode, v.family, v.relax, v.lane_changes
                        );
                    }
                }
            }
        }
    }
    println!(
        "end t = {:.1} s, collisions {}",
        sim.time_s(),
        sim.collisions()
    );
}
