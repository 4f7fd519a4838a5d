//! The server's memory budget (`--memory-budget`): no request, and no
//! number of requests, makes the process run out of memory.
//!
//! Two guards, one before and one during the work:
//!
//! - **Admission.** Before a request's body is read, it reserves what it
//!   is predicted to need ([`need`]: from its declared length and the
//!   picture it asks for). A request that could never fit (more than half
//!   the budget, [`Memory::per_request`]) is refused at once; one that
//!   does not fit now waits, up to [`ADMIT_WAIT`], for others to finish,
//!   and is then refused with 503. The reservation is given back when the
//!   work ends.
//! - **Measurement.** The binary counts its live heap bytes (its global
//!   allocator, `main.rs`). Heavy work checks the count at every progress
//!   report, and stops (503, like a refused admission) when the process
//!   holds more than the budget: a prediction that was wrong, answers not
//!   yet read by their clients, whatever the reason, the process never
//!   grows past the budget by more than what one progress step allocates.
//!
//! The count is of heap bytes in use, not of resident pages: the
//! allocator's own overhead, thread stacks and the binary come on top
//! (docs/limits.md gives the measured peak resident size).

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// How long a request waits for memory before it is refused with 503.
pub const ADMIT_WAIT: Duration = Duration::from_secs(10);

/// What any request needs beyond its input: a picture at the page's size,
/// its SVG text and answer, the occupancy index of a modest growth.
const BASE: u64 = 16 << 20;

/// Heap bytes a request takes per byte of its body: measured on a 40 MB
/// `.lsys` (an axiom of 40 M symbols), whose render peaks at 632 MB in
/// the CLI, 15.8 bytes per byte (docs/limits.md).
const PER_INPUT_BYTE: u64 = 16;

/// The heap bytes in use by the whole process, if counted.
pub type Live = fn() -> u64;

/// The budget and what is reserved of it.
pub struct Memory {
    budget: u64,
    reserved: Mutex<u64>,
    live: Option<Live>,
    /// Reservations made so far: work happened since a count was read.
    made: std::sync::atomic::AtomicU64,
}

/// Why a request got no memory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refused {
    /// It needs more than any one request may have.
    TooBig {
        /// Its predicted need, bytes.
        need: u64,
        /// What one request may have, bytes.
        per_request: u64,
    },
    /// Others hold the memory it needs; it waited [`ADMIT_WAIT`].
    Busy {
        /// Its predicted need, bytes.
        need: u64,
        /// The whole budget, bytes.
        budget: u64,
    },
}

/// Memory reserved for one request's work, given back when dropped.
pub struct Reservation {
    memory: Arc<Memory>,
    bytes: u64,
}

impl Drop for Reservation {
    fn drop(&mut self) {
        let mut r = self.memory.reserved();
        *r = r.saturating_sub(self.bytes);
    }
}

/// The predicted heap bytes of a request whose body is `body_len` bytes
/// (its declared `Content-Length`).
pub fn need(body_len: u64) -> u64 {
    BASE.saturating_add(body_len.saturating_mul(PER_INPUT_BYTE))
}

/// The predicted heap bytes of a PNG of `w` x `h` pixels beyond [`BASE`]:
/// the pixmap and the encoder's copy of it.
pub fn png_need(w: u32, h: u32) -> u64 {
    u64::from(w) * u64::from(h) * 4 * 2
}

/// The predicted heap bytes of reading a file of `len` bytes and
/// answering with its text: the bytes read, and the JSON answer that
/// quotes them (the text itself is the bytes, not a copy).
pub fn file_need(len: u64) -> u64 {
    len.saturating_mul(2)
}

/// Why a request got no memory, in words for its answer.
pub fn refusal(r: Refused) -> String {
    match r {
        Refused::TooBig { need, per_request } => format!(
            "this request would need about {} MiB, more than one request may have ({} MiB, half of --memory-budget): render it with the command line, or start stlc serve with a larger --memory-budget",
            mib(need),
            mib(per_request)
        ),
        Refused::Busy { need, budget } => format!(
            "the server is busy: this request needs about {} MiB and other requests hold its memory budget of {} MiB; try again in a moment",
            mib(need),
            mib(budget)
        ),
    }
}

impl Memory {
    /// A budget of `budget` bytes, measured by `live` where counted.
    pub fn new(budget: u64, live: Option<Live>) -> Self {
        Memory {
            budget,
            reserved: Mutex::new(0),
            live,
            made: std::sync::atomic::AtomicU64::new(0),
        }
    }

