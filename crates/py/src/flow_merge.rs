//! The task of `platoonsim/FlowMerge-v0` (python/platoonsim/flow_merge.py): Flow's merge
//! benchmark `merge0` (Vinitsky et al. 2018, "Benchmarks for reinforcement learning in
//! mixed-autonomy traffic", CoRL; flow-project/flow, `flow/benchmarks/merge0.py` with the
//! environment `MergePOEnv` of `flow/envs/merge.py` and the reward `desired_velocity` of
//! `flow/core/rewards.py`), computed in Rust for every world of a batch in parallel: which
//! learning vehicles the policy drives, their observations and commands, the reward.
//!
//! * **The controlled list** (Flow's `rl_veh`, at most `k` = num_rl vehicles). After each
//!   action the learning vehicles (CAVs) that left the road leave the list and the later ones
//!   move up; CAVs on the road not in the list join its end in order of entry (Flow's
//!   `rl_queue`, first in first out; ids increase in order of entry). Slot `j` of the
//!   observation and the action is the list's `j`-th vehicle.
//! * **Observation** of slot `j` (5 values, 0 for an empty slot), with v_max the speed limit
//!   and L_net the network's length:
//!
//! ```text
//! o = [ v / v_max,  (v_lead − v) / v_max,  g_lead / L_net,  (v − v_fol) / v_max,  g_fol / L_net ]
//! no leader:   v_lead = v_max, g_lead = L_net;     no follower: v_fol = 0, g_fol = L_net
//! clipped:     speeds to [0, 2], differences to [−2, 2], gaps to [0, 1]
//! ```
//!
//!   Gaps are bumper to bumper (Flow's headways; its lead gap subtracts the ego's length, the
//!   same with its equal lengths).
//! * **Action** of slot `j`: an acceleration clipped to [−d_max, a_max], applied for the
//!   action's engine steps as `Command::AccelerateSafe`: within the vehicle's limits and never
//!   above its collision-free speed (SUMO's speed mode 9 in Flow, which regards the safe
//!   speed). Empty slots' actions are ignored. Learning vehicles beyond the list drive by their
//!   own ACC/CACC law (Flow leaves them to SUMO's car following, the humans' model).
//! * **Reward** of an action, after its engine steps, over every vehicle on the road (n of
//!   them, speeds v_i) and the controlled list:
//!
//! ```text
//! r1 = max(‖v* 1‖ − ‖v − v* 1‖, 0) / (‖v* 1‖ + ε)        Flow's desired_velocity; 0 if n = 0
//! r2 = Σ_{j in the list, with a leader, v_j > 0} min((h_j / v_j − t_min) / t_min, 0)
//! r  = max(η1 r1 + η2 r2, 0);   r = 0 in a step with a collision (Flow's `fail`)
//! ```
//!
//! | symbol | field | default | unit | source |
//! |---|---|---|---|---|
//! | num_rl | `k` | 5 | vehicles | merge0 `NUM_RL` |
//! | – | `steps` | 10 (1 s at Δt = 0.1 s) | engine steps | merge0: sim_step 0.5 s × sims_per_step 2 |
//! | v_max | `max_speed` | 30 | m/s | `MergeNetwork` speed limit (Flow's `max_speed()`) |
//! | L_net | `max_length` | 900 | m | the sum of merge0's edges: 100 + 500 + 100 highway, 100 + 100 merge (Flow's `length()`, without SUMO's junction lanes) |
//! | v* | `target_v` | 20 | m/s | merge0 `target_velocity` |
//! | t_min | `t_min` | 1 | s | `MergePOEnv.compute_reward` |
//! | η1, η2 | `eta1`, `eta2` | 1.0, 0.1 | – | `MergePOEnv.compute_reward` |
//! | ε | – | 1.19e-7 | – | `np.finfo(np.float32).eps` in `desired_velocity` |
//! | a_max, d_max | `a_high`, `−a_low` | 1.5, 1.5 | m/s² | merge0 `max_accel`, `max_decel` |

