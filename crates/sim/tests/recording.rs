//! Trip and trajectory records (`record.rs`): they agree with the summary and the detectors,
//! they describe what the vehicles did, and recording does not change the simulation.

use platoonsim_sim::vehicle::{Kind, ModeLabel};
use platoonsim_sim::{
    run, run_recording, Config, DetectorKind, DetectorSpec, LaneExtent, Network, OffRamp, OnRamp,
    Output, Recording, SimError, Simulation, TrajectorySpec, Trip, TripStatus,
};
use std::collections::HashMap;

fn trips_only() -> Recording {
    Recording {
        trips: true,
        trajectories: None,
    }
}

fn without_wall(mut o: Output) -> Output {
    o.summary.wall_seconds = 0.0;
    o
}

/// 3 km, two through lanes (indices 1-2); on-ramp A merges at 800 m through a 250 m
/// acceleration lane (index 0); off-ramp F at 2,000 m takes 20 % of the mainline arrivals.
/// Output coordinate = engine x − 500.
fn small_corridor(seed: u64) -> Config {
    let mut cfg = Config::homogeneous(0.5, 0.0, 900.0, 300.0, seed);
    cfg.name = "small-corridor".into();
    cfg.road.lanes = 3;
    cfg.road.length_m = 3000.0;
    cfg.road.control_start_m = 0.0;
    cfg.road.control_end_m = 3000.0;
    cfg.road.network = Some(Network {
        origin_m: -500.0,
        through_lanes: (1..=2)
            .map(|lane| LaneExtent {
                lane,
                from_m: 0.0,
                to_m: 3000.0,
            })
            .collect(),
        on_ramps: vec![OnRamp {
            name: "A".into(),
            x_m: 800.0,
            accel_lane_m: 250.0,
            ramp_length_m: 300.0,
            demand_vph: vec![400.0],
            meter: None,
            penetration: None,
        }],
        off_ramps: vec![OffRamp {
            name: "F".into(),
            x_m: 2000.0,
            exit_fraction: vec![0.2],
        }],
        interval_s: 900.0,
        mainline_vph: vec![2400.0],
        demand_scale: 1.0,
        ramp_speed_kmh: 90.0,
        lane_speed_limits_kmh: Vec::new(),
        cross_lane_friction: None,
        behaviour: Vec::new(),
    });
    cfg.detectors = vec![
        DetectorSpec::mainline("A-up", 750.0),
        DetectorSpec {
            name: "end".into(),
            position_m: 2990.0,
            kind: DetectorKind::Mainline,
            exit: true,
        },
        DetectorSpec {
            name: "F-off".into(),
            position_m: 2000.0,
            kind: DetectorKind::OffRamp { ramp: 0 },
            exit: true,
        },
    ];
    cfg.measurement_detector = 1;
    cfg
}

