//! Standard output that reports failure instead of panicking: `println!` panics when the
//! write fails (a closed pipe, `platoonsim show sr99 | head -1`; a full disk,
//! `> /dev/full`). Every command prints through `print` / `outln!`, which return the error;
//! `main` maps a closed pipe to a quiet exit with [`crate::EXIT_BROKEN_PIPE`] and any other
//! failure to `error: cannot write to standard output: …`. Messages to stderr go through
//! `errln!`, which never panics.

use std::fmt;
use std::io::Write;

/// Writing to standard output failed.
#[derive(Debug)]
pub struct StdoutError(pub std::io::Error);

impl fmt::Display for StdoutError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot write to standard output: {}", self.0)
    }
}

impl std::error::Error for StdoutError {}

impl StdoutError {
    /// Whether the reader went away (EPIPE): not worth a message.
    pub fn is_broken_pipe(&self) -> bool {
        self.0.kind() == std::io::ErrorKind::BrokenPipe
    }
}

/// Write `text` to standard output and flush it, so that a write error surfaces here (not
/// later, when the buffer is dropped, where it would be lost).
pub fn print(text: &str) -> Result<(), StdoutError> {
    let text = crate::messages::terminal(text, usize::MAX);
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(StdoutError)
}

/// `println!` through [`print`]: evaluates to `Result<(), StdoutError>`.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::stdout::print(&format!("{}\n", format_args!($($arg)*)))
    };
}

/// `eprintln!` that ignores a failed write: `eprintln!` panics when stderr is a closed pipe
/// (`platoonsim run … 2>&1 | true`), and there is nowhere left to report that failure.
macro_rules! errln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        // Escaped and bounded: names and values in messages come from files (issue 48 D10,
        // D11).
        let text = format!($($arg)*);
        let text = $crate::messages::terminal(&text, $crate::messages::MAX_MESSAGE_CHARS);
        let _ = writeln!(std::io::stderr(), "{text}");
    }};
}

/// The [`StdoutError`] somewhere in an error's chain (the commands add context to errors).
pub fn find(e: &anyhow::Error) -> Option<&StdoutError> {
    e.chain().find_map(|c| c.downcast_ref::<StdoutError>())
}

#[cfg(test)]
mod tests {
    use super::*;
    use anyhow::Context;

    #[test]
    fn the_error_is_found_under_context() {
        let e = Err::<(), _>(StdoutError(std::io::ErrorKind::BrokenPipe.into()))
            .context("while printing")
            .unwrap_err();
        assert!(find(&e).is_some_and(StdoutError::is_broken_pipe));
        let other = anyhow::anyhow!("something else");
        assert!(find(&other).is_none());
        let full = StdoutError(std::io::Error::from_raw_os_error(28));
        assert!(!full.is_broken_pipe());
        assert!(full
            .to_string()
            .starts_with("cannot write to standard output: "));
    }
}
