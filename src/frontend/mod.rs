//! What the two front ends ([`crate::cli`] and [`crate::serve`]) share and
//! the library must not do: reading an input (`-` for standard input, a
//! size limit), writing an output file atomically, rendering diagnostics
//! as ariadne reports on stderr, the errors only a front end makes
//! (`error.rs`), what an interrupt needs to know (the temporary files
//! to remove, the exit status), and the heap bytes in use (`heap.rs`).

pub(crate) mod error;
pub(crate) mod heap;
pub(crate) mod interrupt;
pub(crate) mod io;
pub(crate) mod report;
