//! CAV control (spec 3): speed regulation, ACC behind a non-CAV, CACC behind a CAV, the
//! safety override and the vehicle limits.
//!
//! Papers: Milanés & Shladover (2014) ACC/CACC laws; operating modes and gains of Xiao,
//! Wang & van Arem (2017) as implemented in Eclipse SUMO's ACC/CACC models; PATH/Liu et al.
//! (2018) as used by the seed paper; for the field form, Ploeg, Scheepers, van Nunen, van de
//! Wouw & Nijmeijer (2011), "Design and experimental evaluation of cooperative adaptive cruise
//! control", IEEE ITSC, and Naus et al. (2010), IEEE TVT 59(9); ISO 15622:2018. Equations (g = net gap, Δv = v_l − v):
//!
//! ```text
//! speed regulation (3.2): a = k0 (v_F − v)
//! ACC (3.3):  e = g − t_A v − d0,  d0 = max(s_min, min(75/v − 5, 2))
//!             spacing > 120 m → speed regulation; < 100 m → gap family; between: previous family
//!             (spacing = g + leader length, 4 m in `acc`); speed family: a = min(k0 (v_F − v),
//!             closing law) \[D\]
//!             regulation  |e| < 0.2 and |Δv| < 0.1 : a = k1 e + k2 Δv    (0.23, 0.07)
//!             avoidance   e < 0                    : a = k1c e + k2c Δv  (0.8, 0.23)
//!             closing     otherwise                : a = k1g e + k2g Δv  (0.04, 0.8)
//! CACC (3.4): e = g − t_C v − s_min,  ė = Δv − t_C a,  v(k+1) = v(k) + kp e + kd ė  (per 0.1 s)
//!             tg = g/v > 2 s and e > 1.66 m → speed regulation (capped by the closing law \[D\]);
//!             tg < 1.5 s, or tg > 2 s with e ≤ 1.66 m \[D\] → CACC family; between: previous family
//!             regulation  0 < e < 0.2 and |Δv| < 0.1 : (0.45, 0.0125)
//!             avoidance   e < 0                      : (0.45, 0.05)
//!             closing     otherwise                  : (0.005, 0.05)
//!               \[D\] 6.21 (default): "otherwise" only while approaching (Δv < 0); with Δv ≥ 0
//!               the regulation gains (the single Milanés law of the PATH code); the cap on
//!               speed regulation follows the same choice
//!             a = (v(k+1) − v(k)) / 0.1 applied over Δt
//! safety (3.4, 3.8): v_safe = Gipps speed with τ_r = 0.4 s, θ = 0, b̂ = b, jam gap s_min, at its
//!             fixed point v = v_G (= Krauss form): v_safe = bτ_r + sqrt(b²τ_r² + v_l² − 2b(g − s_min));
//!             tol = min(2, max(0, g − s_min)) [D; spec: min(2, g)];
//!             if v_new > v_safe + tol: v_new = max(0, v_safe + tol) (may brake harder than b);
//!             field law: a = max((v_safe + tol − v)/Δt, min(b, a_cmd)), the excess shed at no
//!             more than b unless the law (its kinematic approach included) asks for more \[D\]
//! limits:     (v_new − v)/Δt ∈ [b, a_M], 0 ≤ v_new ≤ v_F
//! ```
//!
//! CACC realism (spec 9.3; all off by default except the braking bound, which only relabels):
//!
//! ```text
//! V2V beacon: every CAV broadcasts its speed each step; the CACC law uses the leader's speed
//!             v_l from the freshest received beacon, sent d = round(comm_delay_s/Δt) steps
//!             before it arrived; the gap g stays the radar's (current); so does the v_l of
//!             the safety override (radar range rate)
//! loss:       each step a follower's reception fails with probability p (packet_loss);
//!             age a = steps since the last reception; v_l = broadcast of step k − a − d;
//!             a·Δt > T_b (beacon_timeout_s) → ACC (fallback) until a beacon arrives again
//! lag:        a_real(k+1) = a_cmd + (a_real(k) − a_cmd) e^{−Δt/τ_a}   (exact for a_cmd held
//!             over the step; τ_a = actuator_lag_s; τ_a = 0: a_real = a_cmd)
//! bound:      a_cmd = max(a_req, −D_auto), a_req = the automation's demand after the
//!             override and the limits; if a_req < −D_auto: AEB, applied a = a_req (no lag,
//!             bounded by b_e in integrate), counted as an intervention
//! ```
//!
//! | symbol | field | default | unit | source |
//! |---|---|---|---|---|
//! | k0 | `speed_gain` | 0.4 | 1/s | SUMO, [P15-code] |
//! | t_A | `acc_time_gap_s` | 1.1 | s | spec 3.3 \[D\] |
//! | k1, k2 | `acc_reg_gains` | 0.23, 0.07 | 1/s², 1/s | Milanés & Shladover 2014 |
//! | k1g, k2g | `acc_closing_gains` | 0.04, 0.8 | | Xiao 2017 |
//! | k1c, k2c | `acc_avoid_gains` | 0.8, 0.23 | | SUMO |
//! | – | `acc_range_m` | 100, 120 | m | hysteresis band |
//! | kp, kd | `cacc_reg_gains` | 0.45, 0.0125 | per 0.1 s | Xiao 2017 |
//! | kp, kd | `cacc_closing_gains` | 0.005, 0.05 | per 0.1 s | Xiao 2017 |
//! | kp, kd | `cacc_avoid_gains` | 0.45, 0.05 | per 0.1 s | SUMO |
//! | – | `cacc_tg_band_s` | 1.5, 2.0 | s | hysteresis band |
//! | – | `speed_control_min_gap_m` | 1.66 | m | SUMO |
//! | – | `reg_gap_band_m`, `reg_speed_band_mps` | 0.2, 0.1 | m, m/s | Xiao 2017 |
//! | s_min | `standstill_gap_m` | 1.5 | m | seed "minimum space gap" |
//! | τ_r | `reaction_s` | 0.4 | s | seed, spec 3.8 |
//! | a_M | `max_accel` | 1.5 | m/s² | seed (swapped row) |
//! | b | `max_decel` | −4.0 | m/s² | seed (swapped row) |
//! | b_e | `emergency_decel_mps2` | 9.0 | m/s² (positive) | SUMO `emergencyDecel`; bounds every applied acceleration (docs/safety.md) |
//! | – | `inter_platoon_gap_s` | 1.5 | s | seed |
//! | – | `max_platoon` | 10 | veh | seed |
//! | – | `sensor_range_m` | 250 | m | spec 3.9 |
//! | – | `time_gap_shares` | 0.6:0.57, 0.7:0.24, 0.9:0.07, 1.1:0.12 | s : share | Nowakowski, spec 3.5 |
//! | – | `time_gap_ramp_per_s` | 0.06 | s/s | spec 3.5 transitions (15 s for 0.9 s) [D: on] |
//! | – | `yield_while_automated` | true | – | spec 6.5 \[D\]: automation answers mandatory yield requests |
//! | – | `yield_to_organizers` | false | – | \[D\]: … and requests of CAVs joining the PD lane |
//! | – | `organize_while_automated` | true | – | \[D\]: automation stays on while waiting for a PD-lane gap |
//! | – | `organize_hold` | narrow | – | \[D\] 6.20: when the waiting automation holds back for the target-lane leader (`off`, `always`, `leader-ahead`, `narrow`) |
//! | – | `organize_hold_timeout_s` | 10 | s | \[D\] 6.20: longest hold below the creep speed (t_T of spec 9.2) |
//! | – | `cacc_closing_only_approaching` | true | – | \[D\] 6.21: CACC gap closing only while Δv < 0 |
//! | – | `organize_regardless_of_speed` | true | – | \[S\] + \[D\] 6.22: no a_ant ≥ 0 test for a PD-lane move |
//! | – | `cooperative_lane_change` | false | – | \[D\] spec 9.2: cooperative lane changes under automation (`cooperative.rs`) |
//! | b_co | `cooperative_gap_decel_mps2` | 2.0 | m/s² (positive) | spec 9.2: b_c = 0.5 b_f of spec 4.3 [P15-doc] |
//! | t_T | `cooperative_timeout_s` | 10 | s | \[D\] spec 9.2: request lifetime |
//! | τ_a | `actuator_lag_s` | 0 | s | spec 9.3: first-order lag; Plexe 0.5 s |
//! | – | `comm_delay_s` | 0 | s | spec 9.3: age of the V2V beacon, whole steps |
//! | p | `packet_loss` | 0 | – | spec 9.3: share of lost beacons, per follower and step |
//! | T_b | `beacon_timeout_s` | 0.5 | s | spec 9.3 \[D\]: 5 beacons at 10 Hz, then ACC (Ploeg 2015) |
//! | D_auto | `max_automated_decel_mps2` | 5.0 | m/s² (positive) | spec 9.3: ISO 15622 \[R\]; harder = AEB |
//! | – | `cacc_law` | field | – | `field` (below) or `spec` (spec 3.4 and 9.3 as above, bit for bit) |
//! | k_p, k_d | `cacc_field_gains` | 0.2, 0.7 | 1/s², 1/s | Ploeg et al. 2011 (field-tested at 0.7 s) |
//! | k_ff | `cacc_feedforward` | 1.0 | – | Ploeg et al. 2011; Naus et al. 2010 |
//! | v_lo, v_hi | `envelope_speeds_mps` | 5, 20 | m/s | ISO 15622:2018 \[R\] |
//! | D(v) | `envelope_decel_mps2` | 5.0, 3.5 | m/s² (positive) | ISO 15622:2018 \[R\]: 5 below 5 m/s, 3.5 above 20 m/s |
//! | J(v) | `envelope_jerk_mps3` | 5.0, 2.5 | m/s³ (positive) | ISO 15622:2018 \[R\]: 5 below 5 m/s, 2.5 above 20 m/s |
//! | τ_ll | `field_low_level_lag_s` | 0.3 | s | \[D\] between Ploeg et al. 2011 (0.1 s) and Plexe (0.5 s) |
//!
//! The field form (`cacc_law = "field"`, default; docs/cacc-field.md) is in `cav/field.rs`, the
//! CACC realism of spec 9.3 (lag, beacons, the braking bound) in `cav/realism.rs`; both are
//! re-exported here, and their parameters are rows of the table above.
//!
//! Yielding through the automation (spec 4.5 applied to an automated CAV, \[D\]):
//! a = min(a_auto, max(a_virtual, b_c)), a_virtual = the driver's relaxed car-following
//! acceleration toward the requester standing its relaxed jam gap further back.

