//! The product's API: what a caller asks ([`Body`]), what comes back
//! ([`RenderAnswer`], [`WordsAnswer`], [`Checked`], [`Failed`]), and the
//! calls that answer ([`render`], [`export`], [`words`], [`compile`],
//! [`check`]), as JSON with serde (feature `serde`).
//!
//! `stlc serve` (HTTP, docs/serve.md) and the WebAssembly module of the
//! static site (`web/`, docs/web.md) are transports over these calls: they
//! read a body, run a call (the server on its pool, within its budgets) and
//! send its answer on; neither holds a call of its own, so the page's two
//! engines answer alike, byte for byte. The calls themselves hold no
//! pipeline logic: everything comes from [`crate::pipeline::Request`].

mod answer;
mod body;
mod calls;
pub mod shapes;
mod spelling;
pub mod stems3;

pub use answer::{
    BIG_TREE_STEMS, DiagnosticJson, Failed, Growth, RenderAnswer, WORD_CHARS, WORD_DEPTHS, Word,
    WordsAnswer, diagnostics_json,
};
pub use body::{BadRequest, Body, Kind, SaveBody, Seed, Settings, parse, parse_save};
pub use calls::{Checked, Format, check, compile, export, render, words};
pub use spelling::Page;
