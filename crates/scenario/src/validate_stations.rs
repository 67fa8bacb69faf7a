//! Validation of the ramps' `station` keys: the field station (e.g. a PeMS station ID) at an
//! on- or off-ramp, which names that ramp's counter in `detectors.csv` so that a run can be
//! compared with the field station by station (`platoonsim compare`; docs/compare.md).

use super::{quoted, Checker};
use crate::network::{valid_id, RampStations};
use crate::raw::RawNetwork;

/// The `station` keys of the ramps, checked: an id of letters, digits, '_', '-' and '.',
/// unique across all ramps.
pub(super) fn check(c: &mut Checker, n: &RawNetwork) -> RampStations {
    let on: Vec<Option<String>> = n.on_ramps.iter().map(|r| r.station.clone()).collect();
    let off: Vec<Option<String>> = n.off_ramps.iter().map(|r| r.station.clone()).collect();
    let fields = (0..on.len())
        .map(|i| format!("network.on_ramps[{i}].station"))
        .chain((0..off.len()).map(|i| format!("network.off_ramps[{i}].station")));
    let mut seen: Vec<(String, &str)> = Vec::new();
    for (field, s) in fields.zip(on.iter().chain(&off)) {
        let Some(s) = s else { continue };
        if !valid_id(s) {
            c.push(
                &field,
                quoted(s),
                "must be a non-empty id of letters, digits, '_', '-' and '.' (it names the ramp's counter)",
            );
        } else if let Some((other, _)) = seen.iter().find(|(_, o)| *o == s) {
            c.push(
                &field,
                quoted(s),
                format!("duplicates {other}; a station names one ramp counter"),
            );
        }
        seen.push((field, s));
    }
    RampStations { on, off }
}
