//! Energy per vehicle (issue 23; docs/energy.md): an [`Observer`] that, after every step,
//! turns each vehicle's applied acceleration and speed into fuel (combustion engine,
//! VT-CPFM-1) or battery energy (electric), with its drag coefficient scaled by its place in a
//! chain of close-following vehicles (`platoonsim_model::energy::drag`).
//!
//! It keeps its state by vehicle id (nothing in the vehicle record), and reads the vehicles
//! through the public API after the step: distance d = x − x_prev, end speed v, applied
//! acceleration a (so start speed v₀ = v − aΔt, exact after integrate), mean speed d/Δt.
//! A vehicle inserted in the step has not moved yet and is skipped; one that leaves in a step
//! has that step added when it leaves (with the drag factor of its previous step).
//!
//! Three energies per vehicle, the basis of the drag-vs-dynamics split:
//! * E: what it used (drag reduced);
//! * E_nd: the same trajectory without drag reduction;
//! * E_st: the same distance in the same time at constant speed, alone.
//!
//! E = E_st + (E_nd − E_st) − (E_nd − E): the steady cost of its mean speed, the dynamics
//! (speed changes; usually > 0), less the drag saving. Runs off unless `energy.enabled`: the
//! sweep costs about a sense pass per step (docs/energy.md).

use crate::config::Config;
use crate::events::{Departure, Observer, StepView};
use crate::vehicle::{Kind, Vehicle};
use crate::view::VehicleView;
use platoonsim_model::energy::drag::Drag;
use platoonsim_model::energy::electric::{Electric, J_PER_KWH};
use platoonsim_model::energy::vt_cpfm::VtCpfm;
use platoonsim_model::energy::{EnergyParams, Powertrain};
use serde::Serialize;

/// Sums over one vehicle's trip so far.
#[derive(Clone, Copy, Debug, Default)]
struct Acc {
    /// Energy used: litres (combustion) or joules (electric).
    used: f64,
    /// The same without drag reduction.
    no_drag: f64,
    /// Aerodynamic work without reduction, and as reduced (J).
    aero: f64,
    aero_reduced: f64,
    dist_m: f64,
    steps: u64,
    /// Drag factor of its last step.
    factor: f64,
    seen: bool,
}

/// Sums over the measured vehicles of one kind (entered in the measurement window).
#[derive(Clone, Copy, Debug, Default)]
struct Totals {
    used: f64,
    no_drag: f64,
    steady: f64,
    aero: f64,
    aero_reduced: f64,
    dist_m: f64,
    vehicles: u64,
}

/// One vehicle's energy, as in `trips.csv`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TripEnergy {
    /// Fuel (L) of a combustion-engine vehicle.
    pub fuel_l: Option<f64>,
    /// Battery energy (kWh, net of recuperation) of an electric vehicle.
    pub energy_kwh: Option<f64>,
    /// Share of the energy it would have used without drag reduction that the reduction
    /// saved (%); `None` before it moved.
    pub drag_saving_pct: Option<f64>,
}

/// The energy fields of `summary.json` (present when `energy.enabled`). Per 100 km over the
/// vehicles that entered in the measurement window, their whole trips (or up to the end of
/// the run). A field is `null` where no such vehicle exists.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EnergySummary {
    /// Combustion-engine vehicles: all, CAVs, human-driven (L/100 km).
    pub fuel_l_per_100km: Option<f64>,
    pub fuel_l_per_100km_cav: Option<f64>,
    pub fuel_l_per_100km_human: Option<f64>,
    /// Electric vehicles: all, CAVs, human-driven (kWh/100 km, net of recuperation).
    pub energy_kwh_per_100km: Option<f64>,
    pub energy_kwh_per_100km_cav: Option<f64>,
    pub energy_kwh_per_100km_human: Option<f64>,
    /// Totals over the same vehicles: fuel (L), electricity (kWh), distance (km).
    pub fuel_l: f64,
    pub energy_kwh: f64,
    pub energy_distance_km: f64,
    /// Mean reduction of the aerodynamic work by drafting (%): 1 − Σ f·W_air / Σ W_air over
    /// the CAVs' (humans') steps, W_air the work against the air of an isolated vehicle.
    pub cav_drag_reduction_pct: Option<f64>,
    pub human_drag_reduction_pct: Option<f64>,
    /// The split (docs/energy.md): energy saved by drag reduction, % of the energy without it
    /// ((E_nd − E)/E_nd) …
    pub cav_drag_saving_pct: Option<f64>,
    pub human_drag_saving_pct: Option<f64>,
    /// … and the energy of the speed changes, % of the same trips at constant speed, alone
    /// ((E_nd − E_st)/E_st).
    pub cav_dynamics_excess_pct: Option<f64>,
    pub human_dynamics_excess_pct: Option<f64>,
}

