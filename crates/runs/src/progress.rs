//! Progress as log lines, for work running without a terminal (a Slurm or Kubernetes log,
//! `nohup`): one line on stderr after the first run and each time another `step_pct` percent
//! of the runs is done, with the runs done, the rate of computed runs and an estimate of the
//! time left. The terminal keeps its progress bar ([`crate::runner::bar`]); the caller chooses
//! one or the other.

use std::sync::Mutex;
use std::time::Instant;

/// Counts runs and prints a line every `step_pct` percent (and at the end).
pub struct Lines {
    label: String,
    total: usize,
    step_pct: f64,
    start: Instant,
    state: Mutex<State>,
    sink: Box<dyn Fn(&str) + Send + Sync>,
}

#[derive(Default)]
struct State {
    done: usize,
    computed: usize,
    /// The next percentage at which a line is due.
    next_pct: f64,
}

impl Lines {
    /// Lines to stderr every 5 %.
    pub fn stderr(label: &str, total: usize) -> Lines {
        Lines::new(label, total, 5.0, Box::new(|l| eprintln!("{l}")))
    }

    pub fn new(
        label: &str,
        total: usize,
        step_pct: f64,
        sink: Box<dyn Fn(&str) + Send + Sync>,
    ) -> Lines {
        Lines {
            label: label.to_string(),
            total,
            step_pct: step_pct.max(0.1),
            start: Instant::now(),
            state: Mutex::new(State::default()),
            sink,
        }
    }

    /// `n` more runs done; `computed` if they were simulated (not read from run files).
    pub fn advance(&self, n: usize, computed: bool) {
        let line = {
            let Ok(mut s) = self.state.lock() else { return };
            s.done += n;
            if computed {
                s.computed += n;
            }
            let pct = if self.total == 0 {
                100.0
            } else {
                100.0 * s.done as f64 / self.total as f64
            };
            if pct + 1e-9 < s.next_pct && s.done < self.total {
                return;
            }
            while s.next_pct <= pct + 1e-9 {
                s.next_pct += self.step_pct;
            }
            self.line(s.done, s.computed, self.start.elapsed().as_secs_f64())
        };
        (self.sink)(&line);
    }

    /// `label: 12/60 runs (20 %), 3 computed, 4.2 runs/min, about 11 min left`.
    pub fn line(&self, done: usize, computed: usize, elapsed_s: f64) -> String {
        let pct = if self.total == 0 {
            100.0
        } else {
            100.0 * done as f64 / self.total as f64
        };
        let rate = if elapsed_s > 0.0 {
            computed as f64 / (elapsed_s / 60.0)
        } else {
            0.0
        };
        let left = self.total.saturating_sub(done);
        let eta = if left == 0 {
            "done".to_string()
        } else if rate > 0.0 {
            format!("about {} left", duration(left as f64 / rate * 60.0))
        } else {
            "time left unknown yet".to_string()
        };
        format!(
            "{}: {done}/{} runs ({pct:.0} %), {computed} computed, {rate:.1} runs/min, {eta}, {} elapsed",
            self.label,
            self.total,
            duration(elapsed_s)
        )
    }
}

/// `45 s`, `12 min`, `3 h 05 min`.
pub fn duration(s: f64) -> String {
    if !s.is_finite() {
        return "?".into();
    }
    if s < 90.0 {
        format!("{s:.0} s")
    } else if s < 5400.0 {
        format!("{:.0} min", s / 60.0)
    } else {
        let m = (s / 60.0).round() as u64;
        format!("{} h {:02} min", m / 60, m % 60)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::{Arc, Mutex};

    #[test]
    fn a_line_every_step_and_at_the_end() {
        let got = Arc::new(Mutex::new(Vec::<String>::new()));
        let g = got.clone();
        let lines = Lines::new(
            "s",
            40,
            10.0,
            Box::new(move |l| g.lock().unwrap().push(l.to_string())),
        );
        for _ in 0..40 {
            lines.advance(1, true);
        }
        let got = got.lock().unwrap();
        // The first run (so that a log shows the rate early), then 10 %, 20 %, ..., 100 %:
        // one line per 4 runs.
        assert_eq!(got.len(), 11, "{got:?}");
        assert!(
            got[0].starts_with("s: 1/40 runs (2 %), 1 computed"),
            "{}",
            got[0]
        );
        assert!(
            got[1].starts_with("s: 4/40 runs (10 %), 4 computed"),
            "{}",
            got[1]
        );
        assert!(got[10].starts_with("s: 40/40 runs (100 %)"), "{}", got[10]);
        assert!(got[10].contains("done"), "{}", got[10]);
    }

    #[test]
    fn rate_and_time_left() {
        let lines = Lines::new("x", 100, 5.0, Box::new(|_| {}));
        let l = lines.line(25, 20, 600.0);
        assert_eq!(
            l,
            "x: 25/100 runs (25 %), 20 computed, 2.0 runs/min, about 38 min left, 10 min elapsed"
        );
        assert_eq!(duration(4.0 * 3600.0 + 300.0), "4 h 05 min");
    }
}
