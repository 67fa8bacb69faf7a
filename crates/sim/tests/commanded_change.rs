//! A commanded lane change (command.rs) after a `DesiredSpeed` command, on an open road
//! (issue 29 item 6): it completes within a few seconds and without braking. Before the fix
//! the driver dropped back (BLC-Slow, spec 4.3) behind the faster target-lane traffic, which
//! only made the gap worse: down to the creep speed, 2.2 m/s, and 10 s in its lane.

use platoonsim_model::cav::CaccLaw;
use platoonsim_sim::{Command, Config, Kind, Side, Simulation, VehicleView};

fn find(sim: &Simulation, id: u64) -> VehicleView<'_> {
    (0..3)
        .flat_map(|l| sim.lane_vehicles(l))
        .find(|v| v.id() == id)
        .expect("on the road")
}

/// Homogeneous road, 50 % CAV at `demand` veh/h/lane: after 200 s an automated CAV in the
/// right lane (1-3 km) is set to `speed` m/s, drives 30 s, and is then commanded to the left.
/// Returns the steps it took and its smallest acceleration meanwhile.
fn set_speed_then_change(demand: f64, speed: f64, law: CaccLaw) -> (Option<u32>, f64) {
    let mut cfg = Config::homogeneous(0.5, demand, 600.0, 0.0, 2);
    cfg.cav.cacc_law = law;
    let mut sim = Simulation::new(cfg).unwrap();
    while sim.time_s() < 200.0 {
        sim.step().unwrap();
    }
    let id = sim
        .lane_vehicles(0)
        .find(|v| v.kind() == Kind::Cav && v.automated() && v.x() > 1000.0 && v.x() < 3000.0)
        .map(|v| v.id())
        .expect("a CAV in the right lane");
    sim.command(id, Command::DesiredSpeed { speed_mps: speed })
        .unwrap();
    for _ in 0..300 {
        sim.step().unwrap();
    }
    assert!((find(&sim, id).v() - speed).abs() < 0.5, "at its set speed");
    sim.command(id, Command::ChangeLane { side: Side::Left })
        .unwrap();
    let mut min_a = f64::INFINITY;
    for k in 1..=300 {
        sim.step().unwrap();
        let v = find(&sim, id);
        min_a = min_a.min(v.a());
        if v.lane() == 1 {
            return (Some(k), min_a);
        }
    }
    (None, min_a)
}

#[test]
fn a_commanded_change_after_a_desired_speed_completes_without_braking() {
    // Under the spec's CACC law (the traffic this test was written against) every change is
    // made within 6 s. Under the field law (docs/cacc-field.md) the surrounding strings differ
    // and the gap at 1,000 veh/h/lane, 10 m/s comes after 6.5 s (measured: 65 steps, no
    // braking); the failure this pins (the driver dropping back to the creep speed, 10 s in
    // its lane) brakes, which `min_a` catches under both laws.
    for (law, max_steps) in [(CaccLaw::Spec, 60), (CaccLaw::Field, 100)] {
        for (demand, speed) in [(600.0, 10.0), (600.0, 20.0), (600.0, 25.0), (1000.0, 10.0)] {
            let (steps, min_a) = set_speed_then_change(demand, speed, law);
            eprintln!("{law:?} {demand} {speed}: {steps:?} steps, min a {min_a}");
            let steps = steps.expect("the change is made");
            assert!(
                steps <= max_steps,
                "{law:?}, {demand} veh/h/lane, {speed} m/s: {steps} steps"
            );
            assert!(
                min_a > -0.1,
                "{law:?}, {demand} veh/h/lane, {speed} m/s: brakes at {min_a}"
            );
        }
    }
}
