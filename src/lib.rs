//! # stlc: Structural Tree Language and classic L-systems
//!
//! stlc reads three kinds of text and draws trees from them:
//!
//! | input | extension | what it is |
//! | --- | --- | --- |
//! | Outline Description | `.od` | rules, a seed and a layout the tree may grow into |
//! | Branch-Expansion Description | `.bed` | the same, with every branching decision written out |
//! | classic L-system | `.lsys` | `generations`, `axiom`, `rule X SUCC`, `angle` |
//!
//! The pipeline, one module per stage:
//!
//! ```text
//! text ──syntax──▶ Description / LSystem ──grow──▶ BED (Description) ──bed::write──▶ .bed text
//!                        │                              │
//!                        └────────interpret─────────────┴──▶ segments ──render──▶ PNG / SVG
//! ```
//!
//! - [`syntax`]: one pest grammar (`grammar.pest`) for all three formats;
//!   typed trees with byte spans; every error a [`diag::Diagnostic`].
//! - [`grow`]: an OD into a BED under space occupancy (`bfs` or `dfs`).
//! - [`bed`]: the BED model's checks and its canonical writer.
//! - [`interpret`]: derivations to turtle operations, depth-first streaming
//!   (`dfs`) or breadth-first rewriting (`bfs`); exact statistics.
//! - [`turtle`]: the [`turtle::Turtle`] backend trait and the turtle's geometry.
//! - [`render`]: PNG (tiny-skia) and SVG backends, fitted to a size.
//!
//! The library never prints and never exits: errors are data
//! ([`diag::Diagnostics`]); the `stlc` binary renders them with ariadne.

#![deny(
    clippy::print_stdout,
    clippy::print_stderr,
    clippy::exit,
    clippy::dbg_macro
)]

pub mod bed;
pub mod choice;
pub mod color;
pub mod diag;
pub mod grow;
pub mod interpret;
pub mod limits;
pub mod model;
pub mod num;
pub mod pipeline;
pub mod progress;
pub mod render;
pub mod rings;
pub mod syntax;
pub mod turtle;

pub use diag::{Diagnostic, Diagnostics, ErrorKind, Severity, Span};
pub use limits::Limits;
