//! Bytes -> `precheck` -> the `.od`/`.bed` parser, both formats. For a BED
//! that parses: `bed::validate` and `Bed::new` (they agree, and the measured
//! stems are the segments drawn), the canonical writer and its round trip
//! (`parse(write(x)) == x` when every number of `x` is written exactly;
//! `write` a fixed point always), and drawing it with both derivations into
//! bounding turtles under small limits (they must agree bit for bit).
//!
//! The body is `fuzz/bodies/stl_parse.rs`, which the test suite also runs over
//! this target's corpus (tests/integration/fuzz_corpus.rs), so it always
//! compiles and the corpus stays a regression test.
#![no_main]

#[path = "../bodies/stl_parse.rs"]
mod body;

libfuzzer_sys::fuzz_target!(|data: &[u8]| body::run(data));
