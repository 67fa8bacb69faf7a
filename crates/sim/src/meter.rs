//! Ramp meters in the engine (issue 45 item 3): the state of each metered on-ramp, the gate
//! the insertion phase asks before it places the ramp's queue head, ALINEA's detector and its
//! control periods, and the account for the summary. The laws are `platoonsim_model::meter`.
//!
//! Without a meter nothing here runs: the insertion phase finds no entry in `by_ramp` (one
//! branch per ramp and step), and the step skips the detectors and the control updates.

use crate::config::{Config, Meter, MeterLaw};
use crate::detector::Detector;
use crate::network::Geometry;
use crate::state::Traffic;
use crate::summary::MeterSummary;
use platoonsim_model::meter as law;

/// Every meter of a run.
#[derive(Debug, Default)]
pub(crate) struct Meters {
    /// Per on-ramp, the index of its meter in `list`; empty when no ramp is metered.
    pub by_ramp: Vec<Option<usize>>,
    pub list: Vec<RampMeter>,
}

/// What the meter says to the queue head of its ramp in this step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Gate {
    /// Not metering (outside its hours, or a fixed-rate meter in queue override): the
    /// insertion rule alone decides.
    Free,
    /// Green: the head may go (if the insertion rule admits it) at this cycle (s).
    Green { cycle_s: f64 },
    /// Red: the head waits.
    Red,
}

/// One metered on-ramp.
#[derive(Debug)]
pub(crate) struct RampMeter {
    /// The on-ramp's name (as in the configuration).
    name: String,
    spec: Meter,
    /// The rate the law sets (veh/h): fixed, or ALINEA's r(k) (r_max until its first update).
    rate_vph: f64,
    /// When the last green started (s); −∞ before the first.
    last_green_s: f64,
    /// ALINEA: its detector over the through lanes, with the search hint per lane, and its
    /// control period in steps.
    alinea: Option<AlineaLoop>,
    account: Account,
}

#[derive(Debug)]
struct AlineaLoop {
    detector: Detector,
    hints: Vec<u32>,
    period_steps: u64,
}

/// What the summary reports of a meter, accumulated step by step while it runs.
#[derive(Debug, Default)]
struct Account {
    active_steps: u64,
    override_steps: u64,
    released: u64,
    queue_sum: u64,
    queue_max: u64,
    /// Σ rate over the metering steps (active, not in override), and the lowest rate run.
    rate_sum: f64,
    rate_min: f64,
}

impl Meters {
    /// The meters of `cfg`'s on-ramps, with ALINEA's detectors placed on `geom`'s through lanes.
    pub fn new(cfg: &Config, geom: &Geometry, n_lanes: usize) -> Meters {
        let Some(net) = &cfg.road.network else {
            return Meters::default();
        };
        if net.on_ramps.iter().all(|r| r.meter.is_none()) {
            return Meters::default();
        }
        let mut out = Meters {
            by_ramp: vec![None; net.on_ramps.len()],
            list: Vec::new(),
        };
        for (i, r) in net.on_ramps.iter().enumerate() {
            let Some(spec) = &r.meter else { continue };
            let alinea = match &spec.law {
                MeterLaw::Fixed { .. } => None,
                MeterLaw::Alinea { law, detector_m } => {
                    let x = r.x_m + detector_m;
                    let mask = (0..n_lanes as u32)
                        .filter(|&l| geom.through(l, x))
                        .fold(0u32, |m, l| m | (1 << l));
                    let detector = Detector::covering(&r.name, x, n_lanes, mask, 0.0);
                    Some(AlineaLoop {
                        detector,
                        hints: vec![0; n_lanes],
                        period_steps: ((law.period_s / cfg.dt_s).round() as u64).max(1),
                    })
                }
            };
            out.by_ramp[i] = Some(out.list.len());
            out.list.push(RampMeter {
                name: r.name.clone(),
                spec: spec.clone(),
                rate_vph: spec.law.max_rate_vph(),
                last_green_s: f64::NEG_INFINITY,
                alinea,
                account: Account {
                    rate_min: f64::INFINITY,
                    ..Account::default()
                },
            });
        }
        out
    }

    /// The meter of on-ramp `ramp`, if it has one.
    #[inline]
    pub fn of_ramp(&self, ramp: usize) -> Option<usize> {
        self.by_ramp.get(ramp).copied().flatten()
    }

