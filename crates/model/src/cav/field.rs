//! The field form of the CACC (`cav.cacc_law = "field"`, the default; docs/cacc-field.md): the
//! gap-error law as a speed reference that the car's low-level control tracks, with the
//! predecessor's acceleration fed forward (Ploeg et al. 2011; Naus et al. 2010), a kinematic
//! approach to a slower leader, and the ISO 15622 envelope. Parameters: the `cacc_field_gains`,
//! `cacc_feedforward`, `envelope_*` and `field_low_level_lag_s` rows of the table in `cav.rs`.
//!
//! ```text
//! CACC:       a = k_ff a_p + k_p e + k_d ė,  e = g − t_C v − s_min,  ė = Δv − t_C a
//!             (a_p: the predecessor's acceleration from its beacon; Ploeg et al. 2011, the
//!             static form of their controller, with the vehicle's own lag τ_a as the
//!             low-level loop); families and regimes labelled as in spec 3.4
//! approach:   a ≤ a_kin once a_kin ≤ −0.5 m/s² \[D\] (CACC and ACC), s = g − s_min, Δv = v − v_l,
//!             ã = min(a_l, 0) the leader's acceleration (beacon under CACC, radar estimate
//!             under ACC): the constant deceleration that matches the leader's speed at s_min
//!             if it keeps braking at ã until it stops (Kesting, Treiber & Helbing 2010's
//!             constant-acceleration heuristic):
//!               ã = 0:                     a_kin = −Δv² / (2 s)          (while Δv > 0)
//!               ã < 0, v_l Δv ≤ −2 s ã:    a_kin = v² ã / (v_l² − 2 s ã) (it stops first)
//!               ã < 0 otherwise:           a_kin = ã − Δv² / (2 s)
//!             (a standing queue at 250 m from 30 m/s: 1.8 m/s²)
//! lag:        the demand is tracked with the lag max(τ_a, τ_ll) (the car's low-level loop)
//! envelope:   a_cmd = max(a_req, −D(v)); a = max(lag(a_cmd), min(a_real, 0) − J(v) Δt);
//!             D, J linear in v between v_lo and v_hi (ISO 15622); a_req < −D: take-over
//!             request (counted); a_req < −D_auto: AEB (UN R152), as in spec 9.3 (counted)
//! cut-in:     on a cut-in or a ramp merge ahead of an automated CAV its effective time gap
//!             becomes min(t_eff, max(τ_r, (g − s_min)/v)) (the actual gap; v ≥ 1 m/s), and the
//!             spec 3.5 transition reopens it at `time_gap_ramp_per_s`; the safe gap rule and
//!             ramp insertion judge the follower by its law after this reset
//! ```

use super::{
    acc, cacc, cacc_family, speed_regulation, CaccLaw, CavMode, CavParams, Command, Family,
};
use crate::{bounded, Leader};

/// The deceleration (m/s², positive) from which on the kinematic approach binds
/// ([`approach_accel`]) \[D\]: below it the gap law alone closes the gap, so a follower a
/// little faster than a distant leader still closes up (docs/cacc-field.md).
pub const APPROACH_ONSET_MPS2: f64 = 0.5;

