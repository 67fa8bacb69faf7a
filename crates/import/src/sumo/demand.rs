//! Routes onto the corridor: each path's entrance (the mainline entrance or an on-ramp) and
//! exit (an off-ramp or the road end), then the scenario's series per interval: the mainline
//! entrance demand, each on-ramp's demand (veh/h), and each off-ramp's exit fraction: of the
//! traffic passing the diverge in an interval, the share whose route leaves there. The model
//! draws each vehicle's exit at the diverge (docs/network-scenarios.md), so the origin-
//! destination pattern is kept as these fractions, not per vehicle; travel time between the
//! entrances and the diverge is not shifted (the series are stationary within an interval).

use super::corridor::Corridor;
use super::routes::{Demand, When};
use crate::Notes;
use std::collections::BTreeMap;

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Entry {
    Mainline,
    OnRamp(usize),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Exit {
    OffRamp(usize),
    End,
}

/// A path's entrance and exit on the corridor, or `None` if it never uses the mainline. The
/// notes collect paths that had to be reduced (keyed so that each kind is said once), naming
/// edges by `names`.
pub fn on_corridor(
    c: &Corridor,
    path: &[usize],
    names: &dyn Fn(usize) -> String,
    reduced: &mut BTreeMap<String, f64>,
    weight: f64,
) -> Option<(Entry, Exit)> {
    let (i0, k0) = path
        .iter()
        .enumerate()
        .find_map(|(i, &e)| c.position(e).map(|k| (i, k)))?;
    let entry = if i0 == 0 {
        if k0 > 0 {
            *reduced
                .entry(format!(
                    "routes that start on mainline edge \"{}\" (not the first) enter at the \
                     mainline entrance",
                    names(path[0])
                ))
                .or_default() += weight;
        }
        Entry::Mainline
    } else {
        let p = path[i0 - 1];
        match c.on_ramp_of(p) {
            Some(r) => Entry::OnRamp(r),
            None => Entry::Mainline, // a feeder of the first edge, or upstream of it
        }
    };
    // Along the mainline while the path follows the chain.
    let mut i1 = i0;
    let mut k1 = k0;
    while i1 + 1 < path.len() && k1 + 1 < c.chain.len() && path[i1 + 1] == c.chain[k1 + 1] {
        i1 += 1;
        k1 += 1;
    }
    let exit = if i1 + 1 < path.len() {
        match c.off_ramp_of(path[i1 + 1]) {
            Some(r) => Exit::OffRamp(r),
            None => {
                if k1 + 1 < c.chain.len() {
                    *reduced
                        .entry(format!(
                            "routes that leave the mainline after edge \"{}\" other than by an \
                             off-ramp drive to the end",
                            names(path[i1])
                        ))
                        .or_default() += weight;
                }
                Exit::End
            }
        }
    } else {
        if k1 + 1 < c.chain.len() {
            *reduced
                .entry(format!(
                    "routes that end on mainline edge \"{}\" drive to the end",
                    names(path[i1])
                ))
                .or_default() += weight;
        }
        Exit::End
    };
    if path[i1 + 1..].iter().any(|&e| c.position(e).is_some()) {
        *reduced
            .entry(
                "routes that leave the mainline and join it again end where they first leave it"
                    .into(),
            )
            .or_default() += weight;
    }
    Some((entry, exit))
}

/// The scenario's demand series.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    pub interval_s: f64,
    pub mainline_vph: Vec<f64>,
    pub on_ramp_vph: Vec<Vec<f64>>,
    pub exit_fraction: Vec<Vec<f64>>,
    /// Vehicles per type over the run (for the vehicle types' shares).
    pub by_type: BTreeMap<String, f64>,
}

