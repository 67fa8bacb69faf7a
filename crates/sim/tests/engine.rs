//! Engine contracts: determinism, conservation, no overlap, no NaN, queueing at the entrance,
//! and two step sizes (issue 2, "What it must show").

use platoonsim_sim::{run, Config, Output, SimError, Simulation};

fn short(pen: f64, demand: f64, seed: u64) -> Config {
    Config::homogeneous(pen, demand, 900.0, 300.0, seed)
}

fn strip_wall(mut o: Output) -> Output {
    o.summary.wall_seconds = 0.0;
    o
}

#[test]
fn same_seed_gives_bit_identical_outputs_and_another_seed_differs() {
    let a = strip_wall(run(&short(0.5, 2000.0, 7), None).unwrap());
    let b = strip_wall(run(&short(0.5, 2000.0, 7), None).unwrap());
    assert_eq!(a.summary, b.summary);
    assert_eq!(a.detectors, b.detectors);
    // Bit-identical floating point, not just equal within a tolerance.
    let bits = |o: &Output| -> Vec<u64> {
        o.detectors
            .iter()
            .filter_map(|r| r.speed_kmh.map(f64::to_bits))
            .collect()
    };
    assert_eq!(bits(&a), bits(&b));
    let c = strip_wall(run(&short(0.5, 2000.0, 8), None).unwrap());
    assert_ne!(a.summary.vehicles_entered, 0);
    assert_ne!(a.detectors, c.detectors);
    assert_ne!(a.summary.vehicle_updates, c.summary.vehicle_updates);
}

#[test]
fn vehicles_are_conserved_and_never_overlap() {
    for (pen, demand, strategy) in [
        (0.0, 2600.0, false),
        (0.5, 1500.0, false),
        (1.0, 4500.0, false),
        (0.5, 2500.0, true),
    ] {
        let mut cfg = Config::homogeneous(pen, demand, 1800.0, 600.0, 3);
        if strategy {
            cfg = cfg.with_pd();
        }
        let s = run(&cfg, None).unwrap().summary;
        assert_eq!(
            s.vehicles_entered,
            s.vehicles_exited + s.vehicles_in_network,
            "{pen} {demand}"
        );
        assert_eq!(s.collisions, 0, "overlap at {pen} {demand} pd={strategy}");
        assert!(s.vehicles_exited > 0);
        // Statistics over CAVs do not apply without CAVs (null, not 0), and the human one
        // not without humans.
        let cavs = [
            s.lane_changes_per_cav,
            s.avg_platoon_length,
            s.platooning_probability,
            s.avg_platoon_length_tg2,
            s.platooning_probability_tg2,
        ];
        assert_eq!(s.cavs_counted == 0, pen == 0.0);
        for x in cavs {
            assert_eq!(x.is_none(), pen == 0.0, "{pen} {demand}: {x:?}");
        }
        assert_eq!(s.lane_changes_per_human.is_none(), pen == 1.0);
        for x in [s.lane_changes_per_vehicle.unwrap(), s.discharge_flow_vphpl] {
            assert!(x.is_finite());
        }
        for x in cavs.into_iter().flatten() {
            assert!(x.is_finite());
        }
    }
}

#[test]
fn every_step_keeps_lanes_sorted_with_positive_gaps_and_finite_states() {
    let mut sim = Simulation::new(Config::homogeneous(0.5, 2500.0, 600.0, 0.0, 11)).unwrap();
    while !sim.finished() {
        sim.step().unwrap();
        for lane in 0..3 {
            let mut ahead: Option<(f64, f64)> = None;
            for v in sim.lane_vehicles(lane) {
                assert!(v.x().is_finite() && v.v().is_finite() && v.a().is_finite());
                assert!(v.v() >= 0.0, "negative speed {}", v.v());
                if let Some((x, len)) = ahead {
                    assert!(
                        x - len - v.x() >= 0.0,
                        "overlap behind x = {x} at t = {}",
                        sim.time_s()
                    );
                }
                ahead = Some((v.x(), v.length_m()));
            }
        }
    }
    assert_eq!(sim.collisions(), 0);
}

#[test]
fn demand_above_capacity_builds_an_entry_queue_instead_of_losing_vehicles() {
    let s = run(&Config::homogeneous(0.0, 3000.0, 1200.0, 0.0, 1), None)
        .unwrap()
        .summary;
    assert!(s.vehicles_waiting > 300, "queue {}", s.vehicles_waiting);
    // About 3 lanes × 3000 veh/h × 1/3 h = 3000 arrivals: all are either on the road, gone, or queued.
    let arrivals = s.vehicles_entered + s.vehicles_waiting;
    assert!((2800..3200).contains(&arrivals), "{arrivals}");
    // Below capacity nobody waits at the end.
    let s = run(&Config::homogeneous(0.5, 1000.0, 900.0, 0.0, 1), None)
        .unwrap()
        .summary;
    assert!(s.vehicles_waiting < 5, "{}", s.vehicles_waiting);
}

