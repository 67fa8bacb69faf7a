//! The gate task of `platoonsim/Platoon-v1` (python/platoonsim/gym.py; docs/learning.md): a
//! policy switches the engine's PD organizer on or off in the control section once per
//! decision interval, and is rewarded on the two quantities of the paper's question, measured
//! against a **twin**: the same road, seed and arrivals with the organizer off.
//!
//! A batch of the task has 2N worlds: world i < N is the policy's (or a baseline strategy's),
//! world i + N its twin. Both are stepped together; the arrivals of the two are the same
//! (per-entity random streams), so what differs is what the organization did.
//!
//! Per decision interval t (length Δ = `decision_s`, the detectors' aggregation interval):
//!
//! ```text
//! L̄_t  = Σ max_platoon / #CAVs, over the CAVs that left the road in t   (the paper's L̄)
//! Q_t  = vehicles counted by the discharge detector in t
//! g_t  = L̄_t / L̄_t^twin − 1        (0 if either world had no CAV leave)
//! c_t  = Q_t / Q_t^twin − 1         (0 if the twin counted none)
//! r_t  = g_t + λ · c_t
//! ```
//!
//! A policy that never organizes drives exactly the twin's traffic: every r_t is 0, bit for
//! bit. Over an episode the same sums give the paper's L̄ gain and discharge change
//! (`python/platoonsim/gym.py` accumulates them).
//!
//! **Observation** (8 values, float32, the policy world only; the twin is a counterfactual the
//! policy cannot see): for the first three detectors (upstream, control section, discharge on
//! the homogeneous road) the flow of the last interval in 1000 veh/h/lane (clipped to [0, 10])
//! and the time-mean speed in 100 km/h (0 if no vehicle crossed; clipped to [0, 3]); the share
//! of the control section's CAVs in the leftmost lane; their mean CACC string size / 10
//! (clipped to [0, 1]; a CAV's string size is the number of vehicles in its string now).
//!
//! | parameter | unit | default (gym.py) | meaning |
//! |---|---|---|---|
//! | `decision_s` Δ | s | 60 | decision interval = detector aggregation interval |
//! | `warmup_s` | s | 600 | organizer off, before the first decision (a multiple of Δ) |
//! | `decisions` | – | 60 | decisions per episode (one hour) |
//! | `discharge_penalty` λ | – | 5 | weight of the discharge change |

use crate::core::{step_world, Inner};

pub const FEATURES: usize = 8;
/// Upstream, control section, discharge: the first three detectors of the scenario.
pub const DETECTORS: usize = 3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Spec {
    /// Policy worlds N (the batch has 2N).
    pub n: usize,
    pub decision_steps: u64,
    pub warmup_steps: u64,
    pub decisions: u64,
    pub penalty: f64,
    /// The control section [from, to) in the output coordinate (m).
    pub zone: (f64, f64),
    /// The leftmost lane of the control section (engine index).
    pub leftmost: u32,
}

/// The CAVs counted by the paper's statistics (metrics.rs: as they leave the road; every
/// vehicle is in the measurement window, `run.warmup_s` = 0), for L̄.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ExitMeter {
    pub cavs: u64,
    pub platoon_sum: u64,
}

/// One world at a decision time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Measure {
    /// Per detector: veh/h/lane and km/h (0 if none crossed) of the last interval.
    pub flow_vphpl: [f64; DETECTORS],
    pub speed_kmh: [f64; DETECTORS],
    /// Vehicles the discharge detector counted in the last interval, and since the warm-up.
    pub discharge: u64,
    pub discharge_total: u64,
    pub leftmost_share: f64,
    pub string_size: f64,
    /// Mean speed of the vehicles on the road now (m/s; 0 on an empty road).
    pub mean_speed_mps: f64,
    /// The exit meter's totals since the warm-up (at the warm-up's end: since t = 0).
    pub exits: ExitMeter,
    pub collisions: u64,
    pub t_s: f64,
    pub done: bool,
}

impl Measure {
    pub fn obs(&self) -> [f32; FEATURES] {
        let mut o = [0f32; FEATURES];
        for k in 0..DETECTORS {
            o[k] = (self.flow_vphpl[k] / 1000.0).clamp(0.0, 10.0) as f32;
            o[DETECTORS + k] = (self.speed_kmh[k] / 100.0).clamp(0.0, 3.0) as f32;
        }
        o[6] = self.leftmost_share.clamp(0.0, 1.0) as f32;
        o[7] = (self.string_size / 10.0).clamp(0.0, 1.0) as f32;
        o
    }
}

/// What one decision interval gave a pair (policy world, twin).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Interval {
    pub l_gain: f64,
    pub discharge_change: f64,
    pub reward: f64,
}

/// `a / b − 1`, or 0 when the ratio is undefined.
fn change(a: f64, b: f64) -> f64 {
    if b > 0.0 && a.is_finite() {
        a / b - 1.0
    } else {
        0.0
    }
}

