//! Syntax: text to typed trees, for all three input kinds.
//!
//! One pest grammar (`grammar.pest` at the crate root) reads classic
//! L-systems (`.lsys`), Outline Descriptions (`.od`) and Branch-Expansion
//! Descriptions (`.bed`). Every failure is a [`Diagnostic`] with a byte span.
//!
//! - [`lsys`]: `.lsys` files into [`LSystem`](crate::model::lsys::LSystem).
//! - [`stl`]: `.od`/`.bed` files into
//!   [`Description`](crate::model::Description), names resolved.
//! - `grammar`: the generated parser (crate-private) and the one description
//!   of its rules that pest's reports are worded with.
//!
//! Before pest sees any text, [`precheck`] enforces the input size and the
//! nesting limit, so no input can drive the recursive-descent parser into a
//! stack overflow.

mod grammar;
pub mod lsys;
pub mod stl;

use crate::diag::{Diagnostic, Diagnostics, InputError};
use crate::limits::{Bound, Limits};

pub(crate) use grammar::{GrammarParser, Rule, pest_error};

/// The three kinds of input (also the values of `--from`: the doc
/// comments of the variants are its help).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum InputKind {
    /// Outline Description.
    Od,
    /// Branch-Expansion Description.
    Bed,
    /// Classic L-system.
    Lsys,
}

impl InputKind {
    /// The kind a file name's extension names, if any.
    pub fn from_path(path: &std::path::Path) -> Option<InputKind> {
        match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
            "od" => Some(InputKind::Od),
            "bed" => Some(InputKind::Bed),
            "lsys" | "ls" => Some(InputKind::Lsys),
            _ => None,
        }
    }

    /// The usual extension.
    pub fn extension(self) -> &'static str {
        match self {
            InputKind::Od => "od",
            InputKind::Bed => "bed",
            InputKind::Lsys => "lsys",
        }
    }
}

/// The largest input any `--max-input` allows: positions in the text are
/// stored in 32 bits (a seed's terms take 20 bytes each that way, not 56).
pub const MAX_INPUT_CEILING: u64 = u32::MAX as u64;

/// Checks raw input before parsing: size, UTF-8, and bracket nesting depth.
/// Returns the text.
pub fn precheck<'a>(bytes: &'a [u8], limits: &Limits) -> Result<&'a str, Diagnostics> {
    let limit = limits.max_input_bytes.min(MAX_INPUT_CEILING);
    if bytes.len() as u64 > limit {
        return Err(Diagnostic::error(InputError::InputTooLarge {
            size: bytes.len() as u64,
            limit,
        })
        .with_help(Bound::InputBytes.raise() + " (at most 4 GiB)")
        .into());
    }
    let text = match std::str::from_utf8(bytes) {
        Ok(t) => t,
        Err(e) => {
            let at = e.valid_up_to();
            return Err(Diagnostic::error(InputError::NotUtf8(at))
                .with_span(at..at)
                .with_help("stlc reads UTF-8 text files; is this the right file?")
                .into());
        }
    };
    let mut depth = 0usize;
    let mut in_comment = false;
    for (i, c) in text.char_indices() {
        match c {
            '\n' => in_comment = false,
            _ if in_comment => {}
            // `#rrggbb` colours are not comments.
            '#' if !is_colour_at(text, i) => in_comment = true,
            '[' | '{' | '(' => {
                depth += 1;
                if depth > limits.max_nesting {
                    return Err(Diagnostic::error(InputError::NestingTooDeep {
                        limit: limits.max_nesting,
                    })
                    .with_span(i..i + 1)
                    .with_label("this bracket is nested too deep")
                    .with_help(Bound::Nesting.raise())
                    .into());
                }
            }
            ']' | '}' | ')' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    Ok(text)
}

/// The error for a colour name no colour has, at `span`, with `help`.
pub(crate) fn unknown_colour(text: &str, span: crate::diag::Span, help: String) -> Diagnostic {
    Diagnostic::error(InputError::UnknownColour {
        text: text.to_string(),
    })
    .with_span(span)
    .with_label("not a colour")
    .with_help(help)
}

/// Whether the `#` at byte `i` starts a `#rgb`/`#rrggbb` colour.
pub fn is_colour_at(text: &str, i: usize) -> bool {
    let rest = &text[i + 1..];
    let n = rest.bytes().take_while(u8::is_ascii_hexdigit).count();
    let next = rest.as_bytes().get(n).copied();
    (n == 6 || n == 3) && !matches!(next, Some(b) if b.is_ascii_alphanumeric() || b == b'_')
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::ErrorKind;

    #[test]
    fn nesting_beyond_the_limit_is_refused_before_parsing() {
        let limits = Limits {
            max_nesting: 3,
            ..Limits::default()
        };
        assert!(precheck(b"[[[F]]]", &limits).is_ok());
        let err = precheck(b"[[[[F]]]]", &limits).unwrap_err();
        assert_eq!(
            err.first_kind(),
            Some(&ErrorKind::Input(InputError::NestingTooDeep { limit: 3 }))
        );
        assert_eq!(err.0[0].span, Some(3..4));
    }

    #[test]
    fn colours_are_not_comments() {
        let limits = Limits {
            max_nesting: 1,
            ..Limits::default()
        };
        // `#00ff00` is a colour, so the brackets after it count.
        assert!(precheck(b"(#00ff00) [[", &limits).is_err());
        // a comment hides brackets
        assert!(precheck(b"# [[[[\nF", &limits).is_ok());
    }

    #[test]
    fn invalid_utf8_is_reported_with_its_offset() {
        let err = precheck(b"ab\xffcd", &Limits::default()).unwrap_err();
        assert_eq!(
            err.first_kind(),
            Some(&ErrorKind::Input(InputError::NotUtf8(2)))
        );
    }
}
