//! Entrance demands and exit fractions of a corridor from field counts: per demand interval,
//! the flows at the mainline entrance and at every on-ramp (veh/h) and the share of the
//! mainline flow taken by every off-ramp, estimated by non-negative least squares on the
//! counts under flow conservation along the corridor. The output is what a `[network]`
//! scenario's `mainline_vph`, on-ramp `demand_vph` and off-ramp `exit_fraction` series need
//! (docs/network-scenarios.md).
//!
//! **Model** (one interval). Unknowns u ≥ 0: the entrance flow q₀, each on-ramp's flow rᵢ and
//! each off-ramp's exit flow eⱼ. The mainline flow just upstream of x is the instantaneous
//! balance
//!
//! q(x) = q₀ + Σ_{on-ramps i: xᵢ < x} rᵢ − Σ_{off-ramps j: xⱼ < x} eⱼ,
//!
//! so every mainline station at x gives an equation q(x) = its flow, and every measured ramp
//! an equation rᵢ = count (or eⱼ = count) with weight `RAMP_WEIGHT`, so measured ramps keep
//! their counts while the mainline stations, the entrance and the unmeasured ramps absorb the
//! disagreements. The weighted problem min ‖W(Au − b)‖² + λ‖u‖², u ≥ 0, is solved by the
//! active-set NNLS of Lawson & Hanson (1974, ch. 23); the tiny ridge λ makes the solution
//! unique where the counts cannot tell two unknowns apart (an unmeasured on-ramp and an
//! unmeasured off-ramp between the same two stations), choosing the smallest flows.
//!
//! **Storage** (issue 45 item 4). The balance above is instantaneous; flow is conserved only
//! with the vehicles stored on the road: what entered upstream of x and has not passed x is
//! still between them. Counts inside a queue are its discharge, not the demand, while the
//! queue grows. So a station's equation, when the caller gives the growth rate G(x) of the
//! vehicles stored on the mainline between the entrance and x (veh/h, `Counts::storage_vph`),
//! reads q(x) = count + G(x): the demand that arrived upstream is what passed plus what
//! queued. [`stored_vehicles`] gives the storage from the stations' densities (k = q/v); the
//! caller differences it between intervals. Without it (no speeds), this is the uncongested
//! balance, in the spirit of SUMO's routeSampler, and in a queue the estimate is the served
//! flow.
//!
//! The exit fraction of off-ramp j is eⱼ / (q(xⱼ) − G(xⱼ)) (the flow arriving at its diverge:
//! the demand upstream less what queued before it, G interpolated between the stations),
//! clamped to [0, 1]; 0 where no flow arrives.
//!
//! | parameter | value | unit |
//! |---|---|---|
//! | `RAMP_WEIGHT` (w) | 100 | – (a ramp residual costs w² times a mainline one) |
//! | `RIDGE` (λ) | 1e-9 | – (relative to a mainline equation of weight 1) |

use nalgebra::{DMatrix, DVector};

/// Weight of a measured ramp's equation relative to a mainline station's.
pub const RAMP_WEIGHT: f64 = 100.0;
/// The ridge term that makes the solution unique (see the module documentation).
pub const RIDGE: f64 = 1e-9;

/// The corridor as plain data (positions in one coordinate, m; ramps in downstream order).
#[derive(Clone, Debug, PartialEq)]
pub struct Corridor {
    pub entrance_x: f64,
    /// (id, x) of every on-ramp's merge.
    pub on_ramps: Vec<(String, f64)>,
    /// (id, x) of every off-ramp's diverge.
    pub off_ramps: Vec<(String, f64)>,
}

/// The counts of one interval.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Counts {
    /// (x, flow in veh/h) of every mainline station with a count.
    pub mainline: Vec<(f64, f64)>,
    /// Parallel to `mainline` (or empty: all 0): the growth rate G(x) of the vehicles stored
    /// on the mainline between the entrance and the station over the interval (veh/h; < 0
    /// while a queue drains). The station's equation is q(x) = count + G(x).
    pub storage_vph: Vec<f64>,
    /// (ramp id, flow in veh/h) of every measured on- or off-ramp.
    pub ramps: Vec<(String, f64)>,
}

/// The estimate, series by interval.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Estimate {
    /// Entrance flow (veh/h) per interval.
    pub mainline_vph: Vec<f64>,
    /// Per on-ramp (corridor order), flow (veh/h) per interval.
    pub on_ramp_vph: Vec<Vec<f64>>,
    /// Per off-ramp (corridor order), exit fraction per interval.
    pub exit_fraction: Vec<Vec<f64>>,
    /// Per off-ramp, exit flow (veh/h) per interval.
    pub exit_vph: Vec<Vec<f64>>,
}