use crate::core::{step_world, Inner};
use platoonsim_sim::snapshot::VehicleColumns;
use platoonsim_sim::Command;

pub const FEATURES: usize = 5;

/// ε of Flow's `desired_velocity`: float32's machine epsilon.
const EPS: f64 = f32::EPSILON as f64;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spec {
    pub k: usize,
    pub steps: u64,
    pub max_speed: f64,
    pub max_length: f64,
    pub target_v: f64,
    pub t_min: f64,
    pub eta1: f64,
    pub eta2: f64,
    pub a_low: f64,
    pub a_high: f64,
    /// Command the listed vehicles (false: the `acc-only` baseline, actions ignored).
    pub control: bool,
}

impl Spec {
    /// The spec's values are usable (the Python side names the arguments first).
    pub fn check(&self) -> Result<(), String> {
        let pos = [
            self.max_speed,
            self.max_length,
            self.target_v,
            self.t_min,
            self.a_high,
        ];
        let ok = (1..=1024).contains(&self.k)
            && self.steps >= 1
            && pos.iter().all(|v| v.is_finite() && *v > 0.0)
            && [self.eta1, self.eta2].iter().all(|v| v.is_finite())
            && self.a_low.is_finite()
            && self.a_low < 0.0;
        if ok {
            Ok(())
        } else {
            Err(format!("flow_setup: invalid task parameters {self:?}"))
        }
    }
}

/// A world's task state.
#[derive(Clone, Debug, Default)]
pub struct State {
    /// The controlled list, in Flow's order (at most `k`).
    list: Vec<u64>,
    /// Ids on the road after the last action, sorted (for the outflow).
    on_road: Vec<u64>,
    started: bool,
}

/// What one action returns for one world.
#[derive(Clone, Debug, Default)]
pub struct Out {
    pub obs: Vec<f32>,
    /// The vehicle id in each slot, −1 for an empty one.
    pub ids: Vec<i64>,
    pub reward: f64,
    /// Mean speed of the vehicles on the road (m/s; 0 on an empty road).
    pub mean_v: f64,
    /// Vehicles on the road.
    pub vehicles: u64,
    /// Vehicles that left the road during the action.
    pub outflow: u64,
    pub collisions: u64,
    pub done: bool,
}

/// Index of each id in the columns, sorted by id.
fn index(c: &VehicleColumns) -> Vec<(u64, usize)> {
    let mut by_id: Vec<(u64, usize)> = c.id.iter().copied().zip(0..).collect();
    by_id.sort_unstable();
    by_id
}

fn find(by_id: &[(u64, usize)], id: u64) -> Option<usize> {
    by_id
        .binary_search_by_key(&id, |p| p.0)
        .ok()
        .map(|i| by_id[i].1)
}

