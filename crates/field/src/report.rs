//! The fit report as Markdown (`compare.md`; the experiment crate turns it into
//! `compare.html`): the criteria with their verdicts, thresholds and sources, the pooled
//! measures, the speed contours, a table per station, the bottlenecks simulated and in the
//! field, and what data was missing. Verdicts are written "✓ **holds**" / "✗ **does not
//! hold**", the form the project's HTML pages colour.

use crate::bottleneck::{Bottleneck, Pair};
use crate::criteria::Criterion;
use crate::fit::Fit;
use std::fmt::Write;

/// What the report shows.
#[derive(Clone, Debug)]
pub struct Report<'a> {
    /// The run directories compared (their mean when several).
    pub runs: &'a [String],
    /// The field files.
    pub field_files: &'a [String],
    /// The period compared, s after midnight.
    pub window: (u32, u32),
    /// The judged stations' fit (the mainline).
    pub fit: &'a Fit,
    pub criteria: &'a [Criterion],
    /// The ramp counters' fit and flow criteria: the demand's inputs, shown, not judged.
    pub ramps: Option<(&'a Fit, &'a [Criterion])>,
    pub bottlenecks: &'a [Pair],
    /// The contour figure (a path relative to the report), if drawn.
    pub figure: Option<&'a str>,
    /// Further notes on the data (e.g. field intervals left out), one line each.
    pub notes: &'a [String],
}

/// "HH:MM" of `s` seconds after midnight.
pub fn clock(s: u32) -> String {
    format!("{:02}:{:02}", s / 3600, s / 60 % 60)
}

fn verdict(pass: bool) -> &'static str {
    if pass {
        "✓ **holds**"
    } else {
        "✗ **does not hold**"
    }
}

fn num(v: Option<f64>, digits: usize) -> String {
    v.map_or("–".into(), |v| format!("{v:.digits$}"))
}

fn pct(v: Option<f64>) -> String {
    v.map_or("–".into(), |v| format!("{:.1} %", 100.0 * v))
}

fn list(names: &[String]) -> String {
    if names.is_empty() {
        "none".into()
    } else {
        names.join(", ")
    }
}

/// The report's Markdown.
pub fn markdown(r: &Report<'_>) -> String {
    let f = r.fit;
    let mut s = String::new();
    let failed = r.criteria.iter().filter(|c| !c.pass).count();
    let _ = writeln!(s, "# Goodness of fit: simulation against field data\n");
    let _ = writeln!(
        s,
        "Simulation: {} ({}). Field: {}. Period {}–{}. Mainline stations compared: {}{}.\n",
        r.runs.join(", "),
        if r.runs.len() > 1 {
            format!("the mean of {} runs", r.runs.len())
        } else {
            "one run".into()
        },
        r.field_files.join(", "),
        clock(r.window.0),
        clock(r.window.1),
        f.stations_compared.len(),
        match r.ramps {
            Some((rf, _)) if !rf.stations_compared.is_empty() => format!(
                "; ramp counters compared: {} (the demand's inputs: shown apart, not judged)",
                rf.stations_compared.len()
            ),
            _ => String::new(),
        }
    );
    let _ = writeln!(
        s,
        "**Verdict:** {}\n",
        if failed == 0 {
            format!("all {} criteria hold.", r.criteria.len())
        } else {
            format!("{failed} of {} criteria do not hold.", r.criteria.len())
        }
    );

    let _ = writeln!(s, "## Criteria\n");
    let _ = writeln!(s, "| criterion | threshold | measured | verdict | source |");
    let _ = writeln!(s, "|---|---|---|---|---|");
    for c in r.criteria {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} |",
            c.name,
            c.threshold,
            c.measured,
            verdict(c.pass),
            c.source
        );
    }

    if let Some((rf, rc)) = r.ramps.filter(|(rf, _)| !rf.stations_compared.is_empty()) {
        ramp_section(&mut s, rf, rc);
    }

    let _ = writeln!(s, "\n## Measures\n");
    let _ = writeln!(s, "| measure | value |");
    let _ = writeln!(s, "|---|---|");
    let rows = [
        (
            "station-hours compared",
            f.hour_coverage.matched.to_string(),
        ),
        ("GEH of hourly flows: mean", num(f.geh_mean, 2)),
        ("GEH of hourly flows: largest", num(f.geh_max, 2)),
        ("station-hours with GEH < 5", pct(f.geh_pass_share)),
        (
            "simulated vehicles (Σ of hourly volumes)",
            format!("{:.0}", f.total_sim_veh),
        ),
        (
            "counted vehicles (Σ of hourly volumes)",
            format!("{:.0}", f.total_field_veh),
        ),
        (
            "15-min station-intervals with speeds",
            f.speed_intervals.to_string(),
        ),
        ("speed RMSE (km/h)", num(f.speed_rmse_kmh, 1)),
        ("speed RMSNE", num(f.speed_rmsne, 3)),
        ("speed correlation (Pearson)", num(f.speed_correlation, 3)),
        (
            "objective (mean GEH / 5 + speed RMSNE)",
            num(f.objective(), 3),
        ),
    ];
    for (k, v) in rows {
        let _ = writeln!(s, "| {k} | {v} |");
    }

    if !f.hour_sums.is_empty() {
        let _ = writeln!(s, "\n## Hourly sums over the stations\n");
        let _ = writeln!(
            s,
            "| hour | stations | simulated (veh/h) | counted (veh/h) | difference | GEH |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|");
        for h in &f.hour_sums {
            let _ = writeln!(
                s,
                "| {}–{} | {} | {:.0} | {:.0} | {} | {:.2} |",
                clock(h.start_s),
                clock(h.start_s + 3600),
                h.stations,
                h.sim_vph,
                h.field_vph,
                h.diff
                    .map_or("–".into(), |d| format!("{:+.1} %", 100.0 * d)),
                h.geh
            );
        }
    }

    if let Some(fig) = r.figure {
        let _ = writeln!(s, "\n## Speed contours\n");
        let _ = writeln!(
            s,
            "Simulated, field and their difference (simulated − field), 5-min speeds at the \
             compared stations.\n\n![speed contours]({fig})"
        );
    }

    let _ = writeln!(s, "\n## Stations\n");
    let _ = writeln!(
        s,
        "| station | hours | GEH < 5 | GEH max | simulated veh | counted veh | difference | \
         15-min speeds | speed RMSE (km/h) | speed RMSNE | missing in simulation | missing in field |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|---|---|");
    for st in &f.per_station {
        let diff = (st.field_veh > 0.0).then(|| (st.sim_veh - st.field_veh) / st.field_veh);
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.0} | {:.0} | {} | {} | {} | {} | {} | {} |",
            st.station,
            st.hours,
            pct(st.geh_pass_share),
            num(st.geh_max, 2),
            st.sim_veh,
            st.field_veh,
            diff.map_or("–".into(), |d| format!("{:+.1} %", 100.0 * d)),
            st.speed_intervals,
            num(st.speed_rmse_kmh, 1),
            num(st.speed_rmsne, 3),
            st.quarters.missing_in_sim,
            st.quarters.missing_in_field,
        );
    }

    bottleneck_section(&mut s, r.bottlenecks);
    missing_section(&mut s, r);
    s
}

