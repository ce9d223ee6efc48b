//! The one-shot subdivision ([`subdivide`](crate::subdivide::subdivide),
//! [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list),
//! [`verify`](crate::subdivide::verify)): the refinement's one level loop
//! ([`Refinement::refine_levels`]) with the retention [`Retain::LastTwo`]. The same size
//! checks ([`plan_sizes`]), the same topology steps ([`Refinement::next_level`]), the same
//! geometry ([`Refinement::values_after`], the dispatch of the stencils) and the same index
//! buffers ([`to_faces`](super::super::to_faces), as [`Refinement::write_triangles`] writes
//! them), so that a rule changed in the refinement is changed in the one-shot subdivision.
//!
//! What the retention drops: a [`Refinement`] keeps every level's topology (it evaluates many
//! times); the one-shot subdivision evaluates once, level by level, so it keeps only the level
//! it refines (as a half-edge mesh with its positions) and the one it builds, and it does not
//! flatten levels into the rules' fast tables (their building costs more than the one
//! evaluation they would serve). The peak is levels `s - 1` and `s`.
//!
//! Under crease rules ([`SubdivideOptions::sharpness`], [`SubdivideOptions::subdivision`]:
//! the same [`Creases`] that [`Refinement::new`] builds, or none when they change nothing)
//! each level's positions come from the rule's half-edge kernels and the crease weight rows of
//! the level refined written over them (or a dense weight table of every child vertex: the
//! choice [`Refinement::new`] makes for that level, `Fast::creased`), built just before and
//! dropped before the next level's topology; the child's sharpness is then recorded from
//! the two levels ([`Creases::push_child`]) and the parent's dropped, so only the sharpness of
//! the last two levels is alive. In `f64` the positions are those of
//! [`Refinement::evaluate`] to the bit.

use schemes::MeshCounts;

use super::creases::Creases;
use super::levels::{invalid, Retain};
use super::{direct, plan_sizes, Refinement};
use crate::subdivide::{Plan, SubdivideOptions};
use crate::{HalfEdgeMesh, PolygonMesh, Result};

/// What the one-shot subdivision built.
pub(crate) enum OneShot {
    /// The last level as a half-edge mesh (a copy of the input at level 0).
    Mesh(HalfEdgeMesh),
    /// The last level written straight into a face list, with its number of edges.
    Faces(Box<PolygonMesh>, usize),
}

/// Subdivides `mesh` (with `counts`) `levels` times by `plan`: every level is checked against
/// the scheme's counts before anything is built, then built from the one before as a half-edge
/// mesh (only two alive at a time), `visit` seeing each one, the progress callback every level.
/// With `faces`, the last level of the 4:1 family and Catmull-Clark is written straight into a
/// face list (that level's edges and faces need not fit 32-bit handles, its vertex indices
/// must).
pub(crate) fn one_shot(
    plan: &Plan,
    mesh: &HalfEdgeMesh,
    counts: &MeshCounts,
    levels: u32,
    faces: bool,
    opts: &SubdivideOptions<'_>,
    mut visit: impl FnMut(u32, &HalfEdgeMesh) -> Result<()> + Send,
) -> Result<OneShot> {
    plan.scheme.initial_state(counts)?;
    crate::subdivide::check_mesh(plan, mesh)?;
    let creases = Creases::new(mesh, plan.rule, opts.sharpness, &opts.subdivision)?;
    let as_faces = faces;
    let faces = faces && direct(plan.split);
    let planned = plan_sizes(plan, counts, levels, !faces)?;
    if levels == 0 {
        // A face list asked for is the input's, without a copy of its half-edge mesh first.
        return Ok(if as_faces {
            OneShot::Faces(Box::new(mesh.to_polygon_mesh()), mesh.n_edges())
        } else {
            OneShot::Mesh(mesh.clone())
        });
    }
    let mut r = Refinement::empty(plan, counts, levels, opts.threads, None, creases)?;
    let run = || r.refine_levels(mesh, &planned, opts, Retain::LastTwo, &mut visit);
    match crate::subdivide::with_threads(opts.threads, run)? {
        Some(built) => Ok(built),
        None => Err(invalid(&plan.name, levels, "no level kept")),
    }
}
