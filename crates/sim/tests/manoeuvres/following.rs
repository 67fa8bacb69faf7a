//! Car following: a slower leader, a CACC leader, a standing queue, a braking leader.

use super::common::{at, empty, empty_config, gap, run};
use platoonsim_model::cav::CaccLaw;
use platoonsim_sim::vehicle::Kind;
use platoonsim_sim::{Command, Simulation};

#[test]
fn a_driver_closing_on_a_slow_vehicle_settles_behind_it_without_hard_braking() {
    let mut sim = empty(1);
    let slow = sim.place_vehicle(Kind::Human, 0, 1500.0, 15.0).unwrap();
    sim.command(slow, Command::DesiredSpeed { speed_mps: 15.0 })
        .unwrap();
    let fast = sim.place_vehicle(Kind::Human, 0, 1100.0, 30.0).unwrap();
    let mut hardest: f64 = 0.0;
    run(&mut sim, 120.0, |s| hardest = hardest.min(at(s, fast).a));
    let f = at(&sim, fast);
    // It matches the slow speed, behind it at a gap between the jam gap and a 3 s headway,
    // having braked no harder than the model's comfortable bound b = 4 m/s².
    assert!((f.v - 15.0).abs() < 0.3, "speed {}", f.v);
    let g = gap(&sim, slow, fast);
    assert!(g > f.jam_gap && g < 3.0 * 15.0, "gap {g} m");
    assert!(hardest >= -4.0, "hardest braking {hardest} m/s²");
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
    run(&mut sim, 60.0, |s| hardest = hardest.min(at(s, driver).a));
    let d = at(&sim, driver);
    assert!(d.v < 0.1, "still at {} m/s", d.v);
    let g = gap(&sim, stopped, driver);
    assert!(g > 0.0 && g < 10.0, "stopped {g} m behind");
    assert!(hardest >= -9.0, "braked at {hardest} m/s²");
    assert_eq!(sim.collisions(), 0);
}

#[test]
fn drivers_closing_on_a_standing_queue_stop_behind_it_in_order() {
    // Three vehicles standing 12 m apart (front to front), two drivers at 30 m/s 250 m and
    // 310 m behind the last of them: both stop behind the queue, in order, none touching,
    // none braking beyond the emergency limit b_e = 9 m/s².
    let mut sim = empty(1);
    let mut queue = Vec::new();
    for k in 0..3 {
        let id = sim
            .place_vehicle(Kind::Human, 0, 2000.0 - 12.0 * k as f64, 0.0)
            .unwrap();
        let hold = Command::Accelerate {
            accel_mps2: 0.0,
            steps: 1200,
        };
        sim.command(id, hold).unwrap();
        queue.push(id);
    }
    let first = sim.place_vehicle(Kind::Human, 0, 1726.0, 30.0).unwrap();
    let second = sim.place_vehicle(Kind::Human, 0, 1666.0, 30.0).unwrap();
    let mut hardest: f64 = 0.0;
    run(&mut sim, 90.0, |s| {
        hardest = hardest.min(at(s, first).a).min(at(s, second).a)
    });
    let last = queue[2];
    for id in [first, second] {
        assert!(
            at(&sim, id).v < 0.1,
            "vehicle {id} still at {} m/s",
            at(&sim, id).v
        );
    }
    let (g1, g2) = (gap(&sim, last, first), gap(&sim, first, second));
    assert!(
        g1 > 0.0 && g1 < 10.0,
        "first stopped {g1} m behind the queue"
    );
    assert!(
        g2 > 0.0 && g2 < 10.0,
        "second stopped {g2} m behind the first"
    );
    assert!(hardest >= -9.0, "braked at {hardest} m/s²");
    assert_eq!(sim.collisions(), 0);
}

