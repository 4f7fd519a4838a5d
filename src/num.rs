//! Numbers: parameters that decrease linearly with the stem order, and the
//! one formatter of fixed-decimal text.
//!
//! Every number stlc writes (BED files, SVG coordinates, `stats` output)
//! goes through [`fixed`]: a fixed number of decimals, never `-0`, so output
//! is byte-identical across runs and platforms. A BED's root and stem
//! parameters go through [`exact`]: the same, unless rounding would change
//! the number, which must then read back bit for bit.

/// `base - order * decrement`: a stem's length (`L(dL)`) or width (`B(dB)`)
/// at a rule-application order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Linear {
    /// The value at order 0.
    pub base: f64,
    /// Decrease per order.
    pub decrement: f64,
}

impl Linear {
    /// `base` at every order.
    pub const fn constant(base: f64) -> Self {
        Linear {
            base,
            decrement: 0.0,
        }
    }

    /// `base` decreasing by `decrement` per order.
    pub const fn new(base: f64, decrement: f64) -> Self {
        Linear { base, decrement }
    }

    /// The value at `order`.
    #[inline]
    pub fn at(&self, order: u32) -> f64 {
        self.base - f64::from(order) * self.decrement
    }
}

/// How [`fixed`] ends a number.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Trim {
    /// Always `decimals` digits after the point (`2.50`).
    Keep,
    /// Trailing zeros and a bare point removed (`2.5`, `10`).
    Zeros,
}

/// `x` with `decimals` digits after the point, rounded, never `-0` (a
/// negative number that rounds to zero is written without its sign).
pub fn fixed(x: f64, decimals: usize, trim: Trim) -> String {
    let mut s = String::new();
    push_fixed(&mut s, x, decimals, trim);
    s
}

/// [`fixed`], appended to `buf` (no allocation on the hot path of the SVG
/// writer).
pub fn push_fixed(buf: &mut String, x: f64, decimals: usize, trim: Trim) {
    use std::fmt::Write as _;
    let start = buf.len();
    let _ = write!(buf, "{x:.decimals$}");
    if trim == Trim::Zeros && buf[start..].contains('.') {
        let kept = buf.trim_end_matches('0').trim_end_matches('.').len();
        buf.truncate(kept);
    }
    if buf.as_bytes().get(start) == Some(&b'-')
        && buf[start + 1..].bytes().all(|b| b == b'0' || b == b'.')
    {
        buf.remove(start);
    }
}

/// `x` as [`fixed`] with `decimals` decimals (trimmed) when that reads
/// back as exactly `x`, else the shortest decimal that does (Rust's
/// `Display` of `f64`: round-trip exact, never an exponent, the same on
/// every platform). For numbers a reader must get back bit for bit: a
/// BED's root and stem parameters, which decide what the tree draws and
/// whether an order still has positive length and width.
pub fn exact(x: f64, decimals: usize) -> String {
    let short = fixed(x, decimals, Trim::Zeros);
    if !x.is_finite() || short.parse::<f64>() == Ok(x) {
        short
    } else {
        // Not zero (zero reads back): no `-0` to avoid.
        format!("{x}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_numbers_are_fixed_when_fixed_reads_back() {
        assert_eq!(exact(0.35, 3), "0.35");
        assert_eq!(exact(10.0, 3), "10");
        assert_eq!(exact(-0.0, 3), "0");
        assert_eq!(exact(1.0 / 3.0, 3), "0.3333333333333333");
        assert_eq!(exact(0.999999999926, 3), "0.999999999926");
        assert_eq!(exact(1e-7, 3), "0.0000001");
        for x in [0.1 + 0.2, 1.0 / 3.0, 123.456789, 1e-300, 12345678.9] {
            assert_eq!(exact(x, 3).parse::<f64>(), Ok(x), "{x}");
        }
    }

    #[test]
    fn linear_values_by_order() {
        let l = Linear::new(10.0, 1.5);
        assert_eq!(l.at(0), 10.0);
        assert_eq!(l.at(2), 7.0);
        assert_eq!(Linear::constant(3.0).at(1000), 3.0);
    }

    #[test]
    fn fixed_decimals_trimmed_or_kept_and_never_negative_zero() {
        assert_eq!(fixed(10.0, 3, Trim::Zeros), "10");
        assert_eq!(fixed(2.5, 3, Trim::Zeros), "2.5");
        assert_eq!(fixed(1.0 / 3.0, 3, Trim::Zeros), "0.333");
        assert_eq!(fixed(-0.0001, 3, Trim::Zeros), "0");
        assert_eq!(fixed(-0.0, 3, Trim::Zeros), "0");
        assert_eq!(fixed(12.345, 3, Trim::Zeros), "12.345");
        assert_eq!(fixed(-2.5, 3, Trim::Zeros), "-2.5");
        assert_eq!(fixed(2.5, 2, Trim::Keep), "2.50");
        assert_eq!(fixed(-0.001, 2, Trim::Keep), "0.00");
        assert_eq!(fixed(-0.0, 6, Trim::Keep), "0.000000");
        assert_eq!(fixed(-1.25, 2, Trim::Keep), "-1.25");
        let mut buf = String::from("M");
        push_fixed(&mut buf, -0.004, 2, Trim::Keep);
        assert_eq!(buf, "M0.00");
    }
}
