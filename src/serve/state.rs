//! What every request of `stlc serve` sees: a leaf the server builds and
//! the routes read.

use std::sync::Arc;

use stlc::api;

use super::{document, http, memory, work};

/// What every request sees.
pub struct State {
    pub settings: api::Settings,
    /// The file being edited (or the example).
    pub doc: document::Document,
    /// The per-run secret every API call needs (docs/serve.md).
    pub key: http::Key,
    /// Who may ask.
    pub guard: http::Guard,
    /// The heavy slots: work running past `work::LIGHT` takes turns.
    pub heavy: Arc<work::Slots>,
    /// The memory budget requests reserve from.
    pub memory: Arc<memory::Memory>,
}