#[test]
fn a_cacc_string_attenuates_its_leaders_braking() {
    // Five CAVs in one string at 25 m/s (the leader set to 25 m/s, the others to 30 m/s so
    // that they close to their t_C). The leader brakes at 3 m/s² for 4 s (to 13 m/s) and
    // then drives on. No follower's speed dips as low as the leader's (13.43, 13.42, 13.38
    // and 13.47 m/s down the string), and none brakes beyond its bound b = 4 m/s². The
    // attenuation is not strict member by member: the dip deepens by 0.05 m/s from the
    // second to the fourth CAV and the hardest braking grows from 3.0 to 3.38 m/s²
    // (docs/cacc-string-stability.md).
    let mut sim = empty(1);
    let ids: Vec<u64> = (0..5)
        .map(|k| {
            let id = sim
                .place_vehicle(Kind::Cav, 0, 3000.0 - 30.0 * k as f64, 25.0)
                .unwrap();
            let set = if k == 0 { 25.0 } else { 30.0 };
            sim.command(id, Command::DesiredSpeed { speed_mps: set })
                .unwrap();
            id
        })
        .collect();
    run(&mut sim, 60.0, |_| {});
    for w in ids.windows(2) {
        assert_eq!(at(&sim, w[1]).pred, Some(w[0]), "the five form one string");
    }
    let brake = Command::Accelerate {
        accel_mps2: -3.0,
        steps: 40,
    };
    sim.command(ids[0], brake).unwrap();
    for w in ids.windows(2) {
        let (f, g) = (at(&sim, w[1]), gap(&sim, w[0], w[1]));
        assert!(
            (g / f.v - f.t_c).abs() < 0.1,
            "{} s against t_C {}",
            g / f.v,
            f.t_c
        );
    }
    let mut low = [f64::INFINITY; 5];
    let mut hardest = [0.0_f64; 5];
    run(&mut sim, 40.0, |s| {
        for (k, &id) in ids.iter().enumerate() {
            let v = at(s, id);
            low[k] = low[k].min(v.v);
            hardest[k] = hardest[k].min(v.a);
        }
    });
    // 25 − 3 × 4 = 13 m/s; under the field law (the default, docs/cacc-field.md) the
    // low-level lag (0.3 s) carries the braking on briefly after the command ends: 12.73.
    assert!(
        low[0] <= 13.0 + 1e-6 && low[0] > 12.5,
        "leader's low {}",
        low[0]
    );
    for k in 1..5 {
        assert!(low[k] > low[0], "speed dips {low:?}");
        assert!(hardest[k] >= -4.0, "CAV {k} braked at {}", hardest[k]);
    }
    assert_eq!(sim.collisions(), 0);
}

#[test]
fn no_vehicle_brakes_beyond_its_emergency_limit_even_when_told_to() {
    // A command asks for 15 m/s² of braking; integrate bounds every acceleration by the
    // vehicle's emergency limit b_e = 9 m/s² (safety.rs), so the vehicle brakes at exactly
    // that until it stands, and never moves backwards.
    let mut sim = empty(1);
    let id = sim.place_vehicle(Kind::Human, 0, 1000.0, 30.0).unwrap();
    let brake = Command::Accelerate {
        accel_mps2: -15.0,
        steps: 100,
    };
    sim.command(id, brake).unwrap();
    let (mut hardest, mut back) = (0.0_f64, false);
    let mut x_prev = at(&sim, id).x;
    run(&mut sim, 10.0, |s| {
        let v = at(s, id);
        hardest = hardest.min(v.a);
        back |= v.x < x_prev;
        x_prev = v.x;
    });
    assert_eq!(hardest, -9.0, "hardest braking");
    assert!(!back, "moved backwards");
    assert_eq!(at(&sim, id).v, 0.0);
}

#[test]
fn the_field_automation_engages_only_within_its_envelope() {
    // A CAV creeping at 1.8 m/s 1.2 m behind a standing vehicle, inside the automation's
    // standstill gap s_min = 1.5 m (where a driver who drove by hand may leave it), with no
    // regime yet (as after a manual spell). Engaged there, the safety override would stop it
    // within one step (an AEB stop at the 9 m/s² limit); under the field law the driver keeps
    // driving until the automation's demand lies within the ISO 15622 envelope (5 m/s² at
    // low speed), so the stop stays within it. Under the spec law the automation engages at
    // once and brakes at the limit.
    let hardest_with = |law: CaccLaw| {
        let mut cfg = empty_config(1);
        cfg.cav.cacc_law = law;
        let mut sim = Simulation::new(cfg).unwrap();
        let stopped = sim.place_vehicle(Kind::Human, 0, 2000.0, 0.0).unwrap();
        sim.command(
            stopped,
            Command::Accelerate {
                accel_mps2: 0.0,
                steps: 200,
            },
        )
        .unwrap();
        let len = at(&sim, stopped).length;
        let cav = sim
            .place_vehicle(Kind::Cav, 0, 2000.0 - len - 1.2, 1.8)
            .unwrap();
        let mut hardest: f64 = 0.0;
        run(&mut sim, 10.0, |s| hardest = hardest.min(at(s, cav).a));
        assert_eq!(sim.collisions(), 0);
        assert!(gap(&sim, stopped, cav) > 0.0);
        assert!(at(&sim, cav).v < 0.1);
        hardest
    };
    let field = hardest_with(CaccLaw::Field);
    assert!(field >= -5.0, "braked at {field} m/s² under the field law");
    let spec = hardest_with(CaccLaw::Spec);
    assert!(spec < -6.0, "braked at {spec} m/s² under the spec law");
}
