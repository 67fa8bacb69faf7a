//! Cooperative yielding (spec 4.5): which lane-change request a driver, or an automated CAV
//! (spec 6.5 [D], docs/model-choices.md 6.5), agrees to, and the virtual leader it then follows.
//! Part of the decide phase; the yielding car-following law itself is
//! `platoonsim_model::lanechange::yield_accel`.

use crate::decide::{opposite, pair_uniform};
use crate::decide::{Me, View};
use crate::state::NONE;
use crate::vehicle::{Mode, Vehicle};
use platoonsim_model::lanechange::{self as lcm, Side};
use platoonsim_model::Leader;

impl View<'_> {
    /// The virtual leader of a yielder: the requester `r`, standing its own (relaxed) jam gap
    /// further back, so that the yielder leaves the room the requester's gap acceptance needs
    /// (spec 4.3: g0 > d_jam'); otherwise two standing vehicles wait for each other.
    #[inline]
    pub(crate) fn yield_gap(&self, v: &Vehicle, r: &Vehicle) -> Leader {
        Leader {
            gap_m: r.rear() - v.x - r.driver.lc.relax_jam * r.driver.human.jam_gap_m,
            v_mps: r.v,
        }
    }

    /// The requester (slot) of a yield request the driver `me` agrees to, if any (spec 4.5). The
    /// automation (`automated`, spec 6.5 flag) answers only mandatory requests, and, with
    /// `cav.yield_to_organizers`, a CAV moving left toward the PD lane.
    ///
    /// Inlined: most drivers have no adjacent-lane leader in BLC toward their lane, and this
    /// first test of [`Self::yield_request`] answers them without a call.
    #[inline]
    pub(crate) fn agreed_request(&self, me: &Me, automated: bool) -> Option<u32> {
        let nb = me.nb();
        let asks = |ld: u32, toward: Side| {
            ld != NONE
                && matches!(self.traffic.vehicles[ld as usize].mode, Mode::Blc { side, .. } if side == toward)
        };
        if !asks(nb.left_leader, Side::Right) && !asks(nb.right_leader, Side::Left) {
            return None;
        }
        self.agreed_request_from(me, automated)
    }

    /// [`Self::agreed_request`] once a neighbour asks.
    #[inline(never)]
    fn agreed_request_from(&self, me: &Me, automated: bool) -> Option<u32> {
        let v = me.v;
        self.yield_request(me).and_then(|(req, mandatory)| {
            let r = &self.traffic.vehicles[req as usize];
            let joining = || {
                self.cfg.cav.yield_to_organizers
                    && matches!(
                        r.mode,
                        Mode::Blc {
                            side,
                            mandatory: false,
                            ..
                        } if self.organizing_side(r) == Some(side)
                    )
            };
            if automated && !mandatory && !joining() {
                return None;
            }
            lcm::agrees_to_yield(
                &v.driver.lc,
                mandatory,
                pair_uniform(self.cfg.seed, v.id, r.id),
            )
            .then_some(req)
        })
    }

    /// Spec 4.5: the nearer adjacent-lane leader in BLC toward this lane, if any (slot,
    /// mandatory). Automated CAVs do not yield (spec 6.5) unless `cav.yield_while_automated`.
    fn yield_request(&self, me: &Me) -> Option<(u32, bool)> {
        let (v, nb) = (me.v, me.nb());
        let mut best: Option<(u32, bool, f64)> = None;
        for (ld, toward) in [(nb.left_leader, Side::Right), (nb.right_leader, Side::Left)] {
            if ld == NONE {
                continue;
            }
            let r = &self.traffic.vehicles[ld as usize];
            let Mode::Blc {
                side, mandatory, ..
            } = r.mode
            else {
                continue;
            };
            if side != toward {
                continue;
            }
            let dist = r.rear() - v.x;
            // Too late (spec 4.5) once the requester's rear is behind the driver's front; and
            // also while it is closer than the requester's own relaxed jam gap: the yielder
            // cannot back up, so braking could never open the gap the requester's test needs
            // (spec 4.3 g0 > d_jam'); two standing vehicles side by side would wait for each
            // other at the end of an acceleration lane. The driver drives on instead and the
            // next follower receives the request [D].
            if dist < r.driver.lc.relax_jam * r.driver.human.jam_gap_m {
                continue;
            }
            // The adjacent-lane leader may be far ahead (an empty stretch, or a lane that is
            // closed in between): only a nearby requester is a request [D].
            if dist > self.cfg.lane_change.yield_range_m {
                continue;
            }
            // Ignore a request from the lane the driver has just left.
            if let (Some(_), Some(last)) = (v.lcs.relax.started(), v.lcs.last_side) {
                if opposite(last) == opposite(toward) {
                    continue;
                }
            }
            if best.is_none_or(|(_, _, b)| dist < b) {
                best = Some((ld, mandatory, dist));
            }
        }
        best.map(|(s, m, _)| (s, m))
    }
}
