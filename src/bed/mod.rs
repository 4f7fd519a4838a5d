//! The Branch-Expansion Description: the contract between `compile` and
//! `render`. A BED is a [`Description`] read or written as `Format::Bed`.

pub mod write;

use crate::diag::Diagnostics;
use crate::limits::Limits;
use crate::syntax::ast::Description;

/// Checks what the grammar cannot: every term's order leaves its stems a
/// positive length and width, repeat counts within limits.
pub fn validate(desc: &Description, limits: &Limits) -> Result<(), Diagnostics> {
    let _ = (desc, limits);
    unimplemented!("issue 3")
}
