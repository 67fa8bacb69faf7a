//! The calibration objective: a weighted sum of goodness-of-fit terms between the field
//! observations and the mean of a candidate's replications, matched by station (the field
//! station id equals the simulated detector's name) and interval start (clock time). Smaller
//! is better; 0 is a perfect fit. The measures are those of `platoonsim compare`
//! ([`platoonsim_field::fit`]).
//!
//! | term | definition | source |
//! |---|---|---|
//! | `speed_rmsne` | RMSNE √(1/N Σ ((v_sim − v_obs)/v_obs)²) of the speeds at the data's own interval, pairs with a field speed > 0 | RMSNE ([`fit::rmsne`]): Hollander & Liu (2008); FHWA Traffic Analysis Toolbox III |
//! | `flow_rmsne` | the same for the flows, pairs with a field flow > 0 | as above |
//! | `flow_geh` | mean GEH √(2 (q_sim − q_obs)² / (q_sim + q_obs)) of the flows in veh/h at the data's own interval ([`fit::geh`]) | UK DMRB vol. 12; FHWA Toolbox III |
//! | `compare` | `platoonsim compare`'s scalar ([`fit::Fit::objective`]): mean GEH of hourly volumes / 5 + RMSNE of 15-min speeds; needs whole clock hours of data | docs/compare.md |
//! | `prior` | mean over the fitted keys with a `prior_sd` of ((x − x₀)/σ)², x₀ the key's start value ([`prior`]): a Gaussian prior's negative log density up to a constant, which keeps such a key (a section factor) at its start unless the data pays for the move; 0 when no key has one | ridge / MAP estimation; FHWA Toolbox III orders global before link-specific parameters |
//!
//! The first three work at any interval (a short run, 5- or 10-minute data); `compare` is the
//! report's own measure and needs runs of at least one clock hour on a 15-minute grid. A
//! simulated interval in which no vehicle crossed has no speed; against a field speed it counts
//! as 0 km/h (a standstill) in `speed_rmsne`, so a candidate that jams a detector is penalized
//! rather than excused. GEH is defined on hourly volumes; `flow_geh` applies it to the
//! interval's flow rate in veh/h, as the Toolbox does for sub-hourly flows.
//!
//! | weight | default | why |
//! |---|---|---|
//! | `speed_rmsne` | 1.0 | speeds carry the congestion pattern the behaviour shapes |
//! | `flow_rmsne` | 0.0 | off: the relative flow error is what GEH measures more robustly |
//! | `flow_geh` | 0.1 | a mean GEH of 5 (the usual acceptance threshold) weighs like a speed RMSNE of 0.5 |
//! | `compare` | 0.0 | off: it needs hour-long runs |
//! | `prior` | 0.1 | a key two prior widths from its start costs 0.4, a mean GEH of 4 |

use platoonsim_field::fit;
use platoonsim_field::Obs;
use std::collections::BTreeMap;
use toml::{Table, Value};

/// The terms' names, in `trace.csv` order.
pub const TERMS: [&str; 5] = ["speed_rmsne", "flow_rmsne", "flow_geh", "compare", "prior"];

/// Weights of the terms (see the module documentation for the defaults).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Weights(pub [f64; 5]);

impl Default for Weights {
    fn default() -> Weights {
        Weights([1.0, 0.0, 0.1, 0.0, 0.1])
    }
}

impl Weights {
    /// From the `[objective]` table; a missing term keeps its default. Errors:
    /// (`objective.KEY`, message).
    pub fn from_table(t: &Table) -> Result<Weights, (String, String)> {
        let mut w = Weights::default();
        for (k, v) in t {
            let key = format!("objective.{k}");
            let Some(i) = TERMS.iter().position(|n| n == k) else {
                return Err((
                    key,
                    format!("unknown term; the terms are {}", TERMS.join(", ")),
                ));
            };
            match super::params::number(v) {
                Some(x) if x >= 0.0 => w.0[i] = x,
                _ => return Err((key, format!("{v} is not a weight (a number >= 0)"))),
            }
        }
        // The prior alone fits nothing: it only keeps keys where they start.
        if w.0[..4].iter().all(|&x| x == 0.0) {
            return Err((
                "objective".into(),
                "every weight of a data term (speed_rmsne, flow_rmsne, flow_geh, compare) is 0: \
                 nothing to fit"
                    .into(),
            ));
        }
        Ok(w)
    }

    /// As a TOML table (for the provenance).
    pub fn to_table(self) -> Table {
        TERMS
            .iter()
            .zip(self.0)
            .map(|(k, w)| (k.to_string(), Value::Float(w)))
            .collect()
    }
}

