//! Pipeline work that stops: when its client has gone (a newer edit
//! replaced the request, the tab closed) and when it runs past the time
//! budget (`--time-budget`).
//!
//! Stopping is cooperative, through the library's progress sink: the
//! library reports progress every million symbols or so, and at the start
//! of each pass; the sink given to it here ([`Watch`]) answers such a call
//! on stopped work by unwinding with a [`Stopped`] payload. The library
//! holds no lock or global state across those calls, so unwinding frees
//! the work's memory and nothing else; the pool thread is reused. The
//! unwinding is caught where the work was started ([`run`]), and the
//! panic hook keeps quiet about it (it is no crash).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use stlc::pipeline::Progress;

/// Why work stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stopped {
    /// Nobody waits for the answer any more.
    Abandoned,
    /// It ran past the time budget.
    OverBudget(Duration),
}

/// What work ended in.
pub enum Ended<T> {
    /// It finished.
    Done(T),
    /// It was stopped.
    Stopped(Stopped),
    /// It panicked: a bug (the server goes on).
    Crashed,
}

/// Set when the request's handler is dropped: its connection closed.
#[derive(Clone, Default)]
pub struct Abandon(Arc<AtomicBool>);

impl Abandon {
    /// A guard that abandons the work when dropped, unless disarmed.
    pub fn guard(&self) -> AbandonOnDrop {
        AbandonOnDrop(Some(self.clone()))
    }
}

/// Abandons the work when dropped (the handler's future was dropped: the
/// client went away before the answer).
pub struct AbandonOnDrop(Option<Abandon>);

impl AbandonOnDrop {
    /// The answer is ready: nothing to abandon.
    pub fn disarm(mut self) {
        self.0 = None;
    }
}

impl Drop for AbandonOnDrop {
    fn drop(&mut self) {
        if let Some(a) = self.0.take() {
            a.0.store(true, Ordering::Relaxed);
        }
    }
}

/// The progress sink of one request's work: stops it when abandoned or
/// past its deadline.
pub struct Watch {
    abandon: Abandon,
    deadline: Instant,
    budget: Duration,
}

impl Watch {
    /// Work that may run for `budget` from now.
    pub fn new(abandon: Abandon, budget: Duration) -> Self {
        Watch {
            abandon,
            deadline: Instant::now() + budget,
            budget,
        }
    }

    fn check(&self) {
        if self.abandon.0.load(Ordering::Relaxed) {
            std::panic::panic_any(Stopped::Abandoned);
        }
        if Instant::now() > self.deadline {
            std::panic::panic_any(Stopped::OverBudget(self.budget));
        }
    }
}

impl Progress for Watch {
    fn start(&mut self, _what: &str, _total: u64) {
        self.check();
    }
    fn update(&mut self, _done: u64) {
        self.check();
    }
    fn finish(&mut self) {}
}

/// Keeps the panic hook quiet about stopped work; every other panic is
/// reported as before.
pub fn quiet_stops() {
    let report = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if !info.payload().is::<Stopped>() {
            report(info);
        }
    }));
}

/// Runs `work` on the blocking pool with a [`Watch`] that stops it when
/// the returned future is dropped (the client left) or after `budget`.
pub async fn run<T: Send + 'static>(
    budget: Duration,
    work: impl FnOnce(&mut Watch) -> T + Send + 'static,
) -> Ended<T> {
    let abandon = Abandon::default();
    let guard = abandon.guard();
    let mut watch = Watch::new(abandon, budget);
    let joined = tokio::task::spawn_blocking(move || work(&mut watch)).await;
    guard.disarm();
    match joined {
        Ok(t) => Ended::Done(t),
        Err(e) if e.is_panic() => match e.into_panic().downcast::<Stopped>() {
            Ok(s) => Ended::Stopped(*s),
            Err(_) => Ended::Crashed,
        },
        Err(_) => Ended::Crashed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spin(w: &mut Watch) -> u64 {
        let mut n = 0u64;
        loop {
            n += 1;
            w.update(n);
            std::thread::sleep(Duration::from_millis(1));
        }
    }

    #[test]
    fn work_past_its_budget_stops() {
        quiet_stops();
        let rt = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .unwrap();
        let t0 = Instant::now();
        let ended = rt.block_on(run(Duration::from_millis(50), spin));
        assert!(matches!(
            ended,
            Ended::Stopped(Stopped::OverBudget(d)) if d == Duration::from_millis(50)
        ));
        assert!(t0.elapsed() < Duration::from_secs(5));
        let done = rt.block_on(run(Duration::from_secs(5), |w| {
            w.update(1);
            7
        }));
        assert!(matches!(done, Ended::Done(7)));
    }

    #[test]
    fn abandoned_work_stops() {
        quiet_stops();
        let abandon = Abandon::default();
        let mut w = Watch::new(abandon.clone(), Duration::from_secs(60));
        drop(abandon.guard());
        let stopped = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| spin(&mut w)));
        let payload = stopped.unwrap_err();
        assert_eq!(payload.downcast_ref::<Stopped>(), Some(&Stopped::Abandoned));
        // A disarmed guard abandons nothing.
        let kept = Abandon::default();
        kept.guard().disarm();
        assert!(!kept.0.load(Ordering::Relaxed));
    }
}
