//! Section behaviour (issue 45 item 1): per-stretch factors on how people drive there.
//!
//! A corridor's capacity and free speed differ by section (geometry, sight lines, weaving,
//! a lane used differently); two global driver parameters cannot follow that. The usual
//! corridor-scale answer is a factor per section: Aimsun's section reaction-time factor,
//! Vissim's link behaviour types, the "variations in desired headway along the corridor" of
//! Kan et al. (2019, Transportation Research Part C 106). Here, on a stretch [from, to):
//!
//! ```text
//! θ' = f_θ θ      the Gipps buffer (spec 2.3) of whoever drives by the human model
//! v_F' = f_v v_F  every driver's desired speed, and so the CAV's set speed
//! ```
//!
//! θ is the part of the Gipps headway that sets capacity (a mean driver's steady-state
//! capacity is about 3600/(τ_r + θ + 0.5) veh/h/lane, docs/calibration.md section 1), and
//! scaling it changes the headway kept without changing how fast drivers respond: a factor
//! on τ_r would also slow the Gipps response (a_G = (v_G − v)/τ_r) and the safe-gap and
//! insertion rules, which judge followers by their own τ_r, would no longer hold (a first
//! version scaled τ and τ_r and collided in a queue at an acceleration lane's end).
//! f_θ applies to human drivers and CAV drivers in manual control (a driver behaviour; the
//! ACC/CACC laws keep their own time gaps); the lane-change gap criterion (spec 4.3) keeps
//! the driver's own θ. f_v applies to every vehicle, as a section's speed regime would.
//! Outside every stretch both are 1. Stretches do not overlap.
//!
//! **How it is applied.** Once per step, before sensing, `Sections::apply` gives every
//! vehicle on the road the parameters of the stretch at its position: θ and v_F are the
//! vehicle's own (drawn) values times the stretch's factors, rewritten only when the vehicle
//! enters another stretch. So the car-following, lane-change and safety rules read the
//! section's values without any per-call lookup, and a scenario without stretches pays one
//! branch per step. A vehicle waiting to enter is judged with the factors at its entry point
//! (`insert.rs`). A desired speed set from outside (`steer.rs`) becomes the vehicle's own.
//!
//! | symbol | key (`[[network.behaviour]]`) | default | allowed | unit |
//! |---|---|---|---|---|
//! | – | `from_m`, `to_m` | – | inside the corridor, from < to, in order, no overlap | m |
//! | f_θ | `buffer_factor` | 1 | [0, 5] | – |
//! | f_v | `speed_factor` | 1 | [0.5, 1.5] | – |

use crate::config::DriverStretch;
use crate::state::Traffic;
use platoonsim_model::human::HumanParams;

/// The factors (f_θ, f_v) at engine position `x`: those of the stretch containing it, else
/// (1, 1). `stretches` sorted by position and not overlapping (checked by the config).
#[inline]
pub fn factors_at(stretches: &[DriverStretch], x: f64) -> (f64, f64) {
    let i = stretches.partition_point(|s| s.to_m <= x);
    match stretches.get(i) {
        Some(s) if s.from_m <= x => (s.buffer_factor, s.speed_factor),
        _ => (1.0, 1.0),
    }
}

/// The driver parameters `p` on the stretch containing `x`: θ scaled by its f_θ. `None`
/// outside every stretch (drive by `p` itself).
#[inline]
pub fn params_at(stretches: &[DriverStretch], p: &HumanParams, x: f64) -> Option<HumanParams> {
    let i = stretches.partition_point(|s| s.to_m <= x);
    match stretches.get(i) {
        Some(s) if s.from_m <= x => Some(HumanParams {
            buffer_s: p.buffer_s * s.buffer_factor,
            ..*p
        }),
        _ => None,
    }
}

/// The index of the stretch containing `x`, if any.
#[inline]
fn stretch_at(stretches: &[DriverStretch], x: f64) -> Option<usize> {
    let i = stretches.partition_point(|s| s.to_m <= x);
    stretches.get(i).filter(|s| s.from_m <= x).map(|_| i)
}

/// What a slot's vehicle brought and what was last written (per slot).
#[derive(Clone, Copy, Debug)]
struct Slot {
    id: u64,
    /// The vehicle's own v_F and θ.
    v_f: f64,
    theta: f64,
    /// The stretch applied (`None`: none), and the v_F written then.
    at: Option<usize>,
    written_v_f: f64,
}

