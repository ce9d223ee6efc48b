//! Exact linear recurrences `x_s = M x_(s-1)` over square integer matrices.
//!
//! This crate knows nothing of meshes, files or printing to a terminal: it takes an integer
//! matrix with optional component names and answers exactly.
//!
//! - **Counts**: [`Recurrence::state_at`] computes `M^s x0` for any `s: u64` with big
//!   integers by exponentiation by squaring; [`Recurrence::state_at_i128`] is a checked fast
//!   path that reports overflow instead of wrapping.
//! - **Spectrum**: [`Recurrence::characteristic_polynomial`] (exact, integer coefficients)
//!   and [`Recurrence::eigenvalues`] with multiplicities: integers and quadratic surds
//!   exactly, anything else numerically and labelled so ([`Eigenvalue`]).
//! - **Closed forms**: [`Recurrence::closed_form`] gives each component as
//!   `sum p_l(s) l^s` from the spectral decomposition (Jordan blocks included, zero
//!   eigenvalues handled with an explicit `valid_from` and early levels), exact over `Q` or
//!   `Q(sqrt d)`. [`ClosedForm::evaluate`] agrees with powering at every level and turns
//!   powers of two into shifts; [`ClosedForm::summary_at`] gives the digit count, leading and
//!   trailing digits at levels like `10^12` without computing the number.
//! - **Display**: [`ClosedForm::to_text`], [`ClosedForm::to_latex`], [`ClosedForm::to_rust`]
//!   (a compilable checked-`i128` function) and, with the `json` feature, `ClosedForm::to_json`.
//! - **Growth**: [`Recurrence::dominant_eigenvalue`], and
//!   [`ClosedForm::estimated_bits`] for the size of a count before computing it.
//! - **Matrices**: [`Matrix`] is the one dense matrix type ([`IntMatrix`] is `Matrix<i64>`),
//!   with products, matrix-vector products and powers written once over `num_traits`
//!   bounds ([`Matrix::checked_mul`], [`Matrix::checked_apply`], [`Matrix::checked_pow`]):
//!   `i64`/`i128` report overflow, `BigInt` never does.
//!
//! The public API names no dependency's type besides `num-bigint` and `num-rational`
//! (numeric values are [`Complex64`]); the `json` feature adds `ClosedForm::to_json`, which
//! returns a `serde_json::Value`.
//!
//! # Example: the icosahedron under 4:1 subdivision
//!
//! In the paper's (V, E) form, every edge gains a vertex and every triangle becomes four, so
//! `V' = V + E` and `E' = 4E`. From the icosahedron (12 vertices, 30 edges):
//!
//! ```
//! use num_bigint::BigInt;
//! use recurrence::{IntMatrix, Recurrence};
//!
//! let m: IntMatrix = "[[1, 1], [0, 4]]".parse()?;
//! let r = Recurrence::with_names(m, ["V", "E"])?;
//! let x0 = [12, 30].map(BigInt::from);
//! let v: Vec<BigInt> = (0..4).map(|s| r.state_at(&x0, s).map(|x| x[0].clone())).collect::<Result<_, _>>()?;
//! assert_eq!(v, [12, 42, 162, 642].map(BigInt::from));
//!
//! let form = r.closed_form();
//! assert_eq!(form.to_text(), "V(s) = V0 + (4^s - 1)/3 * E0\nE(s) = 4^s * E0");
//! println!("{}", form.to_text()); // V(s) = V0 + (4^s - 1)/3 * E0
//! assert_eq!(form.evaluate(&x0, 1000)?, r.state_at(&x0, 1000)?);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Example: the (V, E, F) form and a huge level
//!
//! ```
//! use num_bigint::BigInt;
//! use recurrence::{IntMatrix, Recurrence};
//!
//! let m: IntMatrix = "[[1, 1, 0], [0, 2, 3], [0, 0, 4]]".parse()?;
//! let r = Recurrence::with_names(m, ["V", "E", "F"])?;
//! let x0 = [12, 30, 20].map(BigInt::from);
//! assert_eq!(r.state_at(&x0, 3)?, [642, 1920, 1280].map(BigInt::from));
//! let at = r.closed_form().summary_at(&x0, 1_000_000_000_000, 20)?;
//! assert_eq!(at[2].digits, 602_059_991_330); // F = 20 * 4^(10^12)
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![deny(missing_docs)]

mod closed_form;
mod complex;
mod eigen;
mod error;
mod field;
#[cfg(feature = "json")]
mod json;
mod matrix;
mod poly;
mod power;
mod recurrence;
mod render;
mod summary;

pub use crate::closed_form::{ClosedForm, Coefficient, ComponentForm, EarlyLevel, Term};
pub use crate::complex::Complex64;
pub use crate::eigen::{Eigenvalue, EigenvalueInfo};
pub use crate::error::{Error, Result};
pub use crate::field::QuadraticSurd;
pub use crate::matrix::{IntMatrix, Matrix, ParseMatrixError};
pub use crate::poly::Polynomial;
pub use crate::power::CheckedRing;
pub use crate::recurrence::Recurrence;
pub use crate::summary::{digit_summary, DigitSummary};
