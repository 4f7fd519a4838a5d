//! Parse a `.lsys`, derive it with both derivations into a bounding turtle
//! (they must agree bit for bit), then render it to a small PNG and SVG.
//! Tight limits keep every input fast; any error after a successful parse
//! must be a limit (or, when rendering a picture whose coordinates are not
//! finite, `DrawingNotFinite`), never a panic.
//!
//! The body is `fuzz/bodies/lsys_render.rs`, which the test suite also runs over
//! this target's corpus (tests/integration/fuzz_corpus.rs), so it always
//! compiles and the corpus stays a regression test.
#![no_main]

#[path = "../bodies/lsys_render.rs"]
mod body;

libfuzzer_sys::fuzz_target!(|data: &[u8]| body::run(data));
