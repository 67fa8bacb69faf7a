//! The engine seams the binding plugs into: an organizer whose advice is a table set from
//! Python between steps, a gated PD organizer switched from Python, and an observer that
//! buffers events until Python asks.

use platoonsim_sim::detector::Broadcast;
use platoonsim_sim::network::Geometry;
use platoonsim_sim::VehicleView;
use platoonsim_sim::{Advice, Event, Observer, Organizer, StepView};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

/// Lock without caring about poisoning: the data is plain and every writer leaves it whole.
pub fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|e| e.into_inner())
}

/// Advice by vehicle id: `advice[id - base]` (ids on the road form a narrow, increasing
/// window, so a vector beats a map). An id outside the table gets no advice.
#[derive(Debug, Default)]
pub struct AdviceTable {
    base: u64,
    advice: Vec<Advice>,
}

impl AdviceTable {
    /// Replace the table: vehicle `ids[i]` is advised to join `lanes[i]` with `strengths[i]`;
    /// a negative lane means no advice. Slices have equal lengths (checked by the caller).
    pub fn set(&mut self, ids: &[u64], lanes: &[i64], strengths: &[f64]) {
        self.advice.clear();
        let Some(&lo) = ids.iter().min() else {
            self.base = 0;
            return;
        };
        let hi = ids.iter().copied().max().unwrap_or(lo);
        self.base = lo;
        self.advice.resize((hi - lo + 1) as usize, Advice::Free);
        for ((&id, &lane), &strength) in ids.iter().zip(lanes).zip(strengths) {
            if lane >= 0 {
                self.advice[(id - lo) as usize] = Advice::Join {
                    lane: lane as u32,
                    strength,
                };
            }
        }
    }

    fn get(&self, id: u64) -> Advice {
        id.checked_sub(self.base)
            .and_then(|i| self.advice.get(i as usize))
            .copied()
            .unwrap_or(Advice::Free)
    }
}

/// A Python organizer as the engine sees it: the engine asks per vehicle and step, from the
/// step-start state; the answer comes from the table Python filled before the step.
#[derive(Debug)]
pub struct TableOrganizer {
    pub name: String,
    pub humans: bool,
    pub cavs: bool,
    pub table: Arc<Mutex<AdviceTable>>,
}

impl Organizer for TableOrganizer {
    fn name(&self) -> &str {
        &self.name
    }
    fn advises_cavs(&self) -> bool {
        self.cavs
    }
    fn advises_humans(&self) -> bool {
        self.humans
    }
    fn advise(&self, v: VehicleView<'_>, _t_s: f64, _road: &Geometry) -> Advice {
        lock(&self.table).get(v.id())
    }
}

/// An organizer of the engine's own (the scenario's PD rule) that gives its advice only while
/// switched on (`set_gate`): the gate of `PlatoonEnv`, native so that batched worlds step
/// without Python in the loop.
#[derive(Debug)]
pub struct GatedOrganizer {
    pub inner: Box<dyn Organizer>,
    pub on: Arc<AtomicBool>,
}

impl Organizer for GatedOrganizer {
    fn name(&self) -> &str {
        "gated-pd"
    }
    fn advises_cavs(&self) -> bool {
        self.inner.advises_cavs()
    }
    fn advises_humans(&self) -> bool {
        self.inner.advises_humans()
    }
    fn on_broadcasts(&mut self, road: &Geometry, broadcasts: &[(f64, Broadcast)]) {
        self.inner.on_broadcasts(road, broadcasts)
    }
    fn advise(&self, v: VehicleView<'_>, t_s: f64, road: &Geometry) -> Advice {
        if self.on.load(Ordering::Relaxed) {
            self.inner.advise(v, t_s, road)
        } else {
            Advice::Free
        }
    }
}

/// Every event of every step, kept until Python drains them.
#[derive(Default)]
pub struct EventBuffer {
    pub events: Arc<Mutex<Vec<Event>>>,
}

impl Observer for EventBuffer {
    fn on_step(&mut self, step: &StepView<'_>) {
        lock(&self.events).extend_from_slice(step.events());
    }
}