/// The trips agree with the summary's counts and statistics, exactly.
fn assert_trips_match_the_summary(out: &Output) {
    let s = &out.summary;
    let trips = out.trips.as_ref().expect("trips recorded");
    assert_eq!(trips.len() as u64, s.vehicles_entered);
    let mut ids: Vec<u64> = trips.iter().map(|t| t.id).collect();
    ids.sort_unstable();
    ids.dedup();
    assert_eq!(ids.len(), trips.len(), "a vehicle has two trips");
    let on_road = trips
        .iter()
        .filter(|t| t.status == TripStatus::InNetwork)
        .count() as u64;
    assert_eq!(on_road, s.vehicles_in_network);
    assert_eq!(trips.len() as u64 - on_road, s.vehicles_exited);

    let measured: Vec<&Trip> = trips.iter().filter(|t| t.measured).collect();
    assert_eq!(measured.len() as u64, s.vehicles_counted);
    let lane_changes: u64 = measured.iter().map(|t| t.lane_changes as u64).sum();
    assert!(lane_changes > 0);
    let n = s.vehicles_counted as f64;
    assert_eq!(
        lane_changes,
        (s.lane_changes_per_vehicle.unwrap() * n).round() as u64
    );
    assert_eq!(lane_changes as f64 / n, s.lane_changes_per_vehicle.unwrap());

    let cavs: Vec<&Trip> = measured
        .iter()
        .copied()
        .filter(|t| t.kind == Kind::Cav)
        .collect();
    assert_eq!(cavs.len() as u64, s.cavs_counted);
    let n = cavs.len() as f64;
    let sum = |f: fn(&Trip) -> u32| cavs.iter().map(|t| f(t) as u64).sum::<u64>() as f64;
    assert_eq!(sum(|t| t.max_platoon) / n, s.avg_platoon_length.unwrap());
    assert_eq!(
        sum(|t| t.max_platoon_tg2) / n,
        s.avg_platoon_length_tg2.unwrap()
    );
    let platooned = cavs.iter().filter(|t| t.max_platoon > 1).count() as f64;
    assert_eq!(platooned / n, s.platooning_probability.unwrap());
    let cav_lc: u64 = cavs.iter().map(|t| t.lane_changes as u64).sum();
    assert_eq!(cav_lc as f64 / n, s.lane_changes_per_cav.unwrap());
    // Humans never platoon.
    assert!(trips
        .iter()
        .filter(|t| t.kind == Kind::Human)
        .all(|t| t.max_platoon == 1 && t.max_platoon_tg2 == 1));

    for t in trips {
        assert!(t.entered_s > 0.0 && t.entered_s <= s.duration_s, "{t:?}");
        assert_eq!(t.measured, t.entered_s >= s.warmup_s, "{t:?}");
        match (t.left_s, t.travel_time_s) {
            (Some(left), Some(tt)) => {
                assert_ne!(t.status, TripStatus::InNetwork);
                assert!(left <= s.duration_s + 1e-9, "{t:?}");
                assert!(tt > 0.0, "{t:?}");
                assert!((tt - (left - t.entered_s)).abs() < 1e-9, "{t:?}");
            }
            (None, None) => assert_eq!(t.status, TripStatus::InNetwork),
            _ => panic!("left_s and travel_time_s disagree: {t:?}"),
        }
        assert!(t.last_x_m >= t.entry_x_m, "{t:?}");
        // Inserted at the end of a step, never before its arrival at the entrance.
        assert!(
            t.depart_delay_s >= 0.0 && t.depart_delay_s <= t.entered_s,
            "{t:?}"
        );
    }
}

#[test]
fn an_overloaded_entrance_makes_vehicles_wait_to_depart() {
    // 1,000 veh/h/lane enters at once; 4,500 veh/h/lane (above capacity) queues at the entrance,
    // and the wait grows along the run as the queue does.
    let delays = |demand: f64| {
        let cfg = Config::homogeneous(0.0, demand, 600.0, 0.0, 3);
        let out = run_recording(&cfg, &trips_only(), None).unwrap();
        let trips = out.trips.unwrap();
        let mean = |ts: &[&platoonsim_sim::Trip]| {
            ts.iter().map(|t| t.depart_delay_s).sum::<f64>() / ts.len() as f64
        };
        let early: Vec<_> = trips.iter().filter(|t| t.entered_s < 200.0).collect();
        let late: Vec<_> = trips.iter().filter(|t| t.entered_s >= 400.0).collect();
        (mean(&early), mean(&late), out.summary.vehicles_waiting)
    };
    let (early, late, waiting) = delays(1000.0);
    assert!(
        early < 0.5 && late < 0.5 && waiting < 5,
        "{early} {late} {waiting}"
    );
    let (early, late, waiting) = delays(4500.0);
    assert!(waiting > 100, "{waiting}");
    assert!(late > 60.0 && late > 3.0 * early, "{early} {late}");
}