/// Vehicles of a demand in each interval of [0, duration).
fn per_interval(when: &When, interval: f64, count: usize) -> Vec<f64> {
    let mut v = vec![0.0; count];
    match *when {
        When::Rate { begin, end, vph } => {
            for (k, slot) in v.iter_mut().enumerate() {
                let (a, b) = (k as f64 * interval, (k + 1) as f64 * interval);
                let overlap = (end.min(b) - begin.max(a)).max(0.0);
                *slot = vph * overlap / 3600.0;
            }
        }
        When::At(t) => {
            let k = (t / interval).floor();
            if k >= 0.0 && (k as usize) < count {
                v[k as usize] = 1.0;
            }
        }
    }
    v
}

pub fn series(
    c: &Corridor,
    demands: &[Demand],
    interval: f64,
    duration: f64,
    names: &dyn Fn(usize) -> String,
    notes: &mut Notes,
) -> Series {
    let count = ((duration / interval).ceil() as usize).max(1);
    // Vehicles per (entry, exit) per interval.
    let mut od: BTreeMap<(Entry, Exit), Vec<f64>> = BTreeMap::new();
    let mut by_type: BTreeMap<String, f64> = BTreeMap::new();
    let mut reduced: BTreeMap<String, f64> = BTreeMap::new();
    let mut off_corridor = 0.0;
    for d in demands {
        let veh = per_interval(&d.when, interval, count);
        let total: f64 = veh.iter().sum();
        for (path, share) in &d.paths {
            let w = total * share;
            match on_corridor(c, path, names, &mut reduced, w) {
                Some(key) => {
                    let slot = od.entry(key).or_insert_with(|| vec![0.0; count]);
                    for (s, v) in slot.iter_mut().zip(&veh) {
                        *s += v * share;
                    }
                    *by_type.entry(d.vtype.clone()).or_default() += w;
                }
                None => off_corridor += w,
            }
        }
    }
    for (what, veh) in reduced {
        notes.reduce(format!("{what} ({veh:.0} vehicles)"));
    }
    if off_corridor > 0.0 {
        notes.drop(format!(
            "{off_corridor:.0} vehicles whose routes do not use the mainline"
        ));
    }
    let to_vph = 3600.0 / interval;
    let mut s = Series {
        interval_s: interval,
        mainline_vph: vec![0.0; count],
        on_ramp_vph: vec![vec![0.0; count]; c.on_ramps.len()],
        exit_fraction: vec![vec![0.0; count]; c.off_ramps.len()],
        by_type,
    };
    let x_entry = |e: Entry| match e {
        Entry::Mainline => 0.0,
        Entry::OnRamp(r) => c.on_ramps[r].x,
    };
    let x_exit = |e: Exit| match e {
        Exit::OffRamp(r) => c.off_ramps[r].x,
        Exit::End => c.length,
    };
    for (&(entry, _), veh) in &od {
        let slot = match entry {
            Entry::Mainline => &mut s.mainline_vph,
            Entry::OnRamp(r) => &mut s.on_ramp_vph[r],
        };
        for (a, v) in slot.iter_mut().zip(veh) {
            *a += v * to_vph;
        }
    }
    for (j, ramp) in c.off_ramps.iter().enumerate() {
        for k in 0..count {
            let (mut passing, mut leaving) = (0.0, 0.0);
            for (&(entry, exit), veh) in &od {
                if x_entry(entry) < ramp.x && x_exit(exit) >= ramp.x {
                    passing += veh[k];
                    if exit == Exit::OffRamp(j) {
                        leaving += veh[k];
                    }
                }
            }
            s.exit_fraction[j][k] = if passing > 0.0 {
                leaving / passing
            } else {
                0.0
            };
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rate_is_spread_over_the_intervals_it_overlaps() {
        let w = When::Rate {
            begin: 450.0,
            end: 1800.0,
            vph: 3600.0,
        };
        assert_eq!(per_interval(&w, 900.0, 3), vec![450.0, 900.0, 0.0]);
        assert_eq!(per_interval(&When::At(905.0), 900.0, 2), vec![0.0, 1.0]);
        assert_eq!(per_interval(&When::At(1800.0), 900.0, 2), vec![0.0, 0.0]);
    }
}
