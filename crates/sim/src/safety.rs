//! Safety accounting (issues 18, 29, docs/safety.md, spec 9.4): the braking limit applied in
//! the integrate phase, hard-braking episodes and their classes, the largest deceleration,
//! collision events, the surrogate safety measures (TTC, TET, TIT, rear-end and lane-change
//! conflicts) and the vehicle-km the counts are rated by, by vehicle kind.
//!
//! The laws are pure functions in `platoonsim_model::safety`; this module only accumulates.
//! Collisions count over the whole run (any one fails the run); the largest deceleration over
//! the whole run too (it checks the braking limit); everything else over the measurement
//! window, like the paper's statistics.

use crate::config::Config;
use crate::events::{CollisionEvent, CollisionKind};
use crate::vehicle::{Kind, Vehicle};
use platoonsim_model::safety as law;

/// Per vehicle kind.
#[derive(Clone, Copy, Debug, Default)]
pub struct ByKind<T> {
    pub human: T,
    pub cav: T,
}

impl<T> ByKind<T> {
    #[inline]
    pub fn get_mut(&mut self, k: Kind) -> &mut T {
        match k {
            Kind::Human => &mut self.human,
            Kind::Cav => &mut self.cav,
        }
    }
}

impl<T: Copy + std::ops::Add<Output = T>> ByKind<T> {
    pub fn total(&self) -> T {
        self.human + self.cav
    }
}

/// The run's safety accumulators, in three parts.
#[derive(Clone, Debug)]
pub struct Safety {
    pub braking: Braking,
    pub exposure: Exposure,
    pub collisions: Collisions,
    /// The counted measures and the vehicle-km they are rated by.
    pub counts: Counts,
}

/// The measures counted in episodes, reported by kind and per 100 veh-km (in this order in
/// `summary.json`; spec 9.4). Adding one: a name here, one `count` call where it happens.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(usize)]
pub enum Counted {
    /// Hard-braking episodes: peak deceleration above d_hard = 4 m/s².
    HardBrakings,
    /// Of which peaking at d_severe = 6 m/s² or more.
    SevereBrakings,
    /// Of which reaching the vehicle's emergency limit b_e.
    BrakingsAtLimit,
    /// TTC conflicts of a (follower, leader) pair that did not start with a lane change.
    RearEndConflicts,
    /// TTC conflicts of a pair formed by a lane change in the step they start.
    LaneChangeConflicts,
    /// AEB interventions (spec 9.3): episodes in which an automated CAV needed harder braking
    /// than `cav.max_automated_decel_mps2` and the emergency system applied it.
    AebInterventions,
    /// Take-over requests (field CACC law, docs/cacc-field.md): episodes in which an automated
    /// CAV's demand exceeded the ISO 15622 deceleration envelope (short of AEB).
    TakeoverRequests,
}

impl Counted {
    /// Every counted measure, in output order.
    pub const ALL: [Counted; 7] = [
        Counted::HardBrakings,
        Counted::SevereBrakings,
        Counted::BrakingsAtLimit,
        Counted::RearEndConflicts,
        Counted::LaneChangeConflicts,
        Counted::AebInterventions,
        Counted::TakeoverRequests,
    ];

    /// The measure's name in the outputs (`summary.json`, the CSVs).
    pub const fn name(self) -> &'static str {
        match self {
            Counted::HardBrakings => "hard_brakings",
            Counted::SevereBrakings => "severe_brakings",
            Counted::BrakingsAtLimit => "brakings_at_limit",
            Counted::RearEndConflicts => "rear_end_conflicts",
            Counted::LaneChangeConflicts => "lane_change_conflicts",
            Counted::AebInterventions => "aeb_interventions",
            Counted::TakeoverRequests => "takeover_requests",
        }
    }
}

