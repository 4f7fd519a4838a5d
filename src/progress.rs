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

/// Prefixes the name of each piece of work with a phase, so a user watching
/// two passes over the same symbols sees which one is running
/// (`measuring: symbols`, then `drawing: symbols`).
pub struct Phase<'a> {
    inner: &'a mut dyn Progress,
    label: &'a str,
}

impl<'a> Phase<'a> {
    /// Reports to `inner`, naming the work `label: what`.
    pub fn new(inner: &'a mut dyn Progress, label: &'a str) -> Self {
        Phase { inner, label }
    }
}

impl Progress for Phase<'_> {
    fn start(&mut self, what: &str, total: u64) {
        self.inner.start(&format!("{}: {what}", self.label), total);
    }
    fn update(&mut self, done: u64) {
        self.inner.update(done);
    }
    fn finish(&mut self) {
        self.inner.finish();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Default)]
    struct Log(Vec<String>);

    impl Progress for Log {
        fn start(&mut self, what: &str, total: u64) {
            self.0.push(format!("start {what} {total}"));
        }
        fn update(&mut self, done: u64) {
            self.0.push(format!("update {done}"));
        }
        fn finish(&mut self) {
            self.0.push("finish".into());
        }
    }

    #[test]
    fn a_phase_names_the_work_and_passes_the_rest_through() {
        let mut log = Log::default();
        let mut p = Phase::new(&mut log, "drawing");
        p.start("symbols", 10);
        p.update(4);
        p.finish();
        assert_eq!(log.0, ["start drawing: symbols 10", "update 4", "finish"]);
    }
}