/// Update the list from the road now (Flow's `additional_command`), then the observation, the
/// reward and the bookkeeping of `out`.
fn observe(c: &VehicleColumns, st: &mut State, spec: &Spec, out: &mut Out) {
    let by_id = index(c);
    st.list.retain(|&id| find(&by_id, id).is_some());
    for &(id, i) in &by_id {
        if st.list.len() >= spec.k {
            break;
        }
        if c.kind[i] == 1 && !st.list.contains(&id) {
            st.list.push(id);
        }
    }
    // Followers: the vehicle whose leader is i.
    let mut follower = vec![usize::MAX; c.len()];
    for j in 0..c.len() {
        if let Some(i) = c.leader_id[j].and_then(|l| find(&by_id, l)) {
            follower[i] = j;
        }
    }
    let (vm, lm) = (spec.max_speed, spec.max_length);
    out.obs.clear();
    out.obs.resize(spec.k * FEATURES, 0.0);
    out.ids.clear();
    out.ids.resize(spec.k, -1);
    let mut headway_cost = 0.0;
    for (j, &id) in st.list.iter().enumerate() {
        let Some(i) = find(&by_id, id) else { continue };
        out.ids[j] = id as i64;
        let v = c.v_mps[i];
        let lead = c.leader_id[i].and_then(|l| find(&by_id, l));
        let (v_lead, g_lead) = match lead {
            Some(l) => (c.v_mps[l], c.x_m[l] - c.length_m[l] - c.x_m[i]),
            None => (vm, lm),
        };
        let (v_fol, g_fol) = match follower[i] {
            usize::MAX => (0.0, lm),
            f => (c.v_mps[f], c.x_m[i] - c.length_m[i] - c.x_m[f]),
        };
        let clip = |x: f64, lo: f64, hi: f64| x.clamp(lo, hi) as f32;
        let o = &mut out.obs[j * FEATURES..(j + 1) * FEATURES];
        o[0] = clip(v / vm, 0.0, 2.0);
        o[1] = clip((v_lead - v) / vm, -2.0, 2.0);
        o[2] = clip(g_lead / lm, 0.0, 1.0);
        o[3] = clip((v - v_fol) / vm, -2.0, 2.0);
        o[4] = clip(g_fol / lm, 0.0, 1.0);
        if lead.is_some() && v > 0.0 {
            let t_headway = (g_lead / v).max(0.0);
            headway_cost += ((t_headway - spec.t_min) / spec.t_min).min(0.0);
        }
    }
    // Flow's desired_velocity over every vehicle on the road.
    let n = c.len();
    let r1 = if n == 0 {
        0.0
    } else {
        let max_cost = spec.target_v * (n as f64).sqrt();
        let cost = c
            .v_mps
            .iter()
            .map(|v| (v - spec.target_v).powi(2))
            .sum::<f64>()
            .sqrt();
        (max_cost - cost).max(0.0) / (max_cost + EPS)
    };
    out.reward = (spec.eta1 * r1 + spec.eta2 * headway_cost).max(0.0);
    out.vehicles = n as u64;
    out.mean_v = if n == 0 {
        0.0
    } else {
        c.v_mps.iter().sum::<f64>() / n as f64
    };
    st.on_road.clear();
    st.on_road.extend_from_slice(&c.id);
    st.on_road.sort_unstable();
}

/// Start (or restart) the task in a world: the first observation (reward as if after an
/// action, for the record; the environments return 0 at a reset).
pub fn start(inner: &mut Inner, spec: &Spec) -> Result<Out, String> {
    let mut st = State {
        started: true,
        ..State::default()
    };
    let mut out = Out::default();
    let mut cols = std::mem::take(&mut inner.columns);
    let sim = inner.sim_ref().ok_or("the simulation is finished")?;
    sim.vehicle_columns(&mut cols);
    observe(&cols, &mut st, spec, &mut out);
    out.done = sim.finished();
    inner.columns = cols;
    inner.flow_merge = st;
    Ok(out)
}

/// One action: the commands of the listed vehicles, `spec.steps` engine steps, the new list,
/// observation and reward.
pub fn step(inner: &mut Inner, spec: &Spec, actions: &[f64]) -> Result<Out, String> {
    let mut st = std::mem::take(&mut inner.flow_merge);
    if !st.started {
        return Err("the task was not started (reset first)".into());
    }
    let collisions_before = inner.sim_ref().map_or(0, |s| s.collisions());
    if spec.control {
        let sim = inner.sim_mut().ok_or("the simulation is finished")?;
        for (j, &id) in st.list.iter().enumerate() {
            let a = actions[j].clamp(spec.a_low, spec.a_high);
            sim.command(
                id,
                Command::AccelerateSafe {
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
    observe(&cols, &mut st, spec, &mut out);
    // Left the road: on it before, not now (both sorted).
    out.outflow = before
        .iter()
        .filter(|id| st.on_road.binary_search(id).is_err())
        .count() as u64;
    out.collisions = sim.collisions() - collisions_before;
    if out.collisions > 0 {
        out.reward = 0.0; // Flow's `fail`
    }
    out.done = sim.finished();
    inner.columns = cols;
    inner.flow_merge = st;
    Ok(out)
}
