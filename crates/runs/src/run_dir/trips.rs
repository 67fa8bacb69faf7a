//! `trips.csv`: one row per vehicle that entered the road, then one per vehicle still in an
//! entrance queue at the end; the names of entrances and off-ramps it uses.

use crate::Error;
use platoonsim_rundir::{
    TRIPS, TRIP_ARRIVAL_COLUMN, TRIP_CLOCK_COLUMNS, TRIP_COLUMNS, TRIP_ENERGY_COLUMNS,
};
use platoonsim_sim::{Config, Queued, Trip, TripStatus};

/// The name of entrance `origin` ([`Trip::origin`]): `mainline`, or the on-ramp's id as in the
/// scenario file and the detector names (`OR3`).
pub fn entrance_name(config: &Config, origin: usize) -> String {
    let ramp = origin
        .checked_sub(1)
        .and_then(|i| config.road.network.as_ref()?.on_ramps.get(i));
    match ramp {
        Some(r) => platoonsim_scenario::network::split_name(&r.name).0,
        None => "mainline".to_string(),
    }
}

/// The id of off-ramp `k` (`FR2`; its exits are counted by detector `FR2-off`).
pub fn off_ramp_name(config: &Config, k: usize) -> String {
    config
        .road
        .network
        .as_ref()
        .and_then(|n| n.off_ramps.get(k))
        .map_or_else(
            || format!("off-ramp {k}"),
            |r| platoonsim_scenario::network::split_name(&r.name).0,
        )
}

/// `trips.csv`: the header, then one row per trip, then one per vehicle still queued at the
/// end. `destination` is the off-ramp's id, `end` (the road end) or empty (still on the road
/// or queued); `status` is `exited`, `missed_exit_then_end` (it chose an off-ramp, was not in
/// its lane there and drove on to the end), `in_network`, `collided` (it ran past the end of
/// its lane and was removed, see `collisions.csv`) or `queued` (still waiting in its
/// entrance's queue when the run ended); `left_s` and `travel_time_s` are empty for a vehicle
/// still on the road; `depart_delay_s` is the time from its arrival at the entrance to its
/// insertion on the road (the wait in the entrance queue, SUMO's `departDelay`), for a queued
/// vehicle the wait so far. A queued vehicle never entered the road: `entered_s`,
/// `travel_time_s` and the positions are empty, its counters 0 and `measured` false.
pub fn trips_csv(config: &Config, trips: &[Trip], queued: &[Queued]) -> Result<Vec<u8>, Error> {
    let enc = |e: csv::Error| Error::Other(format!("cannot encode {}: {e}", TRIPS.csv));
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    let energy = config.energy.enabled;
    let clock = config.clock_start_s;
    let mut header: Vec<&str> = TRIP_COLUMNS.to_vec();
    if energy {
        header.extend(TRIP_ENERGY_COLUMNS);
    }
    header.push(TRIP_ARRIVAL_COLUMN);
    if clock.is_some() {
        header.extend(TRIP_CLOCK_COLUMNS);
    }
    w.write_record(&header).map_err(enc)?;
    let num = |v: Option<f64>| v.map(|v| format!("{v}")).unwrap_or_default();
    let at = |t: Option<f64>| match (clock, t) {
        (Some(start), Some(t)) => platoonsim_scenario::clock::clock_at(start, t),
        _ => String::new(),
    };
    for t in trips {
        let (destination, status) = match t.status {
            TripStatus::Exited { off_ramp: Some(k) } => (off_ramp_name(config, k), "exited"),
            TripStatus::Exited { off_ramp: None } => ("end".to_string(), "exited"),
            TripStatus::MissedExitThenEnd { .. } => ("end".to_string(), "missed_exit_then_end"),
            TripStatus::InNetwork => (String::new(), "in_network"),
            TripStatus::Collided => (String::new(), "collided"),
        };
        let mut row = vec![
            t.id.to_string(),
            t.kind.as_str().to_string(),
            entrance_name(config, t.origin),
            destination,
            status.to_string(),
            format!("{}", t.entered_s),
            format!("{}", t.depart_delay_s),
            num(t.left_s),
            num(t.travel_time_s),
            format!("{}", t.entry_x_m),
            format!("{}", t.last_x_m),
            t.lane_changes.to_string(),
            t.max_platoon.to_string(),
            t.max_platoon_tg2.to_string(),
            t.measured.to_string(),
        ];
        if energy {
            let e = t.energy;
            row.extend([
                num(e.and_then(|e| e.fuel_l)),
                num(e.and_then(|e| e.energy_kwh)),
                num(e.and_then(|e| e.drag_saving_pct)),
            ]);
        }
        row.push(format!("{}", t.arrived_s));
        if clock.is_some() {
            row.extend([at(Some(t.entered_s)), at(t.left_s)]);
        }
        w.write_record(&row).map_err(enc)?;
    }
    for q in queued {
        let mut row = vec![
            q.id.to_string(),
            q.kind.as_str().to_string(),
            entrance_name(config, q.origin),
            String::new(),
            "queued".to_string(),
            String::new(),
            format!("{}", q.depart_delay_s),
            String::new(),
            String::new(),
            String::new(),
            String::new(),
            "0".to_string(),
            "0".to_string(),
            "0".to_string(),
            "false".to_string(),
        ];
        if energy {
            row.extend([String::new(), String::new(), String::new()]);
        }
        row.push(format!("{}", q.arrived_s));
        if clock.is_some() {
            row.extend([String::new(), String::new()]);
        }
        w.write_record(&row).map_err(enc)?;
    }
    w.into_inner()
        .map_err(|e| Error::Other(format!("cannot encode {}: {e}", TRIPS.csv)))
}
