//! Validation of `[[detectors]]` (names, positions, merged with the detectors generated for a
//! `[network]`) and of `[measurement]` (the measurement detector, the aggregation interval, the
//! number of detector records), split from `validate.rs` by responsibility.

use super::network::Checked;
use super::run::Run;
use super::{defaults, quoted, Checker, Frame, Num};
use crate::limits;
use crate::raw::{num, RawMeasurement, RawScenario};
use platoonsim_sim::config::DetectorKind;
use platoonsim_sim::DetectorSpec;

/// `[[detectors]]` in engine coordinates; with a [network], the generated ones first (these are
/// added), mainline detectors by position, then the off-ramp detectors.
pub(super) fn check_detectors(
    c: &mut Checker,
    raw: &RawScenario,
    net: Option<&Checked>,
    length: Option<f64>,
    frame: &Frame,
) -> Vec<DetectorSpec> {
    let generated = match net {
        Some(v) => crate::network::detectors(
            &v.network,
            length.unwrap_or(f64::NAN),
            &v.on_ids,
            &v.off_ids,
            &v.stations,
            &v.spacing,
        ),
        None => Vec::new(),
    };
    if raw.detectors.is_empty() && !frame.network {
        c.push(
            "detectors",
            "[]",
            "at least one [[detectors]] entry (name, position_m) is required",
        );
    }
    if raw.detectors.len() > limits::MAX_DETECTORS {
        c.push(
            "detectors",
            format!("({} entries)", raw.detectors.len()),
            format!("at most {} [[detectors]] entries", limits::MAX_DETECTORS),
        );
        // The entries are not checked one by one: the duplicate check is quadratic, and
        // 10,000 entries took seconds (found by the fuzz target sumo_shapes, issue 48).
        return Vec::new();
    }
    let mut detectors = Vec::with_capacity(raw.detectors.len().min(limits::MAX_DETECTORS));
    for (i, d) in raw.detectors.iter().enumerate() {
        let field = format!("detectors[{i}].name");
        let name = match &d.name {
            None => {
                c.missing(
                    &field,
                    "a name, used in the detector records and [measurement]",
                );
                String::new()
            }
            Some(n) if n.trim().is_empty() => {
                c.push(&field, quoted(n), "must be a non-empty string");
                n.clone()
            }
            Some(n) => {
                if let Some(j) = raw.detectors[..i]
                    .iter()
                    .position(|o| o.name.as_deref() == Some(n.as_str()))
                {
                    c.push(
                        &field,
                        quoted(n),
                        format!("duplicates detectors[{j}].name; names must be unique"),
                    );
                } else if generated.iter().any(|g| &g.name == n) {
                    c.push(
                        &field,
                        quoted(n),
                        "duplicates a detector generated for the network (\"end\", \
                         \"{id}-up\", \"{id}-down\", \"{id}-off\"); names must be unique",
                    );
                }
                n.clone()
            }
        };
        let field = format!("detectors[{i}].position_m");
        let what = if frame.network {
            "position in metres (corridor coordinate)"
        } else {
            "position in metres from the entrance"
        };
        let pos = c.req(&field, d.position_m, what);
        if let (Some(p), Some(hi)) = (pos, frame.hi) {
            c.check(
                &field,
                p,
                p.v > frame.origin && p.v < hi,
                format!("must lie inside {}", frame.inside_text(hi)),
            );
        }
        detectors.push(DetectorSpec::mainline(
            &name,
            pos.map_or(f64::NAN, |p| p.v - frame.origin),
        ));
    }
    if frame.network {
        // Mainline detectors by position (the generated ones first at a tie), then the
        // off-ramp detectors.
        let (mut all, off): (Vec<_>, Vec<_>) = generated
            .into_iter()
            .partition(|d| d.kind == DetectorKind::Mainline);
        all.append(&mut detectors);
        all.sort_by(|a, b| a.position_m.total_cmp(&b.position_m));
        all.extend(off);
        detectors = all;
    }
    detectors
}

/// The checked `[measurement]`.
pub(super) struct Measurement {
    /// Index of the measurement detector in the detector list.
    pub detector: usize,
    pub aggregation: Num,
}

/// `[measurement]`, given the checked detectors, run and lane count.
pub(super) fn check_measurement(
    c: &mut Checker,
    m: &RawMeasurement,
    detectors: &[DetectorSpec],
    frame: &Frame,
    run: &Run,
    lanes: u32,
) -> Measurement {
    let find = |n: &str| detectors.iter().position(|d| d.name == n);
    let measurement_detector = match (&m.detector, frame.network) {
        (None, true) => find(crate::network::END_DETECTOR).unwrap_or(0),
        (None, false) if detectors.len() == 1 => 0,
        (None, false) => {
            c.missing(
                "measurement.detector",
                &format!(
                    "the name of one of the detectors ({})",
                    detector_names(detectors)
                ),
            );
            0
        }
        (Some(n), _) => match find(n) {
            Some(i) => i,
            None => {
                c.push(
                    "measurement.detector",
                    quoted(n),
                    format!("names no detector; defined: {}", detector_names(detectors)),
                );
                0
            }
        },
    };
    let (dt, duration) = (run.dt, run.duration);
    let aggregation = c.opt(m.aggregation_s, defaults::AGGREGATION_S);
    if run.dt_ok {
        // The engine counts intervals in steps; an interval that is not a whole number of steps
        // would be reported with a length it does not have.
        let steps = aggregation.v / dt.v;
        let whole = (steps - steps.round()).abs() <= 1e-6 * steps.max(1.0);
        c.check(
            "measurement.aggregation_s",
            aggregation,
            aggregation.v >= dt.v && whole,
            format!(
                "must be a whole number of steps of run.dt_s = {}",
                dt.shown()
            ),
        );
    } else {
        c.positive("measurement.aggregation_s", aggregation);
    }
    // Every interval of every detector and lane is kept until the end of the run.
    if run.duration_ok && aggregation.v > 0.0 && aggregation.v.is_finite() {
        let records =
            (duration.v / aggregation.v).ceil() * detectors.len() as f64 * f64::from(lanes + 1);
        if records > limits::MAX_DETECTOR_RECORDS {
            c.push(
                "measurement.aggregation_s",
                aggregation.shown(),
                format!(
                    "gives {} detector records (run.duration_s / aggregation_s × {} detectors × \
                     (lanes + 1)); at most {}: use a longer interval or fewer detectors",
                    num(records),
                    detectors.len(),
                    num(limits::MAX_DETECTOR_RECORDS)
                ),
            );
        }
    }
    Measurement {
        detector: measurement_detector,
        aggregation,
    }
}

/// The detector names for a message (the first 12 if there are more).
fn detector_names(detectors: &[DetectorSpec]) -> String {
    const SHOWN: usize = 12;
    let names: Vec<String> = detectors
        .iter()
        .filter(|d| !d.name.is_empty())
        .map(|d| quoted(&d.name))
        .collect();
    match names.len() {
        0 => "none".into(),
        n if n > SHOWN => format!(
            "{}, … ({n} in all; `platoonsim show` lists them)",
            names[..SHOWN].join(", ")
        ),
        _ => names.join(", "),
    }
}
