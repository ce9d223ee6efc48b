//! Refine once, evaluate many.

pub(crate) mod data;

pub use data::Scalar;
