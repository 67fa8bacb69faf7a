//! Clock times of a field day: seconds since local midnight <-> `HH:MM:SS`.
//!
//! A field file holds one day, so a time is a clock reading in 00:00:00-23:59:59 (no dates, no
//! time zones: PeMS times are local).

/// Seconds in a day.
pub const DAY_S: u32 = 86_400;

/// Formats seconds since midnight as `HH:MM:SS` (hours may pass 23 for times past a day).
pub fn format(start_s: u32) -> String {
    format!(
        "{:02}:{:02}:{:02}",
        start_s / 3600,
        start_s / 60 % 60,
        start_s % 60
    )
}

/// Parses `HH:MM` or `HH:MM:SS` (hours 0-23 with one or two digits, minutes and seconds 00-59
/// with two) into seconds since midnight; `None` if it is not such a time.
pub fn parse(s: &str) -> Option<u32> {
    let parts: Vec<&str> = s.split(':').collect();
    if !(2..=3).contains(&parts.len()) {
        return None;
    }
    let num = |p: &str, digits: std::ops::RangeInclusive<usize>, max: u32| {
        if !digits.contains(&p.len()) || !p.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        p.parse::<u32>().ok().filter(|v| *v <= max)
    };
    let h = num(parts[0], 1..=2, 23)?;
    let m = num(parts[1], 2..=2, 59)?;
    let s = match parts.get(2) {
        Some(p) => num(p, 2..=2, 59)?,
        None => 0,
    };
    Some(h * 3600 + m * 60 + s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_both_forms_and_formats_back() {
        assert_eq!(parse("07:05"), Some(7 * 3600 + 5 * 60));
        assert_eq!(parse("7:05:09"), Some(7 * 3600 + 5 * 60 + 9));
        assert_eq!(parse("23:59:59"), Some(DAY_S - 1));
        assert_eq!(format(7 * 3600 + 5 * 60 + 9), "07:05:09");
        assert_eq!(format(0), "00:00:00");
    }

    #[test]
    fn rejects_out_of_range_and_malformed() {
        for bad in [
            "24:00",
            "12:60",
            "12:00:60",
            "12",
            "12:5",
            "a:00",
            "12:00:00:00",
            "",
        ] {
            assert_eq!(parse(bad), None, "{bad}");
        }
    }
}
