//! The per-run metrics: every numeric field of the engine's [`Summary`] that the tables
//! count (not the configuration echoes of [`crate::record::NOT_METRICS`]), as a typed value.
//!
//! A [`Metric`] is one of
//! * a plain field of the summary ([`Field`], e.g. `discharge_flow_vphpl`),
//! * a field of the energy summary ([`EnergyField`], present with `energy.enabled` only),
//! * one of the six fields of a counted safety measure (`hard_brakings`,
//!   `hard_brakings_cav`, …, `hard_brakings_per_100vkm_human`: [`Counted`] × [`Part`]),
//! * a bin of the braking-peak histogram (`braking_peaks_<cav|human>_<bin>`).
//!
//! The plain and energy fields are listed once each, by the summary's field name (the macros
//! below read the field, so a renamed field does not compile), and a test checks that every
//! numeric field `summary.json` writes is a metric or deliberately excluded. A metric's name
//! is its field name in `summary.json`, the run files and the tables; sweep files name
//! metrics by it ([`Metric::parse`]).

use platoonsim_sim::{Counted, CountedMeasures, Summary};
use std::borrow::Cow;
use std::fmt;

/// A field read as a number: a count, a real, an `Option` (`None` is written as `null` and
/// read back as NaN), or an `Option` not written when `None`.
macro_rules! read {
    (count, $e:expr) => {
        Some($e as f64)
    };
    (real, $e:expr) => {
        Some($e)
    };
    (maybe, $e:expr) => {
        Some($e.unwrap_or(f64::NAN))
    };
    // An `Option` whose `None` is not written at all.
    (absent, $e:expr) => {
        $e
    };
}

macro_rules! is_count {
    (count) => {
        true
    };
    ($other:ident) => {
        false
    };
}

/// The plain numeric fields of [`Summary`], in its order.
macro_rules! plain_fields {
    ($($variant:ident: $field:ident $how:ident;)*) => {
        /// A plain numeric field of [`Summary`] (named as the field).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Field {
            $($variant),*
        }

        impl Field {
            /// Every plain field, in the summary's order.
            pub const ALL: &'static [Field] = &[$(Field::$variant),*];

            /// The field's name in `summary.json`.
            pub const fn name(self) -> &'static str {
                match self {
                    $(Field::$variant => stringify!($field)),*
                }
            }

            /// Does it count things (an integer in `summary.json`)?
            pub const fn is_count(self) -> bool {
                match self {
                    $(Field::$variant => is_count!($how)),*
                }
            }

            fn read(self, s: &Summary) -> Option<f64> {
                match self {
                    $(Field::$variant => read!($how, s.$field)),*
                }
            }
        }
    };
}

plain_fields! {
    VehiclesEntered: vehicles_entered count;
    VehiclesExited: vehicles_exited count;
    VehiclesInNetwork: vehicles_in_network count;
    VehiclesWaiting: vehicles_waiting count;
    LaneChangesPerVehicle: lane_changes_per_vehicle maybe;
    LaneChangesPerCav: lane_changes_per_cav maybe;
    LaneChangesPerHuman: lane_changes_per_human maybe;
    CooperativeLaneChanges: cooperative_lane_changes count;
    AvgPlatoonLength: avg_platoon_length maybe;
    PlatooningProbability: platooning_probability maybe;
    AvgPlatoonLengthTg2: avg_platoon_length_tg2 maybe;
    PlatooningProbabilityTg2: platooning_probability_tg2 maybe;
    CavsCounted: cavs_counted count;
    VehiclesCounted: vehicles_counted count;
    DischargeFlow: discharge_flow_vphpl real;
    MaxSustainedFlow: max_sustained_flow_vphpl real;
    NetworkDischarge: network_discharge_vph absent; // not written on a plain road
    ZeroFlowIntervals: zero_flow_intervals count;
    MissedExits: missed_exits count;
    Collisions: collisions count;
    MaxDeceleration: max_deceleration_mps2 real;
    VehicleKm: vehicle_km real;
    VehicleKmCav: vehicle_km_cav real;
    VehicleKmHuman: vehicle_km_human real;
    TetS: tet_s real;
    TetSCav: tet_s_cav real;
    TetSHuman: tet_s_human real;
    TitS2: tit_s2 real;
    TitS2Cav: tit_s2_cav real;
    TitS2Human: tit_s2_human real;
    MinTtc: min_ttc_s maybe;
    CaccFallbacks: cacc_fallbacks count;
    VehicleUpdates: vehicle_updates count;
    Steps: steps count;
}