use crate::{bounded, Leader};
use serde::{Deserialize, Serialize};

mod field;
mod realism;
pub use field::*;
pub use realism::*;

/// CAV controller parameters (shared by all CAVs; the CACC time gap is per vehicle).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CavParams {
    pub speed_gain: f64,
    pub acc_time_gap_s: f64,
    pub acc_reg_gains: [f64; 2],
    pub acc_closing_gains: [f64; 2],
    pub acc_avoid_gains: [f64; 2],
    pub acc_range_m: [f64; 2],
    pub cacc_reg_gains: [f64; 2],
    pub cacc_closing_gains: [f64; 2],
    pub cacc_avoid_gains: [f64; 2],
    pub cacc_tg_band_s: [f64; 2],
    pub speed_control_min_gap_m: f64,
    pub reg_gap_band_m: f64,
    pub reg_speed_band_mps: f64,
    pub standstill_gap_m: f64,
    pub reaction_s: f64,
    pub max_accel: f64,
    pub max_decel: f64,
    /// b_e (m/s², positive): the hardest braking the vehicle can apply, whatever the controller
    /// or its driver asks for (the safety override may ask for more than b; docs/safety.md).
    pub emergency_decel_mps2: f64,
    pub inter_platoon_gap_s: f64,
    pub max_platoon: u32,
    pub sensor_range_m: f64,
    /// (CACC time gap in s, share) pairs; shares sum to 1.
    pub time_gap_shares: Vec<(f64, f64)>,
    /// Rate at which a CAV's target time gap moves to a new setting (s of gap per s), spec 3.5
    /// "Transitions" (Xiao 2018: over about 15 s, so 0.9 s / 15 s = 0.06). 0 = jump at once.
    pub time_gap_ramp_per_s: f64,
    /// Spec 6.5 flag: an automated CAV answers mandatory yield requests (merging, exiting,
    /// lane-drop changes) through its automation: with the driver's cooperativeness draw it
    /// follows the requester as a virtual leader like a yielding driver (spec 4.5: relaxed
    /// parameters, never braking harder than b_c for the yield) and stays automated, so its
    /// CACC links hold. Default true \[D\], against the spec's recommendation (open question
    /// 6.5): without it CAVs lower the capacity of merges (docs/model-choices.md).
    pub yield_while_automated: bool,
    /// With `yield_while_automated`: an automated CAV also yields, the same way, to a CAV that
    /// moves toward the PD lane for platoon organization (spec 4.7), i.e. it lets a joining CAV
    /// in. Default false \[D\].
    pub yield_to_organizers: bool,
    /// A CAV that wants to move toward the PD lane (platoon organization, spec 4.7) stays
    /// automated while its driver waits for a gap, and hands over only once both gaps are
    /// acceptable (a platoon follower then splits, spec 3.6.4); while the lag gap is acceptable
    /// its automation does not accelerate beyond what the target-lane leader allows. Default
    /// true \[D\]. False = the PATH rule of spec 3.1: manual from the moment the desire arises,
    /// which under PD turns every CAV outside the PD lane into a manual vehicle
    /// (docs/model-choices.md 6.20).
    pub organize_while_automated: bool,
    /// With `organize_while_automated`: when the automation holds back for the target-lane
    /// leader while its driver waits for the gap (`driver::held_back`; docs/model-choices.md
    /// 6.20). Default `narrow` \[D\].
    pub organize_hold: OrganizeHold,
    /// With `organize_hold = "narrow"`: the longest wait (s) below the creep speed during
    /// which the hold applies; after it the automation drives on until the wait ends, so no
    /// mutual wait can last. Default 10 s \[D\] (the request lifetime t_T of spec 9.2).
    pub organize_hold_timeout_s: f64,
    /// The CACC gap-closing sub-mode (spec 3.4, Xiao 2017: weak gains for a smooth approach)
    /// applies only while the follower closes in on its predecessor (Δv < 0). With the gap
    /// above its target and the predecessor not slower (Δv ≥ 0), e.g. a string leaving a
    /// queue behind an accelerating leader, the gap-regulation gains apply, as in the single
    /// Milanés law of the PATH code the seed paper used; the cap on speed regulation uses the
    /// same choice. Default true \[D\] (docs/model-choices.md 6.21). False = spec 3.4 as written.
    pub cacc_closing_only_approaching: bool,
    /// A CAV moving toward the PD lane does so "regardless of the speed difference between the
    /// current lane and the target lanes" (seed paper, spec 4.7): its forward-gap test drops the
    /// discretionary condition a_ant ≥ 0 (spec 4.3: the changer must not have to brake behind
    /// its new leader), which is a condition on the target lane's speed. The gap rules stay
    /// otherwise discretionary: the safety criterion of spec 4.3 applies, and the driver never
    /// brakes to synchronize or drops back for a gap. Default true \[D\] (docs/model-choices.md
    /// 6.22). False = the discretionary rules of spec 4.3 as written.
    pub organize_regardless_of_speed: bool,
    /// Cooperative lane changes (spec 9.2, `cooperative.rs`): an automated CAV with a mandatory
    /// or organizing desire asks the automated CAV that follows it in the target lane to open
    /// a gap and changes under automation. Default false: the seed paper's manual,
    /// non-cooperative CAV lane changes stay the reference.
    pub cooperative_lane_change: bool,
    /// b_co (m/s², positive): the hardest braking with which a CAV opens a gap for a
    /// cooperative change (or a joiner matches the target lane), and the hardest braking the
    /// change may ask of the pair it creates.
    pub cooperative_gap_decel_mps2: f64,
    /// t_T (s): a cooperative request lives this long; then the published behaviour for as
    /// long, then a new request.
    pub cooperative_timeout_s: f64,
    /// The powertrain of the CAVs (`combustion` or `electric`; energy.rs). Not written when
    /// it is the default, so that older configurations keep their identity.
    #[serde(skip_serializing_if = "crate::energy::Powertrain::is_default")]
    pub powertrain: crate::energy::Powertrain,
    /// τ_a (s): first-order lag between the automation's commanded and realized acceleration
    /// (spec 9.3). 0 = none (the command applies within the step).
    pub actuator_lag_s: f64,
    /// Age (s) of the leader's V2V beacon when the CACC law uses it (spec 9.3), rounded to
    /// whole steps. 0 = the leader's current speed.
    pub comm_delay_s: f64,
    /// Probability that a follower receives no beacon in a step (spec 9.3), in [0, 1]; 1 = no
    /// V2V at all (every CACC falls back to ACC after the timeout).
    pub packet_loss: f64,
    /// T_b (s): a follower without a beacon for longer than this falls back to ACC until
    /// beacons return (spec 9.3), rounded to whole steps.
    pub beacon_timeout_s: f64,
    /// D_auto (m/s², positive): the hardest braking the automation commands (spec 9.3);
    /// a safety override that needs more is an AEB intervention (counted).
    pub max_automated_decel_mps2: f64,
    /// Which CACC law automated CAVs run (`field` or `spec`; module docs, docs/cacc-field.md).
    /// `spec` is the gap-error law of spec 3.4 as before, bit for bit; `field` (default) the
    /// field-tested form: feed-forward of the predecessor's acceleration, the kinematic
    /// approach, the ISO 15622 envelope with take-over requests, the cut-in reset.
    pub cacc_law: CaccLaw,
    /// (k_p in 1/s², k_d in 1/s): the field law's feedback on the spacing error and its
    /// derivative (Ploeg et al. 2011).
    pub cacc_field_gains: [f64; 2],
    /// k_ff: the field law's weight on the predecessor's acceleration from its beacon (Ploeg
    /// et al. 2011; Naus et al. 2010); 0 = no feed-forward.
    pub cacc_feedforward: f64,
    /// (v_low, v_high) in m/s: the speeds at which the ISO 15622 envelope takes its low-speed
    /// and high-speed values (linear between).
    pub envelope_speeds_mps: [f64; 2],
    /// (D_low, D_high) in m/s² (positive): the largest automatic deceleration of the envelope
    /// at and below v_low, at and above v_high (ISO 15622:2018).
    pub envelope_decel_mps2: [f64; 2],
    /// (J_low, J_high) in m/s³ (positive): the largest rate at which automatic braking
    /// builds up, at v_low and v_high (ISO 15622:2018).
    pub envelope_jerk_mps3: [f64; 2],
    /// τ_ll (s): the lag of the car's low-level loop that tracks the field law's demand; under
    /// the field law the actuation lags by max(`actuator_lag_s`, τ_ll) (docs/cacc-field.md).
    pub field_low_level_lag_s: f64,
}

