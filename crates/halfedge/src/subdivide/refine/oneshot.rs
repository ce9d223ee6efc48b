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

use schemes::{LevelCounts, MeshCounts};

use super::creases::Creases;
use super::levels::{invalid, Retain};
use super::{direct, plan_sizes, Refinement};
use crate::holes::HoleSet;
use crate::subdivide::{sizes, Plan, Rule, SubdivideOptions};
use crate::{Error, HalfEdgeMesh, PolygonMesh, Result};

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

/// The last level of [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list): the subdivided mesh as a face list.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct FaceListLevel {
    /// Positions and faces, numbered exactly as [`HalfEdgeMesh::to_polygon_mesh`] numbers the
    /// mesh [`subdivide`](crate::subdivide::subdivide) returns (same vertices, faces in the same order, each face from the
    /// same corner).
    pub mesh: PolygonMesh,
    /// The number of edges of the level: counted by the construction from the half-edge mesh
    /// of the level before (4:1: `2E + 3F`; Catmull-Clark: `2E` plus one per face corner), or
    /// read off the half-edge mesh for the schemes built that way. With holes
    /// ([`SubdivideOptions::holes`]) the written edges as predicted (the written vertices and
    /// faces are checked against the prediction).
    pub edges: usize,
    /// With [`SubdivideOptions::base_faces`], the base face each face comes from (OpenSubdiv's
    /// `GetFaceParentFace` chained to level 0): nesting splits give their children their
    /// parent's, and a face that comes from several faces (√3's flipped triangles, Doo-Sabin's
    /// and mid-edge's edge and vertex faces) takes the lowest-numbered base face
    /// ([`Refinement::base_faces`](crate::Refinement::base_faces) gives the same); holes left
    /// out as the faces are.
    pub base_faces: Option<Vec<u32>>,
}

impl FaceListLevel {
    /// Gives the level's faces the groups of their base faces ([`FaceGroups::of_base_faces`]
    /// of `groups`, those of the subdivided mesh's faces), taking
    /// [`base_faces`](Self::base_faces) (the level must have them:
    /// [`SubdivideOptions::base_faces`]).
    ///
    /// # Errors
    ///
    /// [`Error::InvalidOutput`] without base faces, or with groups of another mesh.
    ///
    /// [`FaceGroups::of_base_faces`]: crate::groups::FaceGroups::of_base_faces
    pub fn carry_groups(&mut self, groups: &crate::groups::FaceGroups) -> Result<()> {
        let invalid = |what: String| Error::InvalidOutput {
            scheme: "groups".into(),
            level: 0,
            what,
        };
        let base = self
            .base_faces
            .take()
            .ok_or_else(|| invalid("no base faces".into()))?;
        let groups = groups
            .of_base_faces(base)
            .map_err(|e| invalid(e.to_string()))?;
        self.mesh
            .set_groups(Some(groups))
            .map_err(|e| invalid(e.to_string()))
    }
}

/// `Some(d)` when [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list) writes the last level of `rule` straight into a
/// face list, every face with `d` corners (the 4:1 family: 3; Catmull-Clark: 4); `None` for
/// the rules whose last level is built as a half-edge mesh and converted.
///
/// ```
/// use halfedge::subdivide::{direct_face_degree, Rule};
/// assert_eq!(direct_face_degree(Rule::Loop), Some(3));
/// assert_eq!(direct_face_degree(Rule::Butterfly), Some(3));
/// assert_eq!(direct_face_degree(Rule::CatmullClark), Some(4));
/// assert_eq!(direct_face_degree(Rule::Sqrt3), None);
/// assert_eq!(direct_face_degree(Rule::TriSplit(3)), None);
/// ```
pub fn direct_face_degree(rule: Rule) -> Option<usize> {
    match rule {
        Rule::Loop | Rule::Midpoint | Rule::Butterfly | Rule::Icosphere | Rule::TriSplit(2) => {
            Some(3)
        }
        Rule::CatmullClark => Some(4),
        _ => None,
    }
}

/// What `plan` writes at `levels` of a mesh whose written faces have the counts `written`,
/// checked to fit before anything is built (the last level's vertex indices fit `u32`).
pub(crate) fn written_prediction(
    plan: &Plan,
    written: &MeshCounts,
    levels: u32,
) -> Result<LevelCounts> {
    let c = HoleSet::written_level(plan.rule, written, levels)?;
    sizes(&c, &plan.name, levels, false)?;
    Ok(c)
}

/// The written part of the last level `mesh` and of its base faces (numbered as
/// [`subdivide`](crate::subdivide::subdivide) numbers it: the children of a face contiguous, in the order of their
/// parents), checked against the prediction; its `edges` are the predicted ones.
pub(crate) fn keep_written(
    (mesh, base_faces): (PolygonMesh, Option<Vec<u32>>),
    holes: &HoleSet,
    degrees: &[usize],
    plan: &Plan,
    levels: u32,
    predicted: &LevelCounts,
) -> Result<FaceListLevel> {
    let mask = holes.written_at(plan.rule, degrees, levels)?;
    if mask.len() != mesh.n_faces() {
        return Err(Error::InvalidOutput {
            scheme: plan.name.clone(),
            level: levels,
            what: format!(
                "{} faces where the holes' descendants were counted on {}",
                mesh.n_faces(),
                mask.len()
            ),
        });
    }
    let base_faces = base_faces.map(|faces| {
        let mut keep = mask.iter();
        let mut faces = faces;
        faces.retain(|_| keep.next().copied().unwrap_or(false));
        faces
    });
    let mesh = crate::holes::written_part(mesh, &mask)?;
    crate::holes::check_written(
        &plan.name,
        levels,
        predicted,
        mesh.n_vertices(),
        mesh.n_faces(),
    )?;
    let edges = usize::try_from(&predicted.edges).map_err(|_| Error::TooLarge {
        scheme: plan.name.clone(),
        level: levels,
        what: "edges",
        count: predicted.edges.clone(),
    })?;
    Ok(FaceListLevel {
        mesh,
        edges,
        base_faces,
    })
}
