//! Safety accounting (issue 18, docs/safety.md): the braking limit applied in the integrate
//! phase, emergency-braking episodes, the largest deceleration, collision events and the
//! surrogate safety measures (TTC, TET, TIT, conflicts), by vehicle kind.
//!
//! The laws are pure functions in `platoonsim_model::safety`; this module only accumulates.
//! Collisions count over the whole run (any one fails the run); the largest deceleration over
//! the whole run too (it checks the braking limit); everything else over the measurement
//! window, like the paper's statistics.

use crate::config::Config;
use crate::summary::{CollisionEvent, CollisionKind};
use crate::vehicle::{Kind, Vehicle};
use platoonsim_model::safety as law;

/// Per vehicle kind.
#[derive(Clone, Copy, Debug, Default)]
pub struct ByKind<T> {
    pub human: T,
    pub cav: T,
}

impl<T: Copy + std::ops::Add<Output = T>> ByKind<T> {
    #[inline]
    pub fn get_mut(&mut self, k: Kind) -> &mut T {
        match k {
            Kind::Human => &mut self.human,
            Kind::Cav => &mut self.cav,
        }
    }

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
}

/// The braking limit, emergency-braking episodes and the largest deceleration.
#[derive(Clone, Debug)]
pub struct Braking {
    /// Emergency deceleration b_e by kind (human 0, CAV 1; m/s², positive).
    pub emergency_decel: [f64; 2],
    /// The CAV's normal braking limit b (negative); a human's is its own `human.max_decel`.
    pub cav_max_decel: f64,
    /// The least severe normal limit any vehicle can have (negative): no vehicle braking
    /// less than this is in an emergency.
    loosest_normal: f64,
    /// An applied acceleration below this needs a look (a new largest deceleration, or an
    /// emergency): max(−`max_decel`, `loosest_normal`). One comparison per vehicle and step.
    watch: f64,
    /// Largest applied deceleration, whole run (m/s², positive).
    pub max_decel: f64,
    /// Episodes in the measurement window.
    pub emergency_brakings: ByKind<u64>,
    /// With observers attached: the emergency brakings that started in this step, at any time
    /// (id, kind, deceleration m/s²), drained into events after integrate.
    pub logging: bool,
    pub brakings: Vec<(u64, Kind, f64)>,
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
    pub conflicts: ByKind<u64>,
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

impl Safety {
    pub fn new(cfg: &Config) -> Safety {
        let h = &cfg.human.max_decel;
        let loosest_normal = h.max.max(h.mean).max(cfg.cav.max_decel);
        Safety {
            braking: Braking {
                emergency_decel: [cfg.human.emergency_decel_mps2, cfg.cav.emergency_decel_mps2],
                cav_max_decel: cfg.cav.max_decel,
                loosest_normal,
                watch: 0.0_f64.max(loosest_normal),
                max_decel: 0.0,
                emergency_brakings: ByKind::default(),
                logging: false,
                brakings: Vec::new(),
            },
            exposure: Exposure {
                ttc_threshold_s: cfg.safety.ttc_threshold_s,
                // max(TTC*, smallest TTC so far = ∞).
                ttc_horizon_s: f64::INFINITY,
                in_window: false,
                conflicts: ByKind::default(),
                tet_s: ByKind::default(),
                tit_s2: ByKind::default(),
                min_ttc_s: f64::INFINITY,
            },
            collisions: Collisions::default(),
        }
    }

    /// The vehicle's emergency limit b_e (positive).
    #[inline]
    pub fn limit(&self, kind: Kind) -> f64 {
        self.braking.emergency_decel[kind as usize]
    }

    /// The vehicle's normal braking limit b (negative).
    #[inline]
    pub fn normal(&self, v: &Vehicle) -> f64 {
        match v.kind {
            Kind::Human => v.driver.human.max_decel,
            Kind::Cav => self.braking.cav_max_decel,
        }
    }

    /// Account for the acceleration `a` a vehicle applied in this step, `a_prev` in the step
    /// before (an episode is consecutive emergency steps); `in_window`: the step is in the
    /// measurement window.
    #[inline]
    pub fn on_applied(&mut self, v: &Vehicle, a_prev: f64, a: f64, in_window: bool) {
        if a < self.braking.watch {
            self.on_hard_braking(v, a_prev, a, in_window);
        }
    }

    #[cold]
    #[inline(never)]
    fn on_hard_braking(&mut self, v: &Vehicle, a_prev: f64, a: f64, in_window: bool) {
        if -a > self.braking.max_decel {
            self.braking.max_decel = -a;
            self.braking.watch = (-self.braking.max_decel).max(self.braking.loosest_normal);
        }
        let normal = self.normal(v);
        if law::is_emergency(a, normal) && !law::is_emergency(a_prev, normal) {
            if in_window {
                *self.braking.emergency_brakings.get_mut(v.kind) += 1;
            }
            if self.braking.logging {
                self.braking.brakings.push((v.id, v.kind, -a));
            }
        }
    }

    /// A follower `fol` closing in on leader `lead_id` (speed `lead_v`) with net gap `gap`,
    /// within `ttc_horizon_s` of it (or overlapping it): in the measurement window, the
    /// smallest TTC, TET, TIT and conflict episodes.
    #[cold]
    #[inline(never)]
    pub fn on_close(
        &mut self,
        fol: &mut Vehicle,
        lead_id: u64,
        gap: f64,
        lead_v: f64,
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
                *self.exposure.conflicts.get_mut(fol.kind) += 1;
            }
            fol.stats.conflict_step = step;
            fol.stats.conflict_leader = lead_id;
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
