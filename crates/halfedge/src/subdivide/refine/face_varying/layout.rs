//! The layout channel of Loop and Catmull-Clark: a UV layout's values refined level by level
//! by OpenSubdiv's face-varying rules, with sibling values where the layout has seams.

use super::*;

/// The face-varying channel of the rules whose faces nest: the layout refined as its own mesh.
#[derive(Debug)]
pub(crate) struct LayoutChannel {
    /// The layout's refinement (no holes, no UVs).
    pub(super) refinement: Refinement,
    /// The layout's values (level 0).
    pub(super) n_values: usize,
    /// The layout value of each extra run (channel vertex `n_values + i`).
    pub(super) siblings: Vec<u32>,
    /// The OpenSubdiv value (from level 1 on) of each extra run: its own, or that of the run
    /// of the same value before it.
    pub(super) sibling_value: Vec<u32>,
    /// The extra runs that repeat a value (all runs but the first of each value).
    pub(super) n_repeated: usize,
    /// The UV value of each channel vertex of the last level (`INVALID`: not written), when
    /// siblings or holes renumber them.
    pub(super) merged: Option<Vec<u32>>,
    /// The values written at the last level.
    pub(super) n_last: usize,
    /// With holes: the UV index of each written corner of the last level.
    pub(super) written_corners: Option<Vec<u32>>,
}

/// The value of every face corner of `t` (by half-edge: the corner at its source), checked
/// against `layout`.
pub(super) fn corner_values(
    t: &Topo<'_>,
    layout: &UvLayout,
    mesh_unreferenced: u64,
) -> Result<Vec<u32>> {
    let corners = layout.corners();
    let total: usize = (0..t.nf() as u32).map(|f| t.face_degree(f)).sum();
    if total != corners.len() {
        return Err(Error::UvLayoutMismatch {
            reason: format!(
                "{} corners in the layout, {} in the mesh",
                corners.len(),
                total
            ),
        });
    }
    let mut values = vec![INVALID; 2 * t.ne()];
    let mut vertex_of = vec![INVALID; layout.n_values()];
    // The mesh drops the vertices no face uses and renumbers the others in order: a value's
    // vertex in the mesh is its layout vertex, less at most the vertices dropped.
    let dropped = u64::from(u32::MAX).min(mesh_unreferenced) as u32;
    let mut k = 0usize;
    let mut conflict = None;
    for f in 0..t.nf() as u32 {
        t.for_face(f, |h| {
            let value = corners[k];
            k += 1;
            values[h as usize] = value;
            let v = t.source(h);
            let given = layout.value_vertex(value);
            if (v > given || given - v > dropped) && conflict.is_none() {
                conflict = Some((value, given, v));
            }
            let slot = &mut vertex_of[value as usize];
            if *slot == INVALID {
                *slot = v;
            } else if *slot != v && conflict.is_none() {
                conflict = Some((value, *slot, v));
            }
        });
    }
    if let Some((value, a, b)) = conflict {
        return Err(Error::UvLayoutMismatch {
            reason: format!("value {value} belongs to vertex {a}, the mesh has it at {b}"),
        });
    }
    Ok(values)
}

/// How the values at one vertex are classified.
struct Classify {
    mode: FaceVaryingInterpolation,
    /// Surface corners are smooth (not `edge-and-corner`).
    geometric_corners_smooth: bool,
}

impl Classify {
    fn linear_boundaries(&self) -> bool {
        matches!(
            self.mode,
            FaceVaryingInterpolation::Boundaries | FaceVaryingInterpolation::All
        )
    }
    fn dependent(&self) -> bool {
        matches!(
            self.mode,
            FaceVaryingInterpolation::CornersPlus1 | FaceVaryingInterpolation::CornersPlus2
        )
    }
    fn corners_sharp(&self) -> bool {
        self.mode != FaceVaryingInterpolation::None
    }
}

