//! `none`: no platoon organization (the baseline). CAVs form platoons only by chance
//! encounters (spec 4.7).

use super::{Advice, Organizer, StrategyEntry};
use crate::config::Config;
use crate::network::Geometry;
use crate::view::VehicleView;

pub(super) const ENTRY: StrategyEntry = StrategyEntry {
    name: "none",
    about: "no platoon organization (the baseline)",
    organizes: false,
    needs_thresholds: false,
    build,
};

fn build(_: &Config) -> Box<dyn Organizer> {
    Box::new(NoOrganizer)
}

/// Advises nobody.
#[derive(Debug)]
pub struct NoOrganizer;

impl Organizer for NoOrganizer {
    fn name(&self) -> &str {
        ENTRY.name
    }
    fn advises_cavs(&self) -> bool {
        false
    }
    fn advise(&self, _: VehicleView<'_>, _: f64, _: &Geometry) -> Advice {
        Advice::Free
    }
}