    /// Phase 6 for the meters' detectors (as for the loop detectors, `detect.rs`).
    pub fn observe(&mut self, dt: f64, traffic: &Traffic, lanes_sorted: bool) {
        for m in &mut self.list {
            if let Some(a) = &mut m.alinea {
                crate::detect::observe(dt, traffic, lanes_sorted, &mut a.detector, &mut a.hints);
            }
        }
    }

    /// After step `step` (the clock's count once it is done): every ALINEA meter whose control
    /// period ends reads its detector's occupancy over the period and, if it runs now, sets its
    /// next rate.
    pub fn control(&mut self, step: u64, dt: f64) {
        let now = step as f64 * dt;
        for m in &mut self.list {
            let (Some(a), MeterLaw::Alinea { law, .. }) = (&mut m.alinea, &m.spec.law) else {
                continue;
            };
            if !step.is_multiple_of(a.period_steps) {
                continue;
            }
            let occupancy_pct = 100.0 * a.detector.take_occupancy(a.period_steps as f64 * dt);
            if m.spec.active(now) {
                m.rate_vph = law::alinea_rate(law, m.rate_vph, occupancy_pct);
            }
        }
    }

    /// Each meter's account, in ramp order.
    pub fn summaries(&self, dt: f64) -> Vec<MeterSummary> {
        self.list.iter().map(|m| m.summary(dt)).collect()
    }
}

impl Meter {
    /// Whether the meter runs at simulated time `t_s`: in [from, to).
    #[inline]
    pub(crate) fn active(&self, t_s: f64) -> bool {
        t_s >= self.from_s - law::TIME_EPS_S
            && self.to_s.is_none_or(|to| t_s < to - law::TIME_EPS_S)
    }
}

impl RampMeter {
    /// The gate for the queue head at `now_s` (the end of this step) with `waiting` vehicles
    /// on the ramp; the step counts in the account.
    #[inline]
    pub fn gate(&mut self, now_s: f64, waiting: usize) -> Gate {
        if !self.spec.active(now_s) {
            return Gate::Free;
        }
        let acc = &mut self.account;
        acc.active_steps += 1;
        acc.queue_sum += waiting as u64;
        acc.queue_max = acc.queue_max.max(waiting as u64);
        let overridden = self
            .spec
            .queue_max_veh
            .is_some_and(|n| law::queue_override(waiting, n));
        let rate = if overridden {
            acc.override_steps += 1;
            match self.spec.law {
                MeterLaw::Fixed { .. } => return Gate::Free,
                MeterLaw::Alinea { law, .. } => law.max_rate_vph,
            }
        } else {
            acc.rate_sum += self.rate_vph;
            acc.rate_min = acc.rate_min.min(self.rate_vph);
            self.rate_vph
        };
        let cycle_s = law::cycle_s(rate);
        if law::green(now_s, self.last_green_s, cycle_s) {
            Gate::Green { cycle_s }
        } else {
            Gate::Red
        }
    }

    /// The queue head went at `now_s` through `gate` (a step of `dt_s`).
    #[inline]
    pub fn released(&mut self, gate: Gate, now_s: f64, dt_s: f64) {
        match gate {
            Gate::Green { cycle_s } => {
                self.last_green_s = law::green_start(now_s, self.last_green_s, cycle_s, dt_s);
                self.account.released += 1;
            }
            Gate::Free if self.spec.active(now_s) => {
                // A fixed-rate meter in override: its next green is a cycle after this one.
                self.last_green_s = now_s;
                self.account.released += 1;
            }
            Gate::Free | Gate::Red => {}
        }
    }

    fn summary(&self, dt: f64) -> MeterSummary {
        let a = &self.account;
        let metering = a.active_steps - a.override_steps;
        MeterSummary {
            ramp: self.name.clone(),
            kind: self.spec.law.name(),
            active_s: a.active_steps as f64 * dt,
            released: a.released,
            mean_rate_vph: (metering > 0).then(|| a.rate_sum / metering as f64),
            min_rate_vph: (metering > 0).then_some(a.rate_min),
            override_s: a.override_steps as f64 * dt,
            queue_mean_veh: (a.active_steps > 0)
                .then(|| a.queue_sum as f64 / a.active_steps as f64),
            queue_max_veh: a.queue_max,
        }
    }
}
