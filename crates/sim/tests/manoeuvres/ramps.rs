//! The corridor's fixed geometry: merging from an acceleration lane, leaving for an
//! off-ramp, a lane drop.

use super::common::{at, corridor, run, seen};
use platoonsim_sim::vehicle::Kind;

#[test]
fn a_driver_on_an_acceleration_lane_merges_before_its_end() {
    // On-ramp at 1,000 m with a 200 m acceleration lane (lane 0); a driver enters it at
    // 20 m/s beside a mainline driver at the same speed in lane 1. It finds a gap and moves
    // to the mainline before the lane ends at 1,200 m; it is never past the end in lane 0.
    let mut sim = corridor(2, &[], Some((1000.0, 200.0)), None);
    let merger = sim.place_vehicle(Kind::Human, 0, 1010.0, 20.0).unwrap();
    let beside = sim.place_vehicle(Kind::Human, 1, 1012.0, 20.0).unwrap();
    sim.command(
        beside,
        platoonsim_sim::Command::DesiredSpeed { speed_mps: 20.0 },
    )
    .unwrap();
    let (mut merged_at, mut past_end) = (None, false);
    run(&mut sim, 30.0, |s| {
        let m = at(s, merger);
        past_end |= m.lane == 0 && m.x > 1200.0;
        if merged_at.is_none() && m.lane == 1 {
            merged_at = Some(m.x);
        }
    });
    let x = merged_at.expect("never left the acceleration lane");
    assert!(x <= 1200.0, "merged at {x} m");
    assert!(!past_end, "drove past the end of the acceleration lane");
    assert_eq!(sim.collisions(), 0);
}

#[test]
fn a_driver_bound_for_an_off_ramp_reaches_the_right_lane_and_leaves() {
    // Three through lanes (1-3), a diverge at 3,000 m that every placed vehicle takes; a
    // driver starts in the leftmost lane at 500 m. It makes its mandatory changes to the
    // rightmost through lane before the diverge and leaves the road there.
    let mut sim = corridor(3, &[], None, Some(3000.0));
    let id = sim.place_vehicle(Kind::Human, 3, 500.0, 28.0).unwrap();
    let (mut last, mut lanes) = (at(&sim, id), vec![3]);
    run(&mut sim, 150.0, |s| {
        if let Some(v) = seen(s, id) {
            if v.lane != *lanes.last().unwrap() {
                lanes.push(v.lane);
            }
            last = v;
        }
    });
    assert!(
        seen(&sim, id).is_none(),
        "still on the road at {} m",
        last.x
    );
    assert_eq!(lanes, vec![3, 2, 1], "lanes on the way");
    assert_eq!(last.lane, 1, "left from lane {}", last.lane);
    assert!(
        last.x > 2900.0 && last.x <= 3000.0,
        "last seen at {} m",
        last.x
    );
    assert_eq!(sim.collisions(), 0);
}

#[test]
fn a_driver_in_a_dropped_lane_leaves_it_before_it_ends() {
    // Two through lanes; the left one (lane 2) ends at 2,000 m. A driver in it at 500 m moves
    // right before the end and is never in lane 2 past it.
    let mut sim = corridor(2, &[(2, 2000.0)], None, None);
    let id = sim.place_vehicle(Kind::Human, 2, 500.0, 28.0).unwrap();
    let (mut moved_at, mut past_end) = (None, false);
    run(&mut sim, 80.0, |s| {
        let v = at(s, id);
        past_end |= v.lane == 2 && v.x > 2000.0;
        if moved_at.is_none() && v.lane == 1 {
            moved_at = Some(v.x);
        }
    });
    let x = moved_at.expect("never left the dropped lane");
    assert!(x < 2000.0, "moved at {x} m");
    assert!(!past_end, "drove past the end of its lane");
    assert_eq!(sim.collisions(), 0);
}