/// The braking limit, hard-braking episodes and the largest deceleration.
#[derive(Clone, Debug)]
pub struct Braking {
    /// Emergency deceleration b_e by kind (human 0, CAV 1; m/s², positive).
    pub emergency_decel: [f64; 2],
    /// An applied acceleration below this needs a look (a new largest deceleration, or a
    /// hard-braking step): −min(largest deceleration so far, d_hard). One comparison per
    /// vehicle and step.
    watch: f64,
    /// Largest applied deceleration, whole run (m/s², positive).
    pub max_decel: f64,
    /// The episodes running (a handful at most: braking beyond 4 m/s² is rare), by vehicle.
    running: Vec<Episode>,
    /// Episode peaks of the measurement window by kind, in the bins of
    /// `law::PEAK_BIN_EDGES_MPS2`.
    pub peaks: ByKind<[u64; law::PEAK_BIN_EDGES_MPS2.len()]>,
    /// With observers attached: the hard brakings that started in this step, at any time
    /// (id, kind, deceleration m/s²), drained into events after integrate.
    pub logging: bool,
    pub brakings: Vec<(u64, Kind, f64)>,
}

/// A hard-braking episode in progress.
#[derive(Clone, Copy, Debug)]
struct Episode {
    id: u64,
    /// The last step it braked hard in.
    step: u64,
    /// Its peak deceleration so far (m/s², positive).
    peak: f64,
    /// It started in the measurement window: it counts.
    counted: bool,
}

/// The surrogate safety measures of the measurement window.
#[derive(Clone, Debug)]
pub struct Exposure {
    /// TTC* (s).
    pub ttc_threshold_s: f64,
    /// TTC below which a pair needs a look: max(TTC*, smallest TTC so far).
    pub ttc_horizon_s: f64,
    /// The current step is in the measurement window (set by the invariant phase).
    pub in_window: bool,
    pub tet_s: ByKind<f64>,
    pub tit_s2: ByKind<f64>,
    /// Smallest TTC seen in the window (s); ∞ if none.
    pub min_ttc_s: f64,
}

/// The collisions of the whole run.
#[derive(Clone, Debug, Default)]
pub struct Collisions {
    /// Every collision, in time order.
    pub events: Vec<CollisionEvent>,
    /// (follower id, leader id) pairs overlapping at the end of the previous step, and of this
    /// one: a pair that overlaps in consecutive steps is one collision.
    pub overlapping: Vec<(u64, u64)>,
    pub overlapping_now: Vec<(u64, u64)>,
}

/// The counted measures of the measurement window and the distance they are rated by.
#[derive(Clone, Debug, Default)]
pub struct Counts {
    /// Episodes by measure ([`Counted`] as index) and kind.
    pub by_measure: [ByKind<u64>; Counted::ALL.len()],
    /// Vehicle-km driven in the measurement window, by kind.
    pub vehicle_km: ByKind<f64>,
}

impl Counts {
    #[inline]
    pub fn count(&mut self, what: Counted, kind: Kind) {
        *self.by_measure[what as usize].get_mut(kind) += 1;
    }

    pub fn get(&self, what: Counted) -> ByKind<u64> {
        self.by_measure[what as usize]
    }
}

impl Safety {
    pub fn new(cfg: &Config) -> Safety {
        Safety {
            braking: Braking {
                emergency_decel: [cfg.human.emergency_decel_mps2, cfg.cav.emergency_decel_mps2],
                watch: 0.0,
                max_decel: 0.0,
                running: Vec::new(),
                peaks: ByKind::default(),
                logging: false,
                brakings: Vec::new(),
            },
            exposure: Exposure {
                ttc_threshold_s: cfg.safety.ttc_threshold_s,
                // max(TTC*, smallest TTC so far = ∞).
                ttc_horizon_s: f64::INFINITY,
                in_window: false,
                tet_s: ByKind::default(),
                tit_s2: ByKind::default(),
                min_ttc_s: f64::INFINITY,
            },
            collisions: Collisions::default(),
            counts: Counts::default(),
        }
    }

    /// The vehicle's emergency limit b_e (positive).
    #[inline]
    pub fn limit(&self, kind: Kind) -> f64 {
        self.braking.emergency_decel[kind as usize]
    }

