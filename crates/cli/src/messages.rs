//! Command-line checks whose messages say which flag to change, and how: they complete the
//! scenario's own validation, which names keys, not flags.

use platoonsim_experiment::ExperimentName;

/// `--seed`: a whole number of `run.seed`'s range; a negative one reaches here (the flag allows
/// a leading '-') so that the message gives the range rather than clap's `-- -1` tip.
pub fn parse_seed(text: &str) -> Result<u64, String> {
    text.trim().parse().map_err(|_| {
        format!(
            "run.seed must be a whole number from 0 to {} (the same seed gives identical results)",
            u64::MAX
        )
    })
}

/// `--tolerance`: a finite percentage >= 0 (NaN compared false with every loss and so
/// accepted every threshold).
pub fn parse_tolerance(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err("the tolerance is a discharge loss in percent: a finite number >= 0".into()),
    }
}

/// A number as a message shows it: as written when short, in exponent form when its decimal
/// expansion is long (`1e-300` rather than 300 digits).
pub fn short_num(v: f64) -> String {
    let plain = v.to_string();
    if plain.len() <= 24 {
        plain
    } else {
        format!("{v:e}")
    }
}

/// A warm-up that `--duration` alone made too long (the scenario's own, not set by
/// `--warmup`): the hint to add to the validation's message, naming `--warmup` and a value that
/// works (a third of the duration).
pub fn warmup_hint(duration: Option<f64>, warmup: Option<f64>, error: &str) -> Option<String> {
    let d = duration.filter(|d| d.is_finite() && *d > 0.0)?;
    if warmup.is_some() || !error.contains("run.warmup_s =") {
        return None;
    }
    Some(format!(
        "--duration {d} is not longer than the scenario's warm-up (run.warmup_s); shorten the \
         warm-up too, e.g. --duration {d} --warmup {}",
        (d / 3.0).floor()
    ))
}

/// `experiment`'s --duration and --warmup, defaulted (3600 s, 1200 s). The homogeneous-road
/// experiments measure from a warm-up, which must end before the runs do; checked before
/// anything is created. `capacity`'s baseline stage also measures from
/// [`platoonsim_experiment::CAPACITY_FILL_S`]. The SR-99 experiments simulate the paper's
/// 4-hour morning and refuse both flags rather than ignore them (issue 35 item 6).
pub fn check_experiment_duration(
    name: ExperimentName,
    duration: Option<f64>,
    warmup: Option<f64>,
) -> Result<(f64, f64), String> {
    let given = (duration.is_some(), warmup.is_some());
    let (duration, warmup) = (duration.unwrap_or(3600.0), warmup.unwrap_or(1200.0));
    if name.own_period {
        if given.0 || given.1 {
            let flag = if given.0 { "--duration" } else { "--warmup" };
            return Err(format!(
                "experiment {name} does not take {flag}: it simulates the paper's SR-99 morning, \
                 05:00-09:00 (14400 s), with the scenario's own warm-up; --duration and \
                 --warmup apply to the homogeneous-road experiments"
            ));
        }
        return Ok((duration, warmup));
    }
    if !(duration.is_finite() && duration > 0.0) {
        return Err(format!(
            "invalid --duration {duration}: the simulated time of every run must be a positive \
             number of seconds"
        ));
    }
    if !(warmup.is_finite() && warmup >= 0.0 && warmup < duration) {
        return Err(format!(
            "invalid --duration {duration} with --warmup {warmup}: the warm-up must be >= 0 and \
             shorter than the duration (the default --warmup is the paper's 1200 s); e.g. \
             --duration {duration} --warmup {}",
            (duration / 3.0).floor()
        ));
    }
    let fill = platoonsim_experiment::CAPACITY_FILL_S;
    if name.name == "capacity" && duration <= fill {
        return Err(format!(
            "invalid --duration {duration}: capacity's baseline stage measures after a fixed \
             {fill} s warm-up (the road fills), so --duration must be longer than {fill} s"
        ));
    }
    Ok((duration, warmup))
}

/// The longest message written to stderr (characters); a longer one keeps its start and end.
pub const MAX_MESSAGE_CHARS: usize = 4_000;

/// Whether `c` would change what a terminal shows beyond itself: a control character other
/// than a line break or a tab, or a bidirectional formatting character (which reorders the
/// text around it: U+061C, U+200E-U+200F, U+202A-U+202E, U+2066-U+2069).
fn unsafe_char(c: char) -> bool {
    (c.is_control() && c != '\n' && c != '\t')
        || matches!(c, '\u{061c}' | '\u{200e}' | '\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

/// Text for a terminal (every line the commands print goes through it): control and
/// bidirectional characters written as escapes (`\u{202e}`), and at most `max` characters, a
/// longer text keeping its first and last part around a note of what was left out (a 10 MB id
/// in an error printed 20 MB; issue 48 D10, D11).
pub fn terminal(text: &str, max: usize) -> std::borrow::Cow<'_, str> {
    let n = text.chars().count();
    if n <= max && !text.chars().any(unsafe_char) {
        return std::borrow::Cow::Borrowed(text);
    }
    let escape = |s: &mut String, part: &str| {
        for c in part.chars() {
            if unsafe_char(c) {
                s.extend(c.escape_unicode());
            } else {
                s.push(c);
            }
        }
    };
    let mut out = String::with_capacity(text.len().min(max.saturating_mul(4)) + 16);
    if n <= max {
        escape(&mut out, text);
    } else {
        let head: usize = text.chars().take(max * 3 / 4).map(char::len_utf8).sum();
        let tail_chars = max / 4;
        let tail: usize = text
            .chars()
            .rev()
            .take(tail_chars)
            .map(char::len_utf8)
            .sum();
        escape(&mut out, &text[..head]);
        out.push_str(&format!(
            " […{} characters left out…] ",
            n - max * 3 / 4 - tail_chars
        ));
        escape(&mut out, &text[text.len() - tail..]);
    }
    std::borrow::Cow::Owned(out)
}

/// `text` with its control characters written as escapes (`\u{1b}`), for names from a file
/// printed to a terminal: an escape sequence in a scenario name must not clear the screen or
/// set the window title (issue 35 item 8).
pub fn printable(text: &str) -> std::borrow::Cow<'_, str> {
    let escaped = |c: char| c.is_control() || unsafe_char(c);
    if !text.chars().any(escaped) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if escaped(c) {
            out.extend(c.escape_unicode());
        } else {
            out.push(c);
        }
    }
    std::borrow::Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn terminal_text_is_escaped_and_bounded() {
        // Issue 48 D10: control and bidirectional characters were printed raw.
        assert_eq!(
            terminal("a\u{202e}b\u{1b}[2J\nc\td", 100),
            "a\\u{202e}b\\u{1b}[2J\nc\td"
        );
        assert_eq!(printable("x\u{2066}y\nz"), "x\\u{2066}y\\u{a}z");
        // D11: a 10 MB id gave a 20 MB error.
        let long = format!("error: edge \"{}\" unknown", "e".repeat(10_000_000));
        let t = terminal(&long, MAX_MESSAGE_CHARS);
        assert!(t.chars().count() < MAX_MESSAGE_CHARS + 60, "{}", t.len());
        assert!(t.starts_with("error: edge \"eee") && t.ends_with("eee\" unknown"));
        assert!(t.contains(&format!(
            " […{} characters left out…] ",
            long.len() - 3_000 - 1_000
        )));
        assert!(matches!(
            terminal("plain", 10),
            std::borrow::Cow::Borrowed(_)
        ));
    }
}
