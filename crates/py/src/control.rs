//! The per-vehicle control task of `platoonsim/CavControl-v0` (python/platoonsim/control.py),
//! computed in Rust for every world of a batch in parallel: which CAVs the policy drives (up
//! to `k` slots), their observations, their commands, the reward.
//!
//! * **Slots.** After each step the CAVs that left free their slots; CAVs not yet in a slot
//!   take the free ones in order of entry (vehicle id). A vehicle keeps its slot while it is on
//!   the road, so slot `j` is one vehicle for as long as it drives.
//! * **Observation** of slot `j` (6 values, 0 for an empty slot): position x / road length;
//!   speed / v_ref; gap to the leader / gap_ref and (v_leader − v) / v_ref; gap of the follower
//!   / gap_ref and (v − v_follower) / v_ref (no leader or follower: gap 1 and speed difference
//!   0). Gaps are bumper to bumper, clipped to [0, 1]; speeds and differences to [−2, 2].
//! * **Action** of slot `j`: an acceleration (m/s²), clipped to [a_low, a_high], applied as
//!   `Command::AccelerateCapped` for the step's engine steps: never above the vehicle's own
//!   ACC/CACC acceleration, which keeps its collision avoidance; the braking limit applies in
//!   the engine as for every vehicle. Empty slots' actions are ignored.
//! * **Reward** of a step: mean speed of every vehicle on the road / v_ref, minus
//!   `accel_penalty` × the mean of (a / a_high)² over the commanded vehicles still on the
//!   road, a the acceleration each applied in the step's last engine step (after the cap).

use crate::core::{step_world, Inner};
use platoonsim_sim::snapshot::VehicleColumns;
use platoonsim_sim::Command;

pub const FEATURES: usize = 6;
const EMPTY: u64 = u64::MAX;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spec {
    pub k: usize,
    pub steps: u64,
    pub v_ref: f64,
    pub gap_ref: f64,
    pub accel_penalty: f64,
    pub a_low: f64,
    pub a_high: f64,
}

/// A world's control state.
#[derive(Clone, Debug, Default)]
pub struct State {
    slots: Vec<u64>,
    /// Ids on the road after the last step, sorted (for the outflow).
    on_road: Vec<u64>,
}

/// What one step returns for one world.
#[derive(Clone, Debug, Default)]
pub struct Out {
    pub obs: Vec<f32>,
    pub mask: Vec<bool>,
    pub reward: f64,
    /// Vehicles that left the road during the step.
    pub outflow: u64,
    pub collisions: u64,
    pub done: bool,
}

/// Slots and observations from the road now.
fn observe(
    c: &VehicleColumns,
    st: &mut State,
    spec: &Spec,
    length_m: f64,
    origin_m: f64,
    out: &mut Out,
) {
    let k = spec.k;
    if st.slots.len() != k {
        st.slots = vec![EMPTY; k];
    }
    // Index of each id (ids are unique).
    let mut by_id: Vec<(u64, usize)> = c.id.iter().copied().zip(0..).collect();
    by_id.sort_unstable();
    let find = |id: u64| {
        by_id
            .binary_search_by_key(&id, |p| p.0)
            .ok()
            .map(|i| by_id[i].1)
    };
    for s in st.slots.iter_mut() {
        if *s != EMPTY && find(*s).is_none() {
            *s = EMPTY;
        }
    }
    for &(id, i) in &by_id {
        if c.kind[i] != 1 || st.slots.contains(&id) {
            continue;
        }
        match st.slots.iter_mut().find(|s| **s == EMPTY) {
            Some(s) => *s = id,
            None => break,
        }
    }
    // Followers: the vehicle whose leader is i.
    let mut follower = vec![usize::MAX; c.len()];
    for j in 0..c.len() {
        if let Some(l) = c.leader_id[j] {
            if let Some(i) = find(l) {
                follower[i] = j;
            }
        }
    }
    out.obs.clear();
    out.obs.resize(k * FEATURES, 0.0);
    out.mask.clear();
    out.mask.resize(k, false);
    let clip = |v: f64, lo: f64, hi: f64| v.clamp(lo, hi) as f32;
    for (j, &id) in st.slots.iter().enumerate() {
        let Some(i) = (id != EMPTY).then(|| find(id)).flatten() else {
            continue;
        };
        out.mask[j] = true;
        let v = c.v_mps[i];
        let (gap_l, dv_l) = match c.leader_id[i].and_then(find) {
            Some(l) => (c.x_m[l] - c.length_m[l] - c.x_m[i], c.v_mps[l] - v),
            None => (spec.gap_ref, 0.0),
        };
        let (gap_f, dv_f) = match follower[i] {
            usize::MAX => (spec.gap_ref, 0.0),
            f => (c.x_m[i] - c.length_m[i] - c.x_m[f], v - c.v_mps[f]),
        };
        let o = &mut out.obs[j * FEATURES..(j + 1) * FEATURES];
        o[0] = clip((c.x_m[i] - origin_m) / length_m, 0.0, 1.0);
        o[1] = clip(v / spec.v_ref, -2.0, 2.0);
        o[2] = clip(gap_l / spec.gap_ref, 0.0, 1.0);
        o[3] = clip(dv_l / spec.v_ref, -2.0, 2.0);
        o[4] = clip(gap_f / spec.gap_ref, 0.0, 1.0);
        o[5] = clip(dv_f / spec.v_ref, -2.0, 2.0);
    }
    st.on_road.clear();
    st.on_road.extend_from_slice(&c.id);
    st.on_road.sort_unstable();
}

