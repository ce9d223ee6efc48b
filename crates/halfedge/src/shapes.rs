//! Base meshes generated in code.