/// One contiguous run of faces around a vertex sharing a value.
#[derive(Clone, Copy, Debug)]
struct Run {
    value: u32,
    /// Its OpenSubdiv value at the vertex (the sibling index).
    sibling: usize,
    /// Faces in the run.
    faces: usize,
    /// An infinitely sharp surface edge inside the run.
    inf_sharp_inside: bool,
}

impl LayoutChannel {
    /// The channel of `layout` on `mesh` under `rule` at `levels` with the surface's options.
    pub(super) fn new(
        mesh: &HalfEdgeMesh,
        layout: &UvLayout,
        rule: Rule,
        levels: u32,
        opts: &SubdivideOptions<'_>,
    ) -> Result<LayoutChannel> {
        let ChannelKind::Layout(channel) = channel_kind(rule)? else {
            return Err(Error::UvsNotSupported {
                rule: rule.to_string(),
            });
        };
        let t = Topo::new(mesh);
        let cv = corner_values(&t, layout, mesh.unreferenced_vertices())?;
        let n_values = layout.n_values();
        let smooth = rule == Rule::Loop || rule == Rule::CatmullClark;
        let surface_edges = |e: u32| {
            opts.sharpness
                .map_or(0.0, |s| s.edges().get(e as usize).copied().unwrap_or(0.0))
        };
        let classify = Classify {
            mode: opts.subdivision.face_varying,
            geometric_corners_smooth: opts.subdivision.boundary
                != BoundaryInterpolation::EdgeAndCorner,
        };
        // Per surface vertex, its sharpness as the surface's crease rules see it.
        let surface_vertex = |v: u32| {
            let s = opts.sharpness.map_or(0.0, |s| {
                s.vertices().get(v as usize).copied().unwrap_or(0.0)
            });
            if !classify.geometric_corners_smooth && t.is_boundary_vertex(v) && t.valence(v) == 2 {
                INFINITELY_SHARP
            } else {
                s
            }
        };
        // A surface edge is a seam when its two faces disagree at either end.
        let seam = |h: u32| {
            let g = h ^ 1;
            !t.is_boundary(h)
                && !t.is_boundary(g)
                && (cv[h as usize] != cv[t.next(g) as usize]
                    || cv[t.next(h) as usize] != cv[g as usize])
        };
        // The channel vertex of every corner (by half-edge), and its sharpness.
        let mut corner_vertex = vec![INVALID; 2 * t.ne()];
        let mut siblings: Vec<u32> = Vec::new();
        // Per sibling channel vertex: the channel vertex of its OpenSubdiv value.
        let mut representative: Vec<u32> = Vec::new();
        let mut sibling_of = Vec::new();
        let mut vertex_sharpness = vec![0.0f32; n_values];
        let mut ring = Vec::new();
        let mut runs: Vec<(Run, Vec<u32>)> = Vec::new();
        for v in 0..t.nv() as u32 {
            let boundary = t.is_boundary_vertex(v);
            // OpenSubdiv's order of the faces: from the boundary, or from the lowest face.
            let first = boundary_first(&t, v).unwrap_or_else(|| {
                let mut best = t.vertex_halfedge(v);
                t.for_outgoing(v, |h| {
                    if t.face(h) < t.face(best) {
                        best = h;
                    }
                });
                best
            });
            ccw_ring(&t, v, first, &mut ring);
            // Faces around v in order: ring[i] for the half-edges with a face; face i and
            // face i + 1 share the edge of ring[i + 1].
            let faces: Vec<u32> = ring
                .iter()
                .copied()
                .filter(|&h| !t.is_boundary(h))
                .collect();
            if faces.is_empty() {
                continue;
            }
            // OpenSubdiv's values at v (`completeTopologyFromFaceValues`): a new value
            // wherever the face's value differs from the one before, unless it was seen, but
            // with two values seen only the first is looked at, so A-B-A-B around a vertex
            // is three values (A, B, and the second run of B).
            let mut unique: Vec<u32> = Vec::new();
            sibling_of.clear();
            for (i, &h) in faces.iter().enumerate() {
                let value = cv[h as usize];
                let sibling = if i == 0 {
                    unique.push(value);
                    0
                } else if value == cv[faces[i - 1] as usize] {
                    sibling_of[i - 1]
                } else if unique.len() == 1 || (unique.len() == 2 && unique[0] != value) {
                    unique.push(value);
                    unique.len() - 1
                } else if let Some(k) = unique.iter().position(|&u| u == value) {
                    k
                } else {
                    unique.push(value);
                    unique.len() - 1
                };
                sibling_of.push(sibling);
            }
            runs.clear();
            let mut any_seam = false;
            for (i, &h) in faces.iter().enumerate() {
                let value = cv[h as usize];
                let sibling = sibling_of[i];
                let joined = i > 0 && {
                    let shared = ring[i];
                    let s = seam(shared);
                    any_seam |= s;
                    !s && cv[faces[i - 1] as usize] == value
                };
                if joined {
                    if let Some((run, members)) = runs.last_mut() {
                        run.faces += 1;
                        run.inf_sharp_inside |= surface_edges(ring[i] >> 1) >= INFINITELY_SHARP;
                        members.push(h);
                    }
                } else {
                    runs.push((
                        Run {
                            value,
                            sibling,
                            faces: 1,
                            inf_sharp_inside: false,
                        },
                        vec![h],
                    ));
                }
            }
            if !boundary {
                // The edge between the last face and the first.
                let closing = ring[0];
                let s = seam(closing);
                any_seam |= s;
                let last = faces[faces.len() - 1];
                if runs.len() > 1 && !s && cv[last as usize] == cv[faces[0] as usize] {
                    if let Some((run, members)) = runs.pop() {
                        let head = &mut runs[0];
                        head.0.faces += run.faces;
                        head.0.inf_sharp_inside |=
                            run.inf_sharp_inside || surface_edges(closing >> 1) >= INFINITELY_SHARP;
                        head.1.extend(members);
                    }
                } else if runs.len() == 1 && !s {
                    runs[0].0.inf_sharp_inside |= surface_edges(closing >> 1) >= INFINITELY_SHARP;
                }
            }
            // Channel vertices: a value's first run is the value itself, the others siblings
            // (each pointing to the first run of its OpenSubdiv value).
            let mut seen: Vec<u32> = Vec::new();
            let mut first_of_sibling = vec![INVALID; unique.len()];
            let mut repeated = vec![false; runs.len()];
            for (r, (run, members)) in runs.iter().enumerate() {
                let id = if seen.contains(&run.value) {
                    siblings.push(run.value);
                    vertex_sharpness.push(0.0);
                    let id = (n_values + siblings.len() - 1) as u32;
                    representative.push(if first_of_sibling[run.sibling] == INVALID {
                        id
                    } else {
                        first_of_sibling[run.sibling]
                    });
                    id
                } else {
                    seen.push(run.value);
                    run.value
                };
                if first_of_sibling[run.sibling] == INVALID {
                    first_of_sibling[run.sibling] = id;
                } else {
                    repeated[r] = true;
                }
                for &h in members {
                    corner_vertex[h as usize] = id;
                }
            }
            // Classification (OpenSubdiv's completeTopologyFromFaceValues).
            let sv = surface_vertex(v);
            let mismatch = any_seam
                || (boundary
                    && (classify.linear_boundaries()
                        || (faces.len() == 1
                            && classify.geometric_corners_smooth
                            && classify.corners_sharp())));
            let n = unique.len();
            let corner_siblings: Vec<usize> = if !smooth || !mismatch {
                Vec::new()
            } else {
                // Per sibling: faces and whether it is disjoint.
                let span = |sibling: usize| {
                    let mut faces = 0usize;
                    let mut count = 0usize;
                    let mut inf = false;
                    for (run, _) in runs.iter().filter(|(r, _)| r.sibling == sibling) {
                        faces += run.faces;
                        count += 1;
                        inf |= run.inf_sharp_inside;
                    }
                    (faces, count > 1 || inf)
                };
                let single_disjoint = n == 1
                    && (boundary
                        || runs.len() > 1
                        || ring
                            .iter()
                            .any(|&h| !seam(h) && surface_edges(h >> 1) >= INFINITELY_SHARP));
                let all_sharp = classify.linear_boundaries()
                    || sv >= INFINITELY_SHARP
                    || (classify.dependent() && n > 2)
                    || (matches!(
                        classify.mode,
                        FaceVaryingInterpolation::CornersPlus2
                            | FaceVaryingInterpolation::Boundaries
                            | FaceVaryingInterpolation::All
                    ) && n == 1
                        && !boundary);
                let spans: Vec<(usize, usize, bool)> = (0..n)
                    .map(|k| {
                        let (size, disjoint) = span(k);
                        (k, size, if n == 1 { single_disjoint } else { disjoint })
                    })
                    .collect();
                let both = classify.dependent()
                    && n == 2
                    && (spans.iter().any(|s| s.2)
                        || (classify.mode == FaceVaryingInterpolation::CornersPlus2
                            && spans.iter().any(|s| s.1 == 1)));
                spans
                    .iter()
                    .filter(|&&(_, size, disjoint)| {
                        all_sharp || both || disjoint || (size == 1 && classify.corners_sharp())
                    })
                    .map(|s| s.0)
                    .collect()
            };
            // Sharpness of the channel vertices of v (a sibling in several runs is disjoint,
            // a corner, in every mode).
            for (r, (run, members)) in runs.iter().enumerate() {
                let id = corner_vertex[members[0] as usize] as usize;
                let corner = repeated[r]
                    || runs.iter().enumerate().any(|(q, (other, _))| {
                        q != r && other.sibling == run.sibling && repeated[q]
                    })
                    || corner_siblings.contains(&run.sibling);
                vertex_sharpness[id] = if smooth && corner {
                    INFINITELY_SHARP
                } else {
                    sv
                };
            }
        }
        // The channel's mesh: the surface's faces with channel vertices as corners.
        let n_channel = n_values + siblings.len();
        let mut positions = vec![glam::DVec3::ZERO; n_channel];
        for (h, &id) in corner_vertex.iter().enumerate() {
            if id != INVALID {
                positions[id as usize] = mesh.positions()[t.source(h as u32) as usize];
            }
        }
        let mut polygon = PolygonMesh::with_positions(positions);
        polygon.reserve_faces(t.nf(), cv.len());
        let mut face = Vec::new();
        for f in 0..t.nf() as u32 {
            face.clear();
            t.for_face(f, |h| face.push(corner_vertex[h as usize]));
            polygon.push_face(&face);
        }
        let layout_mesh = HalfEdgeMesh::try_from_polygon_mesh(&polygon)?;
        // Its edges' sharpness: the surface's, through corresponding half-edges; for the
        // limit, its edges along seams (a boundary of the layout inside the surface), whose
        // values OpenSubdiv's LimitFaceVarying treats as mismatched.
        let lt = Topo::new(&layout_mesh);
        let mut edge_sharpness = vec![0.0f32; lt.ne()];
        let mut seams = opts.limit.then(|| vec![false; lt.ne()]);
        let mut surface = Vec::new();
        for f in 0..t.nf() as u32 {
            surface.clear();
            t.for_face(f, |h| surface.push(h));
            let mut k = 0;
            lt.for_face(f, |h| {
                if let Some(&s) = surface.get(k) {
                    edge_sharpness[(h >> 1) as usize] = surface_edges(s >> 1);
                    if let Some(seams) = seams.as_mut() {
                        if lt.is_boundary(h ^ 1) && !t.is_boundary(s ^ 1) {
                            seams[(h >> 1) as usize] = true;
                        }
                    }
                }
                k += 1;
            });
        }
        let linear = match opts.subdivision.face_varying {
            FaceVaryingInterpolation::All => Linear::All,
            FaceVaryingInterpolation::Boundaries => Linear::Boundaries,
            _ => Linear::Nothing,
        };
        let channel_opts = SubdivideOptions {
            threads: opts.threads,
            subdivision: opts.subdivision,
            limit: opts.limit,
            ..SubdivideOptions::default()
        };
        let refinement = Refinement::with_creases(
            &layout_mesh,
            channel,
            levels,
            &channel_opts,
            || {
                if smooth {
                    Creases::for_channel(
                        &layout_mesh,
                        channel,
                        &edge_sharpness,
                        &vertex_sharpness,
                        &opts.subdivision,
                        linear,
                    )
                } else {
                    Ok(None)
                }
            },
            seams,
        )?;
        // The OpenSubdiv value of each sibling (levels 1 and after), numbered after the
        // layout's values: a sibling that starts a value gets the next number.
        // The other rules refine the layout as a mesh: one value per (vertex, vt) pair.
        let mut sibling_value = Vec::with_capacity(siblings.len());
        let mut next = n_values as u32;
        for (i, &rep) in representative.iter().enumerate() {
            let own = (n_values + i) as u32;
            sibling_value.push(if !smooth {
                siblings[i]
            } else if rep == own {
                next += 1;
                next - 1
            } else if (rep as usize) < n_values {
                rep
            } else {
                sibling_value[rep as usize - n_values]
            });
        }
        let mut uv = LayoutChannel {
            refinement,
            n_values,
            n_repeated: n_values + siblings.len() - next as usize,
            siblings,
            sibling_value,
            merged: None,
            n_last: 0,
            written_corners: None,
        };
        let holes = crate::holes::active(opts.holes, rule, mesh.n_faces())?;
        uv.number_last(mesh, rule, levels, holes)?;
        Ok(uv)
    }

