//! The energy observer (`energy.rs`, docs/energy.md): a lone car at a steady speed uses the
//! model's steady-state value, a run's energy is the sum over its vehicles, and measuring
//! energy does not change the simulation.

use platoonsim_model::dist::Dist;
use platoonsim_model::energy::vt_cpfm::VtCpfm;
use platoonsim_model::energy::Powertrain;
use platoonsim_sim::{run, run_recording, Config, Output, Recording, TripStatus};

fn with_energy(mut cfg: Config) -> Config {
    cfg.energy.enabled = true;
    cfg
}

fn trips() -> Recording {
    Recording {
        trips: true,
        trajectories: None,
    }
}

/// Light traffic of human drivers who all want exactly 100 km/h: every car drives alone at
/// a steady 100 km/h, and uses VT-CPFM-1's steady-state 5.473 L/100 km.
#[test]
fn a_lone_car_at_100_kmh_uses_the_steady_state_value() {
    let mut cfg = with_energy(Config::homogeneous(0.0, 20.0, 1200.0, 0.0, 3));
    cfg.human.desired_speed_kmh = Dist::fixed(100.0);
    let out = run_recording(&cfg, &trips(), None).unwrap();
    let s = out.summary.energy.as_ref().unwrap();
    let steady = VtCpfm::default().fuel_rate_lps(100.0 / 3.6, 0.0, 1.0) / (100.0 / 3.6) * 1e5;
    assert!((steady - 5.4733).abs() < 1e-4, "{steady}");
    let done: Vec<_> = out
        .trips
        .unwrap()
        .into_iter()
        .filter(|t| t.status == (TripStatus::Exited { off_ramp: None }))
        .collect();
    assert!(done.len() >= 10, "{}", done.len());
    for t in &done {
        let km = (t.last_x_m - t.entry_x_m) / 1000.0;
        let l_per_100km = t.energy.unwrap().fuel_l.unwrap() / km * 100.0;
        assert!(
            (l_per_100km - steady).abs() < 1e-3 * steady,
            "vehicle {}: {l_per_100km} L/100 km",
            t.id
        );
        // Nobody close enough to draft behind.
        assert!(t.energy.unwrap().drag_saving_pct.unwrap() < 0.01);
    }
    let all = s.fuel_l_per_100km.unwrap();
    assert!((all - steady).abs() < 1e-3 * steady, "{all}");
    assert_eq!(s.fuel_l_per_100km_cav, None);
    assert_eq!(s.energy_kwh_per_100km, None);
}

/// Mixed traffic with electric CAVs: the summary's totals are the sums over the measured
/// vehicles' trips, and the distance is exactly where they went.
#[test]
fn run_energy_is_the_sum_over_vehicles() {
    let mut cfg = with_energy(Config::homogeneous(0.5, 2000.0, 900.0, 300.0, 5));
    cfg.cav.powertrain = Powertrain::Electric;
    let out = run_recording(&cfg, &trips(), None).unwrap();
    assert_eq!(out.summary.collisions, 0);
    let s = out.summary.energy.clone().unwrap();
    let trips = out.trips.unwrap();
    let measured: Vec<_> = trips.iter().filter(|t| t.measured).collect();
    assert!(measured.len() > 500);
    let fuel: f64 = measured.iter().filter_map(|t| t.energy?.fuel_l).sum();
    let kwh: f64 = measured.iter().filter_map(|t| t.energy?.energy_kwh).sum();
    assert!(
        (fuel - s.fuel_l).abs() <= 1e-9 * s.fuel_l,
        "{fuel} vs {}",
        s.fuel_l
    );
    assert!((kwh - s.energy_kwh).abs() <= 1e-9 * s.energy_kwh, "{kwh}");
    let km: f64 = measured
        .iter()
        .map(|t| (t.last_x_m - t.entry_x_m) / 1000.0)
        .sum();
    assert!((km - s.energy_distance_km).abs() <= 1e-9 * km, "{km}");
    // Humans burn fuel, CAVs draw electricity; each in its own unit.
    for t in &trips {
        let e = t.energy.unwrap();
        match t.kind {
            platoonsim_sim::Kind::Human => assert!(e.fuel_l.is_some() && e.energy_kwh.is_none()),
            platoonsim_sim::Kind::Cav => assert!(e.fuel_l.is_none() && e.energy_kwh.is_some()),
        }
    }
    let (l, kwh100) = (
        s.fuel_l_per_100km_human.unwrap(),
        s.energy_kwh_per_100km_cav.unwrap(),
    );
    assert!((4.5..7.0).contains(&l), "{l}");
    assert!((13.0..20.0).contains(&kwh100), "{kwh100}");
    assert_eq!(s.fuel_l_per_100km, s.fuel_l_per_100km_human);
    assert_eq!(s.fuel_l_per_100km_cav, None);
    // CACC strings: the CAVs' air resistance falls by more than the humans'.
    let (c, h) = (
        s.cav_drag_reduction_pct.unwrap(),
        s.human_drag_reduction_pct.unwrap(),
    );
    assert!(c > 1.0 && c > 2.0 * h, "cav {c} %, human {h} %");
    assert!(s.cav_drag_saving_pct.unwrap() > 0.0);
}

/// Energy only observes: with it on, the detectors, collisions and every other summary field
/// are bit-identical.
#[test]
fn measuring_energy_does_not_change_the_run() {
    let cfg = Config::homogeneous(0.5, 2500.0, 600.0, 120.0, 2);
    let plain = run(&cfg, None).unwrap();
    let measured = run(&with_energy(cfg), None).unwrap();
    assert!(plain.summary.energy.is_none() && measured.summary.energy.is_some());
    let strip = |mut o: Output| {
        o.summary.wall_seconds = 0.0;
        o.summary.energy = None;
        o
    };
    assert_eq!(strip(plain), strip(measured));
}

/// Without drag reduction every factor is 1: no saving, and the reduction is 0.
#[test]
fn drag_reduction_off_saves_nothing() {
    let mut cfg = with_energy(Config::homogeneous(0.5, 2000.0, 600.0, 120.0, 4));
    cfg.energy.drag_reduction = false;
    let s = run(&cfg, None).unwrap().summary.energy.unwrap();
    assert_eq!(s.cav_drag_reduction_pct, Some(0.0));
    assert_eq!(s.cav_drag_saving_pct, Some(0.0));
    assert_eq!(s.human_drag_saving_pct, Some(0.0));
    // Humans excluded from drafting: theirs is 0, the CAVs' is not.
    let mut cfg = with_energy(Config::homogeneous(0.5, 2000.0, 600.0, 120.0, 4));
    cfg.energy.humans_draft = false;
    let s = run(&cfg, None).unwrap().summary.energy.unwrap();
    assert_eq!(s.human_drag_reduction_pct, Some(0.0));
    assert!(s.cav_drag_reduction_pct.unwrap() > 1.0);
}
