//! Single manoeuvres with vehicles placed by hand on an empty road (no arrivals), in the
//! manner of SUMO's small scenario tests (`cf_model/.../follow_slow`): each test pins one
//! behaviour of the driver models as the engine runs them, and says what it saw when it fails.

use platoonsim_sim::vehicle::Kind;
use platoonsim_sim::{Command, Config, Side, Simulation};

/// An empty road of `lanes` lanes (no arrivals), 6.5 km, 5 simulated minutes.
fn empty(lanes: u32) -> Simulation {
    let mut cfg = Config::homogeneous(0.0, 0.0, 300.0, 0.0, 1);
    cfg.road.lanes = lanes;
    Simulation::new(cfg).unwrap()
}

/// Step `secs`, calling `watch` after each step.
fn run(sim: &mut Simulation, secs: f64, mut watch: impl FnMut(&Simulation)) {
    let steps = (secs / 0.1).round() as usize;
    for _ in 0..steps {
        sim.step().unwrap();
        watch(sim);
    }
}

/// Bumper-to-bumper gap from `follower` to `leader` (m).
fn gap(sim: &Simulation, leader: u64, follower: u64) -> f64 {
    let (l, f) = (sim.vehicle(leader).unwrap(), sim.vehicle(follower).unwrap());
    l.x() - l.length_m() - f.x()
}

#[test]
fn a_driver_closing_on_a_slow_vehicle_settles_behind_it_without_hard_braking() {
    let mut sim = empty(1);
    let slow = sim.place_vehicle(Kind::Human, 0, 1500.0, 15.0).unwrap();
    sim.command(slow, Command::DesiredSpeed { speed_mps: 15.0 })
        .unwrap();
    let fast = sim.place_vehicle(Kind::Human, 0, 1100.0, 30.0).unwrap();
    let mut hardest: f64 = 0.0;
    run(&mut sim, 120.0, |s| {
        hardest = hardest.min(s.vehicle(fast).unwrap().a())
    });
    let f = sim.vehicle(fast).unwrap();
    // It matches the slow speed, behind it at a gap between the jam gap and a 3 s headway,
    // having braked no harder than the model's comfortable bound b = 4 m/s².
    assert!((f.v() - 15.0).abs() < 0.3, "speed {}", f.v());
    let g = gap(&sim, slow, fast);
    assert!(
        g > f.driver_params().jam_gap_m && g < 3.0 * 15.0,
        "gap {g} m"
    );
    assert!(hardest >= -4.0, "hardest braking {hardest} m/s²");
    assert_eq!(sim.collisions(), 0);
}

#[test]
fn a_cav_behind_a_cav_closes_to_its_cacc_time_gap() {
    let mut sim = empty(1);
    let lead = sim.place_vehicle(Kind::Cav, 0, 1500.0, 25.0).unwrap();
    sim.command(lead, Command::DesiredSpeed { speed_mps: 25.0 })
        .unwrap();
    let follow = sim.place_vehicle(Kind::Cav, 0, 1350.0, 25.0).unwrap();
    run(&mut sim, 120.0, |_| {});
    let f = sim.vehicle(follow).unwrap();
    // It joined the leader's string and follows at its own CACC gap t_C (the time gap of the
    // gap it keeps, bumper to bumper, at the common speed).
    assert_eq!(
        f.joined(),
        Some(lead),
        "the follower is in the leader's string"
    );
    let t = gap(&sim, lead, follow) / f.v();
    assert!(
        (t - f.cacc_gap_s()).abs() < 0.1,
        "time gap {t:.3} s against t_C {:.3} s",
        f.cacc_gap_s()
    );
    assert!((f.v() - 25.0).abs() < 0.1, "speed {}", f.v());
}

#[test]
fn a_cav_makes_room_for_a_driver_that_must_move_in_ahead_of_it() {
    // A CAV at 28 m/s in the right lane; a human driver in the left lane 10 m ahead at 26 m/s,
    // told to move right (a mandatory change). The CAV's automation answers the request as a
    // yielding driver would (spec 4.5, `cav.yield_while_automated`): it drops back at no more
    // than its braking bound and the driver moves in ahead of it. (Without the yield the CAV
    // drives on and the driver moves in 29 m behind it after 17 s.)
    let mut sim = empty(2);
    let cav = sim.place_vehicle(Kind::Cav, 0, 1000.0, 28.0).unwrap();
    sim.command(cav, Command::DesiredSpeed { speed_mps: 28.0 })
        .unwrap();
    let human = sim.place_vehicle(Kind::Human, 1, 1010.0, 26.0).unwrap();
    sim.command(human, Command::DesiredSpeed { speed_mps: 26.0 })
        .unwrap();
    sim.command(human, Command::ChangeLane { side: Side::Right })
        .unwrap();
    let bound = -sim.config().cav.max_decel.abs();
    let mut hardest: f64 = 0.0;
    let mut moved_in = None;
    run(&mut sim, 30.0, |s| {
        hardest = hardest.min(s.vehicle(cav).unwrap().a());
        let (h, c) = (s.vehicle(human).unwrap(), s.vehicle(cav).unwrap());
        if moved_in.is_none() && h.lane() == 0 {
            moved_in = Some((s.time_s(), h.x() - h.length_m() - c.x()));
        }
    });
    let (t, g) = moved_in.expect("the driver never moved right");
    assert!(t < 10.0, "moved in only after {t} s");
    assert!(
        g > 0.0,
        "moved in behind the CAV (gap {g:.1} m): the CAV did not make room"
    );
    assert!(
        hardest >= bound - 1e-9,
        "the CAV braked at {hardest} m/s² (bound {bound})"
    );
    assert_eq!(sim.collisions(), 0);
}

#[test]
fn a_stopped_vehicle_ahead_brings_a_follower_to_a_stop_behind_it() {
    // The emergency case: a vehicle standing in the lane, a driver at 30 m/s 150 m behind. It
    // stops behind it, at no more than the emergency limit, without touching it.
    let mut sim = empty(1);
    let stopped = sim.place_vehicle(Kind::Human, 0, 2000.0, 0.0).unwrap();
    sim.command(
        stopped,
        Command::Accelerate {
            accel_mps2: 0.0,
            steps: 1200,
        },
    )
    .unwrap();
    let driver = sim.place_vehicle(Kind::Human, 0, 1850.0, 30.0).unwrap();
    let mut hardest: f64 = 0.0;
    run(&mut sim, 60.0, |s| {
        hardest = hardest.min(s.vehicle(driver).unwrap().a())
    });
    let d = sim.vehicle(driver).unwrap();
    assert!(d.v() < 0.1, "still at {} m/s", d.v());
    let g = gap(&sim, stopped, driver);
    assert!(g > 0.0 && g < 10.0, "stopped {g} m behind");
    assert!(hardest >= -9.0, "braked at {hardest} m/s²");
    assert_eq!(sim.collisions(), 0);
}