/// The kinematic approach of the field law (docs/cacc-field.md): the constant acceleration
/// that brings the follower to the leader's speed at s_min behind it, assuming the leader
/// keeps its acceleration `a_lead` while it brakes (until it stops) and its speed otherwise.
/// With s = g − s_min (at least 0.1 m; inside it the safety override governs), Δv = v − v_l
/// and ã = min(a_lead, 0):
///
/// - ã = 0 (the leader does not brake): −Δv² / (2 s) while v > v_l (a standing queue at
///   250 m from 30 m/s: 1.8 m/s²);
/// - ã < 0 and v_l Δv ≤ −2 s ã (the leader stops before the follower has matched its speed):
///   stop behind its stopping point, v² ã / (v_l² − 2 s ã);
/// - ã < 0 otherwise: match its speed while both brake, ã − Δv² / (2 s).
///
/// These are the three cases of the constant-acceleration heuristic of Kesting, Treiber &
/// Helbing (2010), here with the gap beyond s_min and used as a lower bound on the demand. It
/// binds once it reaches [`APPROACH_ONSET_MPS2`]; +∞ (no constraint) before. A NaN
/// acceleration counts as 0.
#[inline]
pub fn approach_accel(p: &CavParams, v: f64, leader: Leader, a_lead: f64) -> f64 {
    let (v, v_l) = (v.max(0.0), leader.v_mps.max(0.0));
    let s = (leader.gap_m - p.standstill_gap_m).max(0.1);
    let dv = v - v_l;
    let a = if a_lead < 0.0 {
        if v_l * dv <= -2.0 * s * a_lead {
            v * v * a_lead / (v_l * v_l - 2.0 * s * a_lead)
        } else {
            a_lead - dv * dv / (2.0 * s)
        }
    } else if dv > 0.0 {
        -(dv * dv) / (2.0 * s)
    } else {
        return f64::INFINITY;
    };
    if a <= -APPROACH_ONSET_MPS2 {
        a
    } else {
        f64::INFINITY
    }
}

/// The field form of the CACC (`cav.cacc_law = "field"`; docs/cacc-field.md): Ploeg et al.
/// (2011)'s one-vehicle look-ahead law in its static form,
/// a = k_ff a_p + k_p e + k_d ė, e = g − t_C v − s_min, ė = Δv − t_C a_own,
/// with `a_pred` = a_p the predecessor's acceleration from its beacon, then the kinematic
/// approach [`approach_accel`] as a lower envelope. The family hysteresis on tg is that of
/// [`cacc`]; in the speed family the cruise term is capped by the law and the approach. The
/// regime label: avoidance for e < 0, regulation in the band of spec 3.4 or while not
/// approaching, gap closing while approaching (Δv < 0).
// Inlined into the decide loop: with the braking-leader approach the compiler stopped doing
// so by itself, at +11 instructions per vehicle update (callgrind, docs/cacc-field.md).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn field_cacc(
    p: &CavParams,
    v: f64,
    a_own: f64,
    a_pred: f64,
    v_des: f64,
    leader: Leader,
    time_gap_s: f64,
    prev: Family,
) -> Command {
    let g = leader.gap_m;
    let vv = v.max(0.0);
    let e = g - time_gap_s * v - p.standstill_gap_m;
    let dv = leader.v_mps - v;
    let family = cacc_family(p, g, vv, e, prev);
    let [kp, kd] = p.cacc_field_gains;
    let law = p.cacc_feedforward * a_pred + kp * e + kd * (dv - time_gap_s * a_own);
    let approach = approach_accel(p, v, leader, a_pred);
    if family == Family::Speed {
        return Command {
            accel: bounded::min(speed_regulation(p, v, v_des).min(law), approach),
            mode: CavMode::SpeedRegulation,
            family,
        };
    }
    let mode = if e < 0.0 {
        CavMode::CollisionAvoidance
    } else if (e < p.reg_gap_band_m && dv.abs() < p.reg_speed_band_mps) || dv >= 0.0 {
        CavMode::GapRegulation
    } else {
        CavMode::GapClosing
    };
    Command {
        accel: bounded::min(law, approach),
        mode,
        family,
    }
}

/// The CACC of `p.cacc_law`: [`cacc`] (spec) or [`field_cacc`] (field; `a_pred` is read only
/// there).
#[allow(clippy::too_many_arguments)]
#[inline]
pub fn cacc_by_law(
    p: &CavParams,
    v: f64,
    a_own: f64,
    a_pred: f64,
    v_des: f64,
    leader: Leader,
    time_gap_s: f64,
    prev: Family,
) -> Command {
    match p.cacc_law {
        CaccLaw::Spec => cacc(p, v, a_own, v_des, leader, time_gap_s, prev),
        CaccLaw::Field => field_cacc(p, v, a_own, a_pred, v_des, leader, time_gap_s, prev),
    }
}