#[test]
fn homogeneous_trips_add_up_to_the_summary() {
    let cfg = Config::homogeneous(0.5, 2200.0, 900.0, 300.0, 5);
    let out = run_recording(&cfg, &trips_only(), None).unwrap();
    assert_trips_match_the_summary(&out);
    let trips = out.trips.as_ref().unwrap();
    for t in trips {
        assert_eq!(t.origin, 0);
        assert_eq!(t.entry_x_m, 0.0);
        match t.status {
            // A vehicle leaves in the step its front reaches the end.
            TripStatus::Exited { off_ramp: None } => {
                assert!(t.last_x_m >= 6500.0 && t.last_x_m < 6505.0, "{t:?}")
            }
            TripStatus::InNetwork => assert!(t.last_x_m < 6500.0, "{t:?}"),
            other => panic!("no off-ramps on this road: {other:?}"),
        }
    }
    // Free-flow travel over 6.5 km takes a few minutes.
    let tt: Vec<f64> = trips.iter().filter_map(|t| t.travel_time_s).collect();
    assert!(!tt.is_empty());
    assert!(tt.iter().all(|&t| (150.0..900.0).contains(&t)), "{tt:?}");
    // Trips are listed in the order they left, then the vehicles on the road by id.
    let left: Vec<f64> = trips.iter().filter_map(|t| t.left_s).collect();
    assert!(left.windows(2).all(|w| w[0] <= w[1]));
    let inside: Vec<u64> = trips
        .iter()
        .filter(|t| t.left_s.is_none())
        .map(|t| t.id)
        .collect();
    assert!(inside.windows(2).all(|w| w[0] < w[1]));
    assert!(trips[..trips.len() - inside.len()]
        .iter()
        .all(|t| t.left_s.is_some()));
}

#[test]
fn corridor_trips_match_the_exit_detectors() {
    let cfg = small_corridor(2);
    let out = run_recording(&cfg, &trips_only(), None).unwrap();
    assert_trips_match_the_summary(&out);
    let trips = out.trips.as_ref().unwrap();
    let count = |det: &str| -> u64 {
        out.detectors
            .iter()
            .filter(|r| r.detector == det && r.lane == "all")
            .map(|r| r.count)
            .sum()
    };
    let by_ramp = trips
        .iter()
        .filter(|t| t.status == TripStatus::Exited { off_ramp: Some(0) })
        .count() as u64;
    assert!(by_ramp > 20, "{by_ramp} took F");
    assert_eq!(by_ramp, count("F-off"));
    let missed = trips
        .iter()
        .filter(|t| matches!(t.status, TripStatus::MissedExitThenEnd { missed: 0 }))
        .count() as u64;
    assert!(missed <= out.summary.missed_exits);
    // Both entrances are used; an entry position is its entrance's, in the output coordinate.
    let mut per_origin: HashMap<usize, u64> = HashMap::new();
    for t in trips {
        *per_origin.entry(t.origin).or_default() += 1;
        let entry = [-500.0, 300.0][t.origin];
        assert_eq!(t.entry_x_m, entry, "{t:?}");
        match t.status {
            TripStatus::Exited { off_ramp: Some(0) } => {
                assert!(t.last_x_m >= 1500.0 && t.last_x_m < 1505.0, "{t:?}")
            }
            TripStatus::Exited { off_ramp: None } | TripStatus::MissedExitThenEnd { .. } => {
                assert!(t.last_x_m >= 2500.0 && t.last_x_m < 2505.0, "{t:?}")
            }
            TripStatus::InNetwork => assert!(t.last_x_m < 2500.0, "{t:?}"),
            TripStatus::Exited { off_ramp: Some(r) } => panic!("no off-ramp {r}"),
            TripStatus::Collided => panic!("a collision: {t:?}"),
        }
    }
    assert!(
        per_origin[&0] > 300 && per_origin[&1] > 40,
        "{per_origin:?}"
    );
}

