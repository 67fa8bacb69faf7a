//! Validation of the model sections `[human]`, `[cav]` and `[lane_change]` (ranges of every
//! parameter, well-formed distributions), split from `validate.rs` by responsibility.

use super::Checker;
use crate::limits;
use crate::raw::num;
use platoonsim_model::cav::CavParams;
use platoonsim_model::human::HumanDists;
use platoonsim_model::lanechange::LaneChangeDists;
use platoonsim_model::safety::{SafetyParams, MAX_EMERGENCY_DECEL_MPS2, MAX_TTC_THRESHOLD_S};
use toml::Value;

/// Report every non-finite number (TOML allows `nan` and `inf`) and every number beyond
/// [`limits::MAX_MODEL_MAGNITUDE`] in a model section; true if there is none.
pub(super) fn all_finite<T: serde::Serialize>(c: &mut Checker, section: &str, params: &T) -> bool {
    fn walk(c: &mut Checker, path: &str, v: &Value, ok: &mut bool) {
        match v {
            Value::Float(f) if !f.is_finite() => {
                c.push(path, num(*f), "must be a finite number");
                *ok = false;
            }
            // No physical parameter comes near the bound; beyond it products of parameters
            // overflow or a loop over (say) a platoon size never ends.
            Value::Float(f) if f.abs() > limits::MAX_MODEL_MAGNITUDE => {
                c.push(path, num(*f), magnitude());
                *ok = false;
            }
            Value::Integer(i) if i.unsigned_abs() as f64 > limits::MAX_MODEL_MAGNITUDE => {
                c.push(path, i.to_string(), magnitude());
                *ok = false;
            }
            Value::Table(t) => {
                for (k, v) in t {
                    walk(c, &format!("{path}.{k}"), v, ok);
                }
            }
            Value::Array(items) => {
                for (i, v) in items.iter().enumerate() {
                    walk(c, &format!("{path}[{i}]"), v, ok);
                }
            }
            _ => {}
        }
    }
    fn magnitude() -> String {
        format!(
            "must be in [-{m}, {m}]",
            m = num(limits::MAX_MODEL_MAGNITUDE)
        )
    }
    let mut ok = true;
    match Value::try_from(params) {
        Ok(v) => walk(c, section, &v, &mut ok),
        Err(e) => {
            c.push(section, "-", format!("cannot be represented: {e}"));
            ok = false;
        }
    }
    ok
}

pub(super) fn check_human(c: &mut Checker, h: &HumanDists) {
    c.dist(
        "human.length_m",
        &h.length_m,
        Some((h.length_m.min > 0.0, "min must be > 0 m")),
    );
    c.dist(
        "human.jam_gap_m",
        &h.jam_gap_m,
        Some((h.jam_gap_m.min >= 0.0, "min must be >= 0 m")),
    );
    c.dist(
        "human.headway_s",
        &h.headway_s,
        Some((h.headway_s.min > 0.0, "min must be > 0 s")),
    );
    c.dist(
        "human.reaction_s",
        &h.reaction_s,
        Some((h.reaction_s.min > 0.0, "min must be > 0 s")),
    );
    c.dist(
        "human.max_accel",
        &h.max_accel,
        Some((
            h.max_accel.min > 0.0,
            "min must be > 0 m/s² (an acceleration)",
        )),
    );
    c.dist(
        "human.max_decel",
        &h.max_decel,
        Some((
            h.max_decel.max < 0.0,
            "max must be < 0 m/s² (decelerations are negative)",
        )),
    );
    c.dist(
        "human.desired_speed_kmh",
        &h.desired_speed_kmh,
        Some((
            h.desired_speed_kmh.min > 0.0 && h.desired_speed_kmh.max <= 300.0,
            "must lie in (0, 300] km/h",
        )),
    );
    c.value(
        "human.buffer_s",
        h.buffer_s,
        h.buffer_s >= 0.0,
        "must be >= 0 s",
    );
    c.value(
        "human.leader_brake_factor",
        h.leader_brake_factor,
        h.leader_brake_factor > 0.0,
        "must be > 0",
    );
    c.value(
        "human.free_exponent",
        h.free_exponent,
        h.free_exponent > 0.0,
        "must be > 0",
    );
    c.value(
        "human.smoothing",
        h.smoothing,
        h.smoothing >= 1.0,
        "must be >= 1 (1 = no smoothing)",
    );
    c.value(
        "human.comfort_factor",
        h.comfort_factor,
        h.comfort_factor > 0.0 && h.comfort_factor <= 1.0,
        "must be in (0, 1] (a fraction of max_decel)",
    );
    // b_e no weaker than the hardest normal limit a driver can draw.
    emergency_decel(
        c,
        "human.emergency_decel_mps2",
        h.emergency_decel_mps2,
        -h.max_decel.min,
        "the hardest normal limit a driver draws, -human.max_decel.min",
    );
}

