//! Diagnostic for `sr99` queues: every 5 min, per region (corridor coordinate: Sheldon
//! 500-4,200 m, Florin 5,784-11,700 m, i.e. `OR7-down` to the end of the `OR11` acceleration
//! lane, 47th Ave 11,700-14,000 m) the vehicles on the road, those slower than 50 km/h and the
//! most upstream of these (km); then the vehicles waiting at the entrances and the flows (veh/h)
//! across 5,784 m and 11,800 m. Used for docs/reproduction-notes-sr99.md ("Why the Florin queue did
//! not dissolve"). `qbox SCENARIO [KEY=VALUE ...]` (each a `--set`); the engine coordinate is
//! the corridor coordinate + 500 m on `sr99`.
mod common;

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let name = a.first().cloned().unwrap_or_else(|| "sr99".into());
    let mut sim = common::simulation(&name, &a[1.min(a.len())..]);
    let off = 500.0;
    // regions (external m)
    let regs = [
        ("Sheldon", 500.0, 4200.0),
        ("Florin", 5784.0, 11700.0),
        ("47th", 11700.0, 14000.0),
    ];
    let lines = [5784.0, 11800.0];
    let mut cross = [0u64; 2];
    let mut last_cross = [0u64; 2];
    let mut next = 300.0;
    println!("min | per region: N slow(<50) tail_km | waiting | cross/h at 5784, 11800");
    while !sim.finished() {
        sim.step().expect("step");
        let lanes = sim.config().road.lanes as usize;
        for l in 0..lanes {
            for v in sim.lane_vehicles(l) {
                for (i, &x) in lines.iter().enumerate() {
                    if v.x_prev < x + off && v.x >= x + off {
                        cross[i] += 1;
                    }
                }
            }
        }
        if sim.time_s() + 1e-9 >= next {
            let mut s = format!("{:4.0}", next / 60.0);
            for (_, lo, hi) in regs {
                let (mut n, mut slow, mut tail) = (0, 0, f64::INFINITY);
                for l in 0..lanes {
                    for v in sim.lane_vehicles(l) {
                        let x = v.x - off;
                        if x >= lo && x < hi {
                            n += 1;
                            if v.v < 50.0 / 3.6 {
                                slow += 1;
                                tail = tail.min(x);
                            }
                        }
                    }
                }
                let tail = if tail.is_finite() {
                    format!("{:5.1}", tail / 1000.0)
                } else {
                    "    -".into()
                };
                s += &format!(" | {n:4} {slow:4} {tail}");
            }
            s += &format!(" | {:5}", sim.vehicles_waiting());
            for i in 0..2 {
                s += &format!(" {:5}", (cross[i] - last_cross[i]) * 12);
                last_cross[i] = cross[i];
            }
            println!("{s}");
            next += 300.0;
        }
    }
}
