//! Integration tests of the `halfedge` crate (one test binary; see STYLE.md section 7).

mod base_faces;
mod creases;
mod descriptor;
mod holes;
mod invalid_obj;
mod oneshot_hashes;
mod ply;
mod properties;
mod roundtrip;
mod shared_meshes;
mod tags;
mod uv_counts;
mod uv_dual;
mod uv_io;
mod uv_memory;
mod uv_polygons;
mod uv_refine;
mod uv_sqrt3;
