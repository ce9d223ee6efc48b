//! Integration tests of the `schemes` crate (one test binary, one module per topic).

mod builtins;
mod custom;
mod meshes;