/// b_e (positive, m/s²) in (normal, `MAX_EMERGENCY_DECEL_MPS2`]: a negative value would make
/// the braking limit an acceleration, one at or below the normal limit b would cut the laws
/// short and hide every emergency braking (none can exceed b) (docs/safety.md).
fn emergency_decel(c: &mut Checker, field: &str, b_e: f64, normal: f64, what: &str) {
    let lo = normal.max(0.0);
    c.value(
        field,
        b_e,
        b_e > 0.0 && b_e > lo && b_e <= MAX_EMERGENCY_DECEL_MPS2,
        &format!(
            "must be in ({}, {}] m/s²: positive (a deceleration, as SUMO's emergencyDecel), \
             harder than {what} = {}, at most about 1.2 g",
            num(lo),
            num(MAX_EMERGENCY_DECEL_MPS2),
            num(normal)
        ),
    );
}

/// `[safety]`: TTC* in (0, `MAX_TTC_THRESHOLD_S`] s.
pub(super) fn check_safety(c: &mut Checker, p: &SafetyParams) {
    c.value(
        "safety.ttc_threshold_s",
        p.ttc_threshold_s,
        p.ttc_threshold_s > 0.0 && p.ttc_threshold_s <= MAX_TTC_THRESHOLD_S,
        &format!(
            "must be in (0, {}] s (FHWA SSAM uses 1.5 s)",
            num(MAX_TTC_THRESHOLD_S)
        ),
    );
}

