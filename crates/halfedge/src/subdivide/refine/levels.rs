//! Building a [`Refinement`]'s levels: each level's topology by its rule's step, the
//! flattened tables of Loop and Catmull-Clark, the kept written part under holes.

use super::*;
use crate::subdivide::{finite, to_faces};

/// A level [`Refinement::refine_levels`] built, as the retention keeps it.
enum Built {
    Topology(Connectivity),
    Mesh(HalfEdgeMesh),
}

impl Built {
    fn topo(&self) -> Topo<'_> {
        match self {
            Built::Topology(c) => c.topo(),
            Built::Mesh(m) => Topo::new(m),
        }
    }
}

/// The refinement's own inconsistency at `level` (a bug): [`Error::InvalidOutput`].
pub(super) fn invalid(scheme: &str, level: u32, what: &str) -> Error {
    Error::InvalidOutput {
        scheme: scheme.to_owned(),
        level,
        what: what.into(),
    }
}

/// What a refinement keeps of the levels it builds: the one difference between
/// [`Refinement::new`] and the one-shot subdivision ([`one_shot`](super::one_shot)), which run
/// the same level loop ([`Refinement::refine_levels`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Retain {
    /// Every level's topology, flattened into its rule's fast tables once the next level is
    /// built, and no positions: a refinement evaluated many times.
    All,
    /// Only the level refined and the one built, each a half-edge mesh whose positions are
    /// evaluated on the way (the peak of levels `s - 1` and `s`); the last level of the 4:1
    /// family and Catmull-Clark is written straight into a face list when it is planned so.
    LastTwo,
}

