//! Engine throughput in vehicle updates per second (issue 2 item 8): the paper's homogeneous
//! road at 50 % CAV and 2,500 veh/h/lane, 10 simulated minutes after a 10-minute fill.
//! Compare results as ratios measured in the same sitting (machines are shared and noisy).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use platoonsim_sim::{Config, Simulation};

fn filled(pen: f64, demand: f64) -> Simulation {
    let mut sim = Simulation::new(Config::homogeneous(pen, demand, 1200.0, 0.0, 1)).unwrap();
    for _ in 0..6000 {
        sim.step().unwrap();
    }
    sim
}

fn engine(c: &mut Criterion) {
    let mut g = c.benchmark_group("homogeneous");
    g.sample_size(10);
    for (name, pen, demand) in [
        ("50pct_2500", 0.5, 2500.0),
        ("0pct_2000", 0.0, 2000.0),
        ("100pct_3500", 1.0, 3500.0),
    ] {
        let probe = filled(pen, demand);
        // ~vehicles on the road × 6000 steps per iteration.
        let per_iter = probe.vehicles_in_network() as u64 * 6000;
        g.throughput(Throughput::Elements(per_iter));
        g.bench_function(name, |b| {
            b.iter_batched(
                || filled(pen, demand),
                |mut sim| {
                    for _ in 0..6000 {
                        sim.step().unwrap();
                    }
                    sim
                },
                criterion::BatchSize::LargeInput,
            )
        });
    }
    g.finish();
}

criterion_group!(benches, engine);
criterion_main!(benches);
