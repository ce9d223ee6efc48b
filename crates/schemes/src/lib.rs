//! Subdivision schemes declared as integer matrices.
#![deny(missing_docs)]

mod counts;

pub use crate::counts::MeshCounts;
pub use recurrence;