#[test]
fn half_the_step_gives_the_same_traffic() {
    let mut fine = Config::homogeneous(0.5, 1500.0, 1800.0, 600.0, 5);
    fine.dt_s = 0.05;
    let coarse = run(&Config::homogeneous(0.5, 1500.0, 1800.0, 600.0, 5), None)
        .unwrap()
        .summary;
    let fine = run(&fine, None).unwrap().summary;
    assert_eq!(fine.collisions, 0);
    assert_eq!(fine.steps, 2 * coarse.steps);
    // Same arrivals (same streams), same free-flow discharge within 2 %.
    assert_eq!(
        fine.vehicles_entered + fine.vehicles_waiting,
        coarse.vehicles_entered + coarse.vehicles_waiting
    );
    let rel = (fine.discharge_flow_vphpl - coarse.discharge_flow_vphpl).abs()
        / coarse.discharge_flow_vphpl;
    assert!(
        rel < 0.02,
        "{} vs {}",
        fine.discharge_flow_vphpl,
        coarse.discharge_flow_vphpl
    );
    assert!(
        (fine.platooning_probability.unwrap() - coarse.platooning_probability.unwrap()).abs()
            < 0.05
    );
}

#[test]
fn invalid_config_is_an_error_not_a_panic() {
    let mut cfg = short(0.5, 1000.0, 1);
    cfg.penetration = 1.5;
    assert!(matches!(
        Simulation::new(cfg),
        Err(SimError::Config(m)) if m.contains("run.penetration = 1.5")
    ));
    let mut cfg = short(0.5, 1000.0, 1);
    cfg.detectors[0].position_m = 9000.0;
    assert!(matches!(
        Simulation::new(cfg),
        Err(SimError::Config(m)) if m.contains("detectors[0].position_m")
    ));
}

#[test]
fn cavs_that_let_joiners_in_fill_the_pd_lane_faster() {
    // `cav.yield_to_organizers` [D]: automated CAVs yield to a CAV that moves toward the PD
    // lane, so more organizing CAVs get in: more lane changes and longer platoons (this seed:
    // 0.17 → 0.31 lane changes per vehicle, L̄ 3.98 → 4.80; seeds 1-5 at 2,000 veh/h/lane,
    // 50 % CAV, with `organize_while_automated`: L̄ 4.07 → 5.42 and a discharge change against
    // the baseline of -0.1 → -5.0 %, at 2,500 -13.6 → -22.3 %). Off by default.
    let mut cfg = Config::homogeneous(0.5, 2000.0, 3600.0, 1200.0, 1).with_pd();
    let off = run(&cfg, None).unwrap().summary;
    cfg.cav.yield_to_organizers = true;
    let on = run(&cfg, None).unwrap().summary;
    eprintln!(
        "LC/veh {:.3} -> {:.3}, L {:.2} -> {:.2}, Q {:.0} -> {:.0}",
        off.lane_changes_per_vehicle.unwrap(),
        on.lane_changes_per_vehicle.unwrap(),
        off.avg_platoon_length.unwrap(),
        on.avg_platoon_length.unwrap(),
        off.discharge_flow_vphpl,
        on.discharge_flow_vphpl
    );
    assert_eq!(on.collisions, 0);
    assert!(on.lane_changes_per_vehicle.unwrap() > 1.1 * off.lane_changes_per_vehicle.unwrap());
    assert!(on.avg_platoon_length.unwrap() > off.avg_platoon_length.unwrap());
}

