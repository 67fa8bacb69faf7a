//! Validation of the `[road]` section (lanes, length, control section) and of `[demand]`, and
//! the coordinate frame of the file's positions, split from `validate.rs` by responsibility.
//! With a `[network]` the lanes, the length and the demand follow from it and must be left out.

use super::network::Checked;
use super::{defaults, Checker, Frame, Num};
use crate::limits;
use crate::raw::{num, RawDemand, RawRoad};

/// The checked road. Values are only meaningful if no problem was reported.
pub(super) struct Road {
    /// Lateral lane positions.
    pub lanes: u32,
    /// Road length (engine), if valid.
    pub length: Option<f64>,
    pub frame: Frame,
    /// The control section in the file's coordinate (`None` if a required key is missing).
    pub control_start: Option<Num>,
    pub control_end: Option<Num>,
}

/// `[road]`, given the checked `[network]` if there is one.
pub(super) fn check_road(c: &mut Checker, r: &RawRoad, net: Option<&Checked>) -> Road {
    let (lanes, length) = match net {
        Some(v) => {
            let given = [
                ("road.lanes", r.lanes.map(|n| n.to_string())),
                ("road.length_m", r.length_m.map(num)),
            ];
            for (field, value) in given {
                if let Some(value) = value {
                    c.push(
                        field,
                        value,
                        "must be left out with [network]: the lanes and the length follow from \
                         network.lanes, network.start_m and network.end_m",
                    );
                }
            }
            (v.lanes, v.length)
        }
        None => road_size(c, r),
    };
    let frame = match net {
        Some(v) => Frame {
            network: true,
            origin: v.origin,
            hi: v.end,
        },
        None => Frame {
            network: false,
            origin: 0.0,
            hi: length,
        },
    };
    let (cstart, cend) = if frame.network {
        // Optional: the whole corridor by default.
        (
            Some(c.opt(r.control_start_m, frame.origin)),
            Some(c.opt(r.control_end_m, frame.hi.unwrap_or(f64::NAN))),
        )
    } else {
        (
            c.req(
                "road.control_start_m",
                r.control_start_m,
                "start of the control section (m from the entrance)",
            ),
            c.req(
                "road.control_end_m",
                r.control_end_m,
                "end of the control section (m from the entrance)",
            ),
        )
    };
    if let (Some(s), Some(e)) = (cstart, cend) {
        match frame.hi {
            _ if s.defaulted && e.defaulted => {}
            Some(hi) => {
                let s_ok = c.check(
                    "road.control_start_m",
                    s,
                    s.v >= frame.origin && s.v < hi,
                    format!(
                        "must lie in [{}, {}) (the control section must be on the road)",
                        frame.lo_text(),
                        frame.hi_text(hi)
                    ),
                );
                if s_ok {
                    c.check(
                        "road.control_end_m",
                        e,
                        e.v > s.v && e.v <= hi,
                        format!(
                            "must be > road.control_start_m = {} and <= {}",
                            s.shown(),
                            frame.hi_text(hi)
                        ),
                    );
                }
            }
            None if frame.network => {}
            None => {
                c.non_negative("road.control_start_m", s);
                c.non_negative("road.control_end_m", e);
            }
        }
    }
    Road {
        lanes,
        length,
        frame,
        control_start: cstart,
        control_end: cend,
    }
}

/// `road.lanes` and `road.length_m` of a road without a network (both required).
fn road_size(c: &mut Checker, r: &RawRoad) -> (u32, Option<f64>) {
    let lanes = match r.lanes {
        None => {
            c.missing(
                "road.lanes",
                &format!("an integer from 1 to {}", defaults::MAX_LANES),
            );
            0
        }
        Some(n) => {
            if !(1..=defaults::MAX_LANES).contains(&n) {
                c.push(
                    "road.lanes",
                    n.to_string(),
                    format!("must be an integer from 1 to {}", defaults::MAX_LANES),
                );
            }
            n
        }
    };
    let length = c.req(
        "road.length_m",
        r.length_m,
        "the road length in metres, > 0",
    );
    let length = length
        .filter(|&l| {
            c.check(
                "road.length_m",
                l,
                l.v > 0.0 && l.v <= limits::MAX_LENGTH_M,
                format!("must be in (0, {}] m", num(limits::MAX_LENGTH_M)),
            )
        })
        .map(|n| n.v);
    (lanes, length)
}

/// `[demand]` (with a [network]: its series instead, and `demand.vph_per_lane` must be left
/// out).
pub(super) fn check_demand(c: &mut Checker, d: &RawDemand, frame: &Frame) {
    if frame.network {
        if let Some(q) = d.vph_per_lane {
            c.push(
                "demand.vph_per_lane",
                num(q),
                "must be left out with [network]: the demand is network.mainline_vph and \
                 network.on_ramps[].demand_vph (scale it with network.demand_scale or --demand-scale)",
            );
        }
    } else if let Some(q) = c.req(
        "demand.vph_per_lane",
        d.vph_per_lane,
        "arrival rate per lane (veh/h/lane)",
    ) {
        c.check(
            "demand.vph_per_lane",
            q,
            (0.0..=defaults::MAX_DEMAND_VPHPL).contains(&q.v),
            format!(
                "must be in [0, {}] veh/h/lane",
                num(defaults::MAX_DEMAND_VPHPL)
            ),
        );
    }
}
