//! Growing an OD into a BED (`grow`): errors, the warnings of growth cut
//! short, and why a rule's try did not fit ([`Misfit`], [`MissReason`]),
//! which the warning of a rule that never grew carries.

use std::fmt;

use crate::num::{Trim, fixed};

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
    #[error("the root {} lies outside the layout region", point(*.x, *.y, *.z))]
    RootOutside {
        /// The root's x, as written.
        x: f64,
        /// The root's y, as written.
        y: f64,
        /// The root's z in a 3D description.
        z: Option<f64>,
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
    /// Warning: the stem limit (`--max-stems`) stopped growth; the BED is
    /// cut short. The message names no flag: the hint names the option as
    /// data, for each front end to spell.
    #[error(
        "growth stopped at {stems} stems: the next rule application would pass the stem limit of {limit}"
    )]
    GrowthStopped {
        /// Stems grown when growth stopped.
        stems: u64,
        /// The limit in force.
        limit: u64,
    },
    /// Warning: growth stopped at the file's `M=` (its design's stem count).
    #[error(
        "growth stopped at {stems} stems: the next rule application would pass the file's M={limit}"
    )]
    DesignStemCount {
        /// Stems grown when growth stopped.
        stems: u64,
        /// The file's `M=`.
        limit: u64,
    },
    /// Warning: growth reached the depth limit (`--max-depth`); deeper
    /// branches were not grown.
    #[error(
        "growth reached the depth limit of {limit} nested rule applications; deeper branches were not grown"
    )]
    DepthCapped {
        /// The limit in force.
        limit: u32,
    },
    /// Warning: a rule was tried and never fitted; `why` is the first
    /// try's reason, with its numbers.
    #[error("rule `{rule}` never grew: {}: {why}", tries_failed(*tries))]
    NeverFitted {
        /// The rule (`R1`, or `R1.2` for an alternative).
        rule: String,
        /// How many times it was tried (every try failed).
        tries: u64,
        /// Why the first try failed.
        why: Misfit,
    },
    /// Warning: a rule grew, and then most of its tries failed because its
    /// stems' length or width reached zero (`L` or `B`'s decrement): growth
    /// stopped there, short of the room the layout gives.
    #[error(
        "growth stopped at {stems} stems: rule `{rule}` ran out (most misses: {reason}, {count} of {misses})"
    )]
    RanOut {
        /// Stems grown in all.
        stems: u64,
        /// The rule (`R1`, or `R1.2` for an alternative).
        rule: String,
        /// Its most common reason: [`MissReason::TooThin`] or
        /// [`MissReason::TooShort`].
        reason: MissReason,
        /// Tries that failed for it.
        count: u64,
        /// Tries that failed.
        misses: u64,
    },
}

/// "its one try failed" or "all its N tries failed, the first".
fn tries_failed(tries: u64) -> String {
    if tries == 1 {
        "its one try failed".into()
    } else {
        format!("all its {tries} tries failed, the first")
    }
}

/// Which stem a new stem came too close to, seen from the new stem.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kin {
    /// A stem starting where it starts: a branch of the same tip (or of a
    /// growth point on the same spot).
    Sibling,
    /// The stem it starts from: the end of that stem is its start.
    Parent,
    /// Any other stem.
    Other,
}

/// Why a try of a rule failed, as counted: the first test it failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MissReason {
    /// A stem would leave the layout region (or come closer to its outline
    /// than half its width).
    Outside,
    /// A stem would come closer than the clearance to another stem.
    TooClose(Kin),
    /// The rule's stems have no length at its order (`L` decremented to 0).
    TooShort,
    /// The rule's stems have no width at its order (`B` decremented to 0).
    TooThin,
    /// The try was deeper than `--max-depth`.
    Depth,
    /// `--max-stems` was reached.
    StemLimit,
}

impl MissReason {
    /// How many reasons there are: the length of a table of counts.
    pub const COUNT: usize = 8;

    /// Every reason, in the order of [`MissReason::index`].
    pub const ALL: [MissReason; MissReason::COUNT] = [
        MissReason::Outside,
        MissReason::TooClose(Kin::Sibling),
        MissReason::TooClose(Kin::Parent),
        MissReason::TooClose(Kin::Other),
        MissReason::TooShort,
        MissReason::TooThin,
        MissReason::Depth,
        MissReason::StemLimit,
    ];

    /// The reason's place in a table of counts (and in [`MissReason::ALL`]).
    pub fn index(self) -> usize {
        match self {
            MissReason::Outside => 0,
            MissReason::TooClose(Kin::Sibling) => 1,
            MissReason::TooClose(Kin::Parent) => 2,
            MissReason::TooClose(Kin::Other) => 3,
            MissReason::TooShort => 4,
            MissReason::TooThin => 5,
            MissReason::Depth => 6,
            MissReason::StemLimit => 7,
        }
    }

    /// Whether a limit (`--max-depth`, `--max-stems`) made the miss: those
    /// have warnings of their own.
    pub fn is_limit(self) -> bool {
        matches!(self, MissReason::Depth | MissReason::StemLimit)
    }
}

impl fmt::Display for MissReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            MissReason::Outside => "outside the layout",
            MissReason::TooClose(Kin::Sibling) => "too close to a sibling stem",
            MissReason::TooClose(Kin::Parent) => "too close to its parent stem",
            MissReason::TooClose(Kin::Other) => "too close to another stem",
            MissReason::TooShort => "stem too short: L decremented to 0",
            MissReason::TooThin => "stem too thin: B decremented to 0",
            MissReason::Depth => "depth limit reached",
            MissReason::StemLimit => "stem limit reached",
        })
    }
}

