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
//! Start at [`pipeline`]: a [`Request`] (the input and every option) and
//! its methods (`render`, `compile`, `expand`, `check`, `stats`) are what
//! every front end calls; the stage functions behind them are re-exported
//! here too ([`load`], [`compile`], [`scene`], [`expand`], [`check`],
//! [`stats`]; and [`pipeline::render`], which keeps its module's name
//! for the [`render`] stage).
//!
//! ```text
//! text ──syntax──▶ Description / LSystem ──grow──▶ BED (Description) ──bed::write──▶ .bed text
//!                        │                              │
//!                        └────────interpret─────────────┴──▶ segments ──render──▶ PNG / SVG
//! ```
//!
//! The map, a line a module:
//!
//! - [`pipeline`]: the front door: [`Request`], load, compile, scene,
//!   render, expand, check, stats; every enum a front end needs.
//! - [`api`] (feature `serde`): the product's JSON API, the request and
//!   answer types and the calls `stlc serve` and the WebAssembly module
//!   carry.
//! - [`syntax`]: text to model: one pest grammar (`grammar.pest`) for all
//!   three formats, typed trees with byte spans, every error a diagnostic.
//! - [`model`]: the types every stage shares: descriptions, rules, seeds and
//!   their terms, layouts, L-systems; the one walk over a rule body.
//! - [`grow`]: an OD into a BED under space occupancy (`bfs`, `dfs` or `space`).
//! - [`bed`]: the BED's checks, its measure and its canonical writer.
//! - [`interpret`]: derivations to turtle operations, depth-first
//!   streaming or breadth-first rewriting; exact statistics.
//! - [`turtle`]: the turtle's state machine, its geometry and the backend
//!   trait.
//! - [`render`]: PNG (tiny-skia) and SVG backends, fitted to a size.
//! - [`rings`]: layout shapes as rings, fills and bounds, shared by growth
//!   and rendering.
//! - [`choice`]: stochastic choices as pure functions of the seed and the
//!   place.
//! - [`diag`]: errors as data ([`Diagnostic`], [`ErrorKind`]).
//! - [`limits`]: every `--max-*` bound on input and work.
//! - [`progress`]: the progress sink long work reports to.
//! - [`num`]: numbers written with fixed decimals; linear parameters.
//! - [`color`]: colours, `#rrggbb` and Delphi names.
//!
//! The library never prints and never exits: errors are data
//! ([`diag::Diagnostics`]); the `stlc` binary renders them with ariadne.

#![forbid(unsafe_code)]
#![deny(
    clippy::print_stdout,
    clippy::print_stderr,
    clippy::exit,
    clippy::dbg_macro
)]

#[cfg(feature = "serde")]
pub mod api;
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
pub use limits::{Bound, Limits};
pub use pipeline::{
    Checked, Compiled, Drawn, Loaded, Request, Scene, check, compile, detect_kind, expand, load,
    scene, stats,
};
