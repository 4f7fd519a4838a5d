//! The binary's heap, counted: its global allocator is the system's with
//! counters (`stats_alloc`), so `stlc serve` keeps within its memory
//! budget by measuring the bytes in use (serve/memory.rs;
//! docs/dependencies.md gives the measured cost: none visible).

#[global_allocator]
static ALLOC: &stats_alloc::StatsAlloc<std::alloc::System> = &stats_alloc::INSTRUMENTED_SYSTEM;

/// Heap bytes in use by the process now.
pub fn live_bytes() -> u64 {
    let s = ALLOC.stats();
    // A reallocation adds its growth to the allocated bytes and its
    // shrinking to the freed ones.
    s.bytes_allocated.saturating_sub(s.bytes_deallocated) as u64
}

#[cfg(test)]
mod tests {
    /// The count follows an allocation and its release (other threads of
    /// the test binary allocate too: the margins allow for them).
    #[test]
    fn the_count_follows_allocations() {
        let before = super::live_bytes();
        let big = vec![1u8; 64 << 20];
        let during = super::live_bytes();
        assert!(during >= before + (60 << 20), "{before} -> {during}");
        drop(big);
        let after = super::live_bytes();
        assert!(after + (60 << 20) <= during, "{during} -> {after}");
    }
}