/// The interval's terms from the exit meters and discharge counts at its start (`*0`) and
/// end, for the policy world (`p`) and its twin (`t`).
pub fn interval(p0: &Measure, p1: &Measure, t0: &Measure, t1: &Measure, penalty: f64) -> Interval {
    let lbar = |m0: &Measure, m1: &Measure| {
        let n = m1.exits.cavs - m0.exits.cavs;
        (n > 0).then(|| (m1.exits.platoon_sum - m0.exits.platoon_sum) as f64 / n as f64)
    };
    let l_gain = match (lbar(p0, p1), lbar(t0, t1)) {
        (Some(a), Some(b)) => change(a, b),
        _ => 0.0,
    };
    let discharge_change = change(p1.discharge as f64, t1.discharge as f64);
    Interval {
        l_gain,
        discharge_change,
        reward: l_gain + penalty * discharge_change,
    }
}

/// Every CAV in `[zone.0, zone.1)`: (share in lane `leftmost`, mean size of their strings).
/// `x`, `lane`, `cav` and `string` are per vehicle; `string` is the id of its string's head.
pub fn zone_platoons(
    x: &[f64],
    lane: &[u32],
    cav: &[bool],
    string: &[u64],
    zone: (f64, f64),
    leftmost: u32,
) -> (f64, f64) {
    let mut heads: Vec<u64> = string.to_vec();
    heads.sort_unstable();
    let size = |h: u64| {
        let lo = heads.partition_point(|&s| s < h);
        let hi = heads.partition_point(|&s| s <= h);
        (hi - lo) as f64
    };
    let (mut n, mut left, mut sizes) = (0usize, 0usize, 0.0);
    for i in 0..x.len() {
        if cav[i] && x[i] >= zone.0 && x[i] < zone.1 {
            n += 1;
            left += usize::from(lane[i] == leftmost);
            sizes += size(string[i]);
        }
    }
    if n == 0 {
        (0.0, 1.0)
    } else {
        (left as f64 / n as f64, sizes / n as f64)
    }
}

/// The world now.
pub fn measure(inner: &mut Inner, spec: &Spec) -> Result<Measure, String> {
    let mut cols = std::mem::take(&mut inner.columns);
    let sim = inner.sim_ref().ok_or("the simulation is finished")?;
    sim.vehicle_columns(&mut cols);
    let cav: Vec<bool> = cols.kind.iter().map(|&k| k == 1).collect();
    let (leftmost_share, string_size) = zone_platoons(
        &cols.x_m,
        &cols.lane,
        &cav,
        &cols.platoon_id,
        spec.zone,
        spec.leftmost,
    );
    let mean_speed_mps = if cols.is_empty() {
        0.0
    } else {
        cols.v_mps.iter().sum::<f64>() / cols.len() as f64
    };
    let mut m = Measure {
        leftmost_share,
        string_size,
        mean_speed_mps,
        exits: ExitMeter {
            cavs: sim.metrics().cavs_counted,
            platoon_sum: sim.metrics().platoon_length_sum,
        },
        collisions: sim.collisions(),
        t_s: sim.time_s(),
        done: sim.finished(),
        ..Measure::default()
    };
    let recs = sim.latest_detector_records();
    // The detectors' "all" rows in scenario order; a detector's lanes are its other rows.
    let alls: Vec<_> = recs.iter().filter(|r| r.lane == "all").collect();
    for (k, r) in alls.iter().take(DETECTORS).enumerate() {
        let lanes = recs
            .iter()
            .filter(|q| q.detector == r.detector && q.lane != "all")
            .count()
            .max(1);
        m.flow_vphpl[k] = r.flow_vph / lanes as f64;
        m.speed_kmh[k] = r.speed_kmh.unwrap_or(0.0);
        if k == DETECTORS - 1 {
            m.discharge = r.count;
        }
    }
    inner.columns = cols;
    Ok(m)
}

/// Run a world to the end of the warm-up; it is measured there.
pub fn warm_up(inner: &mut Inner, spec: &Spec) -> Result<Measure, String> {
    let now = inner.sim_ref().map_or(0, |s| s.steps_done());
    step_world(inner, spec.warmup_steps.saturating_sub(now))?;
    measure(inner, spec)
}

/// One decision interval of a world; `start` is its measure at the warm-up's end, `last` at
/// the interval's start (totals since the warm-up).
pub fn advance(
    inner: &mut Inner,
    spec: &Spec,
    start: &Measure,
    last: &Measure,
) -> Result<Measure, String> {
    step_world(inner, spec.decision_steps)?;
    let mut m = measure(inner, spec)?;
    m.exits.cavs -= start.exits.cavs;
    m.exits.platoon_sum -= start.exits.platoon_sum;
    m.discharge_total = last.discharge_total + m.discharge;
    Ok(m)
}