/// Why one try of a rule failed, with the numbers: what a warning about a
/// rule that never grew says. Stems are numbered from 1 in the order the
/// rule draws them (its `F`s in written order, fixed figures expanded).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Misfit {
    /// Stem `stem` would leave the layout region, or come closer to its
    /// outline than half its width.
    Outside {
        /// The stem, numbered from 1.
        stem: u32,
    },
    /// Stem `stem`'s centre line would come within `found` of another
    /// stem's, where `needed` (the clearance plus half of each stem's
    /// width) is needed.
    TooClose {
        /// The stem, numbered from 1.
        stem: u32,
        /// Which stem it came close to.
        kin: Kin,
        /// That stem's number if it is one of the same try's, `None` if it
        /// was already there (grown before, or drawn by the seed).
        other: Option<u32>,
        /// The distance found between the centre lines.
        found: f64,
        /// The distance needed between them.
        needed: f64,
        /// The clearance `C` (part of `needed`).
        clearance: f64,
    },
    /// At order `order` the stems' length `L - order * dL` is `length`, not
    /// positive.
    TooShort {
        /// The order the rule would draw at.
        order: u32,
        /// The length there.
        length: f64,
    },
    /// At order `order` the stems' width `B - order * dB` is `width`, not
    /// positive.
    TooThin {
        /// The order the rule would draw at.
        order: u32,
        /// The width there.
        width: f64,
    },
    /// The try was deeper than `--max-depth`.
    Depth {
        /// The limit in force.
        limit: u32,
    },
    /// The try would have passed `--max-stems`.
    StemLimit {
        /// The limit in force.
        limit: u64,
    },
}

impl Misfit {
    /// The reason counted for it.
    pub fn reason(&self) -> MissReason {
        match self {
            Misfit::Outside { .. } => MissReason::Outside,
            Misfit::TooClose { kin, .. } => MissReason::TooClose(*kin),
            Misfit::TooShort { .. } => MissReason::TooShort,
            Misfit::TooThin { .. } => MissReason::TooThin,
            Misfit::Depth { .. } => MissReason::Depth,
            Misfit::StemLimit { .. } => MissReason::StemLimit,
        }
    }

    /// What to change, in one sentence: the hint of the warning.
    pub fn hint(&self) -> &'static str {
        match self {
            Misfit::Outside { .. } => {
                "shorten `L` (or thin `B`) so the rule's stems fit inside the outline, or give the LAYOUT more room where it grows"
            }
            Misfit::TooClose {
                kin: Kin::Sibling, ..
            } => {
                "raise `A` so sibling branches spread further apart, lower `C`, or thin the stems (`B`)"
            }
            Misfit::TooClose {
                kin: Kin::Parent, ..
            } => {
                "turn the branch less (lower `A`, or fewer `+`/`-`): it folds back onto the stem it starts from; or lower `C`, or thin the stems (`B`)"
            }
            Misfit::TooClose {
                kin: Kin::Other, ..
            } => {
                "lower `C` or shorten `L` so the rule fits between the stems already there, or give it more room"
            }
            Misfit::TooShort { .. } => {
                "lower the decrement of `L` (the number in `L=base(decrement)`) so stems keep a length at that order"
            }
            Misfit::TooThin { .. } => {
                "lower the decrement of `B` (the number in `B=base(decrement)`) so stems keep a width at that order"
            }
            Misfit::Depth { .. } => "raise `--max-depth`",
            Misfit::StemLimit { .. } => "raise `--max-stems`",
        }
    }
}

/// A distance for a message: at most three decimals, trailing zeros cut.
fn num(x: f64) -> String {
    fixed(x, 3, Trim::Zeros)
}

impl fmt::Display for Misfit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Misfit::Outside { stem } => write!(
                f,
                "stem {stem} would leave the layout (or come closer to the outline than half its width)"
            ),
            Misfit::TooClose {
                stem,
                kin,
                other,
                found,
                needed,
                clearance,
            } => {
                let whose = match (kin, other) {
                    (Kin::Sibling, Some(o)) => {
                        format!("stem {o}, its sibling (both start at one point)")
                    }
                    (Kin::Sibling, None) => {
                        "a sibling stem already there (both start at one point)".into()
                    }
                    (Kin::Parent, Some(o)) => format!("stem {o}, the stem it starts from"),
                    (Kin::Parent, None) => "its parent, the stem it starts from".into(),
                    (Kin::Other, Some(o)) => format!("stem {o}"),
                    (Kin::Other, None) => "a stem already there".into(),
                };
                write!(
                    f,
                    "stem {stem} came within {} of {whose}, where {} is needed (between centre lines: C={} plus half of each stem's width)",
                    num(found),
                    num(needed),
                    num(clearance)
                )
            }
            Misfit::TooShort { order, length } => write!(
                f,
                "its stems would be {} long at order {order} (`L` decremented to nothing)",
                num(length)
            ),
            Misfit::TooThin { order, width } => write!(
                f,
                "its stems would be {} wide at order {order} (`B` decremented to nothing)",
                num(width)
            ),
            Misfit::Depth { limit } => write!(f, "it was deeper than the depth limit of {limit}"),
            Misfit::StemLimit { limit } => {
                write!(f, "it would have passed the stem limit of {limit}")
            }
        }
    }
}

/// A root as written: `(x, y)`, or `(x, y, z)` in 3D.
fn point(x: f64, y: f64, z: Option<f64>) -> String {
    match z {
        Some(z) => format!("({x}, {y}, {z})"),
        None => format!("({x}, {y})"),
    }
}