    /// The count of reservations made so far, if none is held now (the
    /// server is idle); `None` while a request holds one.
    pub fn idle(&self) -> Option<u64> {
        let r = self.reserved();
        (*r == 0).then(|| self.made.load(std::sync::atomic::Ordering::Relaxed))
    }

    fn reserved(&self) -> std::sync::MutexGuard<'_, u64> {
        self.reserved.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// The whole budget, bytes.
    pub fn budget(&self) -> u64 {
        self.budget
    }

    /// What one request may have: half the budget, so that two heavy
    /// works (the heavy slots) fit together.
    pub fn per_request(&self) -> u64 {
        self.budget / 2
    }

    /// The heap bytes in use now, if counted.
    pub fn live(&self) -> Option<u64> {
        self.live.map(|f| f())
    }

    /// Whether the process holds more than its budget (`Some(live)`).
    pub fn over(&self) -> Option<u64> {
        self.live().filter(|&l| l > self.budget)
    }

    /// Reserves `need` bytes if they fit now: in what is not reserved, and
    /// in what is not in use.
    fn try_reserve(self: &Arc<Self>, need: u64) -> Option<Reservation> {
        let mut r = self.reserved();
        let in_use = self.live().unwrap_or(0);
        let fits = r.saturating_add(need) <= self.budget
            && in_use.saturating_add(need) <= self.budget
            // The first request always runs when it may run at all (the
            // count includes the server's own few megabytes).
            || *r == 0 && need <= self.per_request();
        if !fits {
            return None;
        }
        *r += need;
        self.made.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        Some(Reservation {
            memory: self.clone(),
            bytes: need,
        })
    }

    /// Reserves `need` bytes if they fit now, without waiting (for work
    /// already on a pool thread, which must not wait holding it).
    pub fn reserve_now(self: &Arc<Self>, need: u64) -> Result<Reservation, Refused> {
        if need > self.per_request() {
            return Err(Refused::TooBig {
                need,
                per_request: self.per_request(),
            });
        }
        self.try_reserve(need).ok_or(Refused::Busy {
            need,
            budget: self.budget,
        })
    }

    /// Reserves `need` bytes, waiting up to `wait` for them (an abandoned
    /// request stops waiting: its future is dropped).
    pub async fn admit(
        self: &Arc<Self>,
        need: u64,
        wait: Duration,
    ) -> Result<Reservation, Refused> {
        if need > self.per_request() {
            return Err(Refused::TooBig {
                need,
                per_request: self.per_request(),
            });
        }
        let t0 = Instant::now();
        loop {
            if let Some(r) = self.try_reserve(need) {
                return Ok(r);
            }
            if t0.elapsed() >= wait {
                return Err(Refused::Busy {
                    need,
                    budget: self.budget,
                });
            }
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
    }
}

/// The system allocator's settings the server runs with (glibc reads them
/// from the environment when the process starts, so the server starts
/// itself again with them, once, as the same process: `exec`). glibc keeps
/// memory freed by a thread in that thread's arena, and after a big block
/// is freed it raises the size from which blocks are mapped on their own,
/// so later big blocks come from the arenas and stay resident after they
/// are freed: measured with four concurrent 300,000-stem growths under a
/// 256 MiB budget, the resident size peaked at 475 MB while the heap in
/// use stayed under the budget; with these settings, 281 MB
/// (docs/limits.md). Elsewhere (or if `exec` fails) nothing changes.
pub fn tune_allocator() {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::process::CommandExt as _;
        const SETTINGS: [(&str, &str); 2] = [
            // Blocks of 128 KiB and more are mapped on their own and given
            // back when freed (no dynamic raise).
            ("MALLOC_MMAP_THRESHOLD_", "131072"),
            // One arena, not eight per core: memory freed by one thread
            // is reused by the next, and none stays behind in an arena
            // no thread uses (8 x 3 growths of 200,000 stems: 95 MB
            // resident 15 s after, against 4 MB fresh, with two arenas;
            // 55 MB with one).
            ("MALLOC_ARENA_MAX", "1"),
        ];
        if std::env::var_os(SETTINGS[0].0).is_some() {
            return;
        }
        if let Ok(exe) = std::env::current_exe() {
            // Returns only if it failed: go on as we are.
            let _ = std::process::Command::new(exe)
                .args(std::env::args_os().skip(1))
                .envs(SETTINGS)
                .exec();
        }
    }
}