impl CavParams {
    /// The lag (s) with which the automation's demand is realized: `actuator_lag_s`, under the
    /// field law at least `field_low_level_lag_s`.
    pub fn effective_lag_s(&self) -> f64 {
        match self.cacc_law {
            CaccLaw::Spec => self.actuator_lag_s,
            CaccLaw::Field => self.actuator_lag_s.max(self.field_low_level_lag_s),
        }
    }
}

/// Which CACC law automated CAVs run (`cav.cacc_law`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CaccLaw {
    /// The field-tested form (module docs): the platform default.
    #[default]
    Field,
    /// The gap-error law of spec 3.4 with the actuation of spec 9.3, as published.
    Spec,
}

impl CaccLaw {
    /// `field` or `spec`, as in scenario files.
    pub fn as_str(self) -> &'static str {
        match self {
            CaccLaw::Field => "field",
            CaccLaw::Spec => "spec",
        }
    }
}

impl Default for CavParams {
    fn default() -> Self {
        CavParams {
            speed_gain: 0.4,
            acc_time_gap_s: 1.1,
            acc_reg_gains: [0.23, 0.07],
            acc_closing_gains: [0.04, 0.8],
            acc_avoid_gains: [0.8, 0.23],
            acc_range_m: [100.0, 120.0],
            cacc_reg_gains: [0.45, 0.0125],
            cacc_closing_gains: [0.005, 0.05],
            cacc_avoid_gains: [0.45, 0.05],
            cacc_tg_band_s: [1.5, 2.0],
            speed_control_min_gap_m: 1.66,
            reg_gap_band_m: 0.2,
            reg_speed_band_mps: 0.1,
            standstill_gap_m: 1.5,
            reaction_s: 0.4,
            max_accel: 1.5,
            max_decel: -4.0,
            emergency_decel_mps2: crate::safety::DEFAULT_EMERGENCY_DECEL_MPS2,
            inter_platoon_gap_s: 1.5,
            max_platoon: 10,
            sensor_range_m: 250.0,
            time_gap_shares: vec![(0.6, 0.57), (0.7, 0.24), (0.9, 0.07), (1.1, 0.12)],
            time_gap_ramp_per_s: 0.06,
            yield_while_automated: true,
            yield_to_organizers: false,
            organize_while_automated: true,
            organize_hold: OrganizeHold::Narrow,
            organize_hold_timeout_s: 10.0,
            cacc_closing_only_approaching: true,
            organize_regardless_of_speed: true,
            cooperative_lane_change: false,
            cooperative_gap_decel_mps2: 2.0,
            cooperative_timeout_s: 10.0,
            powertrain: crate::energy::Powertrain::Combustion,
            actuator_lag_s: 0.0,
            comm_delay_s: 0.0,
            packet_loss: 0.0,
            beacon_timeout_s: DEFAULT_BEACON_TIMEOUT_S,
            max_automated_decel_mps2: DEFAULT_MAX_AUTOMATED_DECEL_MPS2,
            cacc_law: CaccLaw::Field,
            cacc_field_gains: [0.2, 0.7],
            cacc_feedforward: 1.0,
            envelope_speeds_mps: [5.0, 20.0],
            envelope_decel_mps2: [5.0, 3.5],
            envelope_jerk_mps3: [5.0, 2.5],
            field_low_level_lag_s: 0.3,
        }
    }
}

