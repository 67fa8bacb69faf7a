//! Clock times of day (`run.clock_start`, issue 24 item 4): parsed from "HH:MM" or
//! "HH:MM:SS", written as "HH:MM:SS" in the outputs.

/// Seconds after midnight of "HH:MM" or "HH:MM:SS" (two digits each, 00:00 to 23:59:59);
/// `None` for anything else.
pub fn parse_clock(text: &str) -> Option<u32> {
    let parts: Vec<&str> = text.split(':').collect();
    if !(2..=3).contains(&parts.len()) {
        return None;
    }
    let mut fields = [0u32; 3];
    for (i, p) in parts.iter().enumerate() {
        if p.len() != 2 || !p.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        fields[i] = p.parse().ok()?;
    }
    let [h, m, s] = fields;
    (h < 24 && m < 60 && s < 60).then_some(h * 3600 + m * 60 + s)
}

/// "HH:MM:SS" of `s` seconds after midnight (the form `show` writes back).
pub fn format_clock(s: u32) -> String {
    format!("{:02}:{:02}:{:02}", s / 3600 % 24, s / 60 % 60, s % 60)
}

/// The clock time of simulated time `t_s` (s) when t = 0 is `start_s` seconds after midnight:
/// "HH:MM:SS", with the fraction of a second after a point when there is one ("05:00:12.3");
/// a run past midnight wraps to 00:00:00 (a time of day).
pub fn clock_at(start_s: u32, t_s: f64) -> String {
    let whole = t_s.floor();
    let frac = t_s - whole;
    let s = (u64::from(start_s) + whole as u64) % 86_400;
    let hms = format!("{:02}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
    if frac == 0.0 {
        return hms;
    }
    // The fraction as the simulated time prints it (12.3 → ".3"), so no binary noise appears.
    let text = format!("{t_s}");
    match text.split_once('.') {
        Some((_, digits)) if !digits.contains('e') => format!("{hms}.{digits}"),
        _ => hms,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clock_times_parse_in_both_forms() {
        assert_eq!(parse_clock("05:00"), Some(18_000));
        assert_eq!(parse_clock("05:00:30"), Some(18_030));
        assert_eq!(parse_clock("00:00"), Some(0));
        assert_eq!(parse_clock("23:59:59"), Some(86_399));
        for bad in [
            "24:00",
            "5:00",
            "05:60",
            "05:00:60",
            "05",
            "05:00:00:00",
            "",
            "ab:cd",
            "05:0a",
            " 05:00",
            "05:00 ",
            "+5:00",
            "-1:00",
        ] {
            assert_eq!(parse_clock(bad), None, "{bad:?}");
        }
    }

    #[test]
    fn clock_times_round_trip_and_follow_the_simulated_time() {
        assert_eq!(format_clock(18_000), "05:00:00");
        assert_eq!(parse_clock(&format_clock(18_030)), Some(18_030));
        assert_eq!(clock_at(18_000, 0.0), "05:00:00");
        assert_eq!(clock_at(18_000, 300.0), "05:05:00");
        assert_eq!(clock_at(18_000, 14_400.0), "09:00:00");
        assert_eq!(clock_at(18_000, 12.3), "05:00:12.3");
        assert_eq!(clock_at(18_000, 3599.95), "05:59:59.95");
        assert_eq!(clock_at(86_000, 500.0), "00:01:40");
    }
}
