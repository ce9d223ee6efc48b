//! Mesh statistics ([`schemes::MeshCounts`]).