/// When the automation of a CAV waiting for a gap toward its organized lane holds back for
/// the target-lane leader (docs/model-choices.md 6.20; `driver::held_back`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OrganizeHold {
    /// Never: the automation drives on.
    Off,
    /// Whenever the lag gap is acceptable (6.20 as first built).
    Always,
    /// Only while the target-lane leader's rear is ahead of the CAV's front (the first fix of
    /// the standstill deadlock, 2026-12-03).
    LeaderAhead,
    /// At or above the creep speed always; below it only with the leader ahead, and for at
    /// most `organize_hold_timeout_s` of the wait (2026-12-07).
    #[default]
    Narrow,
}

impl OrganizeHold {
    /// The scenario file's spelling.
    pub fn as_str(self) -> &'static str {
        match self {
            OrganizeHold::Off => "off",
            OrganizeHold::Always => "always",
            OrganizeHold::LeaderAhead => "leader-ahead",
            OrganizeHold::Narrow => "narrow",
        }
    }
}

/// Controller family kept between steps for the hysteresis of spec 3.3/3.4.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Family {
    /// Speed regulation (cruise).
    #[default]
    Speed,
    /// Gap control (regulation / closing / avoidance).
    Gap,
}

/// The sub-mode a controller used this step (for statistics and debugging).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CavMode {
    SpeedRegulation,
    GapRegulation,
    GapClosing,
    CollisionAvoidance,
}

