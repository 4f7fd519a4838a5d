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
//!
//! Light work never waits behind heavy work: every request starts at once
//! on its own thread, and work still running after [`LIGHT`] counts as
//! heavy and must hold one of a few heavy slots ([`Slots`]) to go on, so
//! heavy work takes turns while a light render, which is done before it
//! would need a slot, is answered meanwhile. Work known to be heavy before
//! it starts (an input over [`BIG_INPUT`] bytes, whose reading reports no
//! progress and whose memory grows with it) takes a slot from the start, so
//! at most a few big inputs are read at once.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

use stlc::pipeline::Progress;

use super::memory::Memory;

/// Why work stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stopped {
    /// Nobody waits for the answer any more.
    Abandoned,
    /// It ran past the time budget.
    OverBudget(Duration),
    /// The process held more heap than its memory budget (`live` bytes
    /// against `budget`) when this work reported progress.
    OverMemory {
        /// Heap bytes in use when it stopped.
        live: u64,
        /// The budget, bytes.
        budget: u64,
    },
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

/// An input larger than this is heavy from the start (reading an input
/// takes memory in proportion, without reporting progress).
pub const BIG_INPUT: usize = 1 << 20;

/// How long work runs before it counts as heavy.
pub const LIGHT: Duration = Duration::from_millis(300);

/// The heavy slots: how many heavy works may run at once (a counting
/// semaphore for the pool's threads, which block).
pub struct Slots {
    free: Mutex<usize>,
    freed: Condvar,
}

impl Slots {
    /// `n` slots.
    pub fn new(n: usize) -> Self {
        Slots {
            free: Mutex::new(n),
            freed: Condvar::new(),
        }
    }

    fn free(&self) -> std::sync::MutexGuard<'_, usize> {
        self.free.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// Takes a slot, waiting for one; `stop` is asked every 100 ms while
    /// waiting (abandoned work stops waiting too).
    fn take(&self, stop: impl Fn()) {
        let mut free = self.free();
        while *free == 0 {
            let (f, _) = self
                .freed
                .wait_timeout(free, Duration::from_millis(100))
                .unwrap_or_else(|p| p.into_inner());
            free = f;
            if *free == 0 {
                drop(free);
                stop();
                free = self.free();
            }
        }
        *free -= 1;
    }

    fn give(&self) {
        *self.free() += 1;
        self.freed.notify_one();
    }
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
    started: Instant,
    deadline: Instant,
    budget: Duration,
    slots: Arc<Slots>,
    /// Whether this work holds a heavy slot.
    heavy: bool,
    /// The server's memory, measured at every report of heavy work.
    memory: Option<Arc<Memory>>,
}

impl Watch {
    /// Work that may run for `budget` from now, taking one of `slots`
    /// once it runs past [`LIGHT`].
    pub fn new(abandon: Abandon, budget: Duration, slots: Arc<Slots>) -> Self {
        let started = Instant::now();
        Watch {
            abandon,
            started,
            deadline: started + budget,
            budget,
            slots,
            heavy: false,
            memory: None,
        }
    }

    /// Heavy work that also stops when the process holds more heap than
    /// `memory`'s budget.
    pub fn with_memory(mut self, memory: Arc<Memory>) -> Self {
        self.memory = Some(memory);
        self
    }

    fn stop_if_due(abandon: &Abandon, deadline: Instant, budget: Duration) {
        if abandon.0.load(Ordering::Relaxed) {
            std::panic::panic_any(Stopped::Abandoned);
        }
        if Instant::now() > deadline {
            std::panic::panic_any(Stopped::OverBudget(budget));
        }
    }

    fn check(&mut self) {
        Self::stop_if_due(&self.abandon, self.deadline, self.budget);
        if !self.heavy && self.started.elapsed() > LIGHT {
            self.take_slot();
        }
        // Every work checks: light work grows too (a big growth allocates
        // much of its memory in its first 300 ms).
        if let Some(m) = &self.memory
            && let Some(live) = m.over()
        {
            std::panic::panic_any(Stopped::OverMemory {
                live,
                budget: m.budget(),
            });
        }
    }

    /// Takes a heavy slot, waiting for one (and stopping while waiting if
    /// the work is abandoned or past its budget).
    fn take_slot(&mut self) {
        let (abandon, deadline, budget) = (self.abandon.clone(), self.deadline, self.budget);
        self.slots
            .take(|| Self::stop_if_due(&abandon, deadline, budget));
        self.heavy = true;
    }
}

