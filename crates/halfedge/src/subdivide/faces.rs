//! Topology-only subdivision of raw face lists (non-manifold edges and vertices allowed): the
//! per-face refinements 1:N² (4:1 for `N = 2`) and Catmull-Clark.
//!
//! Edges are found by sorting the face sides by their (unordered) vertex pair, so an edge with
//! any number of faces gets one id and its new points are shared by all of them.
//!
//! # Numbering (used vertices `V`, renumbered in order of first use; `E` edges, numbered in
//! the order of their sorted vertex pairs; `F` faces)
//!
//! - 1:N²: old vertices, then `N - 1` points per edge (from its smaller vertex id), then the
//!   interior points of each face; faces `N² f + t`, each triangle's corners written by the
//!   split's one template (`trisplit::Template::write_corners`, on a `Frame` of the face).
//! - Catmull-Clark: old vertices, then one point per edge, then one per face; the corner `k` of
//!   face `f` becomes the quad (corner, point of side `k`, face point, point of side `k - 1`):
//!   `catmull_clark::quad_corners`.
//!
//! The splits are the half-edge levels' own, so on a manifold mesh the faces are those of the
//! half-edge subdivision, face by face from the same corner, up to the numbering of the
//! vertices (`tests/subdivide.rs`).

use glam::{DVec2, DVec3};

use super::build::StepContext;
use super::catmull_clark::quad_corners;
use super::trisplit::Frame;
use super::{sizes, LevelDone, Plan, Rule, Split, SubdivideOptions, Template};
use crate::error::FaceVertices;
use crate::mesh::INVALID;
use crate::{Error, PolygonMesh, Result};

/// A face list with dense vertex ids and its edges.
struct Indexed<'a> {
    mesh: &'a PolygonMesh,
    /// Dense id of every corner's vertex.
    corner_vertex: Vec<u32>,
    /// Edge of the side from corner `c` to the next corner of its face.
    corner_edge: Vec<u32>,
    /// The smaller dense vertex id of each edge.
    edge_low: Vec<u32>,
    /// Old positions by dense id.
    positions: Vec<DVec3>,
}