/// Why the counts cannot be used: the message names the ramp id or the interval.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("demand estimate: {0}")]
pub struct DemandError(pub String);

/// Estimate every interval (see the module documentation).
pub fn estimate(c: &Corridor, intervals: &[Counts]) -> Result<Estimate, DemandError> {
    let (n_on, n_off) = (c.on_ramps.len(), c.off_ramps.len());
    let mut out = Estimate {
        on_ramp_vph: vec![Vec::new(); n_on],
        exit_fraction: vec![Vec::new(); n_off],
        exit_vph: vec![Vec::new(); n_off],
        ..Estimate::default()
    };
    for (k, counts) in intervals.iter().enumerate() {
        let u = solve_interval(c, counts).map_err(|m| DemandError(format!("interval {k}: {m}")))?;
        out.mainline_vph.push(u[0]);
        for i in 0..n_on {
            out.on_ramp_vph[i].push(u[1 + i]);
        }
        for (j, (_, x)) in c.off_ramps.iter().enumerate() {
            let e = u[1 + n_on + j];
            // What arrives at the diverge: the demand upstream less what queued before it.
            let arriving = balance(c, &u, *x) - storage_at(c, counts, *x);
            let f = if arriving > 0.0 {
                (e / arriving).clamp(0.0, 1.0)
            } else {
                0.0
            };
            out.exit_fraction[j].push(f);
            out.exit_vph[j].push(e);
        }
    }
    Ok(out)
}

/// G(x): the storage growth between the entrance and x, linear between the stations that
/// give one (0 at the entrance, the last station's beyond it); 0 without any.
fn storage_at(c: &Corridor, counts: &Counts, x: f64) -> f64 {
    let mut pts: Vec<(f64, f64)> = counts
        .mainline
        .iter()
        .zip(&counts.storage_vph)
        .map(|(&(xs, _), &g)| (xs, g))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut prev = (c.entrance_x, 0.0);
    for &(xs, g) in &pts {
        if x <= xs {
            let w = if xs > prev.0 {
                (x - prev.0) / (xs - prev.0)
            } else {
                1.0
            };
            return prev.1 + w * (g - prev.1);
        }
        prev = (xs, g);
    }
    prev.1
}

/// q(x): the mainline flow just upstream of x under the unknowns u.
pub fn balance(c: &Corridor, u: &[f64], x: f64) -> f64 {
    let n_on = c.on_ramps.len();
    let mut q = u[0];
    for (i, (_, xi)) in c.on_ramps.iter().enumerate() {
        if *xi < x {
            q += u[1 + i];
        }
    }
    for (j, (_, xj)) in c.off_ramps.iter().enumerate() {
        if *xj < x {
            q -= u[1 + n_on + j];
        }
    }
    q
}

fn solve_interval(c: &Corridor, counts: &Counts) -> Result<Vec<f64>, String> {
    let (n_on, n_off) = (c.on_ramps.len(), c.off_ramps.len());
    let n = 1 + n_on + n_off;
    let mut rows: Vec<(Vec<f64>, f64)> = Vec::new();
    for (s, &(x, q)) in counts.mainline.iter().enumerate() {
        if !(q.is_finite() && q >= 0.0) {
            return Err(format!("the mainline count at x = {x} m is {q}"));
        }
        let g = counts.storage_vph.get(s).copied().unwrap_or(0.0);
        if !g.is_finite() {
            return Err(format!("the storage growth at x = {x} m is {g}"));
        }
        if x <= c.entrance_x {
            return Err(format!(
                "a mainline station at x = {x} m is not downstream of the entrance at {} m",
                c.entrance_x
            ));
        }
        let mut a = vec![0.0; n];
        a[0] = 1.0;
        for (i, (_, xi)) in c.on_ramps.iter().enumerate() {
            a[1 + i] = f64::from(u8::from(*xi < x));
        }
        for (j, (_, xj)) in c.off_ramps.iter().enumerate() {
            a[1 + n_on + j] = -f64::from(u8::from(*xj < x));
        }
        rows.push((a, q + g));
    }
    for (id, q) in &counts.ramps {
        let col = c
            .on_ramps
            .iter()
            .position(|(r, _)| r == id)
            .map(|i| 1 + i)
            .or_else(|| {
                c.off_ramps
                    .iter()
                    .position(|(r, _)| r == id)
                    .map(|j| 1 + n_on + j)
            })
            .ok_or_else(|| {
                let ids: Vec<&str> = c
                    .on_ramps
                    .iter()
                    .chain(&c.off_ramps)
                    .map(|(r, _)| r.as_str())
                    .collect();
                format!(
                    "no ramp '{id}' on the corridor; its ramps are {}",
                    ids.join(", ")
                )
            })?;
        if !(q.is_finite() && *q >= 0.0) {
            return Err(format!("the count of ramp '{id}' is {q}"));
        }
        let mut a = vec![0.0; n];
        a[col] = RAMP_WEIGHT;
        rows.push((a, RAMP_WEIGHT * q));
    }
    if rows.is_empty() {
        return Err("no count at all".into());
    }
    // Ridge rows: sqrt(λ) u ≈ 0.
    let ridge = RIDGE.sqrt();
    for k in 0..n {
        let mut a = vec![0.0; n];
        a[k] = ridge;
        rows.push((a, 0.0));
    }
    let a = DMatrix::from_fn(rows.len(), n, |r, k| rows[r].0[k]);
    let b = DVector::from_iterator(rows.len(), rows.iter().map(|r| r.1));
    Ok(nnls(&a, &b).iter().copied().collect())
}

