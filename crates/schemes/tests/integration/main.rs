//! Integration tests of the `schemes` crate (one test binary, one module per topic).

mod builtins;
mod custom;
mod fit;
mod input;
mod meshes;
mod plan;
mod props;
mod real_meshes;
