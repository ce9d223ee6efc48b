//! The built-in scheme names on top of the typed API, the way `subcount subdivide --scheme
//! NAME` uses them: the scheme accepts the mesh first (`checked_rule`: `catmull-clark-quad`
//! refuses a triangle, `sqrt3` a boundary), then its rule runs. Shared by the test binaries
//! that sweep every name.
#![allow(dead_code)]

use halfedge::schemes::{builtin, MeshCounts};
use halfedge::subdivide::{self as sub, FaceListLevel, LevelReport, Rule, SubdivideOptions};
use halfedge::{stats, HalfEdgeMesh, PolygonMesh, Result};

/// The rule of the built-in `name` on a mesh with `counts`, once the scheme accepts it.
pub(crate) fn rule_for(name: &str, counts: &MeshCounts) -> Result<Rule> {
    sub::checked_rule(&builtin(name)?, counts)
}

pub(crate) fn subdivide(
    mesh: &HalfEdgeMesh,
    name: &str,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<HalfEdgeMesh> {
    sub::subdivide(mesh, rule_for(name, &mesh.counts())?, levels, opts)
}

pub(crate) fn subdivide_to_face_list(
    mesh: &HalfEdgeMesh,
    name: &str,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<FaceListLevel> {
    sub::subdivide_to_face_list(mesh, rule_for(name, &mesh.counts())?, levels, opts)
}

pub(crate) fn subdivide_polygons(
    mesh: &PolygonMesh,
    name: &str,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<PolygonMesh> {
    let rule = rule_for(name, &stats::face_list_counts(mesh))?;
    sub::subdivide_polygons(mesh, rule, levels, opts)
}

pub(crate) fn verify(
    mesh: &HalfEdgeMesh,
    name: &str,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<Vec<LevelReport>> {
    sub::verify(mesh, &builtin(name)?, levels, opts)
}

pub(crate) fn verify_polygons(
    mesh: &PolygonMesh,
    name: &str,
    levels: u32,
    opts: &SubdivideOptions<'_>,
) -> Result<Vec<LevelReport>> {
    sub::verify_polygons(mesh, &builtin(name)?, levels, opts)
}

/// [`sub::direct_face_degree`] of the built-in `name`'s rule.
pub(crate) fn direct_face_degree(name: &str) -> Option<usize> {
    builtin(name)
        .ok()
        .and_then(|s| s.subdivision_rule())
        .and_then(sub::direct_face_degree)
}