impl CavMode {
    /// `speed`, `gap`, `gap-closing` or `collision-avoidance`, as in the trajectory records.
    pub fn as_str(self) -> &'static str {
        match self {
            CavMode::SpeedRegulation => "speed",
            CavMode::GapRegulation => "gap",
            CavMode::GapClosing => "gap-closing",
            CavMode::CollisionAvoidance => "collision-avoidance",
        }
    }
}

/// A controller's output: the commanded acceleration (before the safety override and limits),
/// the sub-mode used, and the family to remember for the next step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Command {
    pub accel: f64,
    pub mode: CavMode,
    pub family: Family,
}

/// Length (m) assumed for the leader when [`acc`] turns the net gap into the spacing of the
/// 100/120 m hysteresis band (spec 3.3): every vehicle is 4 m long in the seed (spec 0.1). Use
/// [`acc_with_leader_length`] when the actual leader length is known.
pub const ASSUMED_LEADER_LENGTH_M: f64 = 4.0;

/// The CACC speed-update interval (s) the gains are tuned for (spec 3.4).
pub const CACC_CONTROL_INTERVAL_S: f64 = 0.1;

/// Weakest braking magnitude (m/s²) accepted for `max_decel` (guards b ≥ 0).
const MIN_BRAKE_MPS2: f64 = 1e-3;
/// Smallest step (s) accepted by [`finalize`] (guards dt ≤ 0).
pub(crate) const MIN_DT_S: f64 = 1e-6;

