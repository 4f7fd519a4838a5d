//! `.od` and `.bed` files into [`Description`], names resolved.

use super::Rule;
use super::ast::{Description, Format};
use crate::diag::Diagnostics;
use crate::limits::Limits;

/// Parses an Outline Description (`Format::Od`) or a Branch-Expansion
/// Description (`Format::Bed`).
pub fn parse(src: &str, format: Format, limits: &Limits) -> Result<Description, Diagnostics> {
    let _ = (src, format, limits);
    unimplemented!("issue 3")
}

/// A user-facing description of a grammar rule of the od/bed section.
pub fn describe_rule(rule: Rule) -> Option<&'static str> {
    let _ = rule;
    None
}
