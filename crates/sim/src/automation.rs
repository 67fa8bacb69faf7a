//! The realism of the automation (spec 9.3): actuator lag, the V2V beacons the CACC law reads
//! (delay, loss, the fallback to ACC after a timeout) and the bound on automated braking. The
//! laws are pure functions in `platoonsim_model::cav` (`actuate`, `beacon_age`,
//! `broadcast_step`); this module holds their per-run constants and the broadcast log.
//!
//! The broadcast log keeps, per vehicle slot, the speeds the vehicle broadcast in the last
//! `depth` = d + T_b + 2 steps (d the delay, T_b the timeout, in steps), as a ring indexed by
//! step: a follower that last received a beacon `age` steps ago reads its leader's speed of
//! step k − age − d. It exists only when the delay or the loss is on; otherwise the CACC law
//! reads the leader's current speed, as before. Rows are filled with the vehicle's speed when
//! it enters (it has broadcast nothing before) and move with the vehicles when the slots are
//! renumbered (`Simulation::compact`). No allocation in the step once the slots are warm.

use crate::config::Config;
use crate::rng::{self, Purpose};
use crate::vehicle::Vehicle;
use platoonsim_model::cav;

/// The per-run constants of the automation's realism, and the broadcast log.
#[derive(Clone, Debug)]
pub(crate) struct Automation {
    /// 1 − e^{−Δt/τ} (`cav::lag_gain`), τ = `CavParams::effective_lag_s`; 1 without lag.
    pub lag_gain: f64,
    /// D_auto (m/s², positive).
    pub bound: f64,
    /// The V2V beacons; `None` while the delay and the loss are 0: the CACC law reads the
    /// leader's current speed.
    pub beacons: Option<Beacons>,
}

impl Default for Automation {
    fn default() -> Self {
        Automation {
            lag_gain: 1.0,
            bound: f64::INFINITY,
            beacons: None,
        }
    }
}

/// The V2V channel: delay and timeout in steps, the loss, and the broadcast log.
#[derive(Clone, Debug)]
pub(crate) struct Beacons {
    pub delay_steps: u64,
    pub timeout_steps: u64,
    /// Probability that a follower's reception fails in a step.
    pub loss: f64,
    /// The scenario seed (the loss draws' stream, `rng::Purpose::Beacons`).
    pub seed: u64,
    /// Entries per slot: delay + timeout + 2 (one more than the oldest speed read, for the
    /// acceleration of the field law).
    depth: usize,
    /// Slot-major: `log[s·depth + step mod depth]` is the speed slot s broadcast at `step`.
    log: Vec<f64>,
}

impl Automation {
    pub fn new(cfg: &Config) -> Automation {
        let p = &cfg.cav;
        let delay_steps = cav::whole_steps(p.comm_delay_s, cfg.dt_s);
        let beacons = (delay_steps > 0 || p.packet_loss > 0.0)
            .then(|| Beacons::new(cfg.seed, delay_steps, p.packet_loss, cfg));
        Automation {
            lag_gain: cav::lag_gain(cfg.dt_s, p.effective_lag_s()),
            bound: p.max_automated_decel_mps2,
            beacons,
        }
    }
}

impl Beacons {
    pub(crate) fn new(seed: u64, delay_steps: u64, loss: f64, cfg: &Config) -> Beacons {
        let timeout_steps = cav::whole_steps(cfg.cav.beacon_timeout_s, cfg.dt_s);
        Beacons {
            delay_steps,
            timeout_steps,
            loss,
            seed,
            depth: (delay_steps + timeout_steps + 2) as usize,
            log: Vec::new(),
        }
    }

    /// The leader speed a follower whose freshest beacon is `age` steps old uses at `step`
    /// from the beacons of the leader in slot `leader` (spec 9.3): its broadcast of step
    /// k − age − d, or `None` past the timeout (fall back to ACC).
    #[inline]
    pub fn received_speed(&self, age: u32, leader: u32, step: u64) -> Option<f64> {
        if !cav::beacon_held(age, self.timeout_steps) {
            return None;
        }
        let k = cav::broadcast_step(step, age, self.delay_steps);
        Some(self.log[leader as usize * self.depth + (k % self.depth as u64) as usize])
    }

    /// The leader's acceleration that the same beacon carries (field law): the change of its
    /// broadcast speed into step k − age − d, (v(k) − v(k−1))/Δt; 0 past the timeout.
    #[inline]
    pub fn received_accel(&self, age: u32, leader: u32, step: u64, dt: f64) -> f64 {
        if !cav::beacon_held(age, self.timeout_steps) {
            return 0.0;
        }
        let k = cav::broadcast_step(step, age, self.delay_steps);
        if k == 0 {
            return 0.0;
        }
        let row = leader as usize * self.depth;
        let d = self.depth as u64;
        (self.log[row + (k % d) as usize] - self.log[row + ((k - 1) % d) as usize]) / dt
    }

    /// This step's receptions (spec 9.3), before the sense phase: each CAV's beacon age is 0
    /// if a beacon reached it, else one step more; a reception fails with probability
    /// `loss`, drawn from the CAV's counter-based stream (seed, `Beacons`, id, step). Nothing
    /// to do without loss.
    pub fn receive(&self, step: u64, lanes: &[Vec<u32>], vehicles: &mut [Vehicle]) {
        if self.loss <= 0.0 {
            return;
        }
        for lane in lanes {
            for &s in lane {
                let v = &mut vehicles[s as usize];
                if v.is_cav() {
                    let lost = rng::uniform_at(self.seed, Purpose::Beacons, v.id, step) < self.loss;
                    v.cacc.beacon_age = cav::next_beacon_age(v.cacc.beacon_age, lost);
                }
            }
        }
    }

    /// Slot `s` broadcasts speed `v` for step `step` (the state at that step's start).
    #[inline]
    pub fn broadcast(&mut self, s: u32, step: u64, v: f64) {
        self.log[s as usize * self.depth + (step % self.depth as u64) as usize] = v;
    }

    /// A vehicle enters slot `s` at speed `v`: every entry of its row is `v`.
    pub fn fill(&mut self, s: u32, v: f64) {
        let row = s as usize * self.depth;
        if self.log.len() < row + self.depth {
            self.log.resize(row + self.depth, v);
        }
        self.log[row..row + self.depth].fill(v);
    }

    /// The slots were renumbered: `order[new] = old`.
    pub fn renumber(&mut self, order: &[u32]) {
        let d = self.depth;
        let mut log = vec![0.0; order.len() * d];
        for (new, &old) in order.iter().enumerate() {
            let old = old as usize * d;
            log[new * d..(new + 1) * d].copy_from_slice(&self.log[old..old + d]);
        }
        self.log = log;
    }
}
