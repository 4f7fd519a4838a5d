//! Derivation of classic L-systems: `dfs` streaming and `bfs` rewriting.

use crate::diag::Diagnostics;
use crate::interpret::Strategy;
use crate::limits::Limits;
use crate::progress::Progress;
use crate::syntax::lsys::LSystem;
use crate::turtle::Turtle;

/// Draws `sys` derived to `depth` into `turtle`, starting at the origin
/// heading up, unit step `sys.length`, order 0.
pub fn draw(
    sys: &LSystem,
    depth: u32,
    strategy: Strategy,
    limits: &Limits,
    turtle: &mut dyn Turtle,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    let _ = (sys, depth, strategy, limits, turtle, progress);
    unimplemented!("issue 2")
}