/// The section behaviour's record of each slot's vehicle (its own values); the stretches
/// are the road's (`RoadState::behaviour`).
#[derive(Clone, Debug)]
pub(crate) struct Sections {
    slots: Vec<Option<Slot>>,
}

impl Sections {
    /// `None` without stretches (nothing to apply).
    pub fn new(stretches: &[DriverStretch]) -> Option<Sections> {
        (!stretches.is_empty()).then(|| Sections { slots: Vec::new() })
    }

    /// The slots were renumbered (`Simulation::compact`): `order[new] = old`.
    pub fn renumber(&mut self, order: &[u32]) {
        self.slots = order
            .iter()
            .map(|&old| self.slots.get(old as usize).copied().flatten())
            .collect();
    }

    /// Give every vehicle on the road the θ and v_F of the stretch at its position.
    pub fn apply(&mut self, stretches: &[DriverStretch], traffic: &mut Traffic) {
        for lane in &traffic.lanes {
            for &s in lane {
                let k = s as usize;
                if k >= self.slots.len() {
                    self.slots.resize(k + 1, None);
                }
                let veh = &mut traffic.vehicles[k];
                let (id, x) = (veh.id, veh.x);
                let h = &mut veh.driver.human;
                let slot = match &mut self.slots[k] {
                    Some(sl) if sl.id == id => sl,
                    other => other.insert(Slot {
                        id,
                        v_f: h.desired_speed,
                        theta: h.buffer_s,
                        at: None,
                        written_v_f: h.desired_speed,
                    }),
                };
                if h.desired_speed != slot.written_v_f {
                    // Set from outside since the last write: the vehicle's own from now on.
                    let f_v = slot.at.map_or(1.0, |i| stretches[i].speed_factor);
                    slot.v_f = h.desired_speed / f_v;
                    slot.written_v_f = h.desired_speed;
                }
                let at = stretch_at(stretches, x);
                if at != slot.at {
                    let (f_theta, f_v) = at.map_or((1.0, 1.0), |i| {
                        let st = &stretches[i];
                        (st.buffer_factor, st.speed_factor)
                    });
                    h.buffer_s = slot.theta * f_theta;
                    h.desired_speed = slot.v_f * f_v;
                    slot.at = at;
                    slot.written_v_f = h.desired_speed;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn st(from_m: f64, to_m: f64, b: f64, v: f64) -> DriverStretch {
        DriverStretch {
            from_m,
            to_m,
            buffer_factor: b,
            speed_factor: v,
        }
    }

    #[test]
    fn a_position_takes_the_factors_of_its_stretch_and_one_elsewhere() {
        let s = [
            st(100.0, 200.0, 1.2, 0.9),
            st(200.0, 300.0, 0.8, 1.1),
            st(500.0, 600.0, 1.5, 0.7),
        ];
        assert_eq!(factors_at(&s, 0.0), (1.0, 1.0));
        assert_eq!(factors_at(&s, 99.999), (1.0, 1.0));
        assert_eq!(factors_at(&s, 100.0), (1.2, 0.9)); // from is inside
        assert_eq!(factors_at(&s, 199.9), (1.2, 0.9));
        assert_eq!(factors_at(&s, 200.0), (0.8, 1.1)); // to is outside: the next one
        assert_eq!(factors_at(&s, 300.0), (1.0, 1.0));
        assert_eq!(factors_at(&s, 450.0), (1.0, 1.0));
        assert_eq!(factors_at(&s, 599.0), (1.5, 0.7));
        assert_eq!(factors_at(&s, 1e9), (1.0, 1.0));
        assert_eq!(factors_at(&[], 10.0), (1.0, 1.0));
    }

    #[test]
    fn the_buffer_factor_scales_the_buffer_alone() {
        let s = [st(100.0, 200.0, 2.5, 0.9)];
        let p = HumanParams::default();
        let q = params_at(&s, &p, 150.0).unwrap();
        assert_eq!(q.buffer_s, 2.5 * p.buffer_s);
        assert_eq!(
            HumanParams {
                buffer_s: p.buffer_s,
                ..q
            },
            p
        );
        assert_eq!(params_at(&s, &p, 250.0), None);
        assert_eq!(params_at(&[], &p, 150.0), None);
    }
}
