//! The bound of an acceleration asked for from outside the models (the engine's
//! `AccelerateSafe` command, issue 46): the controller's acceleration, within the vehicle's own
//! limits and its speed cap, and never above what keeps its next speed at or below its model's
//! collision-free ("safe") speed behind the vehicle ahead, or the end of its lane.
//!
//! This is the analogue of Eclipse SUMO's speed mode that obeys the safe speed (TraCI
//! `setSpeedMode`, bit 0 "regard safe speed"), which Flow's benchmarks set for their learning
//! vehicles (Vinitsky et al. 2018, speed mode 9): SUMO then takes the controller's speed unless
//! it exceeds the car-following model's safe speed. Here the safe speed is the vehicle's own
//! model's, no new rule: a CAV's is the safety override's Krauss-form speed
//! ([`crate::cav::safe_speed`], spec 3.4 and 3.8, as SUMO's Krauss model computes it), a human
//! driver's the Gipps speed ([`crate::human::gipps_safe_speed`], spec 2.3).
//!
//! ```text
//! a1 = min(a_cmd, (v_max − v)/Δt)        the speed cap (the vehicle's desired or set speed)
//! a2 = clamp(a1, b, a_M)                 the vehicle's acceleration limits
//! a3 = (v_safe − v)/Δt  if v + a2 Δt > v_safe, else a2       (may brake harder than b)
//! a  = max(a3, −v/Δt)                    never backwards
//! ```
//!
//! The excess over the speed cap is shed at no more than |b| (the limits win over the cap, as
//! in [`crate::cav::finalize`]); only the safe speed may ask for harder braking, which the
//! engine bounds by the vehicle's emergency limit b_e (`safety::braking_limited`).
//!
//! Why it cannot drive into the vehicle ahead: v_safe(g, v_l) is the largest speed from which,
//! after the reaction time τ_r, braking at b stops the follower behind a leader that brakes at b
//! from now on (Gipps 1981; Krauss 1998). The bound holds the speed after every step at or
//! below v_safe of the step-start gap, and it is recomputed each step, so the follower reacts
//! within Δt ≤ τ_r. A leader that brakes harder than b (up to its own b_e) shortens its own
//! stopping distance, but the follower's v_safe then asks for harder braking too, which the
//! engine grants up to the follower's b_e. What the bound cannot cover: a vehicle cutting in
//! closer than the safe distance (the changer's gap acceptance, spec 4.3 and 9.1, is what
//! prevents that), and a leader braking harder than the follower's emergency limit.
//!
//! | symbol | meaning | source | unit |
//! |---|---|---|---|
//! | a_cmd | the controller's acceleration | the command | m/s² |
//! | v_max | the vehicle's speed cap: its desired speed in its lane (a CAV's set speed) | spec 2.2, 2.7, 3.2 | m/s |
//! | b, a_M | its acceleration limits: `cav.max_decel`, `cav.max_accel` for a CAV; the driver's drawn `human.max_decel`, `human.max_accel` for a human | spec 2.6, 3 | m/s² |
//! | v_safe | its collision-free speed behind the leader (net gap g, speed v_l) or the lane's end (a standing obstacle) | spec 2.3 (human), 3.4/3.8 (CAV) | m/s |
//! | Δt | the step | `run.dt_s` | s |

/// The vehicle's side of the bound: its limits and speeds, in SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Its speed (m/s).
    pub v: f64,
    /// Its speed cap (m/s).
    pub v_max: f64,
    /// Its normal braking limit b (m/s², negative).
    pub max_decel: f64,
    /// Its acceleration limit a_M (m/s², positive).
    pub max_accel: f64,
    /// Its collision-free speed behind what is ahead (m/s); `f64::INFINITY` with nothing ahead.
    pub v_safe: f64,
}

/// The commanded acceleration `a_cmd` (m/s²) bounded as the module says, for a step of `dt`
/// seconds. A NaN `a_cmd` is read as 0 (the engine refuses non-finite commands before this).
#[inline]
pub fn bounded_accel(a_cmd: f64, lim: &Limits, dt: f64) -> f64 {
    let dt = dt.max(1e-6);
    let v = lim.v.max(0.0);
    let a_cmd = if a_cmd.is_nan() { 0.0 } else { a_cmd };
    let mut a = a_cmd.min((lim.v_max.max(0.0) - v) / dt);
    a = a.min(lim.max_accel).max(lim.max_decel.min(0.0));
    if v + a * dt > lim.v_safe {
        a = (lim.v_safe.max(0.0) - v) / dt;
    }
    if v + a * dt < 0.0 {
        a = -v / dt;
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    fn free(v: f64) -> Limits {
        Limits {
            v,
            v_max: 30.0,
            max_decel: -4.0,
            max_accel: 1.5,
            v_safe: f64::INFINITY,
        }
    }

    #[test]
    fn within_the_limits_the_command_is_applied_exactly() {
        for a in [-4.0, -1.5, 0.0, 0.7, 1.5] {
            assert_eq!(bounded_accel(a, &free(20.0), 0.1), a);
        }
    }

    #[test]
    fn the_limits_bound_the_command() {
        assert_eq!(bounded_accel(20.0, &free(20.0), 0.1), 1.5);
        assert_eq!(bounded_accel(-20.0, &free(20.0), 0.1), -4.0);
    }

    #[test]
    fn the_speed_cap_is_reached_not_passed_and_excess_is_shed_at_b() {
        // 29.95 m/s, cap 30: +1.5 would give 30.1; the cap gives 0.5 m/s² (to 30.0 exactly).
        let a = bounded_accel(1.5, &free(29.95), 0.1);
        assert!((29.95 + a * 0.1 - 30.0).abs() < 1e-12, "a = {a}");
        // 35 m/s, far above the cap: shed at b, not at once.
        assert_eq!(bounded_accel(1.5, &free(35.0), 0.1), -4.0);
    }

    #[test]
    fn the_safe_speed_wins_and_may_brake_harder_than_b() {
        let lim = Limits {
            v_safe: 18.0,
            ..free(20.0)
        };
        // +1.5 would give 20.15 > 18: the next speed is exactly v_safe (−20 m/s² here; the
        // engine's emergency limit bounds it).
        let a = bounded_accel(1.5, &lim, 0.1);
        assert!((20.0 + a * 0.1 - 18.0).abs() < 1e-12, "a = {a}");
        assert!(a < -4.0);
        // A command below the safe speed stands.
        let lim = Limits {
            v_safe: 25.0,
            ..free(20.0)
        };
        assert_eq!(bounded_accel(1.5, &lim, 0.1), 1.5);
    }

    #[test]
    fn never_backwards() {
        let lim = Limits {
            v_safe: 0.0,
            ..free(0.2)
        };
        let a = bounded_accel(-4.0, &lim, 0.1);
        assert!((0.2 + a * 0.1).abs() < 1e-12, "a = {a}");
        assert_eq!(bounded_accel(-4.0, &free(0.0), 0.1), 0.0);
        assert_eq!(bounded_accel(f64::NAN, &free(10.0), 0.1), 0.0);
    }
}
