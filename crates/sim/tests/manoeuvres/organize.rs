//! Platoon organization: a CAV waiting for a gap toward the PD lane under automation
//! (docs/model-choices.md 6.20).

use super::common::{at, empty_config, run, seen};
use platoonsim_model::cav::OrganizeHold;
use platoonsim_sim::vehicle::Kind;
use platoonsim_sim::{Command, Side, Simulation};

/// A mutual wait, placed by hand on the homogeneous road under PD (3 lanes, PD lane 2):
/// a driver B stands in the PD lane behind a standing vehicle and waits to move right (a
/// commanded, mandatory change); an automated CAV A stands in lane 1 with its front 0.3 m
/// behind B's rear and waits to move left into the PD lane. A's lag gap is open (nobody behind
/// it in the PD lane) and B, its target-lane leader, is ahead, so A's hold keeps it from
/// driving on; B's lag gap is A, too close. Returns the seconds until B is in lane 1 (or
/// `None` within 60 s) and the speed A reached.
fn mutual_wait(hold: OrganizeHold) -> (Option<f64>, f64) {
    let mut cfg = empty_config(3).with_pd();
    cfg.cav.organize_hold = hold;
    let mut sim = Simulation::new(cfg).unwrap();
    let c = sim.place_vehicle(Kind::Human, 2, 5540.0, 0.0).unwrap();
    sim.command(
        c,
        Command::Accelerate {
            accel_mps2: 0.0,
            steps: 1_000_000,
        },
    )
    .unwrap();
    let c_rear = at(&sim, c).x - at(&sim, c).length;
    let b = sim
        .place_vehicle(Kind::Human, 2, c_rear - 2.5, 0.0)
        .unwrap();
    sim.command(b, Command::ChangeLane { side: Side::Right })
        .unwrap();
    let b_rear = at(&sim, b).x - at(&sim, b).length;
    let a = sim.place_vehicle(Kind::Cav, 1, b_rear - 0.3, 0.0).unwrap();
    let (mut t_in, mut v_a) = (None, 0.0_f64);
    run(&mut sim, 60.0, |s| {
        if t_in.is_none() && seen(s, b).is_some_and(|b| b.lane == 1) {
            t_in = Some(s.time_s());
        }
        // A drives off the 6.5 km road once it goes.
        if let Some(seen_a) = seen(s, a) {
            v_a = v_a.max(seen_a.v);
        }
    });
    assert_eq!(sim.collisions(), 0);
    (t_in, v_a)
}

#[test]
fn a_mutual_wait_beside_an_organizing_cav_ends_by_the_hold_timeout() {
    // The hold as first built, and as released only beside an overlapping leader (the fix of
    // 2026-12-03), keep A standing for good: the mutual wait never ends.
    for hold in [OrganizeHold::Always, OrganizeHold::LeaderAhead] {
        let (t_in, v_a) = mutual_wait(hold);
        assert_eq!(t_in, None, "{hold:?}: B moved in");
        assert!(v_a < 0.1, "{hold:?}: A drove on at {v_a} m/s");
    }
    // The narrow hold lets A go after `organize_hold_timeout_s` (10 s) below the creep speed;
    // B then moves in behind it.
    let (t_in, v_a) = mutual_wait(OrganizeHold::Narrow);
    let t_in = t_in.expect("the narrow hold: B never moved in");
    assert!((10.0..25.0).contains(&t_in), "B moved in at {t_in} s");
    assert!(v_a > 2.0, "A reached only {v_a} m/s");
}
