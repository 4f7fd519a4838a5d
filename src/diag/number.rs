//! Numbers in messages: long ones shortened, plurals.

/// Numbers longer than this many digits are shown shortened.
pub const SHOWN_DIGITS: usize = 30;

/// A decimal number as a person reads it: whole up to [`SHOWN_DIGITS`]
/// digits; longer ones (a word length at depth 10,000 has thousands) as
/// their leading digits and their digit count, `1995063116... (3011
/// digits)`. Anything that is not a plain run of digits is shown as it is.
pub fn short_number(value: &str) -> std::borrow::Cow<'_, str> {
    let digits = value.trim_start_matches("more than ");
    if digits.len() <= SHOWN_DIGITS || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return std::borrow::Cow::Borrowed(value);
    }
    let prefix = &value[..value.len() - digits.len()];
    std::borrow::Cow::Owned(format!(
        "{prefix}{}... ({} digits)",
        &digits[..10],
        digits.len()
    ))
}

/// A count computed with saturating arithmetic, as a person reads it:
/// the number, or `more than 18446744073709551614` where it saturated at
/// `u64::MAX` (the true value is that or more).
pub fn saturated(n: u64) -> String {
    if n == u64::MAX {
        format!("more than {}", u64::MAX - 1)
    } else {
        n.to_string()
    }
}

/// `suffix` unless `n` is 1: `format!("{n} shape{}", plural(n, "s"))`.
pub(crate) fn plural(n: usize, suffix: &str) -> &str {
    if n == 1 { "" } else { suffix }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::ErrorKind;

    #[test]
    fn long_numbers_are_shown_shortened_with_their_digit_count() {
        assert_eq!(short_number("12345"), "12345");
        let thirty = "1".repeat(30);
        assert_eq!(short_number(&thirty), thirty.as_str());
        let long = format!("1995063116{}", "8".repeat(3001));
        assert_eq!(short_number(&long), "1995063116... (3011 digits)");
        let more = format!("more than {}", "9".repeat(40));
        assert_eq!(short_number(&more), "more than 9999999999... (40 digits)");
        assert_eq!(saturated(12), "12");
        assert_eq!(saturated(u64::MAX - 1), "18446744073709551614");
        assert_eq!(saturated(u64::MAX), "more than 18446744073709551614");
        assert_eq!(short_number("not a number"), "not a number");
        let d = ErrorKind::Limit {
            bound: crate::diag::Bound::Symbols,
            what: Some("derived word length".into()),
            value: long,
            limit: 20_000_000_000,
        };
        assert_eq!(
            d.to_string(),
            "derived word length: 1995063116... (3011 digits) exceeds the limit of 20000000000"
        );
    }
}
