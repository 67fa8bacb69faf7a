//! Cross-sections made of several field stations: a PeMS mainline station (`ML`) counts the
//! general-purpose lanes only, and the HOV lane at the same postmile is a station of its own
//! (`HV`). A model that runs the HOV lane as an ordinary lane (the built-in SR-99 corridors)
//! must be compared with their sum.
//!
//! For a [`Group`] and an interval in which **every** member has a row:
//!
//! | measure | combined as |
//! |---|---|
//! | flow (veh/h) | sum of the members' flows |
//! | speed (km/h) | flow-weighted mean over the members with a speed (their plain mean if all their flows are 0); none if no member has one |
//! | occupancy (0-1) | lane-weighted mean of the members' occupancies (each member's lanes from the metadata, 1 if unknown); none if any member has none |
//!
//! An interval in which a member has no row is left out and listed: missing data is
//! reported, never invented. Stations in no group pass through unchanged.
//!
//! [`hov_groups`] builds the groups from PeMS metadata: each `HV` station joins the `ML`
//! station of the same freeway and direction nearest in absolute postmile, if it is within
//! `tolerance_mi` (default [`HOV_TOLERANCE_MI`]); the group is named by the `ML` station.

use crate::{Obs, StationKind, StationMeta};
use std::collections::{BTreeMap, BTreeSet};

/// Largest postmile distance (mi) at which an HOV station joins a mainline station: 0.05 mi
/// (80 m), about the spread of the two loops of one cross-section in the SR-99 metadata
/// (at most 0.024 mi there).
pub const HOV_TOLERANCE_MI: f64 = 0.05;

/// One cross-section: the name it is compared under and the stations that make it.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// Name of the combined station (the mainline station's ID).
    pub station: String,
    /// Member stations with their lane counts, the named station among them.
    pub members: Vec<(String, u32)>,
}

/// An interval of a group left out because a member had no row.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Incomplete {
    pub station: String,
    pub start_s: u32,
    /// The members without a row in that interval.
    pub missing: Vec<String>,
}

/// The groups "mainline station + the HOV stations at its postmile" of a metadata file; only
/// mainline stations that have an HOV partner form a group.
pub fn hov_groups(meta: &[StationMeta], tolerance_mi: f64) -> Vec<Group> {
    let mut groups: BTreeMap<&str, Group> = BTreeMap::new();
    let mainline: Vec<&StationMeta> = meta
        .iter()
        .filter(|m| m.kind == StationKind::Mainline)
        .collect();
    for hov in meta.iter().filter(|m| m.kind == StationKind::Hov) {
        let nearest = mainline
            .iter()
            .filter(|m| m.freeway == hov.freeway && m.direction == hov.direction)
            .map(|m| ((m.abs_pm - hov.abs_pm).abs(), *m))
            .filter(|(d, _)| *d <= tolerance_mi)
            .min_by(|a, b| a.0.total_cmp(&b.0).then_with(|| a.1.id.cmp(&b.1.id)));
        if let Some((_, ml)) = nearest {
            groups
                .entry(ml.id.as_str())
                .or_insert_with(|| Group {
                    station: ml.id.clone(),
                    members: vec![(ml.id.clone(), ml.lanes)],
                })
                .members
                .push((hov.id.clone(), hov.lanes));
        }
    }
    groups.into_values().collect()
}

/// The observations with every group's members replaced by the group's combined rows, in
/// (station, start) order, and the group intervals left out.
pub fn combine(obs: &[Obs], groups: &[Group]) -> (Vec<Obs>, Vec<Incomplete>) {
    let member_of: BTreeSet<&str> = groups
        .iter()
        .flat_map(|g| g.members.iter().map(|(id, _)| id.as_str()))
        .collect();
    let mut by_station: BTreeMap<&str, BTreeMap<u32, &Obs>> = BTreeMap::new();
    for o in obs {
        by_station
            .entry(o.station.as_str())
            .or_default()
            .insert(o.start_s, o);
    }
    let mut out: Vec<Obs> = obs
        .iter()
        .filter(|o| !member_of.contains(o.station.as_str()))
        .cloned()
        .collect();
    let mut incomplete = Vec::new();
    for g in groups {
        let starts: BTreeSet<u32> = g
            .members
            .iter()
            .filter_map(|(id, _)| by_station.get(id.as_str()))
            .flat_map(|rows| rows.keys().copied())
            .collect();
        for t in starts {
            let rows: Vec<(Option<&&Obs>, u32)> = g
                .members
                .iter()
                .map(|(id, lanes)| (by_station.get(id.as_str()).and_then(|r| r.get(&t)), *lanes))
                .collect();
            let missing: Vec<String> = g
                .members
                .iter()
                .zip(&rows)
                .filter(|(_, (o, _))| o.is_none())
                .map(|((id, _), _)| id.clone())
                .collect();
            if !missing.is_empty() {
                incomplete.push(Incomplete {
                    station: g.station.clone(),
                    start_s: t,
                    missing,
                });
                continue;
            }
            // Every member has its row here (the missing ones were set aside above).
            let rows: Vec<(&Obs, u32)> = rows
                .into_iter()
                .filter_map(|(o, l)| o.map(|o| (*o, l)))
                .collect();
            out.push(merge(&g.station, &rows));
        }
    }
    out.sort_by(|a, b| a.station.cmp(&b.station).then(a.start_s.cmp(&b.start_s)));
    (out, incomplete)
}

