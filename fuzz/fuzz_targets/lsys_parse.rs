//! Bytes -> `precheck` -> `.lsys` parser. Any input must give an `LSystem`
//! or a `Diagnostics` with at least one error, never a panic, hang or
//! unbounded allocation.
//!
//! The body is `fuzz/bodies/lsys_parse.rs`, which the test suite also runs over
//! this target's corpus (tests/integration/fuzz_corpus.rs), so it always
//! compiles and the corpus stays a regression test.
#![no_main]

#[path = "../bodies/lsys_parse.rs"]
mod body;

libfuzzer_sys::fuzz_target!(|data: &[u8]| body::run(data));
