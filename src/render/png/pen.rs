//! The pen of the open subpath, which [`fold`](super::fold) moves.

use crate::turtle::Point;

/// The pen of the open subpath, in output pixels, for [`FOLD_PX`](crate::render::style::FOLD_PX) folding.
#[derive(Debug, Clone, Copy)]
pub(super) struct Pen {
    /// The last vertex written into the path.
    pub(super) kept: Point,
    /// Where the pen is: the end of the last segment.
    pub(super) at: Point,
    /// `at` is not written yet (it is closer than [`FOLD_PX`](crate::render::style::FOLD_PX) to `kept`).
    pub(super) pending: bool,
}