/// The numeric fields of an optional part of [`Summary`] that is flattened into it (the
/// energy summary, the mechanism measures): an enum named `$name` over the fields of
/// `s.$part`, present only when the part is.
macro_rules! part_fields {
    ($(#[$doc:meta])* $name:ident, $part:ident { $($variant:ident: $field:ident $how:ident;)* }) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum $name {
            $($variant),*
        }

        impl $name {
            /// Every field, in the summary's order.
            pub const ALL: &'static [$name] = &[$($name::$variant),*];

            /// The field's name in `summary.json`.
            pub const fn name(self) -> &'static str {
                match self {
                    $($name::$variant => stringify!($field)),*
                }
            }

            fn read(self, s: &Summary) -> Option<f64> {
                let part = s.$part.as_ref()?;
                match self {
                    $($name::$variant => read!($how, part.$field)),*
                }
            }
        }
    };
}

part_fields! {
    /// A field of the energy summary (`platoonsim_sim::EnergySummary`, with `energy.enabled`),
    /// named as the field.
    EnergyField, energy {
        FuelPer100km: fuel_l_per_100km maybe;
        FuelPer100kmCav: fuel_l_per_100km_cav maybe;
        FuelPer100kmHuman: fuel_l_per_100km_human maybe;
        EnergyPer100km: energy_kwh_per_100km maybe;
        EnergyPer100kmCav: energy_kwh_per_100km_cav maybe;
        EnergyPer100kmHuman: energy_kwh_per_100km_human maybe;
        Fuel: fuel_l real;
        Energy: energy_kwh real;
        EnergyDistance: energy_distance_km real;
        CavDragReduction: cav_drag_reduction_pct maybe;
        HumanDragReduction: human_drag_reduction_pct maybe;
        CavDragSaving: cav_drag_saving_pct maybe;
        HumanDragSaving: human_drag_saving_pct maybe;
        CavDynamicsExcess: cav_dynamics_excess_pct maybe;
        HumanDynamicsExcess: human_dynamics_excess_pct maybe;
    }
}

part_fields! {
    /// A numeric field of the mechanism measures (`platoonsim_sim::mechanism::MechanismSummary`,
    /// with `measurement.mechanism`; its by-lane arrays are not metrics), named as the field.
    MechanismField, mechanism {
        MechanismFrom: mechanism_from_m real;
        MechanismTo: mechanism_to_m real;
        CavWait: cav_wait_veh_s_per_h real;
        CavWaitShare: cav_wait_share maybe;
        SectionLaneChanges: section_lane_changes_per_h real;
        DisturbedFollowers: disturbed_followers_per_h real;
        SectionLaneChangesPerCav: section_lane_changes_per_cav maybe;
        LaneNeedPerCav: lane_need_per_cav maybe;
        OrganizedLaneDischarge: organized_lane_discharge_vph real;
    }
}

/// The by-lane arrays of the mechanism summary: written to `summary.json`, not metrics.
pub const MECHANISM_ARRAYS: [&str; 3] = [
    "cav_wait_veh_s_per_h_by_lane",
    "cav_wait_share_by_lane",
    "discharge_by_lane_vph",
];

/// Which of a counted measure's six fields ([`CountedMeasures::field_names`], in that order).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Part {
    /// `<name>`: all vehicles (a count).
    Total,
    /// `<name>_cav`
    Cav,
    /// `<name>_human`
    Human,
    /// `<name>_per_100vkm`: per 100 veh-km of all vehicles.
    Rate,
    /// `<name>_per_100vkm_cav`
    RateCav,
    /// `<name>_per_100vkm_human`
    RateHuman,
}

impl Part {
    /// The six parts, in output order.
    pub const ALL: [Part; 6] = [
        Part::Total,
        Part::Cav,
        Part::Human,
        Part::Rate,
        Part::RateCav,
        Part::RateHuman,
    ];
}

/// The vehicles of a braking-peak histogram.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    Cav,
    Human,
}

impl Kind {
    pub const fn name(self) -> &'static str {
        match self {
            Kind::Cav => "cav",
            Kind::Human => "human",
        }
    }
}

/// The prefix of the histogram's metrics, `braking_peaks_<kind>_<bin>` (bin 0 = the peaks
/// from 4 m/s², docs/safety.md).
pub const HISTOGRAM: &str = "braking_peaks";

/// A per-run metric (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Metric {
    Field(Field),
    Energy(EnergyField),
    Mechanism(MechanismField),
    Counted(Counted, Part),
    BrakingPeaks(Kind, usize),
}