/// Vehicles stored on the mainline between the entrance (x = 0) and `x`, from the densities
/// (veh/km, all lanes) at stations `(x, k)` sorted by position: k is taken constant from the
/// entrance to the first station and linear between stations (the trapezoid rule); 0 without
/// a station at or before `x`; stations past `x` are not counted.
pub fn stored_vehicles(stations: &[(f64, f64)], x: f64) -> f64 {
    let mut n = 0.0;
    let mut prev: Option<(f64, f64)> = None;
    for &(xs, k) in stations {
        if xs > x {
            break;
        }
        n += match prev {
            None => k * xs / 1000.0,
            Some((xp, kp)) => 0.5 * (kp + k) * (xs - xp) / 1000.0,
        };
        prev = Some((xs, k));
    }
    n
}

/// min ‖Ax − b‖ subject to x ≥ 0: Lawson & Hanson's active-set algorithm (1974, ch. 23).
/// `a` must have full column rank (the ridge rows make it so).
pub fn nnls(a: &DMatrix<f64>, b: &DVector<f64>) -> DVector<f64> {
    let n = a.ncols();
    let mut x = DVector::zeros(n);
    let mut passive = vec![false; n];
    let scale = (a.transpose() * b).amax().max(1.0);
    let tol = 1e-12 * scale;
    for _ in 0..3 * n + 10 {
        let w = a.transpose() * (b - a * &x);
        let next = (0..n)
            .filter(|&j| !passive[j] && w[j] > tol)
            .max_by(|&i, &j| w[i].total_cmp(&w[j]));
        let Some(j) = next else { break };
        passive[j] = true;
        loop {
            let z = restricted_ls(a, b, &passive);
            let blocking: Vec<usize> = (0..n).filter(|&i| passive[i] && z[i] <= 0.0).collect();
            if blocking.is_empty() {
                x = z;
                break;
            }
            let alpha = blocking
                .iter()
                .map(|&i| x[i] / (x[i] - z[i]))
                .fold(f64::INFINITY, f64::min);
            x = &x + (z - &x) * alpha;
            for i in 0..n {
                if passive[i] && x[i] <= tol / scale {
                    passive[i] = false;
                    x[i] = 0.0;
                }
            }
        }
    }
    x
}

/// Least squares on the passive columns (the others held at 0).
fn restricted_ls(a: &DMatrix<f64>, b: &DVector<f64>, passive: &[bool]) -> DVector<f64> {
    let cols: Vec<usize> = (0..a.ncols()).filter(|&j| passive[j]).collect();
    if cols.is_empty() {
        return DVector::zeros(a.ncols());
    }
    let sub = DMatrix::from_fn(a.nrows(), cols.len(), |r, k| a[(r, cols[k])]);
    let sol = sub
        .svd(true, true)
        .solve(b, 1e-14)
        .unwrap_or_else(|_| DVector::zeros(cols.len()));
    let mut z = DVector::zeros(a.ncols());
    for (k, &j) in cols.iter().enumerate() {
        z[j] = sol[k];
    }
    z
}

#[cfg(test)]
#[path = "demand_tests.rs"]
mod tests;