/// `x` clamped to [lo, hi] without panicking when lo > hi (then `lo` wins). `lo` and `hi` are
/// parameters, never NaN ([`bounded`]).
#[inline]
pub(crate) fn bound(x: f64, lo: f64, hi: f64) -> f64 {
    bounded::max(bounded::min(x, hi), lo)
}

/// Speed regulation (spec 3.2): k0 (v_des − v).
#[inline]
pub fn speed_regulation(p: &CavParams, v: f64, v_des: f64) -> f64 {
    p.speed_gain * (v_des - v)
}

/// ACC standstill margin d0(v) = max(s_min, min(75/v − 5, 2)) m (spec 3.3, Xiao 2018 margin
/// floored at the seed's minimum space gap \[D\]); 2 m (then floored) at v ≤ 0.
#[inline]
pub fn acc_standstill_margin(p: &CavParams, v: f64) -> f64 {
    let xiao = if v > 0.0 {
        (75.0 / v - 5.0).min(2.0)
    } else {
        2.0
    };
    xiao.max(p.standstill_gap_m)
}

/// ACC (spec 3.3) with time gap `time_gap_s` (normally `p.acc_time_gap_s`), hysteresis on the
/// spacing; `leader = None` (or beyond the sensor) means speed regulation. The 100/120 m band is
/// on spacing (front to front); this function has no leader length, so it uses
/// spacing = net gap + [`ASSUMED_LEADER_LENGTH_M`]. [`acc_with_leader_length`] takes the length.
#[inline]
pub fn acc(
    p: &CavParams,
    v: f64,
    v_des: f64,
    leader: Option<Leader>,
    time_gap_s: f64,
    prev: Family,
) -> Command {
    acc_with_leader_length(
        p,
        v,
        v_des,
        leader,
        ASSUMED_LEADER_LENGTH_M,
        time_gap_s,
        prev,
    )
}

/// [`acc`] with the leader's length, so that the 100/120 m hysteresis (spec 3.3) is applied to
/// the true spacing = net gap + `leader_length_m`.
#[inline]
pub fn acc_with_leader_length(
    p: &CavParams,
    v: f64,
    v_des: f64,
    leader: Option<Leader>,
    leader_length_m: f64,
    time_gap_s: f64,
    prev: Family,
) -> Command {
    let cruise = Command {
        accel: speed_regulation(p, v, v_des),
        mode: CavMode::SpeedRegulation,
        family: Family::Speed,
    };
    let l = match leader {
        // spec 3.9: a predecessor beyond the sensor range is no predecessor.
        Some(l) if l.gap_m <= p.sensor_range_m => l,
        _ => return cruise,
    };
    // spec 3.3 hysteresis: spacing > 120 m → speed, < 100 m → gap family, between → previous.
    let spacing = l.gap_m + leader_length_m;
    let [near, far] = p.acc_range_m;
    let family = if spacing > far {
        Family::Speed
    } else if spacing < near {
        Family::Gap
    } else {
        prev
    };
    // spec 3.3: e = g − t_A v − d0, Δv = v_l − v.
    if family == Family::Speed {
        // [D] cruise never accelerates harder than gap closing would toward the leader in
        // range (a cruise controller still sees the car ahead); far away the cruise term wins.
        let e = l.gap_m - time_gap_s * v - acc_standstill_margin(p, v);
        let closing = p.acc_closing_gains[0] * e + p.acc_closing_gains[1] * (l.v_mps - v);
        return Command {
            accel: cruise.accel.min(closing),
            ..cruise
        };
    }
    let e = l.gap_m - time_gap_s * v - acc_standstill_margin(p, v);
    let dv = l.v_mps - v;
    let (mode, [k_gap, k_speed]) = if e.abs() < p.reg_gap_band_m && dv.abs() < p.reg_speed_band_mps
    {
        (CavMode::GapRegulation, p.acc_reg_gains)
    } else if e < 0.0 {
        (CavMode::CollisionAvoidance, p.acc_avoid_gains)
    } else {
        (CavMode::GapClosing, p.acc_closing_gains)
    };
    Command {
        accel: k_gap * e + k_speed * dv,
        mode,
        family: Family::Gap,
    }
}

/// The CACC family of spec 3.4 with its hysteresis, shared by both laws: speed regulation
/// when the time gap g / v is above the band's top and the gap error e above
/// `speed_control_min_gap_m`; gap control below the band's bottom (or with g ≤ 0), or above
/// its top with a small error; in between, the previous family. `vv` is the speed floored at 0.
#[inline]
fn cacc_family(p: &CavParams, g: f64, vv: f64, e: f64, prev: Family) -> Family {
    let [tg_low, tg_high] = p.cacc_tg_band_s;
    let tg_large = g > 0.0 && g > tg_high * vv;
    let tg_small = g <= 0.0 || g < tg_low * vv;
    if tg_large && e > p.speed_control_min_gap_m {
        Family::Speed
    } else if tg_small || tg_large {
        Family::Gap
    } else {
        prev
    }
}

