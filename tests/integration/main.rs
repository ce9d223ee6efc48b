//! Cross-crate integration tests: the closed forms of the `schemes` and `recurrence` crates
//! against the real subdivision of the `halfedge` crate.

mod corpus;
mod forms;
mod real_meshes;
mod subdivision;
