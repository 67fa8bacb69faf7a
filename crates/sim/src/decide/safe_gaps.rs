//! The safe gap rule's inputs from the engine (spec 9.1; the pure rule is
//! `platoonsim_model::safegap`): the rule's decelerations and the acceleration the new
//! follower would ask for by its own law. Shared by the decide phase and the re-check at
//! execution (`execute.rs`).

use super::v_des_of;
use crate::config::Config;
use crate::state::RoadState;
use crate::state::Sensed;
use crate::vehicle::Vehicle;
use platoonsim_model::safegap::{self, AutomatedFollower, GapRule, SafeDecel};
use platoonsim_model::{cav, Leader};

/// The safe rule's decelerations (spec 9.1), `None` under the published rule.
#[inline]
pub(crate) fn safe_decel(cfg: &Config) -> Option<SafeDecel> {
    let l = &cfg.lane_change;
    (l.gap_rule == GapRule::Safe).then_some(SafeDecel {
        normal_mps2: l.safe_follower_decel_mps2,
        mandatory_mps2: l.mandatory_safe_decel_mps2,
    })
}

/// The acceleration the new follower `f` (slot `fs`, in the target lane) would ask for by its
/// own law with the changer `c` cut in ahead of it at `changer` (net gap, speed), spec 9.1:
/// a human driver (or a CAV driven by hand) by the human model relaxed as after a cut-in (the
/// engine relaxes it, `execute.rs`); an automated CAV by its ACC or CACC controller with its
/// limits, not relaxed (spec 4.6); under the field law (`cav.cacc_law`) after its cut-in reset.
/// Shared by the decide phase, the re-check at execution and ramp insertion (`insert.rs`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn follower_accel_after(
    cfg: &Config,
    road: &RoadState,
    sensed: &[Sensed],
    dt: f64,
    f: &Vehicle,
    fs: u32,
    c: &Vehicle,
    changer: Leader,
) -> f64 {
    let v_des = road.desired_speed_in(v_des_of(f), f.lane as usize, sensed[fs as usize].here.right);
    if !f.automated() {
        return safegap::human_follower_accel(&f.driver.human, &f.driver.lc, f.v, v_des, changer);
    }
    automated_follower_after(cfg, dt, f, v_des, c, changer)
}

/// [`follower_accel_after`] for an automated follower `f` with desired speed `v_des` (ramp
/// insertion calls it directly: a vehicle placed in the same phase has no sensed record).
pub(crate) fn automated_follower_after(
    cfg: &Config,
    dt: f64,
    f: &Vehicle,
    v_des: f64,
    c: &Vehicle,
    changer: Leader,
) -> f64 {
    let p = &cfg.cav;
    let changer_is_cav = c.is_cav();
    // The sense phase's link test (sense.rs): a CAV within the 2 s band joins the changer's
    // string with its own t_C, otherwise it keeps the inter-platoon gap (spec 3.6).
    let joins = changer_is_cav
        && changer.gap_m
            <= p.cacc_tg_band_s[1] * f.v + p.standstill_gap_m + p.speed_control_min_gap_m;
    let target_gap_s = if !changer_is_cav {
        p.acc_time_gap_s
    } else if joins {
        f.cacc.gap_s
    } else {
        p.inter_platoon_gap_s
    };
    // Under the field law the follower handles the cut-in by resetting its gap reference to
    // the actual gap (`cav::cut_in_time_gap`, as `execute.rs` does when the change happens)
    // and reads the changer's acceleration from its beacon (a CAV) or its radar (a human).
    safegap::automated_follower_accel(
        p,
        &AutomatedFollower {
            v: f.v,
            a: f.a,
            v_des,
            time_gap_s: cav::cut_in_time_gap(p, f.cacc.time_gap_s, changer.gap_m, f.v),
            target_gap_s,
            family: f.cacc.family,
            changer_is_cav,
            a_pred: c.a,
        },
        changer,
        dt,
    )
}

#[cfg(test)]
mod tests {
    use super::safe_decel;
    use crate::Config;
    use platoonsim_model::safegap::GapRule;

    #[test]
    fn the_published_rule_has_no_safe_decelerations() {
        let mut cfg = Config::homogeneous(0.0, 0.0, 60.0, 0.0, 1);
        let d = safe_decel(&cfg).expect("the safe rule is the default");
        assert_eq!((d.normal_mps2, d.mandatory_mps2), (3.0, 4.0));
        cfg.lane_change.gap_rule = GapRule::Published;
        assert!(safe_decel(&cfg).is_none());
    }
}
