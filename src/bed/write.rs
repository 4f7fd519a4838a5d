//! The canonical BED writer: deterministic, diff-friendly text.

use crate::syntax::ast::Description;

/// Writes `desc` as a `.bed` file: header, rules, one seed term per line
/// indented by depth, fixed decimals, LF line ends, trailing newline.
pub fn write(desc: &Description) -> String {
    let _ = desc;
    unimplemented!("issue 3")
}