    /// Numbers the last level's written values: siblings merged, values only holes use left
    /// out.
    pub(super) fn number_last(
        &mut self,
        mesh: &HalfEdgeMesh,
        rule: Rule,
        levels: u32,
        holes: Option<&crate::holes::HoleSet>,
    ) -> Result<()> {
        let r = &self.refinement;
        let nv = r.n_vertices(levels);
        let extra = if levels == 0 {
            self.siblings.len()
        } else {
            self.n_repeated
        };
        if extra == 0 && holes.is_none() {
            self.n_last = if levels == 0 { self.n_values } else { nv };
            return Ok(());
        }
        let n0 = r.n_vertices(0);
        // Channel vertex -> value with repeated runs merged (vertex children keep their
        // index): at level 0 the layout's values, after it OpenSubdiv's.
        let merge = |k: usize| -> usize {
            if k < self.n_values {
                k
            } else if k < n0 {
                let i = k - self.n_values;
                if levels == 0 {
                    self.siblings[i] as usize
                } else {
                    self.sibling_value[i] as usize
                }
            } else {
                k - extra
            }
        };
        let nc = r.n_corners(levels);
        let mut corners = crate::subdivide::alloc::filled(0u32, nc, "uv corners")?;
        r.write_corners(&mut corners)?;
        let mut merged = crate::subdivide::alloc::filled(INVALID, nv, "uv numbering")?;
        let mut written_corners = None;
        let mut count = 0u32;
        match holes {
            None => {
                // Every merged value is written, in order.
                for (k, m) in merged.iter_mut().enumerate() {
                    *m = merge(k) as u32;
                }
                count = (nv - extra) as u32;
            }
            Some(holes) => {
                let degrees = crate::holes::degrees_of(mesh);
                let mask = holes.written_at(rule, &degrees, levels)?;
                let offsets = self.face_offsets(levels, nc)?;
                let mut by_value = vec![INVALID; nv - extra];
                let mut out = Vec::new();
                for (f, w) in offsets.windows(2).enumerate() {
                    if !mask.get(f).copied().unwrap_or(false) {
                        continue;
                    }
                    for &k in &corners[w[0] as usize..w[1] as usize] {
                        let m = merge(k as usize);
                        if by_value[m] == INVALID {
                            by_value[m] = count;
                            count += 1;
                        }
                        merged[k as usize] = by_value[m];
                        out.push(by_value[m]);
                    }
                }
                // Channel vertices not written but merged with a written one carry its value.
                for k in 0..nv {
                    if merged[k] == INVALID {
                        merged[k] = by_value[merge(k)];
                    }
                }
                out.shrink_to_fit();
                written_corners = Some(out);
            }
        }
        self.n_last = count as usize;
        self.merged = Some(merged);
        self.written_corners = written_corners;
        Ok(())
    }