#[test]
fn recording_does_not_change_the_simulation() {
    let all = Recording {
        trips: true,
        trajectories: Some(TrajectorySpec {
            period_s: 0.5,
            window_s: None,
            x_m: None,
        }),
    };
    for cfg in [
        Config::homogeneous(0.5, 2500.0, 600.0, 200.0, 9).with_pd(),
        small_corridor(9),
    ] {
        let plain = without_wall(run(&cfg, None).unwrap());
        let recorded = without_wall(run_recording(&cfg, &all, None).unwrap());
        assert_eq!(plain.trips, None);
        assert_eq!(plain.trajectories, None);
        assert!(!recorded.trips.as_ref().unwrap().is_empty());
        assert!(!recorded.trajectories.as_ref().unwrap().is_empty());
        assert_eq!(plain.summary, recorded.summary);
        assert_eq!(plain.detectors, recorded.detectors);
    }
}

#[test]
fn records_are_deterministic() {
    let rec = Recording {
        trips: true,
        trajectories: Some(TrajectorySpec {
            period_s: 2.0,
            window_s: Some((100.0, 400.0)),
            x_m: Some((0.0, 2000.0)),
        }),
    };
    let a = without_wall(run_recording(&small_corridor(4), &rec, None).unwrap());
    let b = without_wall(run_recording(&small_corridor(4), &rec, None).unwrap());
    assert_eq!(a, b);
    let c = without_wall(run_recording(&small_corridor(5), &rec, None).unwrap());
    assert_ne!(a.trips, c.trips);
}

#[test]
fn trajectories_sample_the_road_at_the_period_inside_the_windows() {
    let cfg = small_corridor(3);
    let (t0, t1, x0, x1) = (100.0, 300.0, 0.0, 1800.0);
    let rec = Recording {
        trips: false,
        trajectories: Some(TrajectorySpec {
            period_s: 1.5,
            window_s: Some((t0, t1)),
            x_m: Some((x0, x1)),
        }),
    };
    let out = run_recording(&cfg, &rec, None).unwrap();
    assert_eq!(out.trips, None);
    let rows = out.trajectories.unwrap();
    // Sample times: the multiples of 1.5 s in [100, 300]: 100.5, 102, ..., 300.
    let mut times: Vec<f64> = rows.iter().map(|r| r.t_s).collect();
    times.dedup();
    let expected: Vec<f64> = (67..=200).map(|k| k as f64 * 1.5).collect();
    assert_eq!(times, expected);
    let mut last: HashMap<u64, (f64, f64)> = HashMap::new();
    for r in &rows {
        assert!(r.x_m >= x0 && r.x_m <= x1, "{r:?}");
        assert!(r.v_mps >= 0.0 && r.v_mps.is_finite(), "{r:?}");
        assert!(r.a_mps2.is_finite(), "{r:?}");
        assert!(r.lane < cfg.road.lanes, "{r:?}");
        // Acceleration-lane rows (index 0) lie on the acceleration lane, 300-550 m.
        if r.lane == 0 {
            assert!(r.x_m >= 300.0 && r.x_m <= 550.0, "{r:?}");
        }
        if r.kind == Kind::Human {
            assert!(!r.mode.automated(), "{r:?}");
        }
        if let Some(&(t, x)) = last.get(&r.id) {
            assert!(r.t_s > t, "{r:?}");
            assert!(r.x_m >= x, "{r:?} after x = {x}");
        }
        last.insert(r.id, (r.t_s, r.x_m));
    }
    assert!(rows.iter().any(|r| r.mode.automated()));
    assert!(rows.iter().any(|r| r.mode == ModeLabel::Blc));
    assert!(rows.iter().any(|r| r.lane == 0));

    // Each sample holds exactly the vehicles on the road inside the x window then.
    let mut sim = Simulation::new(cfg).unwrap();
    let origin = -500.0;
    while sim.time_s() < 201.0 - 1e-9 {
        sim.step().unwrap();
    }
    let mut on_road: Vec<(u64, u32, f64, f64)> = (0..3)
        .flat_map(|l| sim.lane_vehicles(l).collect::<Vec<_>>())
        .filter(|v| v.x() + origin >= x0 && v.x() + origin <= x1)
        .map(|v| (v.id(), v.lane(), v.x() + origin, v.v()))
        .collect();
    on_road.sort_by_key(|r| r.0);
    let sampled: Vec<(u64, u32, f64, f64)> = rows
        .iter()
        .filter(|r| r.t_s == 201.0)
        .map(|r| (r.id, r.lane, r.x_m, r.v_mps))
        .collect();
    assert!(sampled.len() > 10);
    assert_eq!(sampled, on_road);
}

