//! Cooperative lane changes of automated CAVs (spec 9.2, `cav.cooperative_lane_change`), in
//! hand-placed situations on the homogeneous road without demand: the requester asks the
//! automated CAV that follows it in the target lane, which opens the gap at no more than the
//! cooperative deceleration; the change is made under automation and the joiner ends in the
//! string. A human-driven follower is never asked; two CAVs that want each other's lane do not
//! wait for each other.

use platoonsim_sim::vehicle::Mode;
use platoonsim_sim::{
    Advice, Config, Event, Kind, LaneChangeReason, Observer, Organizer, Simulation, VehicleView,
};
use std::sync::{Arc, Mutex};

/// The homogeneous road, no arrivals, PD in the control section (km 5-6) from t = 0.
fn road(coop: bool) -> Config {
    let mut cfg = Config::homogeneous(0.5, 0.0, 120.0, 0.0, 1).with_pd();
    cfg.cav.cooperative_lane_change = coop;
    cfg
}

/// The lane changes of a run: (id, reason, cooperative).
#[derive(Default)]
struct Changes(Arc<Mutex<Vec<(u64, LaneChangeReason, bool)>>>);

impl Observer for Changes {
    fn on_step(&mut self, step: &platoonsim_sim::StepView<'_>) {
        for e in step.events() {
            if let Event::LaneChange {
                id,
                reason,
                cooperative,
                ..
            } = *e
            {
                self.0.lock().unwrap().push((id, reason, cooperative));
            }
        }
    }
}

/// A CACC string in the PD lane (lane 2): leader at `x`, then followers 33 m apart (room for
/// the longest t_C at 25 m/s), all at 25 m/s; returns their ids, front first.
fn string(sim: &mut Simulation, x: f64, kinds: &[Kind]) -> Vec<u64> {
    kinds
        .iter()
        .enumerate()
        .map(|(i, &k)| sim.place_vehicle(k, 2, x - 33.0 * i as f64, 25.0).unwrap())
        .collect()
}

fn v(sim: &Simulation, id: u64) -> VehicleView<'_> {
    sim.vehicle(id).expect("on the road")
}

/// The situation: a string L, F, G in the PD lane and a CAV R in lane 1 alongside F (its
/// front 3 m ahead of F's, so F is its target-lane follower and the lag gap overlaps).
struct Run {
    sim: Simulation,
    log: Arc<Mutex<Vec<(u64, LaneChangeReason, bool)>>>,
    ids: Vec<u64>,
    r: u64,
}

fn situation(coop: bool, follower: Kind) -> Run {
    let mut sim = Simulation::new(road(coop)).unwrap();
    let ids = string(&mut sim, 5400.0, &[Kind::Cav, follower, Kind::Cav]);
    let r = sim.place_vehicle(Kind::Cav, 1, 5370.0, 25.0).unwrap();
    let changes = Changes::default();
    let log = changes.0.clone();
    sim.observe(Box::new(changes)).unwrap();
    Run { sim, log, ids, r }
}

#[test]
fn a_cav_follower_opens_a_gap_gently_and_the_joiner_changes_under_automation() {
    let Run {
        mut sim,
        log,
        ids,
        r,
    } = situation(true, Kind::Cav);
    let (l, f) = (ids[0], ids[1]);
    let mut asked = false;
    let mut hardest_f = 0.0f64;
    let mut changed_at = None;
    let mut in_string = false;
    for k in 0..300 {
        sim.step().unwrap();
        if changed_at.is_none() && !log.lock().unwrap().is_empty() {
            changed_at = Some(k);
        }
        // Two seconds after the change, the joiner is in the string, between L and F (later
        // L, faster, drives away at its own desired speed).
        if changed_at.is_some_and(|c| k == c + 20) {
            let (rv, fv) = (v(&sim, r), v(&sim, f));
            assert_eq!(rv.lane(), 2);
            assert_eq!(rv.joined(), Some(l), "the joiner follows L in its string");
            assert_eq!(fv.joined(), Some(r), "the string forms behind the joiner");
            in_string = true;
        }
        let rv = v(&sim, r);
        assert!(
            rv.automated(),
            "the requester never hands over: {:?}",
            rv.mode()
        );
        assert!(!rv.relaxing());
        let fv = v(&sim, f);
        assert!(
            fv.automated(),
            "the follower opens the gap under automation"
        );
        if matches!(fv.mode(), Mode::Ycf { to, coop: true, auto: true } if to == r) {
            asked = true;
        }
        hardest_f = hardest_f.min(fv.a());
    }
    assert!(asked, "the CAV follower answered the request");
    let changes = log.lock().unwrap().clone();
    assert_eq!(
        changes,
        vec![(r, LaneChangeReason::Organizing, true)],
        "one cooperative change, the requester's"
    );
    assert!(
        hardest_f >= -2.0 - 1e-9,
        "the follower opened the gap at {hardest_f} m/s²"
    );
    assert!(in_string);
    assert_eq!(v(&sim, r).cooperative_lane_changes(), 1);
    assert_eq!(sim.collisions(), 0);
    let out = sim.finish(0.0);
    assert_eq!(out.summary.cooperative_lane_changes, 1);
}

