//! CACC strings (platoons): joining, and the size limit that splits a string.

use super::common::{at, empty, empty_config, gap, run};
use platoonsim_sim::vehicle::Kind;
use platoonsim_sim::{Command, Simulation};

#[test]
fn a_cav_behind_a_cav_closes_to_its_cacc_time_gap() {
    let mut sim = empty(1);
    let lead = sim.place_vehicle(Kind::Cav, 0, 1500.0, 25.0).unwrap();
    sim.command(lead, Command::DesiredSpeed { speed_mps: 25.0 })
        .unwrap();
    let follow = sim.place_vehicle(Kind::Cav, 0, 1350.0, 25.0).unwrap();
    run(&mut sim, 120.0, |_| {});
    let f = at(&sim, follow);
    // It joined the leader's string and follows at its own CACC gap t_C (the time gap of the
    // gap it keeps, bumper to bumper, at the common speed).
    assert_eq!(f.pred, Some(lead), "the follower is in the leader's string");
    let t = gap(&sim, lead, follow) / f.v;
    assert!(
        (t - f.t_c).abs() < 0.1,
        "time gap {t:.3} s against t_C {:.3} s",
        f.t_c
    );
    assert!((f.v - 25.0).abs() < 0.1, "speed {}", f.v);
}

/// Time gap (s) from `follower` to `leader` at the follower's speed.
fn time_gap(sim: &Simulation, leader: u64, follower: u64) -> f64 {
    gap(sim, leader, follower) / at(sim, follower).v
}

#[test]
fn a_string_at_its_size_limit_leaves_the_next_cav_at_the_inter_platoon_gap() {
    // `cav.max_platoon` = 3 and four CAVs in a row (the leader set to 25 m/s, the others to
    // 30 m/s, so that they can close up: a CAV at its set speed never closes a gap): the second and third join the first at
    // their own t_C; the fourth would make the string four long, so it leads a string of its
    // own and keeps the inter-platoon gap (1.5 s) behind the third.
    let mut cfg = empty_config(1);
    cfg.cav.max_platoon = 3;
    let mut sim = Simulation::new(cfg).unwrap();
    let ids: Vec<u64> = (0..4)
        .map(|k| {
            let id = sim
                .place_vehicle(Kind::Cav, 0, 3000.0 - 40.0 * k as f64, 25.0)
                .unwrap();
            let set = if k == 0 { 25.0 } else { 30.0 };
            sim.command(id, Command::DesiredSpeed { speed_mps: set })
                .unwrap();
            id
        })
        .collect();
    run(&mut sim, 120.0, |_| {});
    for k in 1..3 {
        let (t, t_c) = (time_gap(&sim, ids[k - 1], ids[k]), at(&sim, ids[k]).t_c);
        assert!(
            (t - t_c).abs() < 0.1,
            "member {k}: {t:.3} s against t_C {t_c:.3} s"
        );
    }
    let t = time_gap(&sim, ids[2], ids[3]);
    assert!((t - 1.5).abs() < 0.1, "the fourth follows at {t:.3} s");
    assert_eq!(
        at(&sim, ids[3]).pred,
        None,
        "the fourth joined a full string"
    );
    assert_eq!(sim.collisions(), 0);
}
