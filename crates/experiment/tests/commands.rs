//! Control from outside (issue 19 item 6): a commanded lane change happens when and where it
//! was commanded, and a commanded stop on a one-lane road produces the shock wave that
//! kinematic-wave (LWR) theory predicts, with no collision. (On three lanes, vehicles stopped
//! at staggered positions leave a weaving path past them: that is a bottleneck, not a
//! blockage.)

use platoonsim_scenario::{load_with, Overrides, StrategyKind};
use platoonsim_sim::{
    Command, Config, Event, LaneChangeReason, Observer, Recording, Side, Simulation, TrajectorySpec,
};

fn homogeneous(penetration: f64, demand: f64, duration_s: f64, seed: u64, set: &[&str]) -> Config {
    let o = Overrides {
        penetration: Some(penetration),
        demand_vphpl: Some(demand),
        duration_s: Some(duration_s),
        warmup_s: Some(0.0),
        seed: Some(seed),
        strategy: Some(StrategyKind::NONE),
        set: set.iter().map(|s| s.to_string()).collect(),
    };
    load_with("homogeneous", &o).unwrap()
}

/// Keeps every event.
#[derive(Debug, Default)]
struct Log(Vec<Event>);

impl Observer for Log {
    fn on_step(&mut self, step: &platoonsim_sim::StepView<'_>) {
        self.0.extend_from_slice(step.events());
    }
}

fn run_until(sim: &mut Simulation, t_s: f64) {
    while sim.time_s() < t_s - 1e-9 {
        sim.step().unwrap();
    }
}

#[test]
fn a_commanded_lane_change_happens_when_and_where_commanded() {
    let mut sim = Simulation::new(homogeneous(0.0, 600.0, 400.0, 4, &[])).unwrap();
    sim.observe(Box::new(Log::default())).unwrap();
    run_until(&mut sim, 300.0);
    // A driver in the rightmost lane with nobody within 150 m in the lane to its left.
    let free = |x: f64, sim: &Simulation| sim.lane_vehicles(1).all(|o| (o.x() - x).abs() > 80.0);
    let (id, x0, v0) = sim
        .lane_vehicles(0)
        .filter(|v| v.x() > 1000.0 && v.x() < 4000.0 && free(v.x(), &sim))
        .map(|v| (v.id(), v.x(), v.v()))
        .next()
        .expect("a driver with a free lane beside it");
    sim.command(id, Command::ChangeLane { side: Side::Left })
        .unwrap();
    sim.step().unwrap();
    let log = &sim.observer::<Log>().unwrap().0;
    let changes: Vec<_> = log
        .iter()
        .filter(|e| matches!(e, Event::LaneChange { id: i, .. } if *i == id))
        .collect();
    assert_eq!(changes.len(), 1, "{changes:?}");
    let Event::LaneChange {
        t_s,
        from,
        to,
        x_m,
        reason,
        ..
    } = changes[0].clone()
    else {
        unreachable!()
    };
    println!("commanded at t = 300 s, x = {x0:.1} m; changed at t = {t_s} s, x = {x_m:.1} m");
    assert_eq!((from, to, reason), (0, 1, LaneChangeReason::Commanded));
    assert_eq!(t_s, 300.1, "in the step after the command");
    assert!(
        x_m >= x0 && x_m <= x0 + v0 * 0.1 + 0.5,
        "{x_m} from {x0} at {v0} m/s"
    );
    // The command ends once done (seen at the next decide phase).
    sim.step().unwrap();
    assert!(sim.commanded().next().is_none());
    // The vehicle is in lane 2 (index 1) now, and a second command to the left, too.
    assert!(sim.lane_vehicles(1).any(|v| v.id() == id));
    assert!(sim.command(id, Command::Release).is_ok());
    assert!(sim
        .command(
            id,
            Command::Accelerate {
                accel_mps2: f64::NAN,
                steps: 1
            }
        )
        .unwrap_err()
        .to_string()
        .contains("accel_mps2 = NaN"));
    assert!(sim.command(u64::MAX, Command::Release).is_err());
}

const T_STOP: f64 = 400.0;
const X_STOP: f64 = 4000.0;