/// The terms of one candidate, in [`TERMS`] order (`None`: no value, or not computed because
/// its weight is 0), and the number of matched pairs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Terms {
    pub values: [Option<f64>; 5],
    pub pairs: usize,
}

impl Terms {
    /// The weighted sum ([`terms`] has made sure every weighted term has a value).
    pub fn objective(&self, w: &Weights) -> f64 {
        self.values
            .iter()
            .zip(w.0)
            .filter(|(_, w)| *w > 0.0)
            .map(|(v, w)| v.unwrap_or(f64::NAN) * w)
            .sum()
    }
}

/// The terms between field and simulated observations (see the module documentation).
/// `Err` names the stations when no (station, interval) pair matches, or when a weighted
/// term has no pair it can use.
pub fn terms(field: &[Obs], sim: &[Obs], w: &Weights) -> Result<Terms, String> {
    let key = |o: &Obs| (o.station.clone(), o.start_s, o.interval_s);
    let by_key: BTreeMap<_, &Obs> = sim.iter().map(|o| (key(o), o)).collect();
    let (mut speed, mut flow) = (Vec::new(), Vec::new());
    for f in field {
        let Some(s) = by_key.get(&key(f)) else {
            continue;
        };
        if let Some(vf) = f.speed_kmh {
            speed.push((s.speed_kmh.unwrap_or(0.0), vf));
        }
        flow.push((s.flow_vph, f.flow_vph));
    }
    if flow.is_empty() {
        let names = |v: Vec<&str>| {
            let mut v = v;
            v.dedup();
            v.join(", ")
        };
        return Err(format!(
            "no field observation matches a simulated one (same station/detector name, interval \
             start and length); field stations: {}; simulated detectors: {}",
            names(field.iter().map(|o| o.station.as_str()).collect()),
            names(by_key.keys().map(|k| k.0.as_str()).collect())
        ));
    }
    let geh = flow.iter().map(|&(m, c)| fit::geh(m, c)).sum::<f64>() / flow.len() as f64;
    let compare = match w.0[3] > 0.0 {
        false => None,
        true => {
            let span = crate::compare::sim_span(sim).unwrap_or((0, 0));
            fit::fit(sim, &fit::within(field, span.0, span.1)).objective()
        }
    };
    // The prior depends on the candidate, not on the runs: the caller fills it ([`prior`]).
    let values = [
        fit::rmsne(&speed),
        fit::rmsne(&flow),
        Some(geh),
        compare,
        Some(0.0),
    ];
    for (i, v) in values.iter().enumerate() {
        match v {
            // A non-finite term would make every candidate equal ("best objective NaN") and
            // still write a calibrated file (issue 48 D5): stop instead.
            Some(x) if !x.is_finite() => {
                return Err(format!(
                    "the term {} is {x} over {} matched pairs: a field or simulated value is \
                     not a finite number in range",
                    TERMS[i],
                    flow.len()
                ))
            }
            Some(_) => {}
            None if w.0[i] > 0.0 => {
                return Err(format!(
                    "the term {} has no value: {}",
                    TERMS[i],
                    if i == 3 {
                        "platoonsim compare's measure needs whole clock hours of flows and \
                         15-minute speeds on both sides"
                    } else {
                        "no matched pair with a field value > 0"
                    }
                ))
            }
            None => {}
        }
    }
    Ok(Terms {
        values,
        pairs: flow.len(),
    })
}