/// One interval of a group (see the module doc for the rules).
fn merge(station: &str, rows: &[(&Obs, u32)]) -> Obs {
    let flow: f64 = rows.iter().map(|(o, _)| o.flow_vph).sum();
    let speed_kmh = crate::flow_weighted_speed(rows.iter().map(|(o, _)| *o));
    let occupancy = rows
        .iter()
        .map(|(o, l)| o.occupancy.map(|c| (c, f64::from((*l).max(1)))))
        .collect::<Option<Vec<_>>>()
        .map(|v| {
            let lanes: f64 = v.iter().map(|&(_, l)| l).sum();
            v.iter().map(|&(c, l)| c * l).sum::<f64>() / lanes
        });
    Obs {
        station: station.to_string(),
        start_s: rows[0].0.start_s,
        interval_s: rows[0].0.interval_s,
        flow_vph: flow,
        speed_kmh,
        occupancy,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn meta(id: &str, pm: f64, kind: StationKind, lanes: u32) -> StationMeta {
        StationMeta {
            id: id.into(),
            freeway: "99".into(),
            direction: "N".into(),
            abs_pm: pm,
            kind,
            lanes,
            name: String::new(),
        }
    }

    fn obs(station: &str, t: u32, flow: f64, speed: Option<f64>, occ: Option<f64>) -> Obs {
        Obs {
            station: station.into(),
            start_s: t,
            interval_s: 300,
            flow_vph: flow,
            speed_kmh: speed,
            occupancy: occ,
        }
    }

    #[test]
    fn an_hov_station_joins_the_nearest_mainline_station_within_the_tolerance() {
        let m = [
            meta("A", 290.650, StationKind::Mainline, 2),
            meta("B", 290.763, StationKind::Mainline, 2),
            meta("H1", 290.626, StationKind::Hov, 1), // 0.024 from A, 0.137 from B
            meta("H2", 291.000, StationKind::Hov, 1), // 0.237 from B: alone
            meta("R", 290.650, StationKind::OnRamp, 1),
        ];
        let g = hov_groups(&m, HOV_TOLERANCE_MI);
        assert_eq!(
            g,
            vec![Group {
                station: "A".into(),
                members: vec![("A".into(), 2), ("H1".into(), 1)],
            }]
        );
    }

    #[test]
    fn members_add_flows_weight_speeds_by_flow_and_occupancy_by_lanes() {
        let g = [Group {
            station: "A".into(),
            members: vec![("A".into(), 2), ("H".into(), 1)],
        }];
        let rows = [
            obs("A", 0, 3000.0, Some(60.0), Some(0.375)),
            obs("H", 0, 1000.0, Some(100.0), Some(0.0)),
            obs("A", 300, 2000.0, Some(90.0), Some(0.1)),
            obs("X", 0, 500.0, None, None),
        ];
        let (out, incomplete) = combine(&rows, &g);
        // (60 x 3000 + 100 x 1000) / 4000 = 70; (0.375 x 2 + 0 x 1) / 3 = 0.25
        assert_eq!(out[0], obs("A", 0, 4000.0, Some(70.0), Some(0.25)));
        // X passes through; A at 300 s has no HOV row: left out and listed.
        assert_eq!(out[1], rows[3]);
        assert_eq!(out.len(), 2);
        assert_eq!(
            incomplete,
            vec![Incomplete {
                station: "A".into(),
                start_s: 300,
                missing: vec!["H".into()],
            }]
        );
    }
}
