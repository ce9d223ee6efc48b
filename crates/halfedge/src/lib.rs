//! Half-edge meshes: OBJ in and out, statistics, real subdivision.
#![deny(missing_docs)]