/// The energy observer (see the module documentation).
#[derive(Clone, Debug)]
pub struct EnergyMeter {
    params: EnergyParams,
    /// Powertrain by kind: human, CAV.
    powertrain: [Powertrain; 2],
    car: VtCpfm,
    ev: Electric,
    drag: Drag,
    dt: f64,
    lanes: usize,
    /// By vehicle id.
    acc: Vec<Acc>,
    /// By kind: human, CAV.
    totals: [Totals; 2],
}

impl EnergyMeter {
    /// The meter for a run of `cfg` (with its `[energy]` settings and powertrains).
    pub fn new(cfg: &Config) -> EnergyMeter {
        EnergyMeter {
            params: cfg.energy,
            powertrain: [cfg.human.powertrain, cfg.cav.powertrain],
            car: VtCpfm::default(),
            ev: Electric::default(),
            drag: Drag::default(),
            dt: cfg.dt_s,
            lanes: cfg.road.lanes as usize,
            acc: Vec::new(),
            totals: [Totals::default(); 2],
        }
    }

    fn slot(&mut self, id: u64) -> &mut Acc {
        let i = id as usize;
        if i >= self.acc.len() {
            self.acc.resize(i + 1, Acc::default());
        }
        &mut self.acc[i]
    }

    /// Whether a vehicle of `kind` gets drag reduction.
    fn drafts(&self, kind: Kind) -> bool {
        self.params.drag_reduction && (kind == Kind::Cav || self.params.humans_draft)
    }

    /// Add the step that `v` just made, with drag factor `f`.
    fn add_step(&mut self, v: &Vehicle, f: f64) {
        let dt = self.dt;
        let d = (v.x - v.x_prev).max(0.0);
        let v_mean = d / dt;
        let v0 = (v.v - v.a * dt).max(0.0);
        let (used, no_drag, aero) = match self.powertrain[v.kind as usize] {
            Powertrain::Combustion => (
                self.car.step_fuel_l(v_mean, v.a, dt, f),
                self.car.step_fuel_l(v_mean, v.a, dt, 1.0),
                self.car.aero_n(v_mean, 1.0) * d,
            ),
            Powertrain::Electric => (
                self.ev.step_energy_j(v0, v.v, d, dt, f),
                self.ev.step_energy_j(v0, v.v, d, dt, 1.0),
                self.ev.aero_n(v_mean, 1.0) * d,
            ),
        };
        let a = self.slot(v.id);
        a.used += used;
        a.no_drag += no_drag;
        a.aero += aero;
        a.aero_reduced += f * aero;
        a.dist_m += d;
        a.steps += 1;
        a.factor = f;
        a.seen = true;
    }

    /// The energy of the same distance in the same time at constant speed, alone (L or J).
    fn steady(&self, pt: Powertrain, dist_m: f64, steps: u64) -> f64 {
        let t = steps as f64 * self.dt;
        if t <= 0.0 {
            return 0.0;
        }
        let v = dist_m / t;
        match pt {
            Powertrain::Combustion => self.car.step_fuel_l(v, 0.0, t, 1.0),
            Powertrain::Electric => self.ev.step_energy_j(v, v, dist_m, t, 1.0),
        }
    }

    /// One vehicle's energy so far (`None` if it never moved, or the id is unknown).
    pub fn trip(&self, id: u64, kind: Kind) -> Option<TripEnergy> {
        let a = self.acc.get(id as usize).filter(|a| a.seen)?;
        let saving = (a.no_drag > 0.0).then(|| 100.0 * (a.no_drag - a.used) / a.no_drag);
        Some(match self.powertrain[kind as usize] {
            Powertrain::Combustion => TripEnergy {
                fuel_l: Some(a.used),
                energy_kwh: None,
                drag_saving_pct: saving,
            },
            Powertrain::Electric => TripEnergy {
                fuel_l: None,
                energy_kwh: Some(a.used / J_PER_KWH),
                drag_saving_pct: saving,
            },
        })
    }

