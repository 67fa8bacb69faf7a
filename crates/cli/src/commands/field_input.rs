//! Field files for `calibrate`: tidy CSV (`station,time,flow_vph,speed_kmh,occupancy`, time
//! "HH:MM" or "HH:MM:SS" of the interval start; an optional `interval_s` column, else a
//! station's interval is the spacing of its rows, else 300 s for a station with one row).
//!
//! A stop-gap until `platoonsim_field::tidy::read` and the PeMS readers are merged (branch
//! field-io); then this file goes and `calibrate` calls them. Errors name file, line, field and
//! value.

use anyhow::{bail, Context, Result};
use platoonsim_field::Obs;
use std::collections::BTreeMap;
use std::path::Path;

/// Read one tidy CSV file.
pub fn read_tidy(path: &Path) -> Result<Vec<Obs>> {
    let file = path.display();
    let mut r = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_path(path)
        .with_context(|| format!("cannot read field file {file}"))?;
    let header: Vec<String> = r
        .headers()
        .with_context(|| format!("{file}: cannot read the header"))?
        .iter()
        .map(str::to_string)
        .collect();
    let col = |name: &str| header.iter().position(|h| h == name);
    let (Some(st), Some(tm), Some(fl)) = (col("station"), col("time"), col("flow_vph")) else {
        bail!(
            "{file}: line 1: the header must name station, time and flow_vph (and optionally \
             speed_kmh, occupancy, interval_s); it is {}",
            header.join(",")
        );
    };
    let (sp, oc, iv) = (col("speed_kmh"), col("occupancy"), col("interval_s"));
    let mut rows: Vec<(Obs, bool)> = Vec::new();
    for (i, rec) in r.records().enumerate() {
        let line = i + 2;
        let rec = rec.with_context(|| format!("{file}: line {line}: not CSV"))?;
        let field = |c: usize| rec.get(c).unwrap_or("");
        let num = |c: Option<usize>, name: &str| -> Result<Option<f64>> {
            let Some(c) = c else { return Ok(None) };
            let t = field(c);
            if t.is_empty() || t.eq_ignore_ascii_case("nan") {
                return Ok(None);
            }
            match t.parse::<f64>() {
                Ok(v) if v.is_finite() && v >= 0.0 => Ok(Some(v)),
                _ => bail!("{file}: line {line}: {name} = {t:?} is not a number >= 0"),
            }
        };
        let time = field(tm);
        let Some(start_s) = platoonsim_scenario::clock::parse_clock(time) else {
            bail!("{file}: line {line}: time = {time:?} is not a clock time HH:MM or HH:MM:SS");
        };
        let Some(flow_vph) = num(Some(fl), "flow_vph")? else {
            bail!("{file}: line {line}: flow_vph is empty");
        };
        let interval = num(iv, "interval_s")?;
        rows.push((
            Obs {
                station: field(st).to_string(),
                start_s,
                interval_s: interval.map_or(0, |v| v.round() as u32),
                flow_vph,
                speed_kmh: num(sp, "speed_kmh")?,
                occupancy: num(oc, "occupancy")?,
            },
            interval.is_some(),
        ));
    }
    // Intervals from the spacing of each station's rows where no column gives them.
    let mut starts: BTreeMap<String, Vec<u32>> = BTreeMap::new();
    for (o, _) in &rows {
        starts.entry(o.station.clone()).or_default().push(o.start_s);
    }
    let spacing: BTreeMap<String, u32> = starts
        .into_iter()
        .map(|(s, mut t)| {
            t.sort_unstable();
            let d = t.windows(2).map(|w| w[1] - w[0]).filter(|&d| d > 0).min();
            (s, d.unwrap_or(300))
        })
        .collect();
    Ok(rows
        .into_iter()
        .map(|(mut o, given)| {
            if !given {
                o.interval_s = spacing[&o.station];
            }
            o
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_rows_and_intervals_from_spacing() {
        let dir = std::env::temp_dir().join(format!("platoonsim-tidy-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("f.csv");
        std::fs::write(
            &p,
            "station,time,flow_vph,speed_kmh,occupancy\nA,07:00,1200,95.5,0.1\nA,07:05,1300,,\nB,07:00:30,10,nan,\n",
        )
        .unwrap();
        let o = read_tidy(&p).unwrap();
        assert_eq!(o.len(), 3);
        assert_eq!(
            (o[0].start_s, o[0].interval_s, o[0].speed_kmh),
            (25_200, 300, Some(95.5))
        );
        assert_eq!((o[1].speed_kmh, o[1].occupancy), (None, None));
        assert_eq!((o[2].start_s, o[2].interval_s), (25_230, 300));
        std::fs::write(&p, "station,time,flow_vph\nA,7h,1\n").unwrap();
        let e = read_tidy(&p).unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("7h"), "{e}");
    }
}