/// CACC (spec 3.4) with time gap `time_gap_s` (the vehicle's t_C, or the inter-platoon gap for
/// a new string leader behind a full platoon). `a_own` is the vehicle's current acceleration
/// (for ė = Δv − t_C a). Returns the acceleration equivalent of the speed update, per spec
/// (computed for the 0.1 s control interval; independent of the simulation step).
///
/// Family choice on tg = g/v, evaluated without dividing (g > 2 v, g < 1.5 v) so that v → 0 is
/// safe: at v = 0 a positive gap counts as a large tg, a gap ≤ 0 as a small one. tg > 2 s with
/// e ≤ 1.66 m (only possible below about 2.3 m/s at t_C = 0.6 s) selects the CACC family \[D\]:
/// the 1.66 m threshold exists to keep gap control close to a (nearly) stopped leader.
#[inline]
pub fn cacc(
    p: &CavParams,
    v: f64,
    a_own: f64,
    v_des: f64,
    leader: Leader,
    time_gap_s: f64,
    prev: Family,
) -> Command {
    let g = leader.gap_m;
    let vv = v.max(0.0);
    // spec 3.4: e = g − t_C v − s_min, ė = Δv − t_C a.
    let e = g - time_gap_s * v - p.standstill_gap_m;
    let dv = leader.v_mps - v;
    let family = cacc_family(p, g, vv, e, prev);
    if family == Family::Speed {
        // spec 3.4: speed regulation as the speed update v + k0 (v_F − v)Δt, i.e. a = k0 (v_F − v),
        // [D] never above what the gap law above target asks for (gap closing, or regulation
        // under 6.21 while not approaching): at low speed tg > 2 s happens a few metres behind
        // a stopped leader, and plain cruise would accelerate into it.
        let (_, [kp, kd]) = above_target_law(p, dv);
        let closing = (kp * e + kd * (dv - time_gap_s * a_own)) / CACC_CONTROL_INTERVAL_S;
        return Command {
            accel: speed_regulation(p, v, v_des).min(closing),
            mode: CavMode::SpeedRegulation,
            family,
        };
    }
    let (mode, [kp, kd]) = if e > 0.0 && e < p.reg_gap_band_m && dv.abs() < p.reg_speed_band_mps {
        (CavMode::GapRegulation, p.cacc_reg_gains)
    } else if e < 0.0 {
        (CavMode::CollisionAvoidance, p.cacc_avoid_gains)
    } else {
        above_target_law(p, dv)
    };
    let e_dot = dv - time_gap_s * a_own;
    // v(k+1) = v(k) + kp e + kd ė per 0.1 s → a = (v(k+1) − v(k)) / 0.1.
    Command {
        accel: (kp * e + kd * e_dot) / CACC_CONTROL_INTERVAL_S,
        mode,
        family,
    }
}

/// Sub-mode and gains (kp, kd) of the CACC law for a gap above its target outside the
/// regulation band: gap closing (spec 3.4), or with `cacc_closing_only_approaching` \[D\] 6.21
/// the regulation gains unless the follower approaches its predecessor (Δv < 0): the soft
/// closing gains exist for the approach.
#[inline]
fn above_target_law(p: &CavParams, dv: f64) -> (CavMode, [f64; 2]) {
    if p.cacc_closing_only_approaching && dv >= 0.0 {
        (CavMode::GapRegulation, p.cacc_reg_gains)
    } else {
        (CavMode::GapClosing, p.cacc_closing_gains)
    }
}

/// Gipps-type safe speed for the CAV safety override (spec 3.4, 3.8): τ_r = `p.reaction_s`,
/// θ = 0, b̂ = b = `p.max_decel`, jam gap `p.standstill_gap_m`.
///
/// The signature has no own speed, so the Gipps speed (spec 2.3) is taken at its fixed point
/// v = v_G: v² − 2bτ_r v + 2b(g − s_min) − v_l² = 0, i.e.
/// v_safe = bτ_r + sqrt(b²τ_r² + v_l² − 2b(g − s_min)) (b < 0), the Krauss form SUMO uses: the
/// largest speed from which, after τ_r, braking at b stops behind the leader braking at b.
/// 0 if the radicand is negative; never negative.
#[inline]
pub fn safe_speed(p: &CavParams, gap_m: f64, v_leader: f64) -> f64 {
    let b = p.max_decel.min(-MIN_BRAKE_MPS2);
    let tau = p.reaction_s.max(0.0);
    let v_l = v_leader.max(0.0);
    let radicand = b * b * tau * tau + v_l * v_l - 2.0 * b * (gap_m - p.standstill_gap_m);
    if radicand < 0.0 {
        0.0
    } else {
        (b * tau + radicand.sqrt()).max(0.0)
    }
}

/// The smallest net gap at which [`safe_speed`] allows holding speed v behind a leader at the
/// same speed: s_min + τ_r v (spec 3.8; from v_safe(g, v) ≥ v with b̂ = b, θ = 0).
pub fn safety_gap(p: &CavParams, v: f64) -> f64 {
    p.standstill_gap_m + p.reaction_s.max(0.0) * v.max(0.0)
}