impl Refinement {
    /// Builds levels `1..=levels` from `mesh` (level 0), keeping what `retain` says:
    /// [`Retain::All`] fills the refinement's levels and returns `None`; [`Retain::LastTwo`]
    /// returns the last level built, `visit` seeing every level. The same size checks, the
    /// same topology steps ([`Refinement::next_level`]), the same crease sharpness and, for
    /// the one-shot subdivision, the same evaluation ([`Refinement::values_after`]) as every
    /// later [`Refinement::evaluate`].
    pub(super) fn refine_levels(
        &mut self,
        mesh: &HalfEdgeMesh,
        planned: &[(Option<Sizes>, [usize; 3])],
        opts: &SubdivideOptions<'_>,
        retain: Retain,
        visit: &mut (impl FnMut(u32, &HalfEdgeMesh) -> Result<()> + Send),
    ) -> Result<Option<OneShot>> {
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
        // The level the one-shot subdivision holds (Retain::LastTwo).
        let mut current: Option<HalfEdgeMesh> = None;
        for (s, &(sizes, [vertices, edges, faces])) in (1..=levels).zip(planned) {
            let held = current.as_ref().unwrap_or(mesh);
            let t = match retain {
                Retain::LastTwo => Topo::new(held),
                Retain::All => match self.topology.last().and_then(|l| l.topology.as_ref()) {
                    Some(before) => before.topo(),
                    None => return Err(invalid(&self.name, s, "no level to refine")),
                },
            };
            let expected = sizes.unwrap_or(Sizes {
                vertices,
                halfedges: 2 * edges,
                faces,
            });
            let ctx = self.context(s, expected, parallel);
            let step_b = self.step_b(&t, s, sizes, parallel)?;
            // The one-shot subdivision evaluates this level from the one before as it is (no
            // fast tables: one evaluation; the crease table of the level under crease rules),
            // positions first: their temporaries are freed before the topology's exist.
            let positions = match retain {
                Retain::All => None,
                Retain::LastTwo => {
                    let creased = self.crease_table(s, &t, parallel)?;
                    let before = LevelRef {
                        topology: Some(t),
                        step_b: step_b.as_ref(),
                        fast: creased.as_ref(),
                    };
                    let positions =
                        self.values_after(&before, &held.positions, vertices, "positions")?;
                    drop(creased);
                    let origin = finite::Before::Mesh(held);
                    finite::check_positions(&self.name, self.split, s, &origin, &positions)?;
                    Some(positions)
                }
            };
            if sizes.is_none() {
                // The last level of a direct rule: its faces are written from level s - 1.
                let degree = if self.split == Split::Quad { 4 } else { 3 };
                report(s, [vertices, edges, faces]);
                let Some(positions) = positions else {
                    self.face_degree = Some(degree);
                    if let Some(last) = self.topology.last_mut() {
                        last.step_b = step_b;
                    }
                    self.sizes.push(LevelSize {
                        vertices,
                        edges,
                        faces,
                        corners: degree * faces,
                    });
                    break;
                };
                let template = self.template.as_ref();
                let (polygons, edges) = to_faces::faces_after(&t, positions, template, &ctx)?;
                return Ok(Some(OneShot::Faces(Box::new(polygons), edges)));
            }
            let next = self.next_level(&t, &ctx, positions)?;
            let next = match (retain, next) {
                (Retain::All, Next::Topology(c, _)) => Built::Topology(c),
                (Retain::All, Next::Mesh(m)) => Built::Topology(Connectivity::from_mesh(m)),
                (_, Next::Topology(c, Some(positions))) => {
                    let (n, capacity) = (positions.len(), positions.capacity());
                    ctx.expect_exact("vertex positions", vertices, n, capacity)?;
                    Built::Mesh(c.with_positions(positions))
                }
                (_, Next::Topology(..)) => return Err(ctx.invalid("no positions".into())),
                (_, Next::Mesh(m)) => Built::Mesh(m),
            };
            let nt = next.topo();
            if let Some(creases) = self.creases.as_mut() {
                // The child's sharpness, when a level follows (or the limit reads it).
                if s < levels || self.limit_walk.is_some() {
                    creases.push_child(s as usize - 1, &t, &nt);
                }
            }
            if let Some(walk) = self.limit_walk.as_mut() {
                walk.push(&t, &nt)?;
                if s == levels {
                    let sharp = self.creases.as_ref().and_then(|c| c.level(s as usize));
                    walk.finish(&nt, sharp)?;
                    if let Some(creases) = self.creases.as_mut() {
                        creases.release(s as usize);
                    }
                }
            }
            let size = [nt.nv(), nt.ne(), nt.nf()];
            // A walk of the half-edges, for the levels a refinement keeps only.
            let corners = match next {
                Built::Topology(_) => corners_of(&nt),
                Built::Mesh(_) => 0,
            };
            match next {
                Built::Topology(next) => {
                    if let Some(last) = self.topology.last_mut() {
                        last.step_b = step_b;
                    }
                    report(s, size);
                    let [vertices, edges, faces] = size;
                    self.sizes.push(LevelSize {
                        vertices,
                        edges,
                        faces,
                        corners,
                    });
                    if s == levels {
                        let polygons = polygons_of(&next.topo())?;
                        self.face_degree = common_degree(&polygons);
                        self.polygons = Some(polygons);
                    } else {
                        self.topology.push(Level {
                            topology: Some(next),
                            step_b: None,
                            fast: None,
                        });
                        // Level s - 1 is not needed as connectivity any more (a lower peak).
                        self.flatten(s as usize - 1, false, parallel)?;
                    }
                }
                Built::Mesh(next) => {
                    // The parent's sharpness is dropped, and level s - 1 before the last
                    // level is visited.
                    if let Some(creases) = self.creases.as_mut() {
                        creases.release(s as usize - 1);
                    }
                    if s == levels {
                        drop(current.take());
                    }
                    visit(s, &next)?;
                    report(s, size);
                    current = Some(next);
                }
            }
        }
        if let Retain::LastTwo = retain {
            return Ok(Some(OneShot::Mesh(current.unwrap_or_else(|| mesh.clone()))));
        }
        if levels == 0 {
            if let Some(base) = &self.topology[0].topology {
                let polygons = polygons_of(&base.topo())?;
                self.face_degree = common_degree(&polygons);
                self.polygons = Some(polygons);
            }
        }
        // Flatten the levels still holding their connectivity (level `levels - 1` keeps it for
        // the index buffers; the others were flattened as soon as the next level was built).
        for i in 0..self.topology.len() {
            self.flatten(i, true, parallel)?;
        }
        Ok(None)
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
            None => Err(invalid(&self.name, s, "no sharpness for the level refined")),
        }
    }

    /// Flattens level `i` for the Loop and Catmull-Clark rules (a no-op for the others and
    /// for a level already flattened), dropping its connectivity unless `keep`.
    pub(super) fn flatten(&mut self, i: usize, keep: bool, parallel: bool) -> Result<()> {
        let split = self.split;
        // The rules with flattened tables are the rules with crease rules.
        let flattened = crate::subdivide::sdc::masks::Scheme::of(self.rule).is_some();
        if self.levels == 0 || !flattened {
            return Ok(());
        }
        let Some(level) = self.topology.get_mut(i) else {
            return Ok(());
        };
        if level.fast.is_none() {
            if let (Some(c), Some(creases)) = (&level.topology, self.creases.as_mut()) {
                let fast = Fast::creased(creases, i, &c.topo(), split, true, parallel)?;
                let fast = fast.ok_or_else(|| Error::InvalidOutput {
                    scheme: self.name.clone(),
                    level: i as u32 + 1,
                    what: "no sharpness for the level refined".into(),
                })?;
                creases.release(i);
                level.fast = Some(fast);
            }
        }
        if level.fast.is_none() {
            if let Some(c) = &level.topology {
                level.fast = Some(Fast::tables(split, &c.topo(), parallel)?);
            }
        }
        if !keep {
            level.topology = None;
        }
        Ok(())
    }

    /// The boundary tables of a √3 step B refining `t` into level `level` (built as a half-edge
    /// mesh with `sizes`), `None` for the other steps.
    pub(super) fn step_b(
        &self,
        t: &Topo<'_>,
        level: u32,
        sizes: Option<Sizes>,
        parallel: bool,
    ) -> Result<Option<StepB>> {
        match (self.split, sizes) {
            (Split::Sqrt3 { boundary: true }, Some(expected)) if level % 2 == 0 => {
                let ctx = self.context(level, expected, parallel);
                Ok(Some(StepB::new(t, &ctx)?))
            }
            _ => Ok(None),
        }
    }

    pub(super) fn context(&self, level: u32, expected: Sizes, parallel: bool) -> StepContext<'_> {
        StepContext {
            scheme: &self.name,
            level,
            expected,
            parallel,
        }
    }

    /// The level after `t` (`ctx.level`): the topology of every refinement and of the one-shot
    /// subdivision. By index formulas into arrays of the predicted lengths (1:N² and 4:1,
    /// Catmull-Clark, √3, Doo-Sabin and mid-edge on closed meshes), else face by face into
    /// index-addressed arrays (√3, Doo-Sabin and mid-edge on a boundary). `positions`, the new
    /// level's (from [`Refinement::values_after`]), are handed back with a connectivity or
    /// become the mesh's; the face-by-face steps fill zeros without them.
    pub(super) fn next_level(
        &self,
        t: &Topo<'_>,
        ctx: &StepContext<'_>,
        positions: Option<Vec<glam::DVec3>>,
    ) -> Result<Next> {
        use crate::subdivide::{gather, sqrt3};
        let topology = match (self.split, &self.template) {
            (Split::Tri(_), Some(template)) => gather::tri_split_topology(t, template, ctx)?,
            (Split::Tri(..), None) => return Err(ctx.invalid("no split template".into())),
            (Split::Quad, _) => gather::catmull_clark_topology(t, ctx)?,
            (Split::Sqrt3 { .. }, _) if t.is_closed() => gather::sqrt3_closed_topology(t, ctx)?,
            (Split::Sqrt3 { boundary }, _) => {
                let step_b = boundary && ctx.level % 2 == 0;
                let mesh = sqrt3::sqrt3_step(t, positions, step_b, ctx)?;
                return Ok(Next::Mesh(mesh));
            }
            (Split::DualCorners, _) => gather::doo_sabin_topology(t, ctx)?,
            (Split::DualEdges, _) => gather::mid_edge_topology(t, ctx)?,
        };
        Ok(Next::Topology(topology, positions))
    }

    /// Runs `f` in the refinement's pool (or on the calling thread / the global pool).
    pub(super) fn install<R: Send>(
        &mut self,
        f: impl FnOnce(&mut Self) -> Result<R> + Send,
    ) -> Result<R> {
        match self.pool.clone() {
            Some(pool) => pool.install(|| f(self)),
            None => f(self),
        }
    }

    /// Runs `f` in the refinement's pool (shared access).
    pub(super) fn run<R: Send>(&self, f: impl FnOnce() -> R + Send) -> R {
        match &self.pool {
            Some(pool) => pool.install(f),
            None => f(),
        }
    }
}
