//! What every manoeuvre test shares: an empty road or corridor, stepping with a watcher, and a
//! plain copy of the few vehicle fields the tests read (so the tests do not depend on the
//! engine's record layout).

use platoonsim_sim::{Config, LaneExtent, Network, OffRamp, OnRamp, Simulation};

/// What a test reads of one vehicle.
#[derive(Clone, Copy, Debug)]
pub struct Seen {
    /// Front position (engine coordinate, m).
    pub x: f64,
    pub v: f64,
    pub a: f64,
    pub lane: u32,
    pub length: f64,
    pub jam_gap: f64,
    /// The CAV string predecessor's id, if the CAV is in a string.
    pub pred: Option<u64>,
    /// The CAV's own CACC time gap t_C (s).
    pub t_c: f64,
}

/// Vehicle `id` as the tests see it, if it is on the road.
pub fn seen(sim: &Simulation, id: u64) -> Option<Seen> {
    sim.vehicle(id).map(|v| Seen {
        x: v.x(),
        v: v.v(),
        a: v.a(),
        lane: v.lane(),
        length: v.length_m(),
        jam_gap: v.driver_params().jam_gap_m,
        pred: v.joined(),
        t_c: v.cacc_gap_s(),
    })
}

/// Vehicle `id`, which must be on the road.
pub fn at(sim: &Simulation, id: u64) -> Seen {
    seen(sim, id).unwrap_or_else(|| panic!("vehicle {id} is not on the road"))
}

/// An empty homogeneous road of `lanes` lanes (no arrivals), 6.5 km, 5 simulated minutes.
pub fn empty(lanes: u32) -> Simulation {
    Simulation::new(empty_config(lanes)).unwrap()
}

/// The configuration of [`empty`], to change before building the simulation.
pub fn empty_config(lanes: u32) -> Config {
    let mut cfg = Config::homogeneous(0.0, 0.0, 300.0, 0.0, 1);
    cfg.road.lanes = lanes;
    cfg
}

/// An empty corridor 4 km long (no arrivals): through lanes `1..=through` open over the whole
/// length except those listed in `ends` (lane, end m), which drop there; lane 0 is free for an
/// acceleration lane. `on_ramp`: an on-ramp merging at (x m, acceleration lane length m).
/// `off_ramp`: a diverge at x m that every placed vehicle upstream of it takes.
pub fn corridor(
    through: u32,
    ends: &[(u32, f64)],
    on_ramp: Option<(f64, f64)>,
    off_ramp: Option<f64>,
) -> Simulation {
    let length = 4000.0;
    let mut cfg = Config::homogeneous(0.0, 0.0, 300.0, 0.0, 1);
    cfg.name = "manoeuvre-corridor".into();
    cfg.road.lanes = through + 1;
    cfg.road.length_m = length;
    cfg.road.control_start_m = 0.0;
    cfg.road.control_end_m = length;
    cfg.detectors.clear();
    cfg.detectors
        .push(platoonsim_sim::DetectorSpec::mainline("end", 3900.0));
    cfg.measurement_detector = 0;
    let through_lanes = (1..=through)
        .map(|lane| LaneExtent {
            lane,
            from_m: 0.0,
            to_m: ends.iter().find(|e| e.0 == lane).map_or(length, |e| e.1),
        })
        .collect();
    cfg.road.network = Some(Network {
        origin_m: 0.0,
        through_lanes,
        on_ramps: on_ramp
            .map(|(x, accel)| OnRamp {
                name: "on".into(),
                x_m: x,
                accel_lane_m: accel,
                ramp_length_m: 300.0,
                demand_vph: vec![0.0],
                meter: None,
                penetration: None,
            })
            .into_iter()
            .collect(),
        off_ramps: off_ramp
            .map(|x| OffRamp {
                name: "off".into(),
                x_m: x,
                exit_fraction: vec![1.0],
            })
            .into_iter()
            .collect(),
        interval_s: 300.0,
        mainline_vph: vec![0.0],
        demand_scale: 1.0,
        ramp_speed_kmh: 90.0,
        lane_speed_limits_kmh: Vec::new(),
        cross_lane_friction: None,
        behaviour: Vec::new(),
    });
    Simulation::new(cfg).unwrap()
}

/// Step `secs`, calling `watch` after each step.
pub fn run(sim: &mut Simulation, secs: f64, mut watch: impl FnMut(&Simulation)) {
    let steps = (secs / sim.config().dt_s).round() as usize;
    for _ in 0..steps {
        sim.step().unwrap();
        watch(sim);
    }
}

/// Bumper-to-bumper gap from `follower` to `leader` (m).
pub fn gap(sim: &Simulation, leader: u64, follower: u64) -> f64 {
    let (l, f) = (at(sim, leader), at(sim, follower));
    l.x - l.length - f.x
}
