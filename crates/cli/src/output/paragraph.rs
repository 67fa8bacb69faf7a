//! The one-paragraph human summary printed after a run, and its number formatting.

use crate::messages::printable;
use platoonsim_rundir as rundir;
use platoonsim_sim::{Config, Counted, Summary};
use std::path::Path;

/// A statistic with `dec` decimals, or "n/a" where it does not apply (nothing to count).
fn maybe(v: Option<f64>, dec: usize) -> String {
    v.map_or("n/a".to_string(), |v| format!("{v:.dec$}"))
}

/// The one-paragraph human summary printed after a run.
pub fn paragraph(config: &Config, s: &Summary, dir: &Path) -> String {
    let detector = config
        .detectors
        .get(config.measurement_detector)
        .map_or("?", |d| d.name.as_str());
    let detector = printable(detector);
    let rate = if s.wall_seconds > 0.0 {
        format!(
            " ({} per second)",
            si(s.vehicle_updates as f64 / s.wall_seconds)
        )
    } else {
        String::new()
    };
    // A network's demand is its series times a scale; it also reports the discharge through
    // every exit.
    let (demand, network) = match &config.road.network {
        Some(n) => (
            format!("the network's demand x {:.3}", n.demand_scale),
            format!(
                " Network discharge (off-ramps and the end): {} veh/h; {} missed exits.",
                s.network_discharge_vph
                    .map_or("-".to_string(), |q| format!("{q:.0}")),
                s.missed_exits
            ),
        ),
        None => (
            format!("{} veh/h/lane demand", config.demand.vph_per_lane),
            String::new(),
        ),
    };
    let count = |m: Counted| s.counted.get(m.name()).cloned().unwrap_or_default();
    let text = format!(
        "{name}: {dur} s simulated in steps of {dt} s (measured after the {warm} s warm-up) with \
         {pen} % CAV, {demand}, strategy {strategy}, seed {seed}. \
         Vehicles: {entered} entered, {exited} exited, {inside} still on the road, {waiting} \
         waiting at the entrance. Discharge at detector '{detector}': {q:.1} veh/h/lane over \
         the measurement window; highest {agg} s flow {qmax:.1} veh/h/lane.{network} Lane changes per \
         vehicle {lc} ({counted} vehicles; per CAV {lc_cav}, per human {lc_human}); \
         average platoon length {lbar} and platooning probability {pp} ({cavs} CAVs). \
         Safety after the warm-up, over {vkm:.0} veh-km: {hard} hard brakings beyond 4 m/s² \
         ({hard_cav} CAV, {hard_human} human; {hard_rate} per 100 veh-km), {severe} severe \
         (6 m/s² or more; {severe_rate} per 100 veh-km), {at_limit} at the emergency limit; \
         {rear_end} rear-end and {lane_change} lane-change conflicts (TTC below {ttc_star} s), \
         TET {tet:.1} s, TIT {tit:.1} s², minimum TTC {min_ttc}; largest deceleration \
         {max_decel:.2} m/s² over the whole run. \
         Collisions: {collisions}. {updates} vehicle updates in {wall:.2} s{rate}. \
         Files in {dir}: {summary}, {detectors}, {scenario_json}, {scenario_toml}, {road_json}\
         {collisions_file}.",
        summary = rundir::SUMMARY,
        detectors = rundir::DETECTORS.csv,
        scenario_json = rundir::SCENARIO_JSON,
        scenario_toml = rundir::SCENARIO_TOML,
        road_json = rundir::ROAD_JSON,
        name = printable(&s.scenario),
        dur = s.duration_s,
        dt = s.dt_s,
        warm = s.warmup_s,
        pen = s.penetration * 100.0,
        strategy = s.strategy,
        seed = s.seed,
        entered = s.vehicles_entered,
        exited = s.vehicles_exited,
        inside = s.vehicles_in_network,
        waiting = s.vehicles_waiting,
        q = s.discharge_flow_vphpl,
        agg = config.aggregation_s,
        qmax = s.max_sustained_flow_vphpl,
        lc = maybe(s.lane_changes_per_vehicle, 3),
        lc_cav = maybe(s.lane_changes_per_cav, 3),
        lc_human = maybe(s.lane_changes_per_human, 3),
        counted = s.vehicles_counted,
        lbar = maybe(s.avg_platoon_length, 2),
        pp = maybe(s.platooning_probability, 3),
        cavs = s.cavs_counted,
        vkm = s.vehicle_km,
        hard = count(Counted::HardBrakings).total(),
        hard_cav = count(Counted::HardBrakings).cav,
        hard_human = count(Counted::HardBrakings).human,
        hard_rate = maybe(count(Counted::HardBrakings).per_100vkm, 3),
        severe = count(Counted::SevereBrakings).total(),
        severe_rate = maybe(count(Counted::SevereBrakings).per_100vkm, 3),
        at_limit = count(Counted::BrakingsAtLimit).total(),
        rear_end = count(Counted::RearEndConflicts).total(),
        lane_change = count(Counted::LaneChangeConflicts).total(),
        ttc_star = config.safety.ttc_threshold_s,
        tet = s.tet_s,
        tit = s.tit_s2,
        // Null when no follower ever closed in on its leader.
        min_ttc = s
            .min_ttc_s
            .map_or("none (no follower closed in)".to_string(), |t| format!("{t:.2} s")),
        max_decel = s.max_deceleration_mps2,
        collisions = s.collisions,
        collisions_file = if s.collisions > 0 {
            format!(", {}", rundir::COLLISIONS)
        } else {
            String::new()
        },
        updates = s.vehicle_updates,
        wall = s.wall_seconds,
        dir = printable(&dir.display().to_string()),
    );
    wrap(&text, 96)
}

/// 12.3 M, 456.7 k, 89.
pub fn si(v: f64) -> String {
    if v >= 1e9 {
        format!("{:.2} G", v / 1e9)
    } else if v >= 1e6 {
        format!("{:.2} M", v / 1e6)
    } else if v >= 1e3 {
        format!("{:.1} k", v / 1e3)
    } else {
        format!("{v:.0}")
    }
}

/// Greedy word wrap.
pub fn wrap(text: &str, width: usize) -> String {
    let mut out = String::new();
    let mut line = 0;
    for word in text.split_whitespace() {
        if line > 0 && line + 1 + word.len() > width {
            out.push('\n');
            line = 0;
        } else if line > 0 {
            out.push(' ');
            line += 1;
        }
        out.push_str(word);
        line += word.len();
    }
    out
}
