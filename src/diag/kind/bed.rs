//! Validating a BED (`bed::Bed::new`) beyond its syntax.

/// A BED that reads but does not hold together.
/// Wrapped in [`super::ErrorKind::Bed`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BedError {
    /// A rule is applied at an order where stems would have no positive
    /// length or width (`base - order * decrement <= 0`). Numbers as the
    /// BED writer writes them.
    #[error(
        "`{rule}` is applied at order {order}, where stems have length {} and width {}",
        crate::num::fixed(*length, 3, crate::num::Trim::Zeros),
        crate::num::fixed(*width, 3, crate::num::Trim::Zeros)
    )]
    OrderTooDeep {
        /// The rule's name.
        rule: String,
        /// The order of the application.
        order: u32,
        /// Stem length at that order.
        length: f64,
        /// Stem width at that order.
        width: f64,
    },
}
