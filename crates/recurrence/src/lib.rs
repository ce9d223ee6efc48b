//! Exact linear recurrences `x_s = M x_(s-1)` over square integer matrices.
//!
//! This crate knows nothing of meshes, files or printing to a terminal: it takes an integer
//! matrix with optional component names and answers exactly.
//!
//! - [`Recurrence::state_at`] computes `M^s x0` for any `s: u64` with big integers by
//!   exponentiation by squaring; [`Recurrence::state_at_i128`] is a checked fast path that
//!   reports overflow instead of wrapping.
//!
//! # Example: the icosahedron under 4:1 subdivision
//!
//! ```
//! use num_bigint::BigInt;
//! use recurrence::{IntMatrix, Recurrence};
//!
//! let m: IntMatrix = "[[1, 1, 0], [0, 2, 3], [0, 0, 4]]".parse()?;
//! let r = Recurrence::with_names(m, ["V", "E", "F"])?;
//! let x0 = [12, 30, 20].map(BigInt::from);
//! assert_eq!(r.state_at(&x0, 3)?, [642, 1920, 1280].map(BigInt::from));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![deny(missing_docs)]

mod closed_form;
mod eigen;
mod error;
mod field;
mod matrix;
mod poly;
mod power;
mod query;
mod recurrence;
mod render;
mod summary;

pub use crate::closed_form::{ClosedForm, Coefficient, ComponentForm, EarlyLevel, Term};
pub use crate::eigen::{Eigenvalue, EigenvalueInfo};
pub use crate::error::{Error, Result};
pub use crate::field::QuadraticSurd;
pub use crate::matrix::{IntMatrix, ParseMatrixError};
pub use crate::poly::Polynomial;
pub use crate::power::CheckedRing;
pub use crate::query::LevelBound;
pub use crate::recurrence::Recurrence;
pub use crate::summary::{digit_summary, DigitSummary};