    /// Account for the acceleration `a` a vehicle applied in `step`, `a_prev` in the step
    /// before (an episode is consecutive hard-braking steps); `in_window`: the step is in the
    /// measurement window.
    #[inline]
    pub fn on_applied(&mut self, v: &Vehicle, a_prev: f64, a: f64, step: u64, in_window: bool) {
        if a < self.braking.watch {
            self.on_hard_braking(v, a_prev, a, step, in_window);
        }
    }

    #[cold]
    #[inline(never)]
    fn on_hard_braking(&mut self, v: &Vehicle, a_prev: f64, a: f64, step: u64, in_window: bool) {
        let b = &mut self.braking;
        if -a > b.max_decel {
            b.max_decel = -a;
            b.watch = -b.max_decel.min(law::HARD_BRAKING_MPS2);
        }
        if !law::is_hard(a) {
            return;
        }
        let d = -a;
        let limit = b.emergency_decel[v.kind as usize];
        let running = if law::is_hard(a_prev) {
            b.running
                .iter()
                .position(|e| e.id == v.id && e.step + 1 == step)
        } else {
            None
        };
        let (before, counted) = match running {
            Some(i) => {
                let e = &mut b.running[i];
                let before = e.peak;
                e.step = step;
                e.peak = e.peak.max(d);
                (Some(before), e.counted)
            }
            None => {
                // A new episode; the ended ones go.
                b.running.retain(|e| e.step + 1 >= step);
                b.running.push(Episode {
                    id: v.id,
                    step,
                    peak: d,
                    counted: in_window,
                });
                if b.logging {
                    b.brakings.push((v.id, v.kind, d));
                }
                (None, in_window)
            }
        };
        if !counted {
            return;
        }
        // Classes and bin as the peak grows: the counts of an episode running at the end of
        // the window are those of its peak so far.
        let old = before.map(|p| law::classify(p, limit)).unwrap_or_default();
        let peak = before.map_or(d, |p| p.max(d));
        let new = law::classify(peak, limit);
        let c = &mut self.counts;
        if new.hard && !old.hard {
            c.count(Counted::HardBrakings, v.kind);
        }
        if new.severe && !old.severe {
            c.count(Counted::SevereBrakings, v.kind);
        }
        if new.at_limit && !old.at_limit {
            c.count(Counted::BrakingsAtLimit, v.kind);
        }
        let bins = b.peaks.get_mut(v.kind);
        if let Some(p) = before {
            bins[law::peak_bin(p)] -= 1;
        }
        bins[law::peak_bin(peak)] += 1;
    }

    /// A follower `fol` closing in on leader `lead_id` (speed `lead_v`) with net gap `gap`,
    /// within `ttc_horizon_s` of it (or overlapping it): in the measurement window, the
    /// smallest TTC, TET, TIT and conflict episodes. `lane_change`: the pair was formed by a
    /// lane change in this step (the follower or the leader changed): a conflict starting now
    /// is a lane-change conflict.
    #[cold]
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub fn on_close(
        &mut self,
        fol: &mut Vehicle,
        lead_id: u64,
        gap: f64,
        lead_v: f64,
        lane_change: bool,
        step: u64,
        dt: f64,
    ) {
        if !self.exposure.in_window {
            return;
        }
        let Some(ttc) = law::ttc(gap, fol.v, lead_v) else {
            return;
        };
        if ttc < self.exposure.min_ttc_s {
            self.exposure.min_ttc_s = ttc;
            self.exposure.ttc_horizon_s = self.exposure.ttc_threshold_s.max(ttc);
        }
        if ttc < self.exposure.ttc_threshold_s {
            let (tet, tit) = law::exposure(ttc, self.exposure.ttc_threshold_s, dt);
            *self.exposure.tet_s.get_mut(fol.kind) += tet;
            *self.exposure.tit_s2.get_mut(fol.kind) += tit;
            if !(fol.stats.conflict_step == step - 1 && fol.stats.conflict_leader == lead_id) {
                let what = if lane_change {
                    Counted::LaneChangeConflicts
                } else {
                    Counted::RearEndConflicts
                };
                self.counts.count(what, fol.kind);
            }
            fol.stats.conflict_step = step;
            fol.stats.conflict_leader = lead_id;
        }
    }