fn road(inner: &Inner) -> (f64, f64) {
    let r = &inner.config.road;
    let origin = r.origin_m();
    (r.length_m, origin)
}

/// Start (or restart) control in a world: the first observation.
pub fn start(inner: &mut Inner, spec: &Spec) -> Result<Out, String> {
    let (length, origin) = road(inner);
    let mut st = State::default();
    let mut out = Out::default();
    let mut cols = std::mem::take(&mut inner.columns);
    let sim = inner.sim_ref().ok_or("the simulation is finished")?;
    sim.vehicle_columns(&mut cols);
    observe(&cols, &mut st, spec, length, origin, &mut out);
    out.done = sim.finished();
    inner.columns = cols;
    inner.control = st;
    Ok(out)
}

/// One step of the task: the actions of the slots, `spec.steps` engine steps, the new
/// observation and the reward.
pub fn step(inner: &mut Inner, spec: &Spec, actions: &[f64]) -> Result<Out, String> {
    let (length, origin) = road(inner);
    let mut st = std::mem::take(&mut inner.control);
    if st.slots.len() != spec.k {
        return Err("control was not started (reset first)".into());
    }
    let collisions_before = inner.sim_ref().map_or(0, |s| s.collisions());
    let commanded: Vec<u64> = st.slots.iter().copied().filter(|&id| id != EMPTY).collect();
    {
        let sim = inner.sim_mut().ok_or("the simulation is finished")?;
        for (j, &id) in st.slots.iter().enumerate() {
            if id == EMPTY {
                continue;
            }
            let a = actions[j].clamp(spec.a_low, spec.a_high);
            sim.command(
                id,
                Command::AccelerateCapped {
                    accel_mps2: a,
                    steps: spec.steps,
                },
            )
            .map_err(|e| format!("slot {j}: {e}"))?;
        }
    }
    step_world(inner, spec.steps)?;
    let before = std::mem::take(&mut st.on_road);
    let mut cols = std::mem::take(&mut inner.columns);
    let sim = inner.sim_ref().ok_or("the simulation is finished")?;
    sim.vehicle_columns(&mut cols);
    let mut out = Out::default();
    observe(&cols, &mut st, spec, length, origin, &mut out);
    // Left the road: on it before, not now (both sorted).
    out.outflow = before
        .iter()
        .filter(|id| st.on_road.binary_search(id).is_err())
        .count() as u64;
    let mean_v = if cols.is_empty() {
        0.0
    } else {
        cols.v_mps.iter().sum::<f64>() / cols.len() as f64
    };
    // The penalty on the accelerations the commanded vehicles applied in the last engine
    // step (after the cap), those still on the road.
    let (mut penalty, mut n) = (0.0, 0usize);
    for (i, id) in cols.id.iter().enumerate() {
        if commanded.contains(id) {
            penalty += (cols.a_mps2[i] / spec.a_high).powi(2);
            n += 1;
        }
    }
    let pen = if n > 0 { penalty / n as f64 } else { 0.0 };
    out.reward = mean_v / spec.v_ref - spec.accel_penalty * pen;
    out.collisions = sim.collisions() - collisions_before;
    out.done = sim.finished();
    inner.columns = cols;
    inner.control = st;
    Ok(out)
}
