//! A progress bar on stderr for long work, shown only on a terminal, only
//! when the work lasts more than a moment, and never with `--quiet`.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use stlc::pipeline::Progress;

/// How long work may run before a bar appears.
const GRACE: Duration = Duration::from_millis(400);

/// Overrides [`GRACE`], in milliseconds (`0`: show the bar at once; for
/// scripts recording a terminal, and for the tests).
const GRACE_ENV: &str = "STLC_PROGRESS_DELAY_MS";

/// The CLI's [`Progress`]: an indicatif bar that appears after [`GRACE`].
pub struct Bar {
    enabled: bool,
    grace: Duration,
    started: Option<(Instant, String, u64)>,
    bar: Option<ProgressBar>,
}

impl Bar {
    /// A bar that shows itself only if stderr is a terminal and not `quiet`.
    pub fn new(quiet: bool) -> Self {
        let grace = std::env::var(GRACE_ENV)
            .ok()
            .and_then(|v| v.trim().parse().ok())
            .map_or(GRACE, Duration::from_millis);
        Bar {
            enabled: !quiet && std::io::stderr().is_terminal(),
            grace,
            started: None,
            bar: None,
        }
    }
}

impl Progress for Bar {
    fn start(&mut self, what: &str, total: u64) {
        if let Some(b) = self.bar.take() {
            b.finish_and_clear();
        }
        self.started = Some((Instant::now(), what.to_string(), total));
    }

    fn update(&mut self, done: u64) {
        if !self.enabled {
            return;
        }
        if self.bar.is_none() {
            let Some((t0, what, total)) = &self.started else {
                return;
            };
            if t0.elapsed() < self.grace {
                return;
            }
            let bar = ProgressBar::with_draw_target(Some(*total), ProgressDrawTarget::stderr());
            let style = ProgressStyle::with_template(
                "{spinner} {msg} [{wide_bar}] {percent:>3}% {human_pos}/{human_len} ({eta} left)",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> ");
            bar.set_style(style);
            bar.set_message(what.clone());
            self.bar = Some(bar);
        }
        if let Some(b) = &self.bar {
            b.set_position(done);
        }
    }

    fn finish(&mut self) {
        if let Some(b) = self.bar.take() {
            b.finish_and_clear();
        }
        self.started = None;
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        self.finish();
    }
}

/// Clears the line a bar may be drawn on (an interrupt ends the process
/// without dropping the bar).
pub fn clear_on_interrupt() {
    let mut err = std::io::stderr();
    if err.is_terminal() {
        use std::io::Write;
        let _ = err.write_all(b"\r\x1b[2K");
    }
}