impl Metric {
    pub const DISCHARGE_FLOW: Metric = Metric::Field(Field::DischargeFlow);
    pub const MAX_SUSTAINED_FLOW: Metric = Metric::Field(Field::MaxSustainedFlow);
    pub const COLLISIONS: Metric = Metric::Field(Field::Collisions);
    pub const AVG_PLATOON_LENGTH: Metric = Metric::Field(Field::AvgPlatoonLength);
    pub const PLATOONING_PROBABILITY: Metric = Metric::Field(Field::PlatooningProbability);
    pub const LANE_CHANGES_PER_VEHICLE: Metric = Metric::Field(Field::LaneChangesPerVehicle);
    pub const LANE_CHANGES_PER_CAV: Metric = Metric::Field(Field::LaneChangesPerCav);
    pub const LANE_CHANGES_PER_HUMAN: Metric = Metric::Field(Field::LaneChangesPerHuman);
    pub const NETWORK_DISCHARGE: Metric = Metric::Field(Field::NetworkDischarge);

    /// Its name in `summary.json` and the tables.
    pub fn name(self) -> Cow<'static, str> {
        match self {
            Metric::Field(f) => Cow::Borrowed(f.name()),
            Metric::Energy(e) => Cow::Borrowed(e.name()),
            Metric::Mechanism(m) => Cow::Borrowed(m.name()),
            Metric::Counted(m, p) => {
                let i = Part::ALL.iter().position(|x| *x == p).unwrap_or(0);
                let names = CountedMeasures::field_names(m.name());
                Cow::Owned(names.into_iter().nth(i).unwrap_or_default())
            }
            Metric::BrakingPeaks(k, bin) => Cow::Owned(format!("{HISTOGRAM}_{}_{bin}", k.name())),
        }
    }

    /// The metric named `name`, if it is one.
    pub fn parse(name: &str) -> Option<Metric> {
        if let Some(f) = Field::ALL.iter().find(|f| f.name() == name) {
            return Some(Metric::Field(*f));
        }
        if let Some(e) = EnergyField::ALL.iter().find(|e| e.name() == name) {
            return Some(Metric::Energy(*e));
        }
        if let Some(m) = MechanismField::ALL.iter().find(|m| m.name() == name) {
            return Some(Metric::Mechanism(*m));
        }
        for m in Counted::ALL {
            let names = CountedMeasures::field_names(m.name());
            if let Some(i) = names.iter().position(|n| n == name) {
                return Some(Metric::Counted(m, Part::ALL[i]));
            }
        }
        let rest = name.strip_prefix(HISTOGRAM)?.strip_prefix('_')?;
        let (kind, bin) = rest.split_once('_')?;
        let kind = [Kind::Cav, Kind::Human]
            .into_iter()
            .find(|k| k.name() == kind)?;
        // Digits only: `01` or `+1` would name the same bin twice.
        if bin.is_empty()
            || !bin.bytes().all(|b| b.is_ascii_digit())
            || bin.len() > 1 && bin.starts_with('0')
        {
            return None;
        }
        bin.parse().ok().map(|b| Metric::BrakingPeaks(kind, b))
    }

    /// Every metric name, for messages: the fields, the counted measures' fields and the
    /// histogram's pattern.
    pub fn allowed_names() -> String {
        let mut names: Vec<String> = Field::ALL.iter().map(|f| f.name().to_string()).collect();
        names.extend(EnergyField::ALL.iter().map(|e| e.name().to_string()));
        names.extend(MechanismField::ALL.iter().map(|m| m.name().to_string()));
        for m in Counted::ALL {
            names.extend(CountedMeasures::field_names(m.name()));
        }
        names.push(format!("{HISTOGRAM}_<cav|human>_<bin>"));
        names.join(", ")
    }

    /// Does it count things (an integer in `summary.json`, written without a decimal point
    /// in `runs.csv`)?
    pub fn is_count(self) -> bool {
        match self {
            Metric::Field(f) => f.is_count(),
            Metric::Energy(_) | Metric::Mechanism(_) => false,
            Metric::Counted(_, p) => matches!(p, Part::Total | Part::Cav | Part::Human),
            Metric::BrakingPeaks(..) => true,
        }
    }

    /// Its value in a run's summary: `None` where the summary does not write the field (a
    /// plain road's `network_discharge_vph`, the energy fields without `energy.enabled`, a
    /// bin beyond the histogram), NaN where it writes `null`.
    pub fn value(self, s: &Summary) -> Option<f64> {
        match self {
            Metric::Field(f) => f.read(s),
            Metric::Energy(e) => e.read(s),
            Metric::Mechanism(m) => m.read(s),
            Metric::Counted(m, p) => {
                let c = s.counted.get(m.name())?;
                Some(match p {
                    Part::Total => c.total() as f64,
                    Part::Cav => c.cav as f64,
                    Part::Human => c.human as f64,
                    Part::Rate => c.per_100vkm.unwrap_or(f64::NAN),
                    Part::RateCav => c.per_100vkm_cav.unwrap_or(f64::NAN),
                    Part::RateHuman => c.per_100vkm_human.unwrap_or(f64::NAN),
                })
            }
            Metric::BrakingPeaks(k, bin) => {
                let bins = match k {
                    Kind::Cav => &s.braking_peaks.cav,
                    Kind::Human => &s.braking_peaks.human,
                };
                bins.get(bin).map(|n| *n as f64)
            }
        }
    }
}

