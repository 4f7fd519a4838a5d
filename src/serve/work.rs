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
//! Light work never waits behind heavy work, and heavy work never waits
//! holding a thread: every request starts at once on a pool thread, and
//! work still running after [`LIGHT`] counts as heavy and must hold one of
//! a few heavy slots ([`Slots`]) to go on. If none is free, the work stops
//! there (it unwinds, as stopped work does, and gives its thread back) and
//! its request waits for a slot in a bounded queue, on no thread, then
//! runs again from the start holding the slot (at most [`LIGHT`] of work
//! done twice). Past the queue ([`Slots::new`]'s `queue`) it is refused
//! at once: 503 with `Retry-After` ([`RETRY_AFTER`]). So heavy work holds at
//! most as many threads as there are slots, and a light render, done
//! before it would need a slot, finds a thread free. Work known to be heavy
//! before it starts (an input over [`BIG_INPUT`] bytes, whose reading
//! reports no progress and whose memory grows with it) waits for its slot
//! in the queue before it takes a thread, so at most a few big inputs are
//! read at once.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use tokio::sync::{OwnedSemaphorePermit, Semaphore};

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
    /// It is heavy, and the queue for the heavy slots was full: come back
    /// after [`RETRY_AFTER`].
    Busy,
}

/// The payload that stops light work grown heavy when no heavy slot is
/// free: its request waits for one off the thread, then runs it again.
struct Requeue;

/// What a request refused for a full heavy queue is told to wait, seconds
/// (`Retry-After`).
pub const RETRY_AFTER: u64 = 5;

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

/// The heavy slots: how many heavy works may run at once, and the bounded
/// queue of requests waiting for one (on no thread).
pub struct Slots {
    permits: Arc<Semaphore>,
    /// Requests waiting for a slot now.
    waiting: AtomicUsize,
    /// The most that may wait.
    queue: usize,
    /// Works running that have used less than [`FRESH`] of processor
    /// time: every other work steps aside for them ([`YIELD`]).
    fresh: AtomicUsize,
}

/// Processor time a work may use before it stops being fresh: light
/// renders are done by then (fig9 takes 5 ms in a release build).
pub const FRESH: Duration = Duration::from_millis(50);

/// How long a work that is no longer fresh steps aside at a progress
/// report while fresh work runs, at most. The operating system shares the
/// cores evenly among threads, so a small render beside many big ones
/// would otherwise get a sliver of a core: this way, work that has used
/// little goes first (least attained service), which is what a light lane
/// needs when many heavy requests start at once.
pub const YIELD: Duration = Duration::from_millis(20);

/// Processor time the calling thread has used (Linux: from
/// `/proc/thread-self/schedstat`, in nanoseconds); `None` elsewhere.
fn cpu_time() -> Option<Duration> {
    let stat = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns = stat.split_whitespace().next()?.parse::<u64>().ok()?;
    Some(Duration::from_nanos(ns))
}

/// A place in the queue, given back when dropped.
struct Place<'a>(&'a AtomicUsize);

impl Drop for Place<'_> {
    fn drop(&mut self) {
        self.0.fetch_sub(1, Ordering::Relaxed);
    }
}

impl Slots {
    /// `n` slots, and at most `queue` requests waiting for one.
    pub fn new(n: usize, queue: usize) -> Self {
        Slots {
            permits: Arc::new(Semaphore::new(n)),
            waiting: AtomicUsize::new(0),
            queue,
            fresh: AtomicUsize::new(0),
        }
    }

    /// A slot if one is free now (none while others wait: they come first).
    fn try_take(&self) -> Option<OwnedSemaphorePermit> {
        self.permits.clone().try_acquire_owned().ok()
    }

    /// Waits for a slot, in turn, holding no thread; `None` at once when
    /// the queue is full.
    async fn wait(&self) -> Option<OwnedSemaphorePermit> {
        if self.waiting.fetch_add(1, Ordering::Relaxed) >= self.queue {
            self.waiting.fetch_sub(1, Ordering::Relaxed);
            return None;
        }
        let _place = Place(&self.waiting);
        self.permits.clone().acquire_owned().await.ok()
    }

    /// Whether as many requests wait as may.
    fn queue_full(&self) -> bool {
        self.waiting.load(Ordering::Relaxed) >= self.queue
    }