#[test]
fn without_the_option_the_joiner_changes_by_hand_or_not_at_all() {
    let Run {
        mut sim, log, ids, ..
    } = situation(false, Kind::Cav);
    for _ in 0..300 {
        sim.step().unwrap();
        assert!(
            !matches!(v(&sim, ids[1]).mode(), Mode::Ycf { coop: true, .. }),
            "nobody opens a cooperative gap"
        );
    }
    assert!(log.lock().unwrap().iter().all(|c| !c.2));
    assert_eq!(sim.collisions(), 0);
}

#[test]
fn a_human_follower_is_never_asked() {
    let Run {
        mut sim,
        log,
        ids,
        r,
    } = situation(true, Kind::Human);
    let h = ids[1];
    for _ in 0..300 {
        sim.step().unwrap();
        assert!(
            !matches!(v(&sim, h).mode(), Mode::Ycf { coop: true, .. }),
            "the human driver opened a cooperative gap"
        );
        // No request is out: without a CAV follower the counter stays 0.
        if let Mode::Blc { ask, .. } = v(&sim, r).mode() {
            assert_eq!(ask, 0, "a request to a human driver");
        }
    }
    assert!(
        log.lock().unwrap().iter().all(|c| !c.2),
        "no cooperative change"
    );
    assert_eq!(sim.collisions(), 0);
}

/// Advises vehicle `a` to lane 1 and vehicle `b` to lane 0, everywhere.
#[derive(Debug)]
struct Swap {
    a: u64,
    b: u64,
}

impl Organizer for Swap {
    fn name(&self) -> &str {
        "swap"
    }
    fn advise(
        &self,
        v: VehicleView<'_>,
        _t_s: f64,
        _road: &platoonsim_sim::network::Geometry,
    ) -> Advice {
        let lane = if v.id() == self.a {
            1
        } else if v.id() == self.b {
            0
        } else {
            return Advice::Free;
        };
        Advice::Join {
            lane,
            strength: 1.0,
        }
    }
}

#[test]
fn two_cavs_that_want_each_others_lane_do_not_wait_for_each_other() {
    // A in lane 0 and B in lane 1, fronts level: each is the other's target-lane follower,
    // so each asks the other. A vehicle with a desire of its own never opens a gap, so neither
    // request is answered (the rule this test pins: a requester that answered would be in
    // YCF); the requests run into their timeout, the pair drifts apart at the drivers' own
    // speeds, and each changes once it has no CAV follower to ask or its request rests. (The
    // timeout cycle itself is pinned in `platoonsim_model::cooperative`.)
    let mut sim = Simulation::new(road(true)).unwrap();
    let a = sim.place_vehicle(Kind::Cav, 0, 1000.0, 25.0).unwrap();
    let b = sim.place_vehicle(Kind::Cav, 1, 1000.0, 25.0).unwrap();
    sim.set_organizer(Box::new(Swap { a, b })).unwrap();
    let changes = Changes::default();
    let log = changes.0.clone();
    sim.observe(Box::new(changes)).unwrap();
    let timeout = (sim.config().cav.cooperative_timeout_s / sim.config().dt_s).round() as u16;
    let mut timed_out = [false; 2];
    for _ in 0..900 {
        sim.step().unwrap();
        for (k, id) in [a, b].into_iter().enumerate() {
            let Some(x) = sim.vehicle(id) else { continue };
            assert!(
                !matches!(x.mode(), Mode::Ycf { .. }),
                "a requester answered a request"
            );
            if let Mode::Blc { ask, .. } = x.mode() {
                timed_out[k] |= ask > timeout;
            }
        }
        if log.lock().unwrap().len() == 2 {
            break;
        }
    }
    let changes = log.lock().unwrap().clone();
    let ids: Vec<u64> = changes.iter().map(|c| c.0).collect();
    assert!(
        ids.contains(&a) && ids.contains(&b),
        "both changed lanes: {changes:?}"
    );
    assert!(timed_out.iter().any(|&t| t), "a request timed out");
    assert_eq!(sim.collisions(), 0);
}