impl Drop for Watch {
    fn drop(&mut self) {
        if self.heavy {
            self.slots.give();
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
    slots: Arc<Slots>,
    memory: Option<Arc<Memory>>,
    heavy: bool,
    work: impl FnOnce(&mut Watch) -> T + Send + 'static,
) -> Ended<T> {
    let abandon = Abandon::default();
    let guard = abandon.guard();
    let joined = tokio::task::spawn_blocking(move || {
        let mut watch = Watch::new(abandon, budget, slots);
        if let Some(m) = memory {
            watch = watch.with_memory(m);
        }
        if heavy {
            // Known heavy before it starts (a big input, whose reading
            // reports no progress): it takes its turn from the start.
            watch.take_slot();
        }
        work(&mut watch)
    })
    .await;
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

    /// With one heavy slot, a second long work waits for the first (it
    /// reports no progress past the light time until the slot is free),
    /// and a light work is done meanwhile.
    #[test]
    fn heavy_work_takes_turns_and_light_work_does_not_wait() {
        quiet_stops();
        let slots = Arc::new(Slots::new(1));
        let long = |slots: Arc<Slots>| {
            std::thread::spawn(move || {
                let mut w = Watch::new(Abandon::default(), Duration::from_secs(60), slots);
                let t0 = Instant::now();
                let mut past_light = None;
                while t0.elapsed() < Duration::from_millis(900) {
                    w.update(1);
                    if past_light.is_none() && w.heavy {
                        past_light = Some(t0.elapsed());
                    }
                    std::thread::sleep(Duration::from_millis(5));
                }
                (past_light.unwrap(), t0.elapsed())
            })
        };
        let a = long(slots.clone());
        std::thread::sleep(Duration::from_millis(50));
        let b = long(slots.clone());
        std::thread::sleep(Duration::from_millis(100));
        let t0 = Instant::now();
        let mut light = Watch::new(Abandon::default(), Duration::from_secs(60), slots.clone());
        for _ in 0..10 {
            light.update(1);
        }
        assert!(!light.heavy);
        assert!(t0.elapsed() < Duration::from_millis(100));
        let (a_slot, _) = a.join().unwrap();
        let (b_slot, _) = b.join().unwrap();
        assert!(a_slot < Duration::from_millis(400), "{a_slot:?}");
        // b became heavy only once a was done (about 0.85 s after b began).
        assert!(b_slot > Duration::from_millis(700), "{b_slot:?}");
        assert_eq!(*slots.free(), 1, "every slot is given back");
    }

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
        let slots = Arc::new(Slots::new(1));
        let ended = rt.block_on(run(
            Duration::from_millis(50),
            slots.clone(),
            None,
            false,
            spin,
        ));
        assert!(matches!(
            ended,
            Ended::Stopped(Stopped::OverBudget(d)) if d == Duration::from_millis(50)
        ));
        assert!(t0.elapsed() < Duration::from_secs(5));
        let done = rt.block_on(run(Duration::from_secs(5), slots, None, true, |w| {
            w.update(1);
            7
        }));
        assert!(matches!(done, Ended::Done(7)));
    }

    #[test]
    fn abandoned_work_stops() {
        quiet_stops();
        let abandon = Abandon::default();
        let mut w = Watch::new(
            abandon.clone(),
            Duration::from_secs(60),
            Arc::new(Slots::new(1)),
        );
        drop(abandon.guard());
        let stopped = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| spin(&mut w)));
        let payload = stopped.unwrap_err();
        assert_eq!(payload.downcast_ref::<Stopped>(), Some(&Stopped::Abandoned));
        // A disarmed guard abandons nothing.
        let kept = Abandon::default();
        kept.guard().disarm();
        assert!(!kept.0.load(Ordering::Relaxed));
    }

    /// Work stops when the process holds more than its memory budget,
    /// light work as well as heavy.
    #[test]
    fn work_over_the_memory_budget_stops() {
        quiet_stops();
        fn live() -> u64 {
            2000
        }
        let memory = Arc::new(Memory::new(1000, Some(live)));
        let watch = |heavy: bool| {
            let mut w = Watch::new(
                Abandon::default(),
                Duration::from_secs(60),
                Arc::new(Slots::new(1)),
            )
            .with_memory(memory.clone());
            if heavy {
                w.take_slot();
            }
            w
        };
        for heavy in [false, true] {
            let mut w = watch(heavy);
            let stopped = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| w.update(1)));
            assert_eq!(
                stopped.unwrap_err().downcast_ref::<Stopped>(),
                Some(&Stopped::OverMemory {
                    live: 2000,
                    budget: 1000
                })
            );
        }
    }
}