    /// The face offsets of the channel's last level (`nc` corners).
    pub(super) fn face_offsets(&self, levels: u32, nc: usize) -> Result<Vec<u32>> {
        let r = &self.refinement;
        let nf = r.n_faces(levels);
        let mut offsets = vec![0u32; nf + 1];
        let mut indices = vec![0u32; nc];
        r.write_polygons(&mut offsets, &mut indices)?;
        Ok(offsets)
    }

    /// The UV values of level `level`.
    pub(crate) fn n_uvs(&self, level: u32) -> usize {
        let levels = self.refinement.levels;
        if level > levels {
            0
        } else if level == levels {
            self.n_last
        } else if level == 0 {
            self.n_values
        } else {
            self.refinement.n_vertices(level) - self.n_repeated
        }
    }

    pub(crate) fn heap_bytes(&self) -> usize {
        self.refinement.heap_bytes()
            + 8 * self.siblings.len()
            + self.merged.as_ref().map_or(0, |m| 4 * m.len())
            + self.written_corners.as_ref().map_or(0, |c| 4 * c.len())
    }

    pub(crate) fn evaluate<T: Scalar>(&self, base: &[[T; 2]], out: &mut [[T; 2]]) -> Result<()> {
        self.values(base, out, false)
    }

    /// The layout's values at the last level (`limit`: their limit, the layout's own limit
    /// masks, as `LimitFaceVarying`), numbered as written.
    pub(crate) fn values<T: Scalar>(
        &self,
        base: &[[T; 2]],
        out: &mut [[T; 2]],
        limit: bool,
    ) -> Result<()> {
        let r = &self.refinement;
        let levels = r.levels;
        check_len("uv base", self.n_values, base.len())?;
        check_len("uv out", self.n_uvs(levels), out.len())?;
        let extended;
        let input = if self.siblings.is_empty() {
            base
        } else {
            let mut e = crate::subdivide::alloc::with_capacity(r.n_vertices(0), "uv base")?;
            e.extend_from_slice(base);
            e.extend(self.siblings.iter().map(|&s| base[s as usize]));
            extended = e;
            &extended[..]
        };
        if limit {
            r.limit_table()?;
        }
        let refine = |dst: &mut [[T; 2]]| match limit {
            true => r.evaluate_limit(input, dst, None),
            false => r.evaluate(input, dst),
        };
        match &self.merged {
            None if levels == 0 && !limit => out.copy_from_slice(input),
            None => refine(out)?,
            Some(merged) => {
                let mut full = crate::subdivide::alloc::filled(
                    [T::ZERO; 2],
                    r.n_vertices(levels),
                    "uv level",
                )?;
                if levels == 0 && !limit {
                    full.copy_from_slice(input);
                } else {
                    refine(&mut full)?;
                }
                for (&m, x) in merged.iter().zip(&full) {
                    if let Some(o) = out.get_mut(m as usize) {
                        *o = *x;
                    }
                }
            }
        }
        Ok(())
    }

    pub(crate) fn write_indices(&self, out: &mut [u32], expected: usize) -> Result<()> {
        check_len("uv indices", expected, out.len())?;
        if let Some(written) = &self.written_corners {
            out.copy_from_slice(written);
            return Ok(());
        }
        self.refinement.write_corners(out)?;
        if let Some(merged) = &self.merged {
            for k in out.iter_mut() {
                *k = merged[*k as usize];
            }
        }
        Ok(())
    }
}