/// Apply the safety override (if there is a leader) and the vehicle limits to a commanded
/// acceleration: returns the acceleration to integrate over `dt`, such that
/// (v_new − v)/dt ∈ [max_decel, max_accel] except where the safety override requires harder
/// braking (never below what reaches v = 0 in this step), 0 ≤ v_new ≤ v_des.
///
/// Order: the cap v_new ≤ v_des, then the acceleration limits (which win when v > v_des: the
/// excess speed is shed at no more than |b|, as in [P15-code]), then the override
/// v_new ≤ max(0, v_safe + min(2, max(0, g − s_min))) (spec 3.4 with the \[D\] tolerance below),
/// which alone may brake harder than b, then v_new ≥ 0. When v > v_des the limits win, so v_new
/// may stay above v_des for a few steps. Under the field law (`cav.cacc_law`) the override
/// brakes at no more than max(b, |a_cmd|) toward the cap: v_new may stay above it for a few
/// steps while the law's demand, with its kinematic approach to the leader as it actually
/// brakes, asks for less (docs/cacc-field.md).
#[inline]
pub fn finalize(
    p: &CavParams,
    v: f64,
    a_cmd: f64,
    v_des: f64,
    leader: Option<Leader>,
    dt: f64,
) -> f64 {
    let dt = dt.max(MIN_DT_S);
    let v = v.max(0.0);
    let a_cmd = if a_cmd.is_nan() { 0.0 } else { a_cmd };
    // `a_cmd` is not NaN here: a NaN cap gives `a_cmd`, as `a_cmd.min(cap)` would.
    let mut a = bounded::min((v_des.max(0.0) - v) / dt, a_cmd);
    a = bound(a, p.max_decel, p.max_accel);
    if let Some(l) = leader {
        // spec 3.4 "After the law": if v_new > v_safe + min(2, g): v_new = max(0, v_safe + min(2, g)).
        // [D] Here v_safe already keeps s_min, so the tolerance uses the gap beyond s_min:
        // min(2, max(0, g − s_min)). With the raw g a CAV behind a stopped leader inside s_min
        // would creep forward at g m/s into it (seen as collisions in jams).
        let tolerance = (l.gap_m - p.standstill_gap_m).clamp(0.0, 2.0);
        let cap = (safe_speed(p, l.gap_m, l.v_mps) + tolerance).max(0.0);
        if v + a * dt > cap {
            let snap = (cap - v) / dt;
            // Under the field law the excess over the cap goes at no more than b, unless the
            // law itself (its kinematic approach included) asks for more: the cap assumes the
            // leader brakes at b from now on, the law knows how it brakes (docs/cacc-field.md,
            // the override).
            a = if p.cacc_law == CaccLaw::Field {
                snap.max(a_cmd.min(p.max_decel))
            } else {
                snap
            };
        }
    }
    if v + a * dt < 0.0 {
        a = -v / dt;
    }
    a
}

/// Steady-state net gap of a CAV following at time gap t at speed v under CACC (t v + s_min),
/// but never below the safety-override gap (spec 3.8). Used for insertion.
pub fn cacc_equilibrium_gap(p: &CavParams, time_gap_s: f64, v: f64) -> f64 {
    let v = v.max(0.0);
    (time_gap_s * v + p.standstill_gap_m).max(safety_gap(p, v))
}

/// Steady-state net gap of a CAV under ACC at speed v: t_A v + d0(v), not below the safety gap.
pub fn acc_equilibrium_gap(p: &CavParams, time_gap_s: f64, v: f64) -> f64 {
    let v = v.max(0.0);
    (time_gap_s * v + acc_standstill_margin(p, v)).max(safety_gap(p, v))
}

/// Move the effective time gap `current` toward `target` by at most `p.time_gap_ramp_per_s·dt`
/// (spec 3.5 transitions). A non-positive `current` (no previous setting) jumps to `target`.
#[inline]
pub fn ramp_time_gap(p: &CavParams, current: f64, target: f64, dt: f64) -> f64 {
    if current <= 0.0 || p.time_gap_ramp_per_s <= 0.0 {
        return target;
    }
    let step = p.time_gap_ramp_per_s * dt;
    current + (target - current).clamp(-step, step)
}

/// The CACC time gap for a uniform deviate `u` in [0, 1) from `p.time_gap_shares` (spec 3.5).
///
/// Cumulative shares (normalised by their sum): with the defaults u < 0.57 → 0.6 s,
/// u < 0.81 → 0.7 s, u < 0.88 → 0.9 s, otherwise 1.1 s. Negative shares count as 0; if all
/// shares are 0 the listed gaps are equally likely; an empty list gives `p.acc_time_gap_s`.
pub fn draw_time_gap(p: &CavParams, u: f64) -> f64 {
    let shares = &p.time_gap_shares;
    let Some(&(last_gap, _)) = shares.last() else {
        return p.acc_time_gap_s;
    };
    let u = if u.is_nan() { 0.0 } else { u.clamp(0.0, 1.0) };
    let total: f64 = shares.iter().map(|&(_, s)| s.max(0.0)).sum();
    if total <= 0.0 || !total.is_finite() {
        let i = ((u * shares.len() as f64) as usize).min(shares.len() - 1);
        return shares[i].0;
    }
    let target = u * total;
    let mut cumulative = 0.0;
    for &(gap, share) in shares {
        cumulative += share.max(0.0);
        if target < cumulative {
            return gap;
        }
    }
    last_gap
}
