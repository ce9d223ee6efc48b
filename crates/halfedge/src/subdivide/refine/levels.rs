//! Building a [`Refinement`]'s levels: each level's topology by its rule's step, the
//! flattened tables of Loop and Catmull-Clark, the kept written part under holes.

use super::*;

impl Refinement {
    /// Builds levels `1..=levels` (the topology `new` keeps).
    pub(super) fn build(
        &mut self,
        planned: &[(Option<Sizes>, [usize; 3])],
        opts: &SubdivideOptions<'_>,
    ) -> Result<()> {
        let levels = self.levels;
        let parallel = self.threads != 1;
        let report = |level: u32, size: &LevelSize| {
            if let Some(progress) = opts.progress {
                progress(&LevelDone {
                    level,
                    levels,
                    vertices: size.vertices,
                    edges: size.edges,
                    faces: size.faces,
                });
            }
        };
        for (s, &(sizes, [vertices, edges, faces])) in (1..=levels).zip(planned) {
            let before = self.topology.last().and_then(|l| l.topology.as_ref());
            let Some(before) = before else {
                return Err(Error::InvalidOutput {
                    scheme: self.name.clone(),
                    level: s,
                    what: "no level to refine".into(),
                });
            };
            let t = before.topo();
            let step_b = self.step_b(&t, s, sizes, parallel)?;
            let Some(expected) = sizes else {
                // The last level of a direct rule: its faces are written from level s - 1.
                let corners = match self.split {
                    Split::Quad => 4 * faces,
                    _ => 3 * faces,
                };
                let size = LevelSize {
                    vertices,
                    edges,
                    faces,
                    corners,
                };
                self.face_degree = Some(corners / faces.max(1));
                if let Some(last) = self.topology.last_mut() {
                    last.step_b = step_b;
                }
                report(s, &size);
                self.sizes.push(size);
                break;
            };
            let ctx = self.context(s, expected, parallel);
            let next = self.step(&t, &ctx)?;
            let nt = next.topo();
            if let (Some(creases), true) = (self.creases.as_mut(), s < levels) {
                creases.push_child(s as usize - 1, &t, &nt);
            }
            let size = LevelSize {
                vertices: nt.nv(),
                edges: nt.ne(),
                faces: nt.nf(),
                corners: corners_of(&nt),
            };
            if let Some(last) = self.topology.last_mut() {
                last.step_b = step_b;
            }
            report(s, &size);
            self.sizes.push(size);
            if s == levels {
                let polygons = polygons_of(&nt)?;
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
        Ok(())
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

    /// The connectivity of the level after `t` (`ctx.level`).
    pub(super) fn step(&self, t: &Topo<'_>, ctx: &StepContext<'_>) -> Result<Connectivity> {
        Ok(match self.next_level(t, ctx, None)? {
            Next::Topology(c, _) => c,
            Next::Mesh(m) => Connectivity::from_mesh(m),
        })
    }

    /// The level after `t` (`ctx.level`): the topology of every refinement and of the one-shot
    /// subdivision. By index formulas into arrays of the predicted lengths (the 4:1 family,
    /// Catmull-Clark, √3 on closed meshes, Doo-Sabin, mid-edge), else face by face into
    /// index-addressed arrays (1:N² for N >= 3, √3 on a boundary). `positions`, the new
    /// level's (from [`Refinement::values_after`]), are handed back with a connectivity or
    /// become the mesh's; the face-by-face steps fill zeros without them.
    pub(super) fn next_level(
        &self,
        t: &Topo<'_>,
        ctx: &StepContext<'_>,
        positions: Option<Vec<glam::DVec3>>,
    ) -> Result<Next> {
        use crate::subdivide::{gather, sqrt3, trisplit};
        let topology = match (self.split, &self.template) {
            (Split::Tri(2), _) => gather::four_to_one_topology(t, ctx)?,
            (Split::Tri(_), Some(template)) => {
                let mesh = trisplit::tri_split_step(t, positions, template, ctx)?;
                return Ok(Next::Mesh(mesh));
            }
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