#[test]
fn cavs_that_wait_for_a_pd_gap_automated_cost_less_capacity() {
    // `cav.organize_while_automated` [D]: under the PATH rule (spec 3.1) a CAV outside the PD
    // lane is in manual mode for as long as it looks for a gap, so PD turns the CACC strings of
    // the other lanes into human traffic; with the flag the automation stays on until both
    // gaps are acceptable. Seeds 1-5, 50 % CAV, 2,500 veh/h/lane (docs/model-choices.md 6.20):
    // discharge change against the baseline -21 % under the PATH rule, -14 % with the flag
    // (paper Table 3: -9.5 %).
    let mut cfg = Config::homogeneous(0.5, 2500.0, 3600.0, 1200.0, 2).with_pd();
    let waiting = run(&cfg, None).unwrap().summary;
    cfg.cav.organize_while_automated = false;
    let manual = run(&cfg, None).unwrap().summary;
    eprintln!(
        "Q {:.0} -> {:.0}, LC/veh {:.3} -> {:.3}, L {:.2} -> {:.2}, P_P {:.3} -> {:.3}",
        manual.discharge_flow_vphpl,
        waiting.discharge_flow_vphpl,
        manual.lane_changes_per_vehicle.unwrap(),
        waiting.lane_changes_per_vehicle.unwrap(),
        manual.avg_platoon_length.unwrap(),
        waiting.avg_platoon_length.unwrap(),
        manual.platooning_probability.unwrap(),
        waiting.platooning_probability.unwrap()
    );
    assert_eq!(waiting.collisions, 0);
    assert!(waiting.discharge_flow_vphpl > 1.04 * manual.discharge_flow_vphpl);
    // The organization still works: the CAVs still change lanes toward the PD lane.
    assert!(waiting.lane_changes_per_vehicle.unwrap() > 0.1);
}

#[test]
fn cavs_join_the_pd_lane_regardless_of_its_speed() {
    // `cav.organize_regardless_of_speed` [D] 6.22: the move toward the PD lane is made
    // "regardless of the speed difference" (seed paper), so its forward-gap test drops the
    // discretionary a_ant >= 0 condition of spec 4.3. At 1,000 veh/h/lane most organizing CAVs
    // were held back by that condition or by a target-lane leader alongside; without it more
    // of them reach the PD lane within the 1 km control section (this seed: 0.276 -> 0.325
    // lane changes per vehicle), platoons get longer, and light traffic absorbs the changes.
    // Measured under the published CACC law (`cav.cacc_law = "spec"`); under the field law
    // the platoon-length gain of this seed is below the 0.2 asked here.
    let mut cfg = Config::homogeneous(0.5, 1000.0, 3600.0, 1200.0, 1).with_pd();
    cfg.cav.cacc_law = platoonsim_model::cav::CaccLaw::Spec;
    let rule = run(&cfg, None).unwrap().summary;
    cfg.cav.organize_regardless_of_speed = false;
    let as_written = run(&cfg, None).unwrap().summary;
    eprintln!(
        "LC/CAV {:.3} -> {:.3}, L {:.2} -> {:.2}, Q {:.1} -> {:.1}",
        as_written.lane_changes_per_cav.unwrap(),
        rule.lane_changes_per_cav.unwrap(),
        as_written.avg_platoon_length.unwrap(),
        rule.avg_platoon_length.unwrap(),
        as_written.discharge_flow_vphpl,
        rule.discharge_flow_vphpl
    );
    assert_eq!(rule.collisions, 0);
    assert!(rule.lane_changes_per_cav.unwrap() > 1.1 * as_written.lane_changes_per_cav.unwrap());
    assert!(rule.avg_platoon_length.unwrap() > as_written.avg_platoon_length.unwrap() + 0.2);
    let dq = rule.discharge_flow_vphpl / as_written.discharge_flow_vphpl - 1.0;
    assert!(dq.abs() < 0.01, "discharge change {dq}");
}

/// `zero_flow_intervals` counts the (mainline detector, interval) pairs of the measurement
/// window whose cross-section count is zero: exactly what the detector records show, positive
/// on a near-empty road and zero under a steady demand.
#[test]
fn zero_flow_intervals_are_the_empty_mainline_intervals_of_the_window() {
    let count_in_records = |o: &Output, warmup_s: f64| -> u64 {
        o.detectors
            .iter()
            .filter(|r| r.kind == "mainline" && r.lane == "all")
            .filter(|r| r.interval_start_s >= warmup_s && r.count == 0)
            .count() as u64
    };
    let sparse = Config::homogeneous(0.5, 2.0, 3600.0, 600.0, 3);
    let o = run(&sparse, None).unwrap();
    assert!(
        o.summary.zero_flow_intervals > 0,
        "2 veh/h/lane leaves empty intervals"
    );
    assert_eq!(o.summary.zero_flow_intervals, count_in_records(&o, 600.0));
    // Empty intervals before the warm-up ends are not counted.
    let before = o
        .detectors
        .iter()
        .filter(|r| r.kind == "mainline" && r.lane == "all" && r.interval_start_s < 600.0)
        .filter(|r| r.count == 0)
        .count();
    assert!(before > 0, "the road is still empty at the start");
    let steady = run(&short(0.5, 2000.0, 3), None).unwrap();
    assert_eq!(steady.summary.zero_flow_intervals, 0);
}
