//! The error type of the `halfedge` crate.

/// A `Result` whose error defaults to this crate's [`Error`].
pub type Result<T = (), E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong loading, validating or subdividing a mesh.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {}
