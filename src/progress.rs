//! Progress reporting without printing: the library calls a [`Progress`]
//! sink now and then; the CLI shows it as a progress bar on a terminal.

/// Receives progress of long work. Calls are rare (every few thousand units
/// of work at most), so an implementation may do I/O.
pub trait Progress {
    /// The work ahead has `total` units (symbols, stems, ...); `what` names them.
    fn start(&mut self, what: &str, total: u64);
    /// `done` units are finished so far (monotone).
    fn update(&mut self, done: u64);
    /// The work is over.
    fn finish(&mut self);
}

/// Ignores all progress.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn start(&mut self, _what: &str, _total: u64) {}
    fn update(&mut self, _done: u64) {}
    fn finish(&mut self) {}
}