/// One run with the stop: the measured shock speed and the LWR one (m/s).
fn shock(seed: u64) -> (f64, f64) {
    let c = homogeneous(0.5, 1500.0, 700.0, seed, &["road.lanes=1"]);
    let mut sim = Simulation::new(c).unwrap();
    sim.record(&Recording {
        trips: false,
        trajectories: Some(TrajectorySpec {
            period_s: 1.0,
            window_s: Some((300.0, 700.0)),
            x_m: Some((1000.0, 4200.0)),
        }),
    })
    .unwrap();
    run_until(&mut sim, T_STOP);
    // The first vehicle at or upstream of 4 km brakes at 4 m/s² to a stop and stands for 150 s.
    let mut stopped = vec![];
    for lane in 0..1 {
        let v = sim
            .lane_vehicles(lane)
            .find(|v| v.x() <= X_STOP)
            .expect("traffic in every lane");
        stopped.push((v.id(), v.x()));
        sim.command(
            v.id(),
            Command::Accelerate {
                accel_mps2: -4.0,
                steps: 1500,
            },
        )
        .unwrap();
    }
    while !sim.finished() {
        sim.step().unwrap();
    }
    let out = sim.finish(0.0);
    assert_eq!(out.summary.collisions, 0, "{:?}", out.collision_events);
    let rows = out.trajectories.unwrap();
    // Upstream of the wave, the traffic that reaches it during the measurement: samples in
    // 1-3 km over 400-500 s; density k from the counts, speed v, flow q = k v (the arrivals
    // as they came, not the mean demand).
    let up: Vec<_> = rows
        .iter()
        .filter(|r| r.t_s >= T_STOP && r.t_s < T_STOP + 100.0 && r.x_m > 1000.0 && r.x_m < 3000.0)
        .collect();
    let v_up = up.iter().map(|r| r.v_mps).sum::<f64>() / up.len() as f64;
    let k_up = up.len() as f64 / 100.0 / 2000.0; // veh/m: samples per second over 2 km
    let q = k_up * v_up; // veh/s
                         // The congested region: per sample time, the vehicles slower than half the upstream speed
                         // behind the stopped ones; the shock is its upstream end, its density k_c the vehicles per
                         // metre and lane in it. Nothing passes the stopped vehicles (q_c = 0), so the
                         // Rankine-Hugoniot condition of LWR theory gives the shock speed w = (0 - q) / (k_c - k).
    let times: Vec<f64> = (430..=540).step_by(5).map(f64::from).collect();
    let (mut tails, mut k_c) = (vec![], vec![]);
    for &t in &times {
        let slow: Vec<_> = rows
            .iter()
            .filter(|r| r.t_s == t && r.v_mps < 0.5 * v_up && r.x_m < X_STOP + 150.0)
            .collect();
        let tail = slow.iter().map(|r| r.x_m).fold(f64::INFINITY, f64::min);
        tails.push(tail);
        // The state behind the shock with q_c = 0 is the standing queue: its density from the
        // vehicles that stand (below 1 m/s), not from the slow ones still braking into it.
        let standing: Vec<f64> = slow
            .iter()
            .filter(|r| r.v_mps < 1.0)
            .map(|r| r.x_m)
            .collect();
        let lo = standing.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = standing.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if standing.len() >= 2 {
            k_c.push((standing.len() - 1) as f64 / (hi - lo));
        }
    }
    let k_c = k_c.iter().sum::<f64>() / k_c.len() as f64;
    // Least-squares slope of the tail position against time: the wave speed.
    let n = times.len() as f64;
    let (mt, mx) = (times.iter().sum::<f64>() / n, tails.iter().sum::<f64>() / n);
    let w = times
        .iter()
        .zip(&tails)
        .map(|(t, x)| (t - mt) * (x - mx))
        .sum::<f64>()
        / times.iter().map(|t| (t - mt).powi(2)).sum::<f64>();
    let w_lwr = -q / (k_c - k_up);
    println!(
        "seed {seed}: upstream {v_up:.1} m/s, k {:.1} veh/km/lane, congested {:.1} veh/km/lane; shock at \
         {:?}; wave {:.1} km/h, LWR {:.1} km/h",
        k_up * 1000.0,
        k_c * 1000.0,
        tails.iter().map(|x| x.round()).collect::<Vec<_>>(),
        w * 3.6,
        w_lwr * 3.6
    );
    assert!(w < 0.0, "the queue tail moves upstream");
    // After the release the queue discharges: the stopped vehicles move again.
    let moving_again = stopped.iter().all(|(id, _)| {
        rows.iter()
            .any(|r| r.id == *id && r.t_s > T_STOP + 160.0 && r.v_mps > 5.0)
            || !rows.iter().any(|r| r.id == *id && r.t_s > T_STOP + 160.0)
    });
    assert!(moving_again);
    (w, w_lwr)
}

#[test]
fn a_commanded_stop_sends_the_expected_shock_wave_upstream() {
    // Four seeds: one run's shock moves in jerks (Poisson arrivals, stop-and-go at the tail).
    let runs: Vec<(f64, f64)> = (4..=7).map(shock).collect();
    let w = runs.iter().map(|r| r.0).sum::<f64>() / 4.0;
    let w_lwr = runs.iter().map(|r| r.1).sum::<f64>() / 4.0;
    println!("mean wave {:.1} km/h, LWR {:.1} km/h", w * 3.6, w_lwr * 3.6);
    assert!(
        (w - w_lwr).abs() <= 0.2 * w_lwr.abs(),
        "wave {w} m/s against LWR {w_lwr} m/s"
    );
}

#[test]
fn a_capped_acceleration_never_exceeds_the_models_and_never_collides() {
    // Every vehicle on a busy one-lane road is told to accelerate at 3 m/s² for 60 s, capped:
    // the model's car following stays the ceiling, so nobody runs into the vehicle ahead. The
    // same command uncapped is a pile-up.
    let run = |capped: bool| {
        let c = homogeneous(0.5, 1800.0, 400.0, 3, &["road.lanes=1"]);
        let mut sim = Simulation::new(c).unwrap();
        run_until(&mut sim, 300.0);
        let ids: Vec<u64> = sim.lane_vehicles(0).map(|v| v.id()).collect();
        for id in ids {
            let (accel_mps2, steps) = (3.0, 600);
            let cmd = if capped {
                Command::AccelerateCapped { accel_mps2, steps }
            } else {
                Command::Accelerate { accel_mps2, steps }
            };
            sim.command(id, cmd).unwrap();
        }
        let mut max_a: f64 = f64::NEG_INFINITY;
        while !sim.finished() {
            sim.step().unwrap();
            max_a = sim.lane_vehicles(0).map(|v| v.a()).fold(max_a, f64::max);
        }
        (sim.finish(0.0).summary.collisions, max_a)
    };
    let (collisions, max_a) = run(true);
    assert_eq!(collisions, 0);
    assert!(max_a <= 3.0, "largest acceleration {max_a}");
    let (collisions, _) = run(false);
    assert!(collisions > 0, "the uncapped command should collide");
}
