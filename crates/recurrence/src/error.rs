//! The error type of the `recurrence` crate.

/// A `Result` whose error defaults to this crate's [`Error`].
pub type Result<T = (), E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong when building or using a recurrence.
///
/// All variants describe bad input; none of them is a bug in this crate.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The matrix has no rows.
    #[error("the matrix is empty")]
    EmptyMatrix,
    /// A row of the matrix does not have as many entries as the matrix has rows.
    #[error("row {row} of the matrix has {len} entries, expected {expected} (the matrix must be square)")]
    NotSquare {
        /// Zero-based index of the offending row.
        row: usize,
        /// Number of entries in that row.
        len: usize,
        /// Number of rows of the matrix.
        expected: usize,
    },
    /// The number of component names differs from the dimension of the matrix.
    #[error("{names} component names given for a {dim}x{dim} matrix")]
    NamesMismatch {
        /// Number of names given.
        names: usize,
        /// Dimension of the matrix.
        dim: usize,
    },
    /// Two components have the same name.
    #[error("component name `{name}` is used twice")]
    DuplicateName {
        /// The repeated name.
        name: String,
    },
    /// A component name is empty or contains characters that cannot appear in a formula.
    #[error("component name `{name}` is not valid (use letters, digits and `_`, starting with a letter)")]
    InvalidName {
        /// The rejected name.
        name: String,
    },
    /// The initial state vector does not have one entry per component.
    #[error("the initial state has {got} values, expected {expected}")]
    InitialLength {
        /// Number of values given.
        got: usize,
        /// Dimension of the recurrence.
        expected: usize,
    },
    /// A checked fixed-width computation overflowed.
    #[error("the counts at level {level} do not fit in {width}")]
    Overflow {
        /// The requested level.
        level: u64,
        /// The integer type that overflowed, e.g. `i128`.
        width: &'static str,
    },
    /// Exact evaluation was asked of a closed form that is only numeric for a component.
    #[error("the closed form of component `{component}` is numeric (eigenvalues outside Q and Q(sqrt d)); use powering for exact counts")]
    NotExact {
        /// The component whose form is numeric.
        component: String,
    },
    /// A number is too large to be computed in memory.
    #[error("level {level} needs about {bits} bits per count, more than this machine can hold")]
    TooLarge {
        /// The requested level.
        level: u64,
        /// Estimated size of the largest count, in bits.
        bits: u64,
    },
    /// The numeric terms of a closed form miss the exact count
    /// ([`ClosedForm::verify`](crate::ClosedForm::verify)).
    #[error("the closed form of component `{component}` cannot be given: its numeric eigenvalues miss the exact count at level {level} (the characteristic polynomial is too ill-conditioned for floating point); use `at` or `table` for exact counts (they power the matrix)")]
    InaccurateClosedForm {
        /// The first component whose numeric terms fail.
        component: String,
        /// The first level at which they fail.
        level: u64,
    },
    /// A digit count does not fit in the `u64` of a
    /// [`DigitSummary`](crate::DigitSummary).
    #[error("the count `{component}` at level {level} has more than 2^64 decimal digits, more than a digit summary can state")]
    DigitsOverflow {
        /// The component whose count it is.
        component: String,
        /// The requested level.
        level: u64,
    },
    /// Computing the closed form would cost more than the caller allowed
    /// ([`Recurrence::closed_form_cost`](crate::Recurrence::closed_form_cost)).
    #[error("the closed form of this {dim}x{dim} matrix would cost about {cost} work units, more than the limit of {limit}")]
    ClosedFormTooCostly {
        /// Dimension of the matrix.
        dim: usize,
        /// The estimate of [`Recurrence::closed_form_cost`](crate::Recurrence::closed_form_cost).
        cost: u64,
        /// The limit the caller gave.
        limit: u64,
    },
}