/// The `prior` term: the mean over the keys with a prior width σ of ((x − x₀)/σ)², for the
/// values `x`, start values `x0` and widths `sd` (`None`: no prior on that key); 0 without any.
pub fn prior(x: &[f64], x0: &[f64], sd: &[Option<f64>]) -> f64 {
    let z: Vec<f64> = x
        .iter()
        .zip(x0)
        .zip(sd)
        .filter_map(|((x, x0), sd)| sd.map(|s| ((x - x0) / s).powi(2)))
        .collect();
    if z.is_empty() {
        0.0
    } else {
        z.iter().sum::<f64>() / z.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_prior_is_the_mean_squared_standardized_distance_from_the_start() {
        // Keys 0 and 2 have a prior: ((1.5 − 1)/0.25)² = 4 and ((0.9 − 1)/0.5)² = 0.04.
        let p = prior(
            &[1.5, 7.0, 0.9],
            &[1.0, 3.0, 1.0],
            &[Some(0.25), None, Some(0.5)],
        );
        assert!((p - 2.02).abs() < 1e-12, "{p}");
        assert_eq!(
            prior(&[1.0, 1.0], &[1.0, 1.0], &[Some(0.1), Some(0.2)]),
            0.0
        );
        assert_eq!(prior(&[5.0], &[1.0], &[None]), 0.0);
    }

    fn obs(station: &str, t: u32, flow: f64, speed: Option<f64>) -> Obs {
        Obs {
            station: station.into(),
            start_s: t,
            interval_s: 300,
            flow_vph: flow,
            speed_kmh: speed,
            occupancy: None,
        }
    }

    #[test]
    fn exact_values() {
        let field = [
            obs("a", 0, 1000.0, Some(100.0)),
            obs("a", 300, 2000.0, Some(50.0)),
            // No simulated counterpart: ignored.
            obs("b", 0, 1000.0, Some(100.0)),
        ];
        let sim = [obs("a", 0, 1200.0, Some(90.0)), obs("a", 300, 2000.0, None)];
        let t = terms(&field, &sim, &Weights::default()).unwrap();
        assert_eq!(t.pairs, 2);
        let close = |a: f64, b: f64| assert!((a - b).abs() < 1e-12 * b, "{a} vs {b}");
        // speed errors -0.1 and -1 (no vehicle: 0 km/h): sqrt((0.01 + 1) / 2)
        close(t.values[0].unwrap(), (1.01f64 / 2.0).sqrt());
        // flow errors 0.2 and 0: sqrt(0.04 / 2)
        close(t.values[1].unwrap(), (0.04f64 / 2.0).sqrt());
        // GEH sqrt(2 * 200^2 / 2200) and 0, averaged
        close(t.values[2].unwrap(), (80_000.0f64 / 2200.0).sqrt() / 2.0);
        // Unweighted, compare's term is not computed.
        assert_eq!(t.values[3], None);
        let w = Weights([1.0, 2.0, 0.5, 0.0, 0.0]);
        assert_eq!(
            t.objective(&w),
            t.values[0].unwrap() + 2.0 * t.values[1].unwrap() + 0.5 * t.values[2].unwrap()
        );
        // A perfect fit is 0.
        assert_eq!(terms(&field, &field, &w).unwrap().objective(&w), 0.0);
    }

    #[test]
    fn a_non_finite_term_stops_the_calibration() {
        // Issue 48 D5: a field flow of 1e308 made the objective NaN, "best objective NaN",
        // exit 0 and a calibrated.toml.
        let field = [obs("a", 0, 1e308, Some(100.0)), obs("a", 300, 2000.0, None)];
        let sim = [obs("a", 0, 1000.0, Some(90.0)), obs("a", 300, 2000.0, None)];
        let e = terms(&field, &sim, &Weights::default()).unwrap_err();
        assert_eq!(
            e,
            "the term flow_geh is inf over 2 matched pairs: a field or simulated value is not a \
             finite number in range"
        );
    }

    #[test]
    fn the_compare_term_is_platoonsim_compares_measure() {
        // One clock hour of 5-min data: the term is compare's scalar, on the simulated span.
        let hour = |flow: f64, speed: f64| -> Vec<Obs> {
            (0..12)
                .map(|k| obs("a", 25_200 + 300 * k, flow, Some(speed)))
                .collect()
        };
        let (field, sim) = (hour(1000.0, 100.0), hour(1100.0, 90.0));
        // A field row outside the simulated hour is not compared.
        let mut more = field.clone();
        more.push(obs("a", 28_800, 5000.0, Some(10.0)));
        let w = Weights([0.0, 0.0, 0.0, 1.0, 0.0]);
        let t = terms(&more, &sim, &w).unwrap();
        let want = fit::fit(&sim, &field).objective().unwrap();
        // GEH of 1100 vs 1000 / 5 + RMSNE 0.1
        let geh = (2.0 * 100.0f64.powi(2) / 2100.0).sqrt();
        assert!((want - (geh / 5.0 + 0.1)).abs() < 1e-12, "{want}");
        assert_eq!(t.values[3], Some(want));
        // Twenty minutes are not a clock hour: no value, and an error when weighted.
        let e = terms(&field[..4], &sim[..4], &w).unwrap_err();
        assert!(e.contains("compare") && e.contains("clock hours"), "{e}");
    }

    #[test]
    fn nothing_matched_names_the_stations() {
        let e = terms(
            &[obs("316140", 0, 1.0, None)],
            &[obs("up", 0, 1.0, None)],
            &Weights::default(),
        )
        .unwrap_err();
        assert!(e.contains("316140") && e.contains("up"), "{e}");
        // Flows only, but the speed term is weighted.
        let e = terms(
            &[obs("a", 0, 1.0, None)],
            &[obs("a", 0, 1.0, None)],
            &Weights::default(),
        )
        .unwrap_err();
        assert!(e.contains("speed_rmsne"), "{e}");
    }
}
