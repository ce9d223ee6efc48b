//! Shared helpers for subcount's cross-crate integration tests.
