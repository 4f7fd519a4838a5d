//! Bytes -> `.od` parser -> the grower (both growth orders, tight limits) ->
//! the canonical writer. What grows must be a BED that reads back, passes
//! `Bed::new` (or meets only the symbol budget) and draws.
//!
//! The body is `fuzz/bodies/od_compile.rs`, which the test suite also runs over
//! this target's corpus (tests/integration/fuzz_corpus.rs), so it always
//! compiles and the corpus stays a regression test.
#![no_main]

#[path = "../bodies/od_compile.rs"]
mod body;

libfuzzer_sys::fuzz_target!(|data: &[u8]| body::run(data));