pub(super) fn check_cav(c: &mut Checker, p: &CavParams) {
    let pos = |c: &mut Checker, f: &str, v: f64| c.value(f, v, v > 0.0, "must be > 0");
    let nonneg = |c: &mut Checker, f: &str, v: f64| c.value(f, v, v >= 0.0, "must be >= 0");
    pos(c, "cav.speed_gain", p.speed_gain);
    pos(c, "cav.acc_time_gap_s", p.acc_time_gap_s);
    for (f, g) in [
        ("cav.acc_reg_gains", p.acc_reg_gains),
        ("cav.acc_closing_gains", p.acc_closing_gains),
        ("cav.acc_avoid_gains", p.acc_avoid_gains),
        ("cav.cacc_reg_gains", p.cacc_reg_gains),
        ("cav.cacc_closing_gains", p.cacc_closing_gains),
        ("cav.cacc_avoid_gains", p.cacc_avoid_gains),
    ] {
        if !(g[0] >= 0.0 && g[1] >= 0.0) {
            c.push(f, pair(g), "both gains must be >= 0");
        }
    }
    for (f, b, unit) in [
        ("cav.acc_range_m", p.acc_range_m, "m"),
        ("cav.cacc_tg_band_s", p.cacc_tg_band_s, "s"),
    ] {
        if !(b[0] > 0.0 && b[0] <= b[1]) {
            c.push(
                f,
                pair(b),
                format!("must be [low, high] with 0 < low <= high ({unit})"),
            );
        }
    }
    nonneg(c, "cav.speed_control_min_gap_m", p.speed_control_min_gap_m);
    nonneg(c, "cav.reg_gap_band_m", p.reg_gap_band_m);
    nonneg(c, "cav.reg_speed_band_mps", p.reg_speed_band_mps);
    nonneg(c, "cav.standstill_gap_m", p.standstill_gap_m);
    nonneg(c, "cav.reaction_s", p.reaction_s);
    nonneg(c, "cav.time_gap_ramp_per_s", p.time_gap_ramp_per_s);
    c.value(
        "cav.max_accel",
        p.max_accel,
        p.max_accel > 0.0,
        "must be > 0 m/s²",
    );
    c.value(
        "cav.max_decel",
        p.max_decel,
        p.max_decel < 0.0,
        "must be < 0 m/s² (decelerations are negative)",
    );
    emergency_decel(
        c,
        "cav.emergency_decel_mps2",
        p.emergency_decel_mps2,
        -p.max_decel,
        "the normal limit -cav.max_decel",
    );
    pos(c, "cav.inter_platoon_gap_s", p.inter_platoon_gap_s);
    if !(1..=limits::MAX_PLATOON).contains(&p.max_platoon) {
        c.push(
            "cav.max_platoon",
            p.max_platoon.to_string(),
            format!("must be 1 to {} vehicles", limits::MAX_PLATOON),
        );
    }
    pos(c, "cav.sensor_range_m", p.sensor_range_m);
    // Spec 9.2: the cooperative deceleration is a comfortable one, positive and within the
    // normal braking b; the request timeout a positive time of at most 10 min.
    let b = -p.max_decel;
    c.value(
        "cav.cooperative_gap_decel_mps2",
        p.cooperative_gap_decel_mps2,
        p.cooperative_gap_decel_mps2 > 0.0 && p.cooperative_gap_decel_mps2 <= b,
        &format!(
            "must be in (0, {}] m/s² (positive, at most -cav.max_decel)",
            num(b)
        ),
    );
    c.value(
        "cav.cooperative_timeout_s",
        p.cooperative_timeout_s,
        p.cooperative_timeout_s > 0.0 && p.cooperative_timeout_s <= 600.0,
        "must be in (0, 600] s",
    );
    // 6.20: the hold's timeout is a positive time of at most 10 min (0 would be `off` below
    // the creep speed: say so with the key instead).
    c.value(
        "cav.organize_hold_timeout_s",
        p.organize_hold_timeout_s,
        p.organize_hold_timeout_s > 0.0 && p.organize_hold_timeout_s <= 600.0,
        "must be in (0, 600] s",
    );
    // spec 9.3: the automation's realism.
    for (f, v) in [
        ("cav.actuator_lag_s", p.actuator_lag_s),
        ("cav.comm_delay_s", p.comm_delay_s),
        ("cav.beacon_timeout_s", p.beacon_timeout_s),
        ("cav.field_low_level_lag_s", p.field_low_level_lag_s),
    ] {
        c.value(
            f,
            v,
            (0.0..=limits::MAX_CAV_REALISM_S).contains(&v),
            &format!("must be in [0, {}] s", num(limits::MAX_CAV_REALISM_S)),
        );
    }
    c.value(
        "cav.packet_loss",
        p.packet_loss,
        (0.0..=1.0).contains(&p.packet_loss),
        "must be in [0, 1] (a probability; 1 = no V2V)",
    );
    c.value(
        "cav.max_automated_decel_mps2",
        p.max_automated_decel_mps2,
        p.max_automated_decel_mps2 > 0.0,
        "must be > 0 m/s² (a braking magnitude, positive)",
    );
    // The field CACC law (docs/cacc-field.md): gains and feed-forward non-negative, the
    // ISO 15622 envelope positive, its speeds ordered, its deceleration within b_e.
    let [kp, kd] = p.cacc_field_gains;
    if !(kp > 0.0 && kd >= 0.0) {
        c.push(
            "cav.cacc_field_gains",
            pair(p.cacc_field_gains),
            "must be [k_p > 0 (1/s²), k_d >= 0 (1/s)]",
        );
    }
    c.value(
        "cav.cacc_feedforward",
        p.cacc_feedforward,
        (0.0..=1.0).contains(&p.cacc_feedforward),
        "must be in [0, 1] (0 = no feed-forward, 1 = the predecessor's whole acceleration)",
    );
    let sp = p.envelope_speeds_mps;
    if !(sp[0] >= 0.0 && sp[0] < sp[1]) {
        c.push(
            "cav.envelope_speeds_mps",
            pair(sp),
            "must be [low, high] with 0 <= low < high (m/s)",
        );
    }
    // The envelope's deceleration is bounded like b_e (about 1.2 g, above any tyre's grip).
    let top_decel = platoonsim_model::safety::MAX_EMERGENCY_DECEL_MPS2;
    for (f, g, unit, top) in [
        (
            "cav.envelope_decel_mps2",
            p.envelope_decel_mps2,
            "m/s²",
            top_decel,
        ),
        (
            "cav.envelope_jerk_mps3",
            p.envelope_jerk_mps3,
            "m/s³",
            f64::INFINITY,
        ),
    ] {
        if !(g[0] > 0.0 && g[1] > 0.0 && g[0] <= top && g[1] <= top) {
            let bound = if top.is_finite() {
                format!(", at most {} (about 1.2 g)", num(top))
            } else {
                String::new()
            };
            c.push(
                f,
                pair(g),
                format!("must be [at low speed, at high speed], both > 0 {unit}{bound}"),
            );
        }
    }

    let shares = &p.time_gap_shares;
    let text = || {
        let items: Vec<String> = shares
            .iter()
            .map(|&(g, s)| format!("[{}, {}]", num(g), num(s)))
            .collect();
        format!("[{}]", items.join(", "))
    };
    if shares.len() > limits::MAX_TIME_GAP_SHARES {
        c.push(
            "cav.time_gap_shares",
            format!("({} pairs)", shares.len()),
            format!(
                "at most {} [time_gap_s, share] pairs",
                limits::MAX_TIME_GAP_SHARES
            ),
        );
    } else if shares.is_empty() {
        c.push(
            "cav.time_gap_shares",
            "[]",
            "at least one [time_gap_s, share] pair is required",
        );
    } else if let Some(i) = shares
        .iter()
        .position(|&(g, s)| !(g > 0.0 && (0.0..=1.0).contains(&s)))
    {
        c.push(
            format!("cav.time_gap_shares[{i}]"),
            format!("[{}, {}]", num(shares[i].0), num(shares[i].1)),
            "each pair is [time_gap_s > 0, share in [0, 1]]",
        );
    } else {
        let sum: f64 = shares.iter().map(|&(_, s)| s).sum();
        if (sum - 1.0).abs() > 1e-6 {
            c.push(
                "cav.time_gap_shares",
                text(),
                format!("the shares must sum to 1 (they sum to {})", num(sum)),
            );
        }
    }
}

