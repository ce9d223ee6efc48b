//! The one-shot subdivision ([`subdivide`](crate::subdivide::subdivide),
//! [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list),
//! [`verify`](crate::subdivide::verify)) as a refinement built in a private streaming mode:
//! the same size checks ([`plan_sizes`]), the same topology steps
//! ([`Refinement::next_level`]), the same geometry ([`Refinement::values_after`], the dispatch
//! of the stencils) and the same index buffers ([`to_faces`](super::super::to_faces), as
//! [`Refinement::write_triangles`] writes them), so that a rule changed in the refinement is
//! changed in the one-shot subdivision.
//!
//! What the mode drops: a [`Refinement`] keeps every level's topology (it evaluates many
//! times); the one-shot subdivision evaluates once, level by level, so it keeps only the level
//! it refines (as a half-edge mesh with its positions) and the one it builds, and it does not
//! flatten levels into the rules' fast tables (their building costs more than the one
//! evaluation they would serve). The peak is the one of the level loop it replaced: levels
//! `s - 1` and `s`.
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

use glam::DVec3;
use schemes::MeshCounts;

use super::creases::Creases;
use super::{crease_budgets, direct, plan_sizes, Fast, LevelRef, Next, Refinement};
use crate::subdivide::build::Sizes;
use crate::subdivide::topo::Topo;
use crate::subdivide::{finite, to_faces, LevelDone, Plan, Split, SubdivideOptions};
use crate::{HalfEdgeMesh, PolygonMesh, Result};

/// What the one-shot subdivision built.
pub(crate) enum OneShot {
    /// The last level as a half-edge mesh (a copy of the input at level 0).
    Mesh(HalfEdgeMesh),
    /// The last level written straight into a face list, with its number of edges.
    Faces(PolygonMesh, usize),
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
    let mut creases = Creases::new(mesh, plan.rule, opts.sharpness, &opts.subdivision)?;
    if let Some(creases) = creases.as_mut() {
        // The choices of `Refinement::new`, whose tables are bounded per level.
        creases.set_budgets(crease_budgets(plan, counts, levels)?);
    }
    let as_faces = faces;
    let faces = faces && direct(plan.split);
    let planned = plan_sizes(plan, counts, levels, !faces)?;
    if levels == 0 {
        // A face list asked for is the input's, without a copy of its half-edge mesh first.
        return Ok(if as_faces {
            OneShot::Faces(mesh.to_polygon_mesh(), mesh.n_edges())
        } else {
            OneShot::Mesh(mesh.clone())
        });
    }
    let mut r = Refinement::streaming(plan, levels, opts.threads, creases);
    crate::subdivide::with_threads(opts.threads, || r.stream(mesh, &planned, opts, &mut visit))
}

impl Refinement {
    /// A refinement of `plan` to `levels` that keeps no level, with the crease rules of
    /// [`Creases::new`]: the one-shot mode.
    fn streaming(plan: &Plan, levels: u32, threads: usize, creases: Option<Creases>) -> Refinement {
        let template = match plan.split {
            Split::Tri(n) => Some(crate::subdivide::trisplit::Template::new(n)),
            _ => None,
        };
        Refinement {
            rule: plan.rule,
            name: plan.name.clone(),
            split: plan.split,
            levels,
            threads,
            pool: None,
            template,
            topology: Vec::new(),
            sizes: Vec::new(),
            polygons: None,
            face_degree: None,
            creases,
            written: None,
            uvs: None,
        }
    }

    /// The level loop of [`one_shot`] (in its threads).
    fn stream(
        &mut self,
        mesh: &HalfEdgeMesh,
        planned: &[(Option<Sizes>, [usize; 3])],
        opts: &SubdivideOptions<'_>,
        visit: &mut (impl FnMut(u32, &HalfEdgeMesh) -> Result<()> + Send),
    ) -> Result<OneShot> {
        let levels = self.levels;
        let parallel = self.threads != 1;
        let report = |level: u32, [vertices, edges, faces]: [usize; 3]| {
            if let Some(progress) = opts.progress {
                progress(&LevelDone {
                    level,
                    levels,
                    vertices,
                    edges,
                    faces,
                });
            }
        };
        let mut current: Option<HalfEdgeMesh> = None;
        for (s, &(sizes, [nv, ne, nf])) in (1..=levels).zip(planned) {
            let input = current.as_ref().unwrap_or(mesh);
            let t = Topo::new(input);
            let expected = sizes.unwrap_or(Sizes {
                vertices: nv,
                halfedges: 2 * ne,
                faces: nf,
            });
            let ctx = self.context(s, expected, parallel);
            // The level before as the evaluation reads it: no fast tables (one evaluation),
            // the crease weight table of this level under crease rules.
            let step_b = self.step_b(&t, s, sizes, parallel)?;
            let creased = self.crease_table(s, &t, parallel)?;
            let before = LevelRef {
                topology: Some(t),
                step_b: step_b.as_ref(),
                fast: creased.as_ref(),
            };
            // Positions first: their temporaries (Catmull-Clark's face points, the crease
            // table) are freed before the topology's are allocated.
            let positions: Vec<DVec3> =
                self.values_after(&before, &input.positions, nv, "positions")?;
            drop(creased);
            let origin = finite::Before::Mesh(input);
            finite::check_positions(&self.name, self.split, s, &origin, &positions)?;
            if sizes.is_none() {
                // The last level, written from this one.
                let quads = self.split == Split::Quad;
                let (polygons, edges) = to_faces::faces_after(&t, positions, quads, &ctx)?;
                drop(current);
                report(s, [polygons.n_vertices(), edges, polygons.n_faces()]);
                return Ok(OneShot::Faces(polygons, edges));
            }
            let next = match self.next_level(&t, &ctx, Some(positions))? {
                Next::Topology(topology, Some(positions)) => {
                    let (n, capacity) = (positions.len(), positions.capacity());
                    ctx.expect_exact("vertex positions", nv, n, capacity)?;
                    topology.with_positions(positions)
                }
                Next::Topology(..) => return Err(ctx.invalid("no positions".into())),
                Next::Mesh(m) => m,
            };
            if let Some(creases) = self.creases.as_mut() {
                // The child's sharpness (only when a level follows), then the parent's dropped.
                let level = s as usize - 1;
                if s < levels {
                    creases.push_child(level, &t, &Topo::new(&next));
                }
                creases.release(level);
            }
            if s == levels {
                // Level s - 1 is dropped before the last level is visited.
                drop(current.take());
            }
            visit(s, &next)?;
            report(s, [next.n_vertices(), next.n_edges(), next.n_faces()]);
            // Level s - 1 is dropped here.
            current = Some(next);
        }
        match current {
            Some(last) => Ok(OneShot::Mesh(last)),
            None => Ok(OneShot::Mesh(mesh.clone())),
        }
    }

    /// What refines level `s - 1` (`t`) under crease rules, as [`Refinement::new`] builds it
    /// for that level but with the half-edge kernels of the rule in place of its flattened
    /// tables; `None` without crease rules.
    fn crease_table(&self, s: u32, t: &Topo<'_>, parallel: bool) -> Result<Option<Fast>> {
        let Some(creases) = &self.creases else {
            return Ok(None);
        };
        match Fast::creased(creases, s as usize - 1, t, self.split, false, parallel)? {
            Some(fast) => Ok(Some(fast)),
            None => Err(crate::Error::InvalidOutput {
                scheme: self.name.clone(),
                level: s,
                what: "no sharpness for the level refined".into(),
            }),
        }
    }
}