impl<'a> Indexed<'a> {
    fn new(mesh: &'a PolygonMesh) -> Result<Indexed<'a>> {
        let nv = mesh.positions.len();
        let mut dense = super::alloc::filled(INVALID, nv, "dense")?;
        let mut positions = Vec::new();
        let mut corner_vertex = super::alloc::with_capacity(mesh.n_corners(), "corner vertex")?;
        for (f, face) in mesh.faces().enumerate() {
            let face_id = u32::try_from(f).unwrap_or(u32::MAX);
            if face.len() < 3 {
                return Err(Error::FaceTooSmall {
                    face: face_id,
                    vertices: FaceVertices(face.to_vec()),
                    degree: face.len(),
                });
            }
            for (i, &v) in face.iter().enumerate() {
                if v as usize >= nv {
                    return Err(Error::VertexOutOfRange {
                        face: face_id,
                        vertices: FaceVertices(face.to_vec()),
                        vertex: v,
                        n_vertices: nv,
                    });
                }
                if face[..i].contains(&v) {
                    return Err(Error::RepeatedVertex {
                        face: face_id,
                        vertices: FaceVertices(face.to_vec()),
                        vertex: v,
                    });
                }
                let slot = &mut dense[v as usize];
                if *slot == INVALID {
                    *slot = positions.len() as u32;
                    positions.push(mesh.positions[v as usize]);
                }
                corner_vertex.push(*slot);
            }
        }
        // Sides sorted by their unordered vertex pair.
        let offsets = mesh.face_offsets();
        let mut keys: Vec<(u64, u32)> = super::alloc::with_capacity(corner_vertex.len(), "keys")?;
        for f in 0..mesh.n_faces() {
            let (start, end) = (offsets[f], offsets[f + 1]);
            for c in start..end {
                let a = corner_vertex[c];
                let b = corner_vertex[if c + 1 == end { start } else { c + 1 }];
                let key = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
                keys.push((key, c as u32));
            }
        }
        keys.sort_unstable();
        let mut corner_edge = super::alloc::filled(0u32, corner_vertex.len(), "corner edge")?;
        let mut edge_low = Vec::new();
        let mut last = u64::MAX;
        for &(key, c) in &keys {
            if key != last {
                edge_low.push((key >> 32) as u32);
                last = key;
            }
            corner_edge[c as usize] = edge_low.len() as u32 - 1;
        }
        Ok(Indexed {
            mesh,
            corner_vertex,
            corner_edge,
            edge_low,
            positions,
        })
    }
}

/// One 1:N² step on a triangle face list.
fn tri_split(
    ix: &Indexed<'_>,
    template: &Template,
    expected_vertices: usize,
    expected_faces: usize,
) -> Result<PolygonMesh> {
    let n = template.n;
    let nv = ix.positions.len() as u32;
    let ne = ix.edge_low.len() as u32;
    let mut corners = vec![0u32; 3 * template.n_triangles()];

    let mut positions = super::alloc::with_capacity(expected_vertices, "positions")?;
    positions.extend_from_slice(&ix.positions);
    // Endpoints of each edge (the first side found).
    let mut edge_high = super::alloc::filled(INVALID, ne as usize, "edge high")?;
    let offsets = ix.mesh.face_offsets();
    for f in 0..ix.mesh.n_faces() {
        let (start, end) = (offsets[f], offsets[f + 1]);
        for c in start..end {
            let a = ix.corner_vertex[c];
            let b = ix.corner_vertex[if c + 1 == end { start } else { c + 1 }];
            edge_high[ix.corner_edge[c] as usize] = a.max(b);
        }
    }
    for (&low, &high) in ix.edge_low.iter().zip(&edge_high) {
        let a = ix.positions[low as usize];
        let b = ix.positions[high as usize];
        for k in 1..n {
            positions.push(template.edge_point(a, b, k));
        }
    }
    let mut out = PolygonMesh::with_positions(Vec::new());
    super::alloc::reserve_faces(&mut out, expected_faces, 3 * expected_faces)?;
    for (f, &start) in offsets[..ix.mesh.n_faces()].iter().enumerate() {
        let vs = [
            ix.corner_vertex[start],
            ix.corner_vertex[start + 1],
            ix.corner_vertex[start + 2],
        ];
        let es = [
            ix.corner_edge[start],
            ix.corner_edge[start + 1],
            ix.corner_edge[start + 2],
        ];
        let p = vs.map(|v| ix.positions[v as usize]);
        for i in 0..template.interior_points.len() {
            positions.push(template.interior_point(p, i));
        }
        let sides = [0, 1, 2].map(|s| (es[s], vs[s] == ix.edge_low[es[s] as usize]));
        let frame = Frame {
            corners: vs,
            sides,
            face: f as u32,
        };
        template.write_corners(&frame, nv, ne, &mut corners);
        for tri in corners.chunks_exact(3) {
            out.push_face(tri);
        }
    }
    out.positions = positions;
    Ok(out)
}

/// One Catmull-Clark step (topology, linear points) on any face list.
fn catmull_clark(
    ix: &Indexed<'_>,
    expected_vertices: usize,
    expected_faces: usize,
) -> Result<PolygonMesh> {
    let nv = ix.positions.len() as u32;
    let ne = ix.edge_low.len() as u32;
    let offsets = ix.mesh.face_offsets();
    let mut positions = super::alloc::with_capacity(expected_vertices, "positions")?;
    positions.extend_from_slice(&ix.positions);
    let mut edge_mid = super::alloc::filled(DVec3::ZERO, ne as usize, "edge mid")?;
    for f in 0..ix.mesh.n_faces() {
        let (start, end) = (offsets[f], offsets[f + 1]);
        for c in start..end {
            let a = ix.positions[ix.corner_vertex[c] as usize];
            let b =
                ix.positions[ix.corner_vertex[if c + 1 == end { start } else { c + 1 }] as usize];
            edge_mid[ix.corner_edge[c] as usize] = (a + b) * 0.5;
        }
    }
    positions.extend_from_slice(&edge_mid);
    let mut out = PolygonMesh::with_positions(Vec::new());
    super::alloc::reserve_faces(&mut out, expected_faces, 4 * expected_faces)?;
    for f in 0..ix.mesh.n_faces() {
        let (start, end) = (offsets[f], offsets[f + 1]);
        let mut centroid = DVec3::ZERO;
        for c in start..end {
            centroid += ix.positions[ix.corner_vertex[c] as usize];
            let prev = if c == start { end - 1 } else { c - 1 };
            let (v, side, before) = (ix.corner_vertex[c], ix.corner_edge[c], ix.corner_edge[prev]);
            out.push_face(&quad_corners(nv, ne, f as u32, v, side, before));
        }
        positions.push(centroid / (end - start) as f64);
    }
    out.positions = positions;
    Ok(out)
}

/// The level loop for face lists; `visit(level, mesh)` sees every level built.
pub(super) fn run_levels(
    plan: &Plan,
    mesh: &PolygonMesh,
    levels: u32,
    opts: &SubdivideOptions<'_>,
    mut visit: impl FnMut(u32, &PolygonMesh) -> Result<()>,
) -> Result<PolygonMesh> {
    let name = plan.name.as_str();
    let template = match plan.split {
        Split::Tri(n) => Some(n),
        Split::Quad => None,
        _ => {
            return Err(Error::NoSubdivision {
                scheme: name.to_owned(),
                reason: "on a raw face list only the rules that refine each face on its own run \
                         (the 4:1 family, tri-split-N, catmull-clark)"
                    .into(),
            })
        }
    };
    // Validates the corners before counting.
    let first = Indexed::new(mesh)?;
    let counts = crate::stats::face_list_counts(mesh);
    plan.scheme.initial_state(&counts)?;
    if template.is_some() {
        let offsets = mesh.face_offsets();
        if let Some(f) = (0..mesh.n_faces()).find(|&f| offsets[f + 1] - offsets[f] != 3) {
            return Err(Error::SchemeNotApplicable {
                scheme: name.to_owned(),
                reason: format!(
                    "face {f} has {} vertices, the scheme needs triangles",
                    offsets[f + 1] - offsets[f]
                ),
            });
        }
        // Two triangles on the same three vertices would give the same interior edges under
        // a triangle split, which the counts (new edges per face) do not allow for: refused.
        crate::build::check_duplicate_faces(mesh.n_faces(), &|f| mesh.face(f))?;
    }
    let mut expected = Vec::with_capacity(levels as usize);
    for s in 1..=levels {
        let c = plan.scheme.counts_at(&counts, u64::from(s))?;
        expected.push(sizes(&c, name, s, true)?);
    }
    let template = match template {
        Some(n) if levels > 0 => Some(Template::new(n)),
        _ => None,
    };
    let mut current: Option<PolygonMesh> = None;
    let mut indexed = Some(first);
    for (s, e) in (1..=levels).zip(&expected) {
        let ix = match indexed.take() {
            Some(ix) => ix,
            None => Indexed::new(current.as_ref().unwrap_or(mesh))?,
        };
        let next = match &template {
            Some(t) => tri_split(&ix, t, e.vertices, e.faces)?,
            None => catmull_clark(&ix, e.vertices, e.faces)?,
        };
        let ctx = StepContext {
            scheme: name,
            level: s,
            expected: *e,
            parallel: false,
        };
        ctx.expect("vertices", e.vertices, next.positions.len())?;
        ctx.expect("faces", e.faces, next.n_faces())?;
        ctx.expect("position capacity", e.vertices, next.positions.capacity())?;
        let before = super::finite::Before::Counts {
            vertices: ix.positions.len(),
            edges: ix.edge_low.len(),
        };
        super::finite::check_positions(name, plan.split, s, &before, &next.positions)?;
        drop(ix);
        visit(s, &next)?;
        if let Some(progress) = opts.progress {
            progress(&LevelDone {
                level: s,
                levels,
                vertices: next.n_vertices(),
                edges: e.halfedges / 2,
                faces: next.n_faces(),
            });
        }
        current = Some(next);
    }
    match current {
        Some(last) => Ok(last),
        // Level 0 is the face list as written: the vertices no face uses are left out, as
        // every later level (and the half-edge path) leaves them out.
        None => crate::holes::written_part(mesh.clone(), &vec![true; mesh.n_faces()]),
    }
}

/// The UVs of the last level `last` of `mesh` refined by `plan`: the layout refined as a face
/// list of its own (its values as vertices at their UV, `z = 0`; its faces the value-index
/// faces) by the same subdivider `levels` times. The face-list subdividers are per-face
/// refinements with linear points, so a child value lands where its child vertex does in
/// its face (an edge midpoint or a point on the edge, a face centroid, a point on the flat
/// triangle), and the layout level has the faces of `last` in the same order with the same
/// sizes (checked: a mismatch is a bug, [`Error::InvalidOutput`]). Two faces that disagree
/// at an end of a shared edge give it a child value each. `written`: the faces of `last`
/// that are written (holes), whose corners alone are kept, values renumbered in order of
/// first use.
pub(super) fn refined_uvs(
    plan: &Plan,
    mesh: &PolygonMesh,
    layout: &crate::uv::UvLayout,
    levels: u32,
    opts: &SubdivideOptions<'_>,
    last: &PolygonMesh,
    written: Option<&[bool]>,
) -> Result<crate::uv::Uvs> {
    if layout.corners().len() != mesh.n_corners() {
        return Err(Error::UvLayoutMismatch {
            reason: format!(
                "{} layout corners for a mesh with {} face corners",
                layout.corners().len(),
                mesh.n_corners()
            ),
        });
    }
    let values: Vec<DVec3> = layout
        .values()
        .iter()
        .map(|uv| DVec3::new(uv.x, uv.y, 0.0))
        .collect();
    let flat = PolygonMesh::from_raw_parts(
        values,
        mesh.face_offsets().to_vec(),
        layout.corners().to_vec(),
    );
    // The layout is sized by the rule's matrix for any face list: the layout of a manifold
    // mesh may itself be non-manifold, or the other way round.
    let scheme = match plan.rule {
        Rule::TriSplit(_) => plan.scheme.clone(),
        Rule::CatmullClark => schemes::builtin("catmull-clark-general")?,
        _ => schemes::builtin("loop-general")?,
    };
    let layout_plan = Plan {
        rule: plan.rule,
        name: format!("{} (UV layout)", plan.name),
        scheme,
        split: plan.split,
    };
    let layout_opts = SubdivideOptions {
        progress: None,
        holes: None,
        uvs: None,
        limit: false,
        ..*opts
    };
    let refined = run_levels(&layout_plan, &flat, levels, &layout_opts, |_, _| Ok(()))?;
    let mismatch = |what: String| Error::InvalidOutput {
        scheme: plan.name.clone(),
        level: levels,
        what,
    };
    if refined.n_faces() != last.n_faces() {
        return Err(mismatch(format!(
            "the UV layout refined to {} faces, the mesh to {}",
            refined.n_faces(),
            last.n_faces()
        )));
    }
    if refined.face_offsets() != last.face_offsets() {
        return Err(mismatch(
            "the UV layout's faces differ in size from the mesh's".into(),
        ));
    }
    let coords = |v: u32| {
        let p = refined.positions[v as usize];
        DVec2::new(p.x, p.y)
    };
    let uvs = match written {
        None => crate::uv::Uvs::new(
            refined
                .positions
                .iter()
                .map(|p| DVec2::new(p.x, p.y))
                .collect(),
            refined.face_indices().to_vec(),
        ),
        Some(mask) => {
            if mask.len() != refined.n_faces() {
                return Err(mismatch(format!(
                    "{} faces where the holes' descendants were counted on {}",
                    refined.n_faces(),
                    mask.len()
                )));
            }
            let mut id = vec![INVALID; refined.positions.len()];
            let mut kept = Vec::new();
            let mut corners = Vec::new();
            for (face, _) in refined.faces().zip(mask).filter(|(_, &w)| w) {
                for &v in face {
                    let slot = &mut id[v as usize];
                    if *slot == INVALID {
                        *slot = kept.len() as u32;
                        kept.push(coords(v));
                    }
                    corners.push(*slot);
                }
            }
            crate::uv::Uvs::new(kept, corners)
        }
    };
    uvs.map_err(|e| Error::UvLayoutMismatch {
        reason: e.to_string(),
    })
}
