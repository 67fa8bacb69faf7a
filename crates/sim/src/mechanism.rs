//! Where an organizing strategy's discharge change comes from (issue 43 item 4;
//! docs/outputs.md, "The mechanism measures"): CAVs waiting for a gap, lane-change
//! disturbances, lane changes beside their geometric need, and the discharge by lane.
//!
//! Measured over the *section* [x₀, x₁] (the strategy's zone; without one, the control section
//! of a plain road or the whole corridor) in the measurement window t ≥ warm-up, from the
//! vehicles as they are after each step (Δt each):
//!
//! ```text
//! W_l  = Σ Δt over CAVs in lane l of the section in a `blc` mode   (veh-s; waiting for a gap)
//! O_l  = Σ Δt over every vehicle in lane l of the section          (veh-s)
//! share_l = W_l / O_l
//! LC   = lane changes made inside the section (a vehicle's lane differs from its lane
//!        of the previous step, both inside)
//! D    = of those, the changes whose new follower (the vehicle right behind in the new lane
//!        at that step) brakes harder than b_D within T_D, the step of the change included
//! need = Σ over CAVs entering the section of |organized lane − lane| at their first step in it
//! ```
//!
//! The ΔQ split by lane is read from the measurement detector at the end
//! ([`crate::Simulation::finish`]): per lane, its count over the window in veh/h.
//!
//! Everything is read at every step (Δt), not at a trajectory sampling period: a new
//! follower's short braking peak is not missed between samples (docs/reproduction-notes.md).
//!
//! | parameter | symbol | unit | value | source |
//! |---|---|---|---|---|
//! | follower braking threshold | b_D | m/s² | 2.0 | b_c, the comfortable deceleration of spec 4.3 (docs/model-choices.md) |
//! | follower window | T_D | s | 5.0 | a few reaction times after the change (docs/outputs.md) |
//!
//! Off unless `measurement.mechanism = true`; it costs a pass over the vehicles and a hash
//! lookup per vehicle in the section per step.

use crate::events::StepView;
use crate::network::Geometry;
use crate::organize::{organized_lane_at, LaneChoice};
use crate::vehicle::{Kind, ModeLabel};
use serde::Serialize;
use std::collections::HashMap;

/// b_D: a new follower braking harder than this (m/s²) counts as disturbed.
pub const FOLLOWER_BRAKE_MPS2: f64 = 2.0;
/// T_D: how long after a lane change its new follower is watched (s).
pub const FOLLOWER_WINDOW_S: f64 = 5.0;
/// Steps between two purges of the vehicles that left the section.
const PURGE_EVERY_STEPS: u64 = 600;

/// A vehicle seen in the section.
#[derive(Clone, Copy, Debug)]
struct Seen {
    lane: u32,
    step: u64,
}

/// A new follower under watch after a lane change.
#[derive(Clone, Copy, Debug)]
struct Watch {
    follower: u64,
    until_s: f64,
    hardest_mps2: f64,
}

/// The accumulator (one per run).
#[derive(Debug)]
pub struct Mechanism {
    from_m: f64,
    to_m: f64,
    warmup_s: f64,
    dt: f64,
    choice: LaneChoice,
    seen: HashMap<u64, Seen>,
    watches: Vec<Watch>,
    /// W_l and O_l by engine lane (veh-s).
    wait: Vec<f64>,
    occupied: Vec<f64>,
    changes: u64,
    changes_cav: u64,
    disturbed: u64,
    cavs: u64,
    need: u64,
    window_s: f64,
}

/// What the mechanism measures report (`summary.json`, flattened; docs/outputs.md).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MechanismSummary {
    /// The section, output coordinates (m).
    pub mechanism_from_m: f64,
    pub mechanism_to_m: f64,
    /// Σ W_l per hour of the window (veh-s/h).
    pub cav_wait_veh_s_per_h: f64,
    /// Σ W_l / Σ O_l.
    pub cav_wait_share: Option<f64>,
    /// W_l per hour, lane 1 (the rightmost) first.
    pub cav_wait_veh_s_per_h_by_lane: Vec<f64>,
    /// share_l, lane 1 first (`null` for a lane nobody used).
    pub cav_wait_share_by_lane: Vec<Option<f64>>,
    /// LC per hour.
    pub section_lane_changes_per_h: f64,
    /// D per hour.
    pub disturbed_followers_per_h: f64,
    /// CAV lane changes in the section per CAV that entered it.
    pub section_lane_changes_per_cav: Option<f64>,
    /// need per CAV that entered it.
    pub lane_need_per_cav: Option<f64>,
    /// The measurement detector's flow by lane over the window (veh/h), lane 1 first
    /// (lanes it does not cover: 0).
    pub discharge_by_lane_vph: Vec<f64>,
    /// Its flow in the organized lane at the detector (veh/h): the leftmost covered lane
    /// unless the strategy names another.
    pub organized_lane_discharge_vph: f64,
}