fn pair(g: [f64; 2]) -> String {
    format!("[{}, {}]", num(g[0]), num(g[1]))
}

pub(super) fn check_lane_change(c: &mut Checker, l: &LaneChangeDists, road_length: Option<f64>) {
    c.dist(
        "lane_change.mandatory_distance_m",
        &l.mandatory_distance_m,
        Some((
            l.mandatory_distance_m.min > l.mandatory_min_distance_m,
            "min must be > lane_change.mandatory_min_distance_m",
        )),
    );
    c.dist(
        "lane_change.mandatory_time_s",
        &l.mandatory_time_s,
        Some((
            l.mandatory_time_s.min > l.mandatory_min_time_s,
            "min must be > lane_change.mandatory_min_time_s",
        )),
    );
    c.dist(
        "lane_change.threshold",
        &l.threshold,
        Some((
            l.threshold.min >= 0.0 && l.threshold.max <= 1.0,
            "must lie in [0, 1]",
        )),
    );
    c.dist(
        "lane_change.cooperativeness",
        &l.cooperativeness,
        Some((
            l.cooperativeness.min >= 0.0 && l.cooperativeness.max <= 1.0,
            "must lie in [0, 1] (a probability)",
        )),
    );
    let nonneg = |c: &mut Checker, f: &str, v: f64| c.value(f, v, v >= 0.0, "must be >= 0");
    let unit = |c: &mut Checker, f: &str, v: f64| {
        c.value(f, v, (0.0..=1.0).contains(&v), "must be in [0, 1]")
    };
    let relax =
        |c: &mut Checker, f: &str, v: f64| c.value(f, v, v > 0.0 && v <= 1.0, "must be in (0, 1]");
    nonneg(
        c,
        "lane_change.mandatory_min_distance_m",
        l.mandatory_min_distance_m,
    );
    nonneg(
        c,
        "lane_change.mandatory_min_time_s",
        l.mandatory_min_time_s,
    );
    unit(c, "lane_change.right_discount", l.right_discount);
    unit(c, "lane_change.mandatory_weight", l.mandatory_weight);
    unit(
        c,
        "lane_change.discretionary_coop_factor",
        l.discretionary_coop_factor,
    );
    unit(c, "lane_change.slow_down_desire", l.slow_down_desire);
    unit(c, "lane_change.cav_weight_leader", l.cav_weight_leader);
    unit(c, "lane_change.cav_weight_follower", l.cav_weight_follower);
    c.value(
        "lane_change.sigma_forward",
        l.sigma_forward,
        l.sigma_forward > 0.0,
        "must be > 0",
    );
    c.value(
        "lane_change.sigma_backward",
        l.sigma_backward,
        l.sigma_backward > 0.0,
        "must be > 0",
    );
    relax(c, "lane_change.relax_headway", l.relax_headway);
    relax(c, "lane_change.relax_jam", l.relax_jam);
    relax(c, "lane_change.relax_reaction", l.relax_reaction);
    c.value(
        "lane_change.relax_time_s",
        l.relax_time_s,
        l.relax_time_s > 0.0,
        "must be > 0 s",
    );
    nonneg(c, "lane_change.scan_distance_m", l.scan_distance_m);
    if l.scan_vehicles < 1 {
        c.push(
            "lane_change.scan_vehicles",
            l.scan_vehicles.to_string(),
            "must be >= 1",
        );
    }
    nonneg(c, "lane_change.min_interval_s", l.min_interval_s);
    nonneg(c, "lane_change.return_factor", l.return_factor);
    nonneg(c, "lane_change.min_speed_gain_mps", l.min_speed_gain_mps);
    nonneg(
        c,
        "lane_change.anticipation_distance_m",
        l.anticipation_distance_m,
    );
    nonneg(
        c,
        "lane_change.anticipation_strength",
        l.anticipation_strength,
    );
    nonneg(c, "lane_change.exit_no_change_m", l.exit_no_change_m);
    unit(c, "lane_change.exit_lane_penalty", l.exit_lane_penalty);
    nonneg(c, "lane_change.yield_range_m", l.yield_range_m);
    c.value(
        "lane_change.min_reference_speed_mps",
        l.min_reference_speed_mps,
        l.min_reference_speed_mps > 0.0,
        "must be > 0 m/s",
    );
    // spec 9.1: decelerations, positive; the urgent bound is the harder one.
    c.value(
        "lane_change.safe_follower_decel_mps2",
        l.safe_follower_decel_mps2,
        l.safe_follower_decel_mps2 > 0.0,
        "must be > 0 m/s² (a deceleration, written positive)",
    );
    c.value(
        "lane_change.mandatory_safe_decel_mps2",
        l.mandatory_safe_decel_mps2,
        l.mandatory_safe_decel_mps2 >= l.safe_follower_decel_mps2,
        &format!(
            "must be >= lane_change.safe_follower_decel_mps2 = {} m/s² (positive)",
            num(l.safe_follower_decel_mps2)
        ),
    );
    match road_length {
        Some(len) => c.value(
            "lane_change.forbid_zone_m",
            l.forbid_zone_m,
            l.forbid_zone_m >= 0.0 && l.forbid_zone_m < len,
            &format!("must be >= 0 and < road.length_m = {}", num(len)),
        ),
        None => nonneg(c, "lane_change.forbid_zone_m", l.forbid_zone_m),
    }
}