    /// The counted measures as the summary gives them, with their rates.
    pub fn counted_measures(&self) -> crate::summary::CountedMeasures {
        let km = self.counts.vehicle_km;
        crate::summary::CountedMeasures(
            Counted::ALL
                .iter()
                .map(|&what| {
                    let n = self.counts.get(what);
                    crate::summary::CountedMeasure {
                        name: what.name(),
                        cav: n.cav,
                        human: n.human,
                        per_100vkm: law::per_100_vkm(n.total(), km.total()),
                        per_100vkm_cav: law::per_100_vkm(n.cav, km.cav),
                        per_100vkm_human: law::per_100_vkm(n.human, km.human),
                    }
                })
                .collect(),
        )
    }

    /// The episode-peak histogram as the summary gives it.
    pub fn braking_peaks(&self) -> crate::summary::BrakingPeaks {
        crate::summary::BrakingPeaks {
            lower_edges_mps2: law::PEAK_BIN_EDGES_MPS2.to_vec(),
            cav: self.braking.peaks.cav.to_vec(),
            human: self.braking.peaks.human.to_vec(),
        }
    }

    /// A collision event.
    #[cold]
    #[allow(clippy::too_many_arguments)]
    pub fn collide(
        &mut self,
        t_s: f64,
        kind: CollisionKind,
        lane: usize,
        x_m: f64,
        v: &Vehicle,
        other: Option<&Vehicle>,
        overlap_m: f64,
    ) {
        self.collisions.events.push(CollisionEvent {
            t_s,
            kind,
            lane: lane as u32 + 1,
            x_m,
            vehicle: v.id,
            vehicle_kind: v.kind.as_str(),
            v_mps: v.v,
            other: other.map(|o| o.id),
            other_kind: other.map(|o| o.kind.as_str()),
            other_v_mps: other.map(|o| o.v),
            overlap_m,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A vehicle of `kind` drawn from the homogeneous road's config.
    fn vehicle(cfg: &Config, id: u64, kind: Kind) -> Vehicle {
        let mut v = crate::insert::create(cfg, id, 0.0, 0.0, 0);
        v.kind = kind;
        v
    }

    /// Feed one vehicle's applied accelerations, one per step from step 1, all in the window.
    fn brake(safety: &mut Safety, v: &Vehicle, accels: &[f64]) {
        let mut a_prev = 0.0;
        for (k, &a) in accels.iter().enumerate() {
            safety.on_applied(v, a_prev, a, k as u64 + 1, true);
            a_prev = a;
        }
    }

    fn counts(s: &Safety, kind: Kind) -> [u64; 3] {
        let get = |w| *s.counts.get(w).clone().get_mut(kind);
        [
            get(Counted::HardBrakings),
            get(Counted::SevereBrakings),
            get(Counted::BrakingsAtLimit),
        ]
    }

    #[test]
    fn an_episode_is_classed_by_its_peak() {
        let cfg = Config::homogeneous(0.5, 1000.0, 60.0, 0.0, 1);
        let b_e = cfg.cav.emergency_decel_mps2;
        // Peak 5: hard only.
        let mut s = Safety::new(&cfg);
        let h = vehicle(&cfg, 1, Kind::Human);
        brake(&mut s, &h, &[-2.0, -4.5, -5.0, -4.2, -1.0]);
        assert_eq!(counts(&s, Kind::Human), [1, 0, 0]);
        assert_eq!(s.braking.peaks.human, [0, 1, 0, 0, 0, 0]);
        // Peak 6.5, growing and falling back within one episode: hard and severe, once.
        let mut s = Safety::new(&cfg);
        brake(&mut s, &h, &[-4.5, -6.5, -5.0, -6.5, -4.1, 0.0]);
        assert_eq!(counts(&s, Kind::Human), [1, 1, 0]);
        assert_eq!(s.braking.peaks.human, [0, 0, 1, 0, 0, 0]);
        // At the CAV's emergency limit b_e: all three, in the last bin.
        let mut s = Safety::new(&cfg);
        let c = vehicle(&cfg, 2, Kind::Cav);
        brake(&mut s, &c, &[-5.0, -b_e, -b_e, -3.0]);
        assert_eq!(counts(&s, Kind::Cav), [1, 1, 1]);
        assert_eq!(counts(&s, Kind::Human), [0, 0, 0]);
        assert_eq!(s.braking.peaks.cav, [0, 0, 0, 0, 0, 1]);
        // Exactly 4 is not hard braking; two episodes separated by a lighter step are two.
        let mut s = Safety::new(&cfg);
        brake(&mut s, &h, &[-4.0, -4.0, -3.0]);
        assert_eq!(counts(&s, Kind::Human), [0, 0, 0]);
        brake(&mut s, &h, &[-4.8, -3.9, -5.5]);
        assert_eq!(counts(&s, Kind::Human), [2, 0, 0]);
        assert_eq!(s.braking.peaks.human, [1, 1, 0, 0, 0, 0]);
        assert_eq!(s.braking.max_decel, 5.5);
    }

    #[test]
    fn episodes_of_two_vehicles_are_apart_and_the_window_decides() {
        let cfg = Config::homogeneous(0.5, 1000.0, 60.0, 0.0, 1);
        let mut s = Safety::new(&cfg);
        let (a, b) = (vehicle(&cfg, 1, Kind::Human), vehicle(&cfg, 2, Kind::Human));
        // Interleaved: a peaks at 6.2, b at 4.5, in the same steps.
        for (k, (&x, &y)) in [-5.0, -6.2, -4.5]
            .iter()
            .zip(&[-4.5, -4.5, -4.5])
            .enumerate()
        {
            let prev = |v: &[f64]| if k == 0 { 0.0 } else { v[k - 1] };
            s.on_applied(&a, prev(&[-5.0, -6.2, -4.5]), x, k as u64 + 1, true);
            s.on_applied(&b, prev(&[-4.5, -4.5, -4.5]), y, k as u64 + 1, true);
        }
        assert_eq!(counts(&s, Kind::Human), [2, 1, 0]);
        // An episode that starts before the window does not count, even as it grows in it.
        let mut s = Safety::new(&cfg);
        s.on_applied(&a, 0.0, -5.0, 1, false);
        s.on_applied(&a, -5.0, -7.0, 2, true);
        assert_eq!(counts(&s, Kind::Human), [0, 0, 0]);
        assert_eq!(s.braking.max_decel, 7.0);
    }

    #[test]
    fn rates_are_per_hundred_vehicle_km_of_the_same_kind() {
        let cfg = Config::homogeneous(0.5, 1000.0, 60.0, 0.0, 1);
        let mut s = Safety::new(&cfg);
        let h = vehicle(&cfg, 1, Kind::Human);
        brake(&mut s, &h, &[-6.0, 0.0, -5.0, 0.0, -4.5]);
        s.counts.vehicle_km = ByKind {
            human: 150.0,
            cav: 50.0,
        };
        let m = s.counted_measures();
        let hard = m.get("hard_brakings").unwrap();
        assert_eq!((hard.human, hard.cav, hard.total()), (3, 0, 3));
        assert_eq!(hard.per_100vkm, Some(1.5));
        assert_eq!(hard.per_100vkm_human, Some(2.0));
        assert_eq!(hard.per_100vkm_cav, Some(0.0));
        let severe = m.get("severe_brakings").unwrap();
        assert_eq!(severe.per_100vkm, Some(0.5));
        // No CAV drove: its rates do not apply.
        s.counts.vehicle_km.cav = 0.0;
        let m = s.counted_measures();
        assert_eq!(m.get("hard_brakings").unwrap().per_100vkm_cav, None);
        let names: Vec<&str> = m.0.iter().map(|c| c.name).collect();
        assert_eq!(
            names,
            [
                "hard_brakings",
                "severe_brakings",
                "brakings_at_limit",
                "rear_end_conflicts",
                "lane_change_conflicts",
                "aeb_interventions",
                "takeover_requests"
            ]
        );
    }
}