/// The ramp counters: their flow criteria and stations, not part of the verdict.
fn ramp_section(s: &mut String, f: &Fit, criteria: &[Criterion]) {
    let _ = writeln!(s, "\n## Ramp counters (inputs, not judged)\n");
    let _ = writeln!(
        s,
        "The ramps' counts are what the demand is built from, so a fit to them says little \
         about the model; they are measured here and left out of the verdict and of every \
         measure above and below. Stations: {}.\n",
        list(&f.stations_compared)
    );
    let _ = writeln!(s, "| criterion | threshold | measured | would be |");
    let _ = writeln!(s, "|---|---|---|---|");
    for c in criteria {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} |",
            c.name,
            c.threshold,
            c.measured,
            if c.pass { "met" } else { "not met" }
        );
    }
}

fn where_when(b: &Option<Bottleneck>) -> (String, String) {
    match b {
        Some(b) => (
            format!(
                "{} → {} ({:.2} km)",
                b.upstream,
                b.downstream,
                b.x_m / 1000.0
            ),
            format!(
                "{}–{} ({:.0} min active)",
                clock(b.onset_s),
                clock(b.clearance_s),
                b.active_minutes
            ),
        ),
        None => ("–".into(), "–".into()),
    }
}

fn bottleneck_section(s: &mut String, pairs: &[Pair]) {
    let _ = writeln!(s, "\n## Bottlenecks\n");
    if pairs.is_empty() {
        let _ = writeln!(
            s,
            "No active bottleneck in the field data nor in the simulation."
        );
        return;
    }
    let _ = writeln!(
        s,
        "| field: between | field: onset–clearance | simulated: between | simulated: \
         onset–clearance | Δx (m) | Δ onset (min) | Δ clearance (min) | verdict |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for p in pairs {
        let (fw, ft) = where_when(&p.field);
        let (sw, st) = where_when(&p.sim);
        let _ = writeln!(
            s,
            "| {fw} | {ft} | {sw} | {st} | {} | {} | {} | {} |",
            p.distance_m.map_or("–".into(), |d| format!("{d:+.0}")),
            p.onset_diff_min.map_or("–".into(), |d| format!("{d:+.0}")),
            p.clearance_diff_min
                .map_or("–".into(), |d| format!("{d:+.0}")),
            verdict(p.within)
        );
    }
}