impl Mechanism {
    /// Over [from_m, to_m] (engine coordinates) from `warmup_s` on, with steps of `dt` and
    /// the organized lane of `choice`.
    pub fn new(
        from_m: f64,
        to_m: f64,
        warmup_s: f64,
        dt: f64,
        lanes: usize,
        choice: LaneChoice,
    ) -> Self {
        Mechanism {
            from_m,
            to_m,
            warmup_s,
            dt,
            choice,
            seen: HashMap::new(),
            watches: Vec::new(),
            wait: vec![0.0; lanes],
            occupied: vec![0.0; lanes],
            changes: 0,
            changes_cav: 0,
            disturbed: 0,
            cavs: 0,
            need: 0,
            window_s: 0.0,
        }
    }

    /// The accumulator a configuration asks for: over the strategy's zone, or without one
    /// the control section of a plain road or the whole corridor.
    pub fn of(cfg: &crate::config::Config) -> Self {
        let (from_m, to_m) = match (&cfg.strategy.pd, &cfg.road.network) {
            (Some(pd), _) => (pd.zone_start_m, pd.zone_end_m),
            (None, Some(_)) => (0.0, cfg.road.length_m),
            (None, None) => (cfg.road.control_start_m, cfg.road.control_end_m),
        };
        let choice = cfg.strategy.pd.as_ref().map(|p| p.lane).unwrap_or_default();
        Mechanism::new(
            from_m,
            to_m,
            cfg.warmup_s,
            cfg.dt_s,
            cfg.road.lanes as usize,
            choice,
        )
    }

    /// After a step: the vehicles as `view` shows them (each lane front first).
    pub fn on_step(&mut self, view: &StepView<'_>, road: &Geometry) {
        let (step, t_s) = (view.step(), view.time_s());
        // The step ending at t covers (t − Δt, t]: it is in the window if it ends after the
        // warm-up (as the detectors count it).
        if t_s <= self.warmup_s + 1e-9 {
            return;
        }
        self.window_s += self.dt;
        let watching = !self.watches.is_empty();
        for l in 0..view.lanes() {
            let mut lane_vehicles = view.lane_vehicles(l).peekable();
            while let Some(v) = lane_vehicles.next() {
                if watching {
                    for w in self.watches.iter_mut().filter(|w| w.follower == v.id()) {
                        w.hardest_mps2 = w.hardest_mps2.min(v.a());
                    }
                }
                let x = v.x();
                if x < self.from_m || x > self.to_m {
                    continue;
                }
                let lane = v.lane();
                let l = lane as usize;
                self.occupied[l] += self.dt;
                let cav = v.kind() == Kind::Cav;
                if cav && matches!(v.mode_label(), ModeLabel::Blc | ModeLabel::BlcAuto) {
                    self.wait[l] += self.dt;
                }
                match self.seen.insert(v.id(), Seen { lane, step }) {
                    None => {
                        if cav {
                            self.cavs += 1;
                            let target = organized_lane_at(self.choice, road, x, lane);
                            self.need += target.map_or(0, |t| t.abs_diff(lane)) as u64;
                        }
                    }
                    Some(before) if before.lane != lane => {
                        self.changes += 1;
                        if cav {
                            self.changes_cav += 1;
                        }
                        if let Some(f) = lane_vehicles.peek() {
                            self.watches.push(Watch {
                                follower: f.id(),
                                until_s: t_s + FOLLOWER_WINDOW_S,
                                hardest_mps2: f.a(),
                            });
                        }
                    }
                    Some(_) => {}
                }
            }
        }
        let disturbed = &mut self.disturbed;
        self.watches.retain(|w| {
            if t_s + 1e-9 < w.until_s {
                return true;
            }
            if w.hardest_mps2 < -FOLLOWER_BRAKE_MPS2 {
                *disturbed += 1;
            }
            false
        });
        if step.is_multiple_of(PURGE_EVERY_STEPS) {
            self.seen.retain(|_, s| s.step == step);
        }
    }

