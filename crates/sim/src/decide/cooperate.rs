//! Cooperative lane changes of automated CAVs in the decide phase (spec 9.2; the pure rules
//! are `platoonsim_model::cooperative`): the requester's step, the opener's answer, and how a
//! request is found. Methods of the decide phase's read-only [`View`].

use super::{Desire, Me, View};
use crate::events::LaneChangeReason;
use crate::state::Decision;
use crate::state::NONE;
use crate::vehicle::{Mode, Vehicle};
use platoonsim_model::cooperative as coop;
use platoonsim_model::lanechange::Side;
use platoonsim_model::Leader;

/// Adjacent-lane vehicles a CAV looks through for a cooperative request (spec 9.2): requests
/// come from between it and its own leader, so a few suffice [D].
const COOP_SCAN: usize = 4;

/// Cooperative lane changes (spec 9.2; `platoonsim_model::cooperative`).
impl View<'_> {
    /// The request timeout in steps (at least 1).
    #[inline]
    fn coop_timeout_steps(&self) -> u16 {
        (self.cfg.cav.cooperative_timeout_s / self.clock.dt)
            .round()
            .clamp(1.0, f64::from(u16::MAX / 2)) as u16
    }

    /// The effective time gap of an automated CAV's controller (its drawn t_C before the first
    /// setting).
    #[inline]
    fn effective_gap(v: &Vehicle) -> f64 {
        if v.cacc.time_gap_s > 0.0 {
            v.cacc.time_gap_s
        } else {
            v.cacc.gap_s
        }
    }

    /// An automated CAV `me` with a mandatory or organizing desire `d`: the cooperative change
    /// if its target-lane follower is an automated CAV within V2V (sensor) range and the
    /// request lives; otherwise the published behaviour, with the request counter carried in
    /// the BLC mode (0 without a CAV follower: a new request starts once there is one).
    #[inline(never)]
    pub(super) fn cooperative_or_published(&self, me: &Me, d: Desire) -> Decision {
        let p = &self.cfg.cav;
        let v = me.v;
        let tf = self.side_follower(me, d.side);
        let partner = tf != NONE && {
            let f = &self.traffic.vehicles[tf as usize];
            f.automated() && v.rear() - f.x <= p.sensor_range_m
        };
        let prev = match v.mode {
            Mode::Blc { side, ask, .. } if side == d.side => ask,
            _ => 0,
        };
        let timeout = self.coop_timeout_steps();
        let ask = if partner {
            coop::next_ask(prev, timeout)
        } else {
            0
        };
        if coop::asking(ask, timeout) {
            return self.cooperative_change(me, d, tf, ask);
        }
        let mut dec = self.published_change(me, d);
        if let Mode::Blc { ask: a, .. } = &mut dec.mode {
            *a = ask;
        }
        dec
    }

    /// The requester's step (spec 9.2): its automation keeps control; once the follower `tf`
    /// answers, it matches the target lane's leader (never braking harder than b_co), and it
    /// changes when both gaps pass the gap acceptance of spec 4.3 and the change is safe for
    /// both new pairs under their own automated laws (`cooperative::join_safe`).
    fn cooperative_change(&self, me: &Me, d: Desire, tf: u32, ask: u16) -> Decision {
        let p = &self.cfg.cav;
        let (v, nb) = (me.v, me.nb());
        let b_co = p.cooperative_gap_decel_mps2;
        let f = &self.traffic.vehicles[tf as usize];
        let answered = matches!(f.mode, Mode::Ycf { to, coop: true, .. } if to == v.id);
        let tl = match d.side {
            Side::Left => nb.left_leader,
            Side::Right => nb.right_leader,
        };
        let target = match d.side {
            Side::Left => v.lane as usize + 1,
            Side::Right => (v.lane as usize).saturating_sub(1),
        };
        let v_des_target = self.v_des_in(me.s, v, target);
        let mut dec = self.cav_control(me);
        let t_own = Self::effective_gap(v);
        // The target lane's leader within sensor range, as the automation sees it.
        let lead = self
            .view(v, tl)
            .filter(|l| l.gap_m <= p.sensor_range_m)
            .map(|l| (l, self.is_cav(tl)));
        if let Some((l, cav_l)) = lead {
            let a_match = coop::open_gap_accel(
                p,
                v.v,
                v.a,
                v_des_target,
                l,
                cav_l,
                coop::opening_time_gap(p, t_own),
                b_co,
            );
            // Before the answer, no acceleration beyond what the target lane allows (never
            // braking for it, as 6.20); after it, the speed match.
            dec.accel = if answered {
                dec.accel.min(a_match)
            } else {
                dec.accel.min(a_match.max(0.0))
            };
        }
        let mut change = false;
        if answered {
            let (_, g) = self.before_lane_change(me, d, false);
            let lag = Leader {
                gap_m: v.rear() - f.x,
                v_mps: v.v,
            };
            let f_des = self.v_des_in(tf, f, f.lane as usize);
            let dt = self.clock.dt;
            change = g.lead_ok
                && g.lag_ok
                && coop::join_safe(
                    p,
                    f.v,
                    f.a,
                    f_des,
                    lag,
                    true,
                    Self::effective_gap(f),
                    b_co,
                    dt,
                )
                && lead.is_none_or(|(l, cav_l)| {
                    coop::join_safe(p, v.v, v.a, v_des_target, l, cav_l, t_own, b_co, dt)
                });
        }
        // The demand goes through the actuators (spec 9.3), as every automated one.
        self.actuate(v, &mut dec);
        dec.mode = Mode::Blc {
            side: d.side,
            mandatory: d.mandatory,
            auto: true,
            ask,
        };
        dec.change = change.then_some(d.side);
        dec.coop = change;
        dec.why = if d.mandatory {
            LaneChangeReason::Mandatory
        } else {
            LaneChangeReason::Organizing
        };
        dec
    }

    /// The opener's step (spec 9.2): an automated CAV without a desire of its own answers the
    /// nearest live request addressed to it (an automated CAV ahead of it in an adjacent lane,
    /// behind its own leader, asking toward its lane) by following the requester as a virtual
    /// leader at the opening gap, never braking harder than b_co.
    #[inline(never)]
    pub(super) fn open_gap(&self, me: &Me) -> Option<Decision> {
        let r = self.cooperative_request(me)?;
        let p = &self.cfg.cav;
        let v = me.v;
        let rv = &self.traffic.vehicles[r as usize];
        let mut dec = self.cav_control(me);
        let vl = Leader {
            gap_m: rv.rear() - v.x,
            v_mps: rv.v,
        };
        let t_open = coop::opening_time_gap(p, self.join_time_gap(me));
        dec.accel = dec.accel.min(coop::open_gap_accel(
            p,
            v.v,
            v.a,
            self.own_v_des(me),
            vl,
            true,
            t_open,
            p.cooperative_gap_decel_mps2,
        ));
        self.actuate(v, &mut dec);
        dec.mode = Mode::Ycf {
            to: rv.id,
            auto: true,
            coop: true,
        };
        Some(dec)
    }

    /// The time gap a CAV `me` will keep behind a joiner that enters between it and its
    /// leader: its own t_C if the joined string stays within `max_platoon` (the joiner takes
    /// the leader's position + 1 when the leader is a CAV in range with room, spec 3.6; the
    /// opener brings its own sub-string), else the inter-platoon gap.
    fn join_time_gap(&self, me: &Me) -> f64 {
        let p = &self.cfg.cav;
        let sensed = me.sensed;
        let ld = sensed.nb.leader;
        let pos_ld = if sensed.cav_ahead {
            self.sensed[ld as usize].platoon_pos
        } else {
            0
        };
        let pos_joiner = if pos_ld >= 1 && pos_ld < p.max_platoon {
            pos_ld + 1
        } else {
            1
        };
        if pos_joiner + sensed.sub_size <= p.max_platoon {
            me.v.cacc.gap_s
        } else {
            p.inter_platoon_gap_s
        }
    }

    /// The nearest live cooperative request addressed to `me` (slot), if any: in each adjacent
    /// lane, from the vehicle alongside forward, the first automated CAV asking toward `me`'s
    /// lane whose target-lane follower is `me` (ahead of it, behind its leader), within
    /// sensor range; the nearer of the two sides, the left one on a tie. Deterministic, and a
    /// vehicle with a desire of its own never gets here (so two requesters never wait for each
    /// other).
    fn cooperative_request(&self, me: &Me) -> Option<u32> {
        let p = &self.cfg.cav;
        let (v, nb) = (me.v, me.nb());
        let timeout = self.coop_timeout_steps();
        let x_limit = if nb.leader != NONE {
            self.traffic.vehicles[nb.leader as usize].x
        } else {
            f64::INFINITY
        };
        let lanes = &self.traffic.lanes;
        let mut best: Option<(u32, f64)> = None;
        for (lane, j, toward) in [
            (v.lane as usize + 1, nb.left_j as usize, Side::Right),
            (
                (v.lane as usize).wrapping_sub(1),
                nb.right_j as usize,
                Side::Left,
            ),
        ] {
            let Some(list) = lanes.get(lane) else {
                continue;
            };
            for &o in list[..j.min(list.len())].iter().rev().take(COOP_SCAN) {
                let r = &self.traffic.vehicles[o as usize];
                if r.x >= x_limit || r.rear() - v.x > p.sensor_range_m {
                    break;
                }
                let asks = matches!(r.mode, Mode::Blc { side, auto: true, ask, .. }
                    if side == toward && coop::asking(ask, timeout));
                if asks && r.automated() {
                    let dist = r.x - v.x;
                    if best.is_none_or(|(_, b)| dist < b) {
                        best = Some((o, dist));
                    }
                    break;
                }
            }
        }
        best.map(|(o, _)| o)
    }
}