/// How often [`give_back_when_idle`] looks.
const IDLE_LOOK: Duration = Duration::from_secs(2);

/// Gives the allocator's free memory back to the system each time the
/// server falls idle: every [`IDLE_LOOK`], if no request holds a
/// reservation and one was made since the last look that gave back
/// ([`give_back`]). One arena ([`tune_allocator`]) reuses freed memory but
/// keeps it resident: after 8 x 3 growths of 200,000 stems the idle
/// server stayed 47-56 MB above a fresh one without this (docs/limits.md).
pub async fn give_back_when_idle(memory: Arc<Memory>) {
    let mut given_back_at = 0;
    loop {
        tokio::time::sleep(IDLE_LOOK).await;
        if let Some(made) = memory.idle()
            && made != given_back_at
        {
            given_back_at = made;
            let _ = tokio::task::spawn_blocking(give_back).await;
        }
    }
}

/// Gives the free memory glibc's allocator holds back to the system
/// (`malloc_trim(0)`: the free pages of its heap, not only its top); the
/// one call of the binary outside safe Rust (the library forbids unsafe
/// code; the package denies it, and allows it here alone). Elsewhere
/// nothing.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[allow(unsafe_code)]
pub fn give_back() {
    // SAFETY: malloc_trim takes no pointer and has no precondition on its
    // caller; glibc locks each arena while it walks it, as malloc does.
    unsafe {
        libc::malloc_trim(0);
    }
}

/// Elsewhere the allocator gives memory back by itself, or has no call
/// for it.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
pub fn give_back() {}

/// Bytes in MiB, rounded up, for messages.
pub fn mib(bytes: u64) -> u64 {
    bytes.div_ceil(1 << 20)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn block_on<T>(f: impl std::future::Future<Output = T>) -> T {
        tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .unwrap()
            .block_on(f)
    }

    /// Reservations add up to at most the budget; a request over half of
    /// it is refused at once; one that does not fit waits and gets its
    /// memory when another's is given back, or is refused after the wait.
    #[test]
    fn admission_keeps_reservations_within_the_budget() {
        let m = Arc::new(Memory::new(100, None));
        let big = block_on(m.admit(51, ADMIT_WAIT));
        assert_eq!(
            big.err(),
            Some(Refused::TooBig {
                need: 51,
                per_request: 50
            })
        );
        let a = block_on(m.admit(50, ADMIT_WAIT)).unwrap();
        let b = block_on(m.admit(40, ADMIT_WAIT)).unwrap();
        assert_eq!(*m.reserved(), 90);
        let t0 = Instant::now();
        let c = block_on(m.admit(20, Duration::from_millis(200)));
        assert_eq!(
            c.err(),
            Some(Refused::Busy {
                need: 20,
                budget: 100
            })
        );
        assert!(t0.elapsed() >= Duration::from_millis(200));
        // Given back while waiting: admitted.
        let m2 = m.clone();
        let late = std::thread::spawn(move || block_on(m2.admit(20, ADMIT_WAIT)).is_ok());
        std::thread::sleep(Duration::from_millis(120));
        drop(a);
        assert!(late.join().unwrap());
        drop(b);
        assert_eq!(*m.reserved(), 0, "every reservation is given back");
    }

    /// What is in use counts too (answers not read yet, a wrong
    /// prediction): a request that fits in the reservations but not in the
    /// live bytes waits; the first request may always run.
    #[test]
    fn live_bytes_count_at_admission() {
        fn busy() -> u64 {
            95
        }
        let m = Arc::new(Memory::new(100, Some(busy)));
        let first = block_on(m.admit(10, Duration::ZERO)).unwrap();
        let second = block_on(m.admit(10, Duration::ZERO));
        assert!(matches!(second, Err(Refused::Busy { .. })));
        assert_eq!(m.over(), None);
        drop(first);
        fn over() -> u64 {
            101
        }
        assert_eq!(Memory::new(100, Some(over)).over(), Some(101));
    }

    /// The prediction: 16 MiB, 16 bytes per body byte, 8 per pixel.
    #[test]
    fn need_is_the_documented_formula() {
        assert_eq!(need(0), 16 << 20);
        assert_eq!(need(40_000_000), (16 << 20) + 640_000_000);
        assert_eq!(need(u64::MAX), u64::MAX);
        assert_eq!(png_need(16384, 16384), 2 << 30);
    }
}