fn missing_section(s: &mut String, r: &Report<'_>) {
    let f = r.fit;
    let _ = writeln!(s, "\n## Missing data\n");
    let _ = writeln!(
        s,
        "Nothing is filled in: an interval one side lacks is left out of the measures and \
         counted here.\n"
    );
    let _ = writeln!(
        s,
        "| level | compared | missing in the simulation | missing in the field |"
    );
    let _ = writeln!(s, "|---|---|---|---|");
    for (level, c) in [
        ("station-hours", f.hour_coverage),
        ("15-min station-intervals", f.quarter_coverage),
    ] {
        let _ = writeln!(
            s,
            "| {level} | {} | {} | {} |",
            c.matched, c.missing_in_sim, c.missing_in_field
        );
    }
    let _ = writeln!(
        s,
        "\n15-min intervals compared without a speed on one side: {}.\n",
        f.quarters_without_speed
    );
    let _ = writeln!(
        s,
        "- Simulated stations without field data: {}.",
        list(&f.sim_only_stations)
    );
    let _ = writeln!(
        s,
        "- Field stations without a simulated detector of the same name: {}.",
        list(&f.field_only_stations)
    );
    for n in r.notes {
        let _ = writeln!(s, "- {n}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bottleneck::MatchParams;
    use crate::criteria::judge;
    use crate::fit::fit;
    use crate::Obs;

    fn day(station: &str, flow: f64) -> Vec<Obs> {
        (0..12)
            .map(|k| Obs {
                station: station.into(),
                start_s: 18_000 + 300 * k,
                interval_s: 300,
                flow_vph: flow,
                speed_kmh: Some(100.0 - f64::from(k)),
                occupancy: None,
            })
            .collect()
    }

    #[test]
    fn the_report_shows_verdicts_stations_and_what_is_missing() {
        let sim = [day("A", 1000.0), day("S", 1.0)].concat();
        let field = [day("A", 1500.0), day("F", 1.0)].concat();
        let fit = fit(&sim, &field);
        let criteria = judge(&fit, &[], &MatchParams::default());
        let ramp_fit = crate::fit::fit(&day("R", 500.0), &day("R", 500.0));
        let ramp_criteria = crate::criteria::judge_flows(&ramp_fit);
        let md = markdown(&Report {
            runs: &["out/run".into()],
            field_files: &["f.csv".into()],
            window: (18_000, 21_600),
            fit: &fit,
            criteria: &criteria,
            ramps: Some((&ramp_fit, &ramp_criteria)),
            bottlenecks: &[],
            figure: Some("contours.png"),
            notes: &["a note".into()],
        });
        assert!(
            md.contains(
                "Period 05:00–06:00. Mainline stations compared: 1; ramp counters compared: 1 \
                 (the demand's inputs: shown apart, not judged)."
            ),
            "{md}"
        );
        assert!(md.contains("## Ramp counters (inputs, not judged)"));
        assert!(md.contains(
            "| Hourly flows: GEH < 5 | > 85.0 % of station-hours | 100.0 % of 1 station-hours | \
             met |"
        ));
        assert!(md.contains(
            "| Hourly flows: GEH < 5 | > 85.0 % of station-hours | 0.0 % of 1 station-hours | \
             ✗ **does not hold** |"
        ));
        assert!(md.contains("| 15-min speeds: Pearson correlation | ≥ 0.8 | 1.000 over 4 station-intervals | ✓ **holds** |"));
        // The ramp's criteria, all met, are not among the verdict's.
        assert!(md.contains("**Verdict:** 4 of 7 criteria do not hold."));
        assert!(md.contains("| A | 1 | 0.0 % | 14.14 | 1000 | 1500 | -33.3 % | 4 | 0.0 |"));
        assert!(md.contains("![speed contours](contours.png)"));
        assert!(
            md.contains("| 05:00–06:00 | 1 | 1000 | 1500 | -33.3 % | 14.14 |"),
            "{md}"
        );
        assert!(md.contains("- Simulated stations without field data: S."));
        assert!(md.contains("- Field stations without a simulated detector of the same name: F."));
        assert!(md.contains("- a note"));
        assert!(md.contains("No active bottleneck"));
    }

    #[test]
    fn bottleneck_rows_show_both_sides_and_the_differences() {
        let b = |x_m: f64, on: u32, off: u32| Bottleneck {
            upstream: "U".into(),
            downstream: "D".into(),
            x_m,
            onset_s: on,
            clearance_s: off,
            active_minutes: 60.0,
        };
        let pairs = crate::bottleneck::compare(
            &[b(5400.0, 25_800, 28_800)],
            &[b(5000.0, 25_200, 28_800)],
            &MatchParams::default(),
        );
        let mut s = String::new();
        bottleneck_section(&mut s, &pairs);
        assert!(
            s.contains(
                "| U → D (5.00 km) | 07:00–08:00 (60 min active) | U → D (5.40 km) | \
             07:10–08:00 (60 min active) | +400 | +10 | +0 | ✓ **holds** |"
            ),
            "{s}"
        );
    }
}