    /// The summary, with the measurement detector at `position_m` (engine coordinates), whose
    /// lowest covered lane is `lowest` and whose window counts by covered lane are `counts`
    /// over `window_h` hours; `origin_m` converts the section to output coordinates.
    pub fn summary_at(
        &self,
        position_m: f64,
        lowest: usize,
        counts: &[u64],
        window_h: f64,
        road: &Geometry,
        origin_m: f64,
    ) -> MechanismSummary {
        let flows = counts
            .iter()
            .map(|&c| {
                if window_h > 0.0 {
                    c as f64 / window_h
                } else {
                    0.0
                }
            })
            .collect();
        let organized = organized_lane_at(self.choice, road, position_m, lowest as u32)
            .map_or(usize::MAX, |l| (l as usize).saturating_sub(lowest));
        self.summary(flows, organized, origin_m)
    }

    /// The summary, with the measurement detector's window flow by lane (veh/h, lane 1
    /// first) and the lane of it that is organized; `origin_m` converts the section.
    pub fn summary(
        &self,
        discharge_by_lane_vph: Vec<f64>,
        organized_lane: usize,
        origin_m: f64,
    ) -> MechanismSummary {
        // Watches still open at the end count with what they saw.
        let open = self
            .watches
            .iter()
            .filter(|w| w.hardest_mps2 < -FOLLOWER_BRAKE_MPS2)
            .count() as u64;
        let h = self.window_s / 3600.0;
        let per_h = |x: f64| if h > 0.0 { x / h } else { 0.0 };
        let ratio = |a: f64, b: f64| (b > 0.0).then(|| a / b);
        let total_wait: f64 = self.wait.iter().sum();
        let total_occupied: f64 = self.occupied.iter().sum();
        MechanismSummary {
            mechanism_from_m: self.from_m + origin_m,
            mechanism_to_m: self.to_m + origin_m,
            cav_wait_veh_s_per_h: per_h(total_wait),
            cav_wait_share: ratio(total_wait, total_occupied),
            cav_wait_veh_s_per_h_by_lane: self.wait.iter().map(|&w| per_h(w)).collect(),
            cav_wait_share_by_lane: self
                .wait
                .iter()
                .zip(&self.occupied)
                .map(|(&w, &o)| ratio(w, o))
                .collect(),
            section_lane_changes_per_h: per_h(self.changes as f64),
            disturbed_followers_per_h: per_h((self.disturbed + open) as f64),
            section_lane_changes_per_cav: ratio(self.changes_cav as f64, self.cavs as f64),
            lane_need_per_cav: ratio(self.need as f64, self.cavs as f64),
            organized_lane_discharge_vph: discharge_by_lane_vph
                .get(organized_lane)
                .copied()
                .unwrap_or(0.0),
            discharge_by_lane_vph,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::Config;
    use crate::vehicle::{Mode, Vehicle};
    use platoonsim_model::lanechange::Side;

    const DT: f64 = 0.1;

    fn vehicle(cfg: &Config, id: u64, kind: Kind, lane: u32, x: f64) -> Vehicle {
        let mut v = crate::insert::create(cfg, id, x, 0.0, 0);
        v.kind = kind;
        v.lane = lane;
        v.x = x;
        v
    }

    fn waiting(v: &mut Vehicle) {
        v.mode = Mode::Blc {
            side: Side::Left,
            mandatory: false,
            auto: false,
            ask: 0,
        };
    }

    /// One step: `lanes` holds each lane's vehicles front first (indices into `all`).
    fn step(m: &mut Mechanism, k: u64, all: &[Vehicle], lanes: &[Vec<u32>], road: &Geometry) {
        let t = (k as f64 * DT * 10.0).round() / 10.0;
        m.on_step(&StepView::new(k, t, 0.0, lanes, all, &[]), road);
    }

    /// Three lanes, section 5,000-6,000 m, warm-up 10 s, the leftmost lane organized.
    fn setup() -> (Config, Geometry, Mechanism) {
        let cfg = Config::homogeneous(0.5, 2000.0, 100.0, 10.0, 1);
        let road = Geometry::new(&cfg).unwrap();
        let m = Mechanism::new(5000.0, 6000.0, 10.0, DT, 3, LaneChoice::Leftmost);
        (cfg, road, m)
    }

    #[test]
    fn a_waiting_cav_counts_its_time_its_need_and_its_change_disturbs_its_new_follower() {
        let (cfg, road, mut m) = setup();
        let mut cav = vehicle(&cfg, 1, Kind::Cav, 0, 5500.0);
        waiting(&mut cav);
        // A human driver waiting for a gap does not count.
        let mut leader = vehicle(&cfg, 2, Kind::Human, 1, 5600.0);
        waiting(&mut leader);
        let mut follower = vehicle(&cfg, 3, Kind::Human, 1, 5450.0);
        // 10 s in the window with the CAV waiting in lane 0: steps 101..=200.
        for k in 101..=200 {
            let all = [cav.clone(), leader.clone(), follower.clone()];
            step(&mut m, k, &all, &[vec![0], vec![1, 2], vec![]], &road);
        }
        // It changes into lane 1 between the leader and the follower, which then brakes at
        // 2.5 m/s² for one step within the 5 s.
        cav.lane = 1;
        cav.mode = Mode::Cf;
        for k in 201..=260 {
            follower.a = if k == 230 { -2.5 } else { -0.5 };
            let all = [cav.clone(), leader.clone(), follower.clone()];
            step(&mut m, k, &all, &[vec![], vec![1, 0, 2], vec![]], &road);
        }
        let s = m.summary(vec![1000.0, 1100.0, 1200.0], 2, 0.0);
        let h = 16.0 / 3600.0;
        assert!((s.cav_wait_veh_s_per_h - 10.0 / h).abs() < 1e-6, "{s:?}");
        assert!((s.cav_wait_veh_s_per_h_by_lane[0] - 10.0 / h).abs() < 1e-6);
        assert_eq!(s.cav_wait_veh_s_per_h_by_lane[1], 0.0);
        // Lane 0 held only the waiting CAV; lane 1 the two humans for 16 s and the CAV for 6.
        assert!((s.cav_wait_share_by_lane[0].unwrap() - 1.0).abs() < 1e-9);
        assert!((s.cav_wait_share.unwrap() - 10.0 / 48.0).abs() < 1e-9);
        assert_eq!(s.cav_wait_share_by_lane[2], None);
        assert!((s.section_lane_changes_per_h - 1.0 / h).abs() < 1e-6);
        assert!((s.disturbed_followers_per_h - 1.0 / h).abs() < 1e-6);
        // One CAV entered, in lane 0 of three with the leftmost organized: a need of 2.
        assert_eq!(s.lane_need_per_cav, Some(2.0));
        assert_eq!(s.section_lane_changes_per_cav, Some(1.0));
        assert_eq!(s.organized_lane_discharge_vph, 1200.0);
    }

    #[test]
    fn a_follower_braking_gently_or_late_is_not_disturbed() {
        for (k_brake, a) in [(230, -1.9), (252, -3.0)] {
            let (cfg, road, mut m) = setup();
            let mut cav = vehicle(&cfg, 1, Kind::Cav, 0, 5500.0);
            let mut follower = vehicle(&cfg, 3, Kind::Human, 1, 5450.0);
            step(
                &mut m,
                200,
                &[cav.clone(), follower.clone()],
                &[vec![0], vec![1], vec![]],
                &road,
            );
            cav.lane = 1;
            for k in 201..=300 {
                follower.a = if k == k_brake { a } else { 0.0 };
                let all = [cav.clone(), follower.clone()];
                step(&mut m, k, &all, &[vec![], vec![0, 1], vec![]], &road);
            }
            let s = m.summary(vec![0.0; 3], 2, 0.0);
            assert!(s.section_lane_changes_per_h > 0.0);
            assert_eq!(
                s.disturbed_followers_per_h, 0.0,
                "brake {a} at step {k_brake}"
            );
        }
    }

    #[test]
    fn nothing_counts_outside_the_section_or_before_the_warm_up() {
        let (cfg, road, mut m) = setup();
        let mut cav = vehicle(&cfg, 1, Kind::Cav, 0, 6001.0);
        waiting(&mut cav);
        let mut early = vehicle(&cfg, 2, Kind::Cav, 1, 5500.0);
        waiting(&mut early);
        // Before the warm-up (t ≤ 10 s) the CAV in the section is not seen; after it, the
        // one beyond the section is not.
        for k in 1..=100 {
            let all = [cav.clone(), early.clone()];
            step(&mut m, k, &all, &[vec![0], vec![1], vec![]], &road);
        }
        let s = m.summary(vec![0.0; 3], 2, 0.0);
        assert_eq!(s.cav_wait_veh_s_per_h, 0.0);
        assert_eq!(s.lane_need_per_cav, None);
        for k in 101..=110 {
            let all = [cav.clone()];
            step(&mut m, k, &all, &[vec![0], vec![], vec![]], &road);
        }
        let s = m.summary(vec![0.0; 3], 2, 0.0);
        assert_eq!(s.cav_wait_share, None);
        assert_eq!(s.section_lane_changes_per_h, 0.0);
    }
}
