//! Pairing simulated bottlenecks with field ones, and whether each pair is "at the right
//! place with onset and clearance within 15 minutes of the field" (platoonsim's acceptance
//! target, issue #30; FHWA Toolbox III (2004) Table 4 asks only for a visual audit of
//! bottlenecks, "to analyst's satisfaction").
//!
//! Candidates are a field and a simulated bottleneck at most [`MatchParams::max_distance_m`]
//! apart whose active periods overlap; they are taken nearest first (then by onset
//! difference), each bottleneck at most once, so a morning and an evening episode at one
//! place pair with their own counterparts. What is left is a field bottleneck the simulation
//! misses or a simulated one the field does not have.
//!
//! | parameter | unit | default |
//! |---|---|---|
//! | `max_distance_m` | m | 1,500 |
//! | `max_time_diff_s` | s | 900 (15 min), for onset and for clearance |

use super::Bottleneck;
use serde::{Deserialize, Serialize};

/// Tolerances of the pairing (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct MatchParams {
    pub max_distance_m: f64,
    pub max_time_diff_s: u32,
}

impl Default for MatchParams {
    fn default() -> Self {
        MatchParams {
            max_distance_m: 1500.0,
            max_time_diff_s: 900,
        }
    }
}

/// A field bottleneck and its simulated counterpart; one of them may be missing.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pair {
    pub field: Option<Bottleneck>,
    pub sim: Option<Bottleneck>,
    /// Simulated minus field position (m).
    pub distance_m: Option<f64>,
    /// Simulated minus field onset (min).
    pub onset_diff_min: Option<f64>,
    /// Simulated minus field clearance (min).
    pub clearance_diff_min: Option<f64>,
    /// Both present, in place, onset and clearance within the tolerance.
    pub within: bool,
}

/// Pair `sim` bottlenecks with `field` ones (see the module doc): matched pairs, then field
/// bottlenecks without a counterpart, then simulated ones, each by position and onset.
pub fn compare(sim: &[Bottleneck], field: &[Bottleneck], p: &MatchParams) -> Vec<Pair> {
    let mut cand: Vec<(f64, u32, usize, usize)> = Vec::new();
    for (i, f) in field.iter().enumerate() {
        for (j, s) in sim.iter().enumerate() {
            let d = (s.x_m - f.x_m).abs();
            let overlap = s.onset_s < f.clearance_s && f.onset_s < s.clearance_s;
            if d <= p.max_distance_m && overlap {
                cand.push((d, s.onset_s.abs_diff(f.onset_s), i, j));
            }
        }
    }
    cand.sort_by(|a, b| {
        a.0.total_cmp(&b.0)
            .then(a.1.cmp(&b.1))
            .then((a.2, a.3).cmp(&(b.2, b.3)))
    });
    let (mut used_f, mut used_s) = (vec![false; field.len()], vec![false; sim.len()]);
    let mut matched: Vec<(usize, usize)> = Vec::new();
    for (_, _, i, j) in cand {
        if !used_f[i] && !used_s[j] {
            used_f[i] = true;
            used_s[j] = true;
            matched.push((i, j));
        }
    }
    matched.sort();
    let minutes = |a: u32, b: u32| (f64::from(a) - f64::from(b)) / 60.0;
    let limit_min = f64::from(p.max_time_diff_s) / 60.0;
    let mut out: Vec<Pair> = matched
        .into_iter()
        .map(|(i, j)| {
            let (f, s) = (&field[i], &sim[j]);
            let onset = minutes(s.onset_s, f.onset_s);
            let clearance = minutes(s.clearance_s, f.clearance_s);
            Pair {
                field: Some(f.clone()),
                sim: Some(s.clone()),
                distance_m: Some(s.x_m - f.x_m),
                onset_diff_min: Some(onset),
                clearance_diff_min: Some(clearance),
                within: onset.abs() <= limit_min && clearance.abs() <= limit_min,
            }
        })
        .collect();
    let alone = |b: &Bottleneck, is_field: bool| Pair {
        field: is_field.then(|| b.clone()),
        sim: (!is_field).then(|| b.clone()),
        distance_m: None,
        onset_diff_min: None,
        clearance_diff_min: None,
        within: false,
    };
    out.extend(
        field
            .iter()
            .zip(&used_f)
            .filter(|(_, &u)| !u)
            .map(|(b, _)| alone(b, true)),
    );
    out.extend(
        sim.iter()
            .zip(&used_s)
            .filter(|(_, &u)| !u)
            .map(|(b, _)| alone(b, false)),
    );
    out
}

/// Whether the bottlenecks agree: every pair matched and within the tolerances (true when
/// neither side has a bottleneck).
pub fn all_within(pairs: &[Pair]) -> bool {
    pairs.iter().all(|p| p.within)
}
