//! Expansion of Branch-Expansion Descriptions into drawing components.

use crate::diag::Diagnostics;
use crate::interpret::Strategy;
use crate::limits::Limits;
use crate::progress::Progress;
use crate::syntax::ast::Description;
use crate::turtle::Turtle;

/// Draws a BED's seed into `turtle`: the turtle starts at the root, heading
/// up, order 0; stems of order k have length `L - k*dL`.
pub fn draw(
    desc: &Description,
    strategy: Strategy,
    limits: &Limits,
    turtle: &mut dyn Turtle,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    let _ = (desc, strategy, limits, turtle, progress);
    unimplemented!("issue 3")
}