#[test]
fn recording_requests_are_checked() {
    let cfg = Config::homogeneous(0.5, 1000.0, 60.0, 0.0, 1);
    let traj = |period_s: f64, window_s, x_m| Recording {
        trips: false,
        trajectories: Some(TrajectorySpec {
            period_s,
            window_s,
            x_m,
        }),
    };
    for (bad, field) in [
        (traj(0.0, None, None), "trajectories.period_s = 0"),
        (traj(0.15, None, None), "trajectories.period_s = 0.15"),
        (traj(f64::NAN, None, None), "trajectories.period_s = NaN"),
        (traj(1.0, Some((5.0, 1.0)), None), "trajectories.window_s"),
        (traj(1.0, Some((-1.0, 1.0)), None), "trajectories.window_s"),
        (traj(1.0, None, Some((10.0, 10.0))), "trajectories.x_m"),
    ] {
        let err = run_recording(&cfg, &bad, None).unwrap_err();
        assert!(
            matches!(&err, SimError::Recording(m) if m.contains(field)),
            "{err}"
        );
    }
    let mut sim = Simulation::new(cfg.clone()).unwrap();
    sim.step().unwrap();
    assert!(matches!(
        sim.record(&trips_only()),
        Err(SimError::AfterFirstStep(_))
    ));
    // A period of 0.3 s is three steps.
    let out = run_recording(&cfg, &traj(0.3, Some((30.0, 31.0)), None), None).unwrap();
    let mut times: Vec<f64> = out.trajectories.unwrap().iter().map(|r| r.t_s).collect();
    times.dedup();
    assert_eq!(times, [30.0, 30.3, 30.6, 30.9]);
}

#[test]
fn vehicles_still_queued_at_the_end_are_recorded_with_their_wait_so_far() {
    // (queued records, vehicles waiting when the run ended, the end time) at a demand.
    let queued_at = |demand: f64| {
        let cfg = Config::homogeneous(0.5, demand, 600.0, 0.0, 3);
        let mut sim = Simulation::new(cfg).unwrap();
        sim.record(&trips_only()).unwrap();
        while !sim.finished() {
            sim.step().unwrap();
        }
        let (waiting, end_s) = (sim.vehicles_waiting(), sim.time_s());
        let out = sim.finish(0.0);
        let entered = out.trips.as_ref().unwrap();
        (out.queued.clone().unwrap(), waiting, end_s, entered.len())
    };
    // Above capacity: a queue that the records list vehicle by vehicle, each with the time
    // from its arrival to the end of the run.
    let (queued, waiting, end_s, entered) = queued_at(4500.0);
    assert!(waiting > 100, "{waiting}");
    assert_eq!(queued.len(), waiting);
    assert!(queued.windows(2).all(|w| w[0].id < w[1].id));
    for q in &queued {
        assert!(q.depart_delay_s > 0.0, "{q:?}");
        assert_eq!(q.depart_delay_s, end_s - q.arrived_s, "{q:?}");
        assert_eq!(q.origin, 0, "{q:?}");
    }
    // Ids are dense: the vehicles that entered and those queued are every arrival.
    assert_eq!(
        entered + queued.len(),
        queued.last().unwrap().id as usize + 1
    );
    // First come, first served: the oldest still queued has waited more than a minute.
    assert!(queued[0].depart_delay_s > 60.0, "{:?}", queued[0]);
    // Light traffic: nobody is left waiting, and there are no queued records.
    let (queued, waiting, _, _) = queued_at(1000.0);
    assert_eq!((queued.len(), waiting), (0, 0));
}
