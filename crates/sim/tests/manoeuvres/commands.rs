//! Commands from the library (`Simulation::command`, module `command`): what each does to
//! the vehicle it is given to, and what it cannot do.

use super::common::{at, empty, gap, run};
use platoonsim_sim::vehicle::Kind;
use platoonsim_sim::Command;

#[test]
fn an_accelerate_command_is_applied_exactly_for_its_steps() {
    // +1 m/s² for 30 steps of 0.1 s from 20 m/s on an empty road: 23 m/s after 3 s, and the
    // model drives again afterwards (its own acceleration, no longer exactly 1).
    let mut sim = empty(1);
    let id = sim.place_vehicle(Kind::Human, 0, 1000.0, 20.0).unwrap();
    let cmd = Command::Accelerate {
        accel_mps2: 1.0,
        steps: 30,
    };
    sim.command(id, cmd).unwrap();
    let mut accels = Vec::new();
    run(&mut sim, 3.0, |s| accels.push(at(s, id).a));
    assert!(accels.iter().all(|&a| a == 1.0), "accelerations {accels:?}");
    assert!(
        (at(&sim, id).v - 23.0).abs() < 1e-9,
        "speed {}",
        at(&sim, id).v
    );
    run(&mut sim, 0.1, |_| {});
    assert_ne!(at(&sim, id).a, 1.0, "the command outlived its steps");
}

#[test]
fn a_desired_speed_command_holds_until_released() {
    // Told 18 m/s, a driver slows to it and holds it; released, it goes back to its own
    // desired speed (drawn above 18 m/s: the default distribution's mean is 31.3 m/s).
    let mut sim = empty(1);
    let id = sim.place_vehicle(Kind::Human, 0, 500.0, 27.0).unwrap();
    sim.command(id, Command::DesiredSpeed { speed_mps: 18.0 })
        .unwrap();
    run(&mut sim, 60.0, |_| {});
    assert!(
        (at(&sim, id).v - 18.0).abs() < 0.05,
        "held {} m/s",
        at(&sim, id).v
    );
    sim.command(id, Command::Release).unwrap();
    run(&mut sim, 60.0, |_| {});
    assert!(
        at(&sim, id).v > 22.0,
        "after release {} m/s",
        at(&sim, id).v
    );
}

#[test]
fn a_capped_acceleration_cannot_drive_a_vehicle_into_the_one_ahead() {
    // A controller asks a driver for +3 m/s² for 60 s, 100 m behind a vehicle held at
    // 15 m/s. `AccelerateCapped` takes the model's acceleration whenever it is lower, so the
    // driver closes, then follows at 15 m/s without touching the leader.
    let mut sim = empty(1);
    let lead = sim.place_vehicle(Kind::Human, 0, 1200.0, 15.0).unwrap();
    sim.command(lead, Command::DesiredSpeed { speed_mps: 15.0 })
        .unwrap();
    let id = sim.place_vehicle(Kind::Human, 0, 1100.0, 15.0).unwrap();
    let cmd = Command::AccelerateCapped {
        accel_mps2: 3.0,
        steps: 600,
    };
    sim.command(id, cmd).unwrap();
    let (mut above, mut closest) = (0usize, f64::INFINITY);
    run(&mut sim, 60.0, |s| {
        above += usize::from(at(s, id).a > 3.0);
        closest = closest.min(gap(s, lead, id));
    });
    assert_eq!(above, 0, "steps above the commanded acceleration");
    assert!(closest > 0.0, "closest gap {closest} m");
    assert!(
        (at(&sim, id).v - 15.0).abs() < 0.5,
        "speed {}",
        at(&sim, id).v
    );
    assert_eq!(sim.collisions(), 0);
}

#[test]
fn a_safe_acceleration_is_applied_within_the_vehicles_limits() {
    // On an empty road `AccelerateSafe` gives the command exactly inside the limits, and the
    // limits outside them: a CAV's `cav.max_accel` / `cav.max_decel` (1.5, −4), a driver's own
    // drawn a_M and b_f. Unlike `AccelerateCapped` it accelerates above the model's law.
    for kind in [Kind::Cav, Kind::Human] {
        let mut sim = empty(1);
        let id = sim.place_vehicle(kind, 0, 1000.0, 20.0).unwrap();
        let p = sim.vehicle(id).unwrap().driver_params();
        let (lo, hi) = match kind {
            Kind::Cav => (sim.config().cav.max_decel, sim.config().cav.max_accel),
            Kind::Human => (p.max_decel, p.max_accel),
        };
        let mut step_with = |a: f64| {
            let cmd = Command::AccelerateSafe {
                accel_mps2: a,
                steps: 1,
            };
            sim.command(id, cmd).unwrap();
            sim.step().unwrap();
            at(&sim, id).a
        };
        assert_eq!(step_with(0.7), 0.7, "{kind:?} inside the limits");
        assert_eq!(step_with(20.0), hi, "{kind:?} above a_M");
        assert_eq!(step_with(-20.0), lo, "{kind:?} below b");
        assert_eq!(step_with(-1.5), -1.5, "{kind:?} inside again");
    }
}

#[test]
fn a_safe_acceleration_never_drives_a_vehicle_into_the_one_ahead() {
    // Told +1.5 m/s² for 60 s, 100 m behind a vehicle that brakes to a stop at 4 m/s² and
    // stays there: the safe speed takes over, the follower stops behind it without touching
    // it, for a CAV and a human driver. The same command given as `Accelerate` runs into it.
    let mut closest_by_kind = Vec::new();
    for kind in [Kind::Cav, Kind::Human] {
        for safe in [true, false] {
            let mut sim = empty(1);
            let lead = sim.place_vehicle(Kind::Human, 0, 1100.0, 20.0).unwrap();
            let id = sim.place_vehicle(kind, 0, 1000.0, 20.0).unwrap();
            sim.command(
                lead,
                Command::Accelerate {
                    accel_mps2: -4.0,
                    steps: 600,
                },
            )
            .unwrap();
            let (accel_mps2, steps) = (1.5, 600);
            let cmd = if safe {
                Command::AccelerateSafe { accel_mps2, steps }
            } else {
                Command::Accelerate { accel_mps2, steps }
            };
            sim.command(id, cmd).unwrap();
            let mut closest = f64::INFINITY;
            run(&mut sim, 60.0, |s| closest = closest.min(gap(s, lead, id)));
            if safe {
                assert_eq!(sim.collisions(), 0, "{kind:?}: closest gap {closest} m");
                assert!(closest > 0.0, "{kind:?}: closest gap {closest} m");
                assert!(at(&sim, id).v < 1e-9, "{kind:?} still moving");
                closest_by_kind.push(closest);
            } else {
                assert!(
                    sim.collisions() > 0,
                    "{kind:?}: unbounded, closest {closest} m"
                );
            }
        }
    }
    assert_eq!(closest_by_kind.len(), 2);
}
