//! What a new file (`stlc serve new.od`, not there yet) starts from.

/// A new Outline Description.
pub const OD: &str = include_str!("new.od");
/// A new Branch-Expansion Description: the paper's worked example.
pub const BED: &str = include_str!("../../../examples/paper-worked.bed");
/// A new L-system.
pub const LSYS: &str = include_str!("new.lsys");
