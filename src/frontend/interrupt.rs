//! What an interrupt (Ctrl-C, SIGTERM) needs to know, whichever front end
//! runs: the temporary files being written, to remove them (their targets
//! were never touched), and whether stopping is how the work ends (a
//! server) or cuts it short (a command).

use std::collections::BTreeSet;
use std::fs;
use std::path::PathBuf;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

/// Every temporary file being written: a server may save while it exports,
/// and each needs removing on an interrupt.
static PENDING: Mutex<BTreeSet<PathBuf>> = Mutex::new(BTreeSet::new());

/// Set once stopping is how the work ends (a server): an interrupt then
/// exits with status 0.
static STOP_IS_SUCCESS: AtomicBool = AtomicBool::new(false);

fn pending() -> std::sync::MutexGuard<'static, BTreeSet<PathBuf>> {
    PENDING
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// A temporary file in the registry while this lives.
#[must_use = "the file leaves the registry when this is dropped"]
pub struct Pending(PathBuf);

impl Pending {
    /// Registers `path` until the returned value is dropped.
    pub fn new(path: PathBuf) -> Self {
        pending().insert(path.clone());
        Pending(path)
    }
}

impl Drop for Pending {
    fn drop(&mut self) {
        pending().remove(&self.0);
    }
}

/// Removes every temporary file being written (the interrupt handler
/// calls it before the process exits).
pub fn remove_pending() {
    let paths = std::mem::take(&mut *pending());
    for p in paths {
        let _ = fs::remove_file(p);
    }
}

/// From now on an interrupt is how the work ends: exit status 0.
pub fn stop_is_success() {
    STOP_IS_SUCCESS.store(true, Ordering::SeqCst);
}

/// The exit status for `signal`: 0 where stopping is how the work ends,
/// else 128 + the signal's number (130, 143), as a shell reports a
/// process killed by it.
pub fn exit_status(signal: i32) -> i32 {
    if STOP_IS_SUCCESS.load(Ordering::SeqCst) {
        0
    } else {
        128 + signal
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_registry_holds_every_pending_file_until_it_is_done() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.tmp"), dir.path().join("b.tmp"));
        fs::write(&a, "a").unwrap();
        fs::write(&b, "b").unwrap();
        let first = Pending::new(a.clone());
        let second = Pending::new(b.clone());
        assert!(pending().contains(&a) && pending().contains(&b));
        drop(first);
        assert!(!pending().contains(&a) && pending().contains(&b));
        remove_pending();
        assert!(a.exists(), "a finished file is not removed");
        assert!(!b.exists(), "a pending one is");
        drop(second);
        assert!(!pending().contains(&b));
    }
}
