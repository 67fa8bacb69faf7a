//! Diagnostic: print the lane segments of a scenario's geometry. `geomdump SCENARIO`
use platoonsim_sim::network::Geometry;

fn main() {
    let name = std::env::args().nth(1).unwrap_or_else(|| "sr99".into());
    let cfg = platoonsim_scenario::load(&name).expect("scenario");
    let g = Geometry::new(&cfg).expect("geometry");
    for lane in 0..cfg.road.lanes {
        let mut x = -600.0;
        let mut last = String::new();
        while x < 17200.0 {
            let s = match g.seg(lane, x) {
                Some(s) => format!(
                    "from {} to {} accel {} wall {:?}",
                    s.from,
                    s.to,
                    s.accel,
                    g.wall_ahead(lane, x)
                ),
                None => "closed".into(),
            };
            if s != last {
                println!("lane {lane} x {x}: {s}");
                last = s;
            }
            x += 10.0;
        }
    }
}
