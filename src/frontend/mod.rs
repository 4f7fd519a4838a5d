//! What the two front ends ([`crate::cli`] and [`crate::serve`]) share and
//! the library must not do: reading an input (`-` for standard input, a
//! size limit), writing an output file atomically, rendering diagnostics
//! as ariadne reports on stderr, and the errors only a front end makes
//! (`error.rs`).

pub(crate) mod error;
pub(crate) mod io;
pub(crate) mod report;