impl fmt::Display for Metric {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use platoonsim_sim::Config;

    /// A summary with every optional part present: energy on, a network discharge, values
    /// in the histogram.
    fn full_summary() -> Summary {
        let mut cfg = Config::homogeneous(0.5, 1500.0, 300.0, 60.0, 2);
        cfg.energy.enabled = true;
        cfg.mechanism = true;
        let mut s = platoonsim_sim::run(&cfg, None).unwrap().summary;
        s.network_discharge_vph = Some(1234.5);
        s.braking_peaks.cav = vec![3, 0, 1];
        s.braking_peaks.human = vec![2, 5, 0];
        s
    }

    /// Every numeric field `summary.json` writes is a metric whose value is the written one,
    /// or one of the configuration echoes; and every metric is written.
    #[test]
    fn every_numeric_summary_field_is_a_metric_or_excluded() {
        let s = full_summary();
        assert!(s.energy.is_some(), "the test needs the energy fields");
        assert!(s.mechanism.is_some(), "the test needs the mechanism fields");
        let json = serde_json::to_value(&s).unwrap();
        let mut seen = Vec::new();
        for (k, v) in json.as_object().unwrap() {
            if crate::record::NOT_METRICS.contains(&k.as_str()) {
                continue;
            }
            if MECHANISM_ARRAYS.contains(&k.as_str()) {
                assert!(v.is_array(), "{k}");
                continue;
            }
            let written: Vec<(String, f64)> = match v {
                serde_json::Value::Number(n) => vec![(k.clone(), n.as_f64().unwrap())],
                serde_json::Value::Null => vec![(k.clone(), f64::NAN)],
                serde_json::Value::Object(o) if k == HISTOGRAM => o
                    .iter()
                    .filter(|(kind, _)| *kind != "lower_edges_mps2")
                    .flat_map(|(kind, bins)| {
                        let bins = bins.as_array().unwrap().clone();
                        bins.into_iter()
                            .enumerate()
                            .map(move |(i, b)| (format!("{k}_{kind}_{i}"), b.as_f64().unwrap()))
                    })
                    .collect(),
                other => panic!("{k}: {other} is neither a metric nor excluded"),
            };
            for (name, x) in written {
                let m = Metric::parse(&name).unwrap_or_else(|| panic!("{name} is no metric"));
                assert_eq!(m.name(), name);
                let got = m.value(&s).unwrap();
                assert!(
                    got == x || got.is_nan() && x.is_nan(),
                    "{name}: {got} vs {x}"
                );
                assert_eq!(
                    m.is_count(),
                    v.is_u64() || name.starts_with(HISTOGRAM),
                    "{name}"
                );
                seen.push(m);
            }
        }
        let mut all: Vec<Metric> = Field::ALL.iter().map(|f| Metric::Field(*f)).collect();
        all.extend(EnergyField::ALL.iter().map(|e| Metric::Energy(*e)));
        all.extend(MechanismField::ALL.iter().map(|m| Metric::Mechanism(*m)));
        for m in Counted::ALL {
            all.extend(Part::ALL.map(|p| Metric::Counted(m, p)));
        }
        for m in all {
            assert!(seen.contains(&m), "{m} is not written by the summary");
        }
    }

    #[test]
    fn absent_fields_have_no_value() {
        let mut s = full_summary();
        s.network_discharge_vph = None;
        s.energy = None;
        assert_eq!(Metric::Field(Field::NetworkDischarge).value(&s), None);
        assert_eq!(Metric::Energy(EnergyField::Fuel).value(&s), None);
        assert_eq!(Metric::BrakingPeaks(Kind::Cav, 3).value(&s), None);
        assert_eq!(Metric::BrakingPeaks(Kind::Human, 1).value(&s), Some(5.0));
    }

    #[test]
    fn names_parse_back_and_others_do_not() {
        for name in [
            "discharge_flow_vphpl",
            "fuel_l",
            "severe_brakings_per_100vkm_cav",
            "aeb_interventions",
            "braking_peaks_human_12",
        ] {
            assert_eq!(Metric::parse(name).map(|m| m.name()), Some(name.into()));
        }
        for name in [
            "discharge_flow",
            "seed",
            "scenario",
            "wall_seconds",
            "braking_peaks_human_01",
            "braking_peaks_human_",
            "braking_peaks_bus_0",
            "braking_peaks_lower_edges_mps2",
            "discharge_change_pct",
        ] {
            assert_eq!(Metric::parse(name), None, "{name}");
        }
    }
}
