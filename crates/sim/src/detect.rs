//! Phase 6 (detectors): crossings and occupancy per lane, for every loop detector.

use crate::detector::{Detector, Passage};
use crate::state::{Detectors, Traffic};

/// Phase 6: detectors, per lane by a search on the sorted lane list; reads the vehicles and
/// lanes, writes the detectors (and their search hints).
///
/// The search starts from where it ended in the previous step (`hint`): the lanes change
/// little between steps. The walk finds the same index as a binary search when the lane is
/// sorted (descending x); integrate is the only phase that can unsort a lane (lane changes and
/// insertions insert at their sorted position), and if it did (`lanes_sorted` false), this
/// step searches as before.
#[inline]
pub(crate) fn observe_detectors(
    dt: f64,
    traffic: &Traffic,
    lanes_sorted: bool,
    detectors: &mut Detectors,
) {
    let n_lanes = traffic.lanes.len();
    detectors.hint.resize(detectors.list.len() * n_lanes, 0);
    for (i, det) in detectors.list.iter_mut().enumerate() {
        if det.kind != "mainline" {
            continue; // ramp counters count at exits and insertions
        }
        let hints = &mut detectors.hint[i * n_lanes..(i + 1) * n_lanes];
        observe(dt, traffic, lanes_sorted, det, hints);
    }
}

/// One detector's lanes in phase 6, `hints` its search hints by lane (the loop detectors
/// above, and a ramp meter's detector, `meter.rs`).
#[inline(always)]
pub(crate) fn observe(
    dt: f64,
    traffic: &Traffic,
    lanes_sorted: bool,
    det: &mut Detector,
    hints: &mut [u32],
) {
    let p = det.position_m;
    for (l, lane) in traffic.lanes.iter().enumerate() {
        if det.mask & (1 << l) == 0 {
            continue;
        }
        // Candidates: front now in [p, p + L + travel]; lane is sorted descending.
        let hi = p + 60.0;
        let ahead = |s: u32| traffic.vehicles[s as usize].x > hi;
        let start = if lanes_sorted {
            let hint = &mut hints[l];
            let mut k = (*hint as usize).min(lane.len());
            while k > 0 && !ahead(lane[k - 1]) {
                k -= 1;
            }
            while k < lane.len() && ahead(lane[k]) {
                k += 1;
            }
            *hint = k as u32;
            k
        } else {
            lane.partition_point(|&s| ahead(s))
        };
        for &s in &lane[start..] {
            let v = &traffic.vehicles[s as usize];
            if v.x < p {
                break;
            }
            let v0 = (v.v - v.a * dt).max(0.0);
            let m = Passage {
                x0: v.x_prev,
                x1: v.x,
                v0,
                v1: v.v,
                len: v.driver.human.length_m,
                cav: v.is_cav(),
            };
            det.observe(l, m, dt);
        }
    }
}
