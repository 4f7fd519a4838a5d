//! Growing an OD into a BED (`grow`): errors, and the warnings of growth
//! cut short.

/// A problem, or a warning, of growth.
/// Wrapped in [`super::ErrorKind::Grow`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GrowError {
    /// Growth has nothing to start from: no `SEED` and no rule.
    #[error("nothing to grow: the description has no SEED and no rule")]
    NothingToGrow,
    /// The clearance (`C=` or `--clearance`) is negative or not finite.
    #[error("the clearance must be a finite number >= 0, not {value}")]
    BadClearance {
        /// The clearance asked for.
        value: f64,
    },
    /// Warning: a root of a forest on the point of an earlier root.
    #[error(
        "root {root} is on the point of root {first}: the two trees start in one place, and the later finds its room taken"
    )]
    SharedRoot {
        /// The later root, counted from 1 in root-line order.
        root: usize,
        /// The earlier root on the same point.
        first: usize,
    },
    /// The root lies outside the layout region, so nothing can grow.
    #[error("the root ({x}, {y}) lies outside the layout region")]
    RootOutside {
        /// The root's x, as written.
        x: f64,
        /// The root's y, as written.
        y: f64,
    },
    /// Growth with nothing to bound it: a growth point without a count whose
    /// rules can branch forever, and no layout, decrement or explicit
    /// `--max-stems`.
    #[error(
        "growth has no bound: `{rule}` can branch forever (through `{through}`), and there is no LAYOUT, no count and no decrement to stop it"
    )]
    UnboundedGrowth {
        /// The rule of the growth point.
        rule: String,
        /// A rule on the endless cycle reachable from it.
        through: String,
    },
    /// Warning: `--max-stems` stopped growth; the BED is cut short.
    #[error(
        "growth stopped at {stems} stems: the next rule application would pass the limit of {} {limit}",
        crate::limits::Bound::Stems.flag()
    )]
    GrowthStopped {
        /// Stems grown when growth stopped.
        stems: u64,
        /// The limit in force.
        limit: u64,
    },
    /// Warning: growth reached `--max-depth`; deeper branches were not grown.
    #[error(
        "growth reached the depth limit of {limit} nested rule applications ({}); deeper branches were not grown",
        crate::limits::Bound::Depth.flag()
    )]
    DepthCapped {
        /// The limit in force.
        limit: u32,
    },
}
