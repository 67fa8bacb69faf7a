//! Lane changes: a cut-in under the two gap rules, overtaking, and yielding to a driver that
//! must move in.

use super::common::{at, empty, empty_config, run};
use platoonsim_model::safegap::GapRule;
use platoonsim_sim::vehicle::Kind;
use platoonsim_sim::{Command, Side, Simulation};

/// A driver at 18 m/s in the left lane, 50 m ahead of a driver at 30 m/s in the right lane,
/// is told to move right (a commanded, mandatory change). Returns (seconds until it is in,
/// the hardest braking of the right-lane driver while it is behind the changer, m/s²).
fn cut_in(rule: GapRule) -> (f64, f64) {
    let mut cfg = empty_config(2);
    cfg.lane_change.gap_rule = rule;
    let mut sim = Simulation::new(cfg).unwrap();
    let follower = sim.place_vehicle(Kind::Human, 0, 1000.0, 30.0).unwrap();
    sim.command(follower, Command::DesiredSpeed { speed_mps: 30.0 })
        .unwrap();
    let changer = sim.place_vehicle(Kind::Human, 1, 1050.0, 18.0).unwrap();
    sim.command(changer, Command::DesiredSpeed { speed_mps: 18.0 })
        .unwrap();
    sim.command(changer, Command::ChangeLane { side: Side::Right })
        .unwrap();
    let (mut t_in, mut hardest) = (None, 0.0_f64);
    run(&mut sim, 30.0, |s| {
        if t_in.is_none() && at(s, changer).lane == 0 {
            t_in = Some(s.time_s());
        }
        if t_in.is_some() && at(s, follower).x < at(s, changer).x {
            hardest = hardest.min(at(s, follower).a);
        }
    });
    assert_eq!(sim.collisions(), 0);
    (t_in.expect("never moved in"), hardest)
}

#[test]
fn a_cut_in_never_makes_the_new_follower_brake_beyond_the_safe_bound() {
    // The published rule (spec 4.3) accepts the 50 m gap at once although the follower
    // closes at 12 m/s, and the follower brakes at 5.7 m/s², beyond its comfortable bound
    // of 4. The safe rule (spec 9.1: no change that makes the new follower brake harder than
    // b_safe = 3 m/s² by its own law) refuses it; the changer waits until the follower has
    // gone by and moves in behind it.
    let (t_published, hard_published) = cut_in(GapRule::Published);
    assert!(
        t_published < 0.5,
        "published rule: in after {t_published} s"
    );
    assert!(
        hard_published < -4.0,
        "published rule: follower braked at {hard_published}"
    );
    let (t_safe, hard_safe) = cut_in(GapRule::Safe);
    assert!(t_safe > 2.0, "safe rule: in after {t_safe} s");
    assert!(
        hard_safe >= -3.0,
        "safe rule: follower braked at {hard_safe} m/s²"
    );
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
        hardest = hardest.min(at(s, cav).a);
        let (h, c) = (at(s, human), at(s, cav));
        if moved_in.is_none() && h.lane == 0 {
            moved_in = Some((s.time_s(), h.x - h.length - c.x));
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