    /// The summary's energy fields.
    pub fn summary(&self) -> EnergySummary {
        let per_100km = |pt: Powertrain, kinds: &[usize]| -> Option<f64> {
            let (mut e, mut km) = (0.0, 0.0);
            for &k in kinds {
                if self.powertrain[k] == pt {
                    e += self.totals[k].used;
                    km += self.totals[k].dist_m / 1000.0;
                }
            }
            let scale = match pt {
                Powertrain::Combustion => 1.0,
                Powertrain::Electric => 1.0 / J_PER_KWH,
            };
            let any = kinds
                .iter()
                .any(|&k| self.powertrain[k] == pt && self.totals[k].vehicles > 0);
            (any && km > 0.0).then(|| 100.0 * e * scale / km)
        };
        let total = |pt: Powertrain| -> f64 {
            (0..2)
                .filter(|&k| self.powertrain[k] == pt)
                .fold(0.0, |sum, k| sum + self.totals[k].used)
        };
        let pct = |num: f64, den: f64| (den > 0.0).then(|| 100.0 * num / den);
        let t = &self.totals;
        let reduction = |k: usize| pct(t[k].aero - t[k].aero_reduced, t[k].aero);
        let saving = |k: usize| pct(t[k].no_drag - t[k].used, t[k].no_drag);
        let dynamics = |k: usize| pct(t[k].no_drag - t[k].steady, t[k].steady);
        let (h, c) = (Kind::Human as usize, Kind::Cav as usize);
        EnergySummary {
            fuel_l_per_100km: per_100km(Powertrain::Combustion, &[h, c]),
            fuel_l_per_100km_cav: per_100km(Powertrain::Combustion, &[c]),
            fuel_l_per_100km_human: per_100km(Powertrain::Combustion, &[h]),
            energy_kwh_per_100km: per_100km(Powertrain::Electric, &[h, c]),
            energy_kwh_per_100km_cav: per_100km(Powertrain::Electric, &[c]),
            energy_kwh_per_100km_human: per_100km(Powertrain::Electric, &[h]),
            fuel_l: total(Powertrain::Combustion),
            energy_kwh: total(Powertrain::Electric) / J_PER_KWH,
            energy_distance_km: (t[h].dist_m + t[c].dist_m) / 1000.0,
            cav_drag_reduction_pct: reduction(c),
            human_drag_reduction_pct: reduction(h),
            cav_drag_saving_pct: saving(c),
            human_drag_saving_pct: saving(h),
            cav_dynamics_excess_pct: dynamics(c),
            human_dynamics_excess_pct: dynamics(h),
        }
    }
}

/// Longest chain position the drag model distinguishes (the 4th and further are alike).
const DEEPEST: u32 = 4;

impl Observer for EnergyMeter {
    fn on_step(&mut self, view: &StepView<'_>) {
        let step = view.step();
        let (lanes, vehicles) = view.records();
        for lane in &lanes[..self.lanes] {
            // Front to back: the chain position of the vehicle ahead and its rear.
            let mut ahead: Option<(u32, f64)> = None;
            let mut it = lane.iter().map(|&s| &vehicles[s as usize]).peekable();
            while let Some(v) = it.next() {
                let behind_m = it.peek().map_or(f64::INFINITY, |b| v.rear() - b.x);
                let ahead_m = ahead.map_or(f64::INFINITY, |(_, rear)| rear - v.x);
                let k = match ahead {
                    Some((k, _)) if self.drag.linked(ahead_m) => (k + 1).min(DEEPEST),
                    _ => 1,
                };
                ahead = Some((k, v.rear()));
                // Inserted in this step: it has not moved yet.
                if v.stats.entered_step >= step {
                    continue;
                }
                let f = if self.drafts(v.kind) {
                    self.drag.factor(k, ahead_m, behind_m)
                } else {
                    1.0
                };
                self.add_step(v, f);
            }
        }
    }

    fn on_exit(&mut self, v: VehicleView<'_>, how: Departure, _t_s: f64) {
        let v = v.record();
        if how != Departure::OnRoad {
            // The step in which it left: it moved, then left before the sweep.
            let f = self
                .acc
                .get(v.id as usize)
                .map_or(1.0, |a| if a.seen { a.factor } else { 1.0 });
            self.add_step(v, f);
        }
        if !v.stats.measured {
            return;
        }
        let Some(a) = self.acc.get(v.id as usize).copied() else {
            return;
        };
        let pt = self.powertrain[v.kind as usize];
        let steady = self.steady(pt, a.dist_m, a.steps);
        let t = &mut self.totals[v.kind as usize];
        t.used += a.used;
        t.no_drag += a.no_drag;
        t.steady += steady;
        t.aero += a.aero;
        t.aero_reduced += a.aero_reduced;
        t.dist_m += a.dist_m;
        t.vehicles += 1;
    }
}
