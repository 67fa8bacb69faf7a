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

/// `text` with its control characters written as escapes (`\u{1b}`), for names from a file
/// printed to a terminal: an escape sequence in a scenario name must not clear the screen or
/// set the window title (issue 35 item 8).
pub fn printable(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.chars().any(char::is_control) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_unicode());
        } else {
            out.push(c);
        }
    }
    std::borrow::Cow::Owned(out)
}