    /// Slots free now.
    #[cfg(test)]
    fn free(&self) -> usize {
        self.permits.available_permits()
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
/// past its deadline, and when it grows heavy with no heavy slot free.
pub struct Watch {
    abandon: Abandon,
    started: Instant,
    deadline: Instant,
    budget: Duration,
    slots: Arc<Slots>,
    /// The heavy slot this work holds, if it is heavy.
    slot: Option<OwnedSemaphorePermit>,
    /// Whether it has used less than [`FRESH`], and the thread's
    /// processor time when it began.
    fresh: bool,
    cpu_at_start: Option<Duration>,
    /// The server's memory, measured at every report of heavy work.
    memory: Option<Arc<Memory>>,
}

impl Watch {
    /// Work that may run for `budget` from now, taking one of `slots`
    /// once it runs past [`LIGHT`].
    pub fn new(abandon: Abandon, budget: Duration, slots: Arc<Slots>) -> Self {
        let started = Instant::now();
        slots.fresh.fetch_add(1, Ordering::Relaxed);
        Watch {
            abandon,
            started,
            deadline: started + budget,
            budget,
            slots,
            slot: None,
            fresh: true,
            cpu_at_start: cpu_time(),
            memory: None,
        }
    }

    /// Heavy work that also stops when the process holds more heap than
    /// `memory`'s budget.
    pub fn with_memory(mut self, memory: Arc<Memory>) -> Self {
        self.memory = Some(memory);
        self
    }

    fn stop_if_due(&self) {
        if self.abandon.0.load(Ordering::Relaxed) {
            std::panic::panic_any(Stopped::Abandoned);
        }
        if Instant::now() > self.deadline {
            std::panic::panic_any(Stopped::OverBudget(self.budget));
        }
    }

    fn check(&mut self) {
        self.stop_if_due();
        if self.fresh {
            let used = match (self.cpu_at_start, cpu_time()) {
                (Some(a), Some(b)) => b.saturating_sub(a),
                _ => self.started.elapsed(),
            };
            if used > FRESH {
                self.fresh = false;
                self.slots.fresh.fetch_sub(1, Ordering::Relaxed);
            }
        }
        // Heavy: past the light time, and not only because it shared the
        // processor with many others (it used more than FRESH of it); at
        // once when the queue is full, so a refusal costs little work.
        if self.slot.is_none()
            && !self.fresh
            && (self.started.elapsed() > LIGHT || self.slots.queue_full())
        {
            // A free slot, or give the thread back and wait for one in the
            // queue.
            match self.slots.try_take() {
                Some(p) => self.hold(p),
                None => std::panic::panic_any(Requeue),
            }
        }
        if !self.fresh {
            // Fresh work first: step aside while some runs.
            let t0 = Instant::now();
            while self.slots.fresh.load(Ordering::Relaxed) > 0 && t0.elapsed() < YIELD {
                std::thread::sleep(Duration::from_millis(1));
            }
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
}

impl Watch {
    /// Holds a heavy slot: heavy from now on.
    fn hold(&mut self, slot: OwnedSemaphorePermit) {
        self.slot = Some(slot);
    }
}

impl Drop for Watch {
    fn drop(&mut self) {
        if self.fresh {
            self.slots.fresh.fetch_sub(1, Ordering::Relaxed);
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
        let p = info.payload();
        if !p.is::<Stopped>() && !p.is::<Requeue>() {
            report(info);
        }
    }));
}

/// Runs `work` on the blocking pool with a [`Watch`] that stops it when
/// the returned future is dropped (the client left) or after `budget`
/// (counted from now, waiting included). Light work grown heavy with no
/// slot free, and work `heavy` from the start, wait for a heavy slot off
/// the pool (or are refused, [`Stopped::Busy`], past the queue) and then
/// run holding it.
pub async fn run<T: Send + 'static>(
    budget: Duration,
    slots: Arc<Slots>,
    memory: Option<Arc<Memory>>,
    heavy: bool,
    work: impl Fn(&mut Watch) -> T + Send + Sync + 'static,
) -> Ended<T> {
    let abandon = Abandon::default();
    let guard = abandon.guard();
    let deadline = Instant::now() + budget;
    let work = Arc::new(work);
    let attempt = |slot: Option<OwnedSemaphorePermit>| {
        let (abandon, slots, memory, work) =
            (abandon.clone(), slots.clone(), memory.clone(), work.clone());
        tokio::task::spawn_blocking(move || {
            let mut watch = Watch::new(abandon, budget, slots);
            watch.deadline = deadline;
            if let Some(slot) = slot {
                watch.hold(slot);
            }
            if let Some(m) = memory {
                watch = watch.with_memory(m);
            }
            work(&mut watch)
        })
    };
    if !heavy {
        match ended(attempt(None).await) {
            Err(Requeue) => {}
            Ok(e) => {
                guard.disarm();
                return e;
            }
        }
    }
    let waited = tokio::time::timeout_at(deadline.into(), slots.wait()).await;
    let e = match waited {
        Err(_) => Ended::Stopped(Stopped::OverBudget(budget)),
        Ok(None) => Ended::Stopped(Stopped::Busy),
        // Holding a slot, it is never requeued.
        Ok(Some(slot)) => ended(attempt(Some(slot)).await).unwrap_or(Ended::Crashed),
    };
    guard.disarm();
    e
}

/// What a pool task ended in; `Err(Requeue)`: it grew heavy with no slot.
fn ended<T>(joined: Result<T, tokio::task::JoinError>) -> Result<Ended<T>, Requeue> {
    match joined {
        Ok(t) => Ok(Ended::Done(t)),
        Err(e) if e.is_panic() => {
            let payload = e.into_panic();
            if payload.is::<Requeue>() {
                return Err(Requeue);
            }
            Ok(match payload.downcast::<Stopped>() {
                Ok(s) => Ended::Stopped(*s),
                Err(_) => Ended::Crashed,
            })
        }
        Err(_) => Ok(Ended::Crashed),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uses the processor for `d` (work, not a sleep: only work that uses
    /// the processor stops being fresh).
    fn burn(d: Duration) {
        let (t0, c0) = (Instant::now(), cpu_time());
        let mut x = 0u64;
        let used = || match (c0, cpu_time()) {
            (Some(a), Some(b)) => b - a,
            _ => t0.elapsed(),
        };
        while used() < d {
            for _ in 0..10_000 {
                x = std::hint::black_box(x.wrapping_add(1));
            }
        }
    }

    /// A work that sleeps past the light time has used no processor: it
    /// stays fresh and never takes a slot (it shared the processor, it
    /// did not use it).
    #[test]
    fn only_work_that_uses_the_processor_grows_heavy() {
        let slots = Arc::new(Slots::new(1, 4));
        let mut w = Watch::new(Abandon::default(), Duration::from_secs(60), slots.clone());
        std::thread::sleep(LIGHT + Duration::from_millis(50));
        w.update(1);
        assert!(w.fresh && w.slot.is_none());
        burn(FRESH + Duration::from_millis(20));
        w.update(1);
        assert!(!w.fresh && w.slot.is_some());
        drop(w);
        assert_eq!(slots.fresh.load(Ordering::Relaxed), 0);
    }

    /// With one heavy slot, a second long work does not wait for it on
    /// its thread: it stops (to wait off the pool); a light work is done
    /// meanwhile, and the slot is given back when the first ends.
    #[test]
    fn heavy_work_without_a_slot_gives_its_thread_back() {
        quiet_stops();
        let slots = Arc::new(Slots::new(1, 4));
        let long = |w: &mut Watch| {
            let t0 = Instant::now();
            while t0.elapsed() < LIGHT + Duration::from_millis(100) {
                w.update(1);
                burn(Duration::from_millis(5));
            }
        };
        let mut a = Watch::new(Abandon::default(), Duration::from_secs(60), slots.clone());
        long(&mut a);
        assert!(a.slot.is_some(), "the first heavy work holds the slot");
        assert_eq!(slots.free(), 0);
        let mut b = Watch::new(Abandon::default(), Duration::from_secs(60), slots.clone());
        let stopped = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| long(&mut b)));
        assert!(stopped.unwrap_err().is::<Requeue>());
        let mut light = Watch::new(Abandon::default(), Duration::from_secs(60), slots.clone());
        for _ in 0..10 {
            light.update(1);
        }
        assert!(light.slot.is_none());
        drop((a, b, light));
        assert_eq!(slots.free(), 1, "every slot is given back");
        assert_eq!(slots.fresh.load(Ordering::Relaxed), 0, "no fresh work left");
    }

    /// A request whose work grew heavy with no slot free waits in the
    /// queue and runs again holding the slot once it is given back; past
    /// the queue, one is refused at once.
    #[test]
    fn heavy_work_waits_in_a_bounded_queue_off_the_pool() {
        quiet_stops();
        let rt = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(1)
            .enable_all()
            .build()
            .unwrap();
        let slots = Arc::new(Slots::new(1, 1));
        rt.block_on(async {
            let held = slots.try_take().unwrap();
            let runs = Arc::new(AtomicUsize::new(0));
            let r = runs.clone();
            let queued = tokio::spawn(run(
                Duration::from_secs(30),
                slots.clone(),
                None,
                false,
                move |w| {
                    r.fetch_add(1, Ordering::Relaxed);
                    let t0 = Instant::now();
                    while t0.elapsed() < LIGHT + Duration::from_millis(50) {
                        w.update(1);
                        burn(Duration::from_millis(5));
                    }
                    7
                },
            ));
            // It grew heavy, gave its thread back and waits: the queue is full.
            while slots.waiting.load(Ordering::Relaxed) == 0 {
                tokio::time::sleep(Duration::from_millis(10)).await;
            }
            let refused = run(Duration::from_secs(30), slots.clone(), None, true, |_| 8).await;
            assert!(matches!(refused, Ended::Stopped(Stopped::Busy)));
            drop(held);
            assert!(matches!(queued.await.unwrap(), Ended::Done(7)));
            assert_eq!(runs.load(Ordering::Relaxed), 2, "run again with the slot");
        });
        assert_eq!(slots.free(), 1);
        assert_eq!(slots.waiting.load(Ordering::Relaxed), 0);
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
        let slots = Arc::new(Slots::new(1, 4));
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
            Arc::new(Slots::new(1, 4)),
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
            let slots = Arc::new(Slots::new(1, 4));
            let mut w = Watch::new(Abandon::default(), Duration::from_secs(60), slots.clone())
                .with_memory(memory.clone());
            if heavy {
                w.hold(slots.try_take().unwrap());
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