/// The ACC of `p.cacc_law`: [`acc`], under the field law with the kinematic approach
/// [`approach_accel`] as a lower envelope (a leader within the sensor range; `a_lead` its
/// acceleration as the radar estimates it, read only there).
#[inline]
pub fn acc_by_law(
    p: &CavParams,
    v: f64,
    v_des: f64,
    leader: Option<Leader>,
    a_lead: f64,
    time_gap_s: f64,
    prev: Family,
) -> Command {
    let mut c = acc(p, v, v_des, leader, time_gap_s, prev);
    if p.cacc_law == CaccLaw::Field {
        if let Some(l) = leader.filter(|l| l.gap_m <= p.sensor_range_m) {
            c.accel = bounded::min(c.accel, approach_accel(p, v, l, a_lead));
        }
    }
    c
}

/// The ISO 15622 envelope at speed v (field law): (D, J), the largest automatic deceleration
/// (m/s², positive) and the largest rate at which braking builds up (m/s³), linear in v
/// between `envelope_speeds_mps` and constant outside.
#[inline]
pub fn envelope(p: &CavParams, v: f64) -> (f64, f64) {
    let [v0, v1] = p.envelope_speeds_mps;
    let w = if v1 > v0 {
        ((v - v0) / (v1 - v0)).clamp(0.0, 1.0)
    } else if v >= v1 {
        1.0
    } else {
        0.0
    };
    let lerp = |[lo, hi]: [f64; 2]| lo + (hi - lo) * w;
    (lerp(p.envelope_decel_mps2), lerp(p.envelope_jerk_mps3))
}

/// What the field automation applies, and what it had to call: the demand `a_req` (the law
/// after the safety override and the limits) bounded by the ISO 15622 deceleration D, a_cmd =
/// max(a_req, −D), then the lag `gain` from `a_real`, then the jerk bound on the realized
/// acceleration, a ≥ min(a_real, 0) − J Δt (braking builds up at most at J; releasing the
/// throttle is not braking). A demand beyond −D asks the driver to take over (`tor`, counted;
/// the automation keeps braking at the envelope meanwhile). A demand beyond −`aeb_bound`
/// (D_auto) is an AEB intervention (UN R152): it applies `a_req` within the step, as
/// [`actuate`](super::actuate). Returns (a, aeb, tor).
#[inline]
pub fn actuate_field(
    a_real: f64,
    a_req: f64,
    gain: f64,
    aeb_bound: f64,
    (decel, jerk): (f64, f64),
    dt: f64,
) -> (f64, bool, bool) {
    if a_req < -aeb_bound {
        return (a_req, true, false);
    }
    let tor = a_req < -decel;
    let a_cmd = a_req.max(-decel);
    let lagged = if gain >= 1.0 {
        a_cmd
    } else {
        a_real + (a_cmd - a_real) * gain
    };
    (lagged.max(a_real.min(0.0) - jerk * dt), false, tor)
}

/// The effective time gap of an automated follower right after a vehicle cut in ahead of it at
/// net gap `gap_m` (field law; docs/cacc-field.md): the gap reference is reset to the actual
/// gap, t = (g − s_min)/v, not below τ_r (the safety override's own gap) nor above the
/// current reference; the time-gap transition (spec 3.5) then reopens it at
/// `time_gap_ramp_per_s`. Under the spec law, or below 1 m/s, `current` unchanged. A
/// non-positive `current` (no reference yet) is replaced by the reset value.
#[inline]
pub fn cut_in_time_gap(p: &CavParams, current: f64, gap_m: f64, v: f64) -> f64 {
    if p.cacc_law == CaccLaw::Spec || v < 1.0 {
        return current;
    }
    let actual = ((gap_m - p.standstill_gap_m) / v).max(p.reaction_s.max(0.0));
    if current > 0.0 {
        current.min(actual)
    } else {
        actual
    }
}
