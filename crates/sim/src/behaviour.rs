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
//! | symbol | key (`[[network.behaviour]]`) | default | allowed | unit |
//! |---|---|---|---|---|
//! | – | `from_m`, `to_m` | – | inside the corridor, from < to, in order, no overlap | m |
//! | f_θ | `buffer_factor` | 1 | [0, 5] | – |
//! | f_v | `speed_factor` | 1 | [0.5, 1.5] | – |

use crate::config::DriverStretch;
use platoonsim_model::Relax;

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

/// `r` with the buffer factor `f_theta` on θ (the other factors as they are).
#[inline]
pub fn with_buffer_factor(r: Relax, f_theta: f64) -> Relax {
    Relax {
        buffer: r.buffer * f_theta,
        ..r
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
        let r = Relax {
            headway: 0.5,
            jam: 0.7,
            reaction: 0.8,
            buffer: 1.0,
        };
        let b = with_buffer_factor(r, 2.5);
        assert_eq!(
            (b.headway, b.jam, b.reaction, b.buffer),
            (0.5, 0.7, 0.8, 2.5)
        );
        assert_eq!(with_buffer_factor(Relax::NONE, 1.0), Relax::NONE);
    }
}
