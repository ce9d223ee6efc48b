//! Refine once, evaluate many (`subdivide --precision f32`, `--frames N`): the topology refined once
//! ([`halfedge::Refinement`]), positions evaluated into caller-owned buffers, in `f32` or
//! `f64`, once or once per frame; with a UV layout ([`SubdivideOptions::uvs`]) the UVs
//! refined by the same refinement, evaluated into caller-owned buffers and written.

use std::any::type_name;
use std::path::Path;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use halfedge::glam::{DVec2, DVec3};
use halfedge::io::{FaceBuffers, MeshBuffers, ObjWriteOptions, UvBuffers};
use halfedge::subdivide::{LevelDone, SubdivideOptions};
use halfedge::uv::Uvs;
use halfedge::{HalfEdgeMesh, PolygonMesh, Refinement, Rule, Scalar};

/// The floating-point type a refine-once run computes and writes positions and UVs in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Precision {
    /// `f32`.
    F32,
    /// `f64` (the default).
    #[default]
    F64,
}

impl Precision {
    /// Bytes per coordinate.
    pub fn bytes(self) -> usize {
        match self {
            Precision::F32 => 4,
            Precision::F64 => 8,
        }
    }
}

/// The last level's buffers, in `f32` or `f64`.
#[derive(Debug)]
enum LevelBuffers {
    F32(Buffers<f32>),
    F64(Buffers<f64>),
}

/// Two per-vertex buffers: the limit tangents.
type Pair<T> = (Vec<[T; 3]>, Vec<[T; 3]>);

/// The buffers a refine-once run evaluated into: positions, faces (of one degree, or with
/// offsets), UVs, colors and groups.
#[derive(Debug)]
struct Buffers<T> {
    positions: Vec<[T; 3]>,
    /// The faces' degree (3 or 4), `None` for polygons with `offsets`.
    degree: Option<usize>,
    offsets: Vec<u32>,
    indices: Vec<u32>,
    /// UV values and one per corner.
    uvs: Option<(Vec<[T; 2]>, Vec<u32>)>,
    colors: Option<Vec<[T; 3]>>,
    groups: Option<halfedge::groups::FaceGroups>,
    /// The limit tangents, when the normals written are the limit surface's.
    tangents: Option<Pair<T>>,
    /// The rule and level, for messages.
    scheme: String,
    level: u32,
}

impl<T: Scalar> Buffers<T> {
    fn faces(&self) -> FaceBuffers<'_> {
        match self.degree {
            Some(degree) => FaceBuffers::Uniform {
                degree,
                indices: &self.indices,
            },
            None => FaceBuffers::Polygons {
                offsets: &self.offsets,
                indices: &self.indices,
            },
        }
    }

    fn write(&self, path: &Path, options: &ObjWriteOptions) -> crate::Result<()> {
        let mut mesh = MeshBuffers::new(&self.positions, self.faces());
        if let Some((values, corners)) = &self.uvs {
            mesh = mesh.with_uvs(UvBuffers { values, corners });
        }
        if let Some(colors) = &self.colors {
            mesh = mesh.with_colors(colors);
        }
        if let Some(groups) = &self.groups {
            mesh = mesh.with_groups(groups);
        }
        if let Some((first, second)) = &self.tangents {
            mesh = mesh.with_tangents(first, second);
        }
        crate::output::write_mesh_buffers_file(&mesh, path, options)
    }

    /// The buffers as a face list, values widened to `f64` (exactly).
    fn into_polygon_mesh(self) -> halfedge::Result<PolygonMesh> {
        let invalid = |what: String| halfedge::Error::InvalidOutput {
            scheme: self.scheme.clone(),
            level: self.level,
            what,
        };
        let widen3 = |v: &[T; 3]| DVec3::from_array(v.map(T::to_f64));
        let mut mesh = PolygonMesh::with_positions(self.positions.iter().map(widen3).collect());
        match self.degree {
            Some(degree) => {
                mesh.reserve_faces(self.indices.len() / degree.max(1), self.indices.len());
                for face in self.indices.chunks(degree.max(1)) {
                    mesh.push_face(face);
                }
            }
            None => {
                mesh.reserve_faces(self.offsets.len().saturating_sub(1), self.indices.len());
                for w in self.offsets.windows(2) {
                    mesh.push_face(&self.indices[w[0] as usize..w[1] as usize]);
                }
            }
        }
        if let Some((values, corners)) = self.uvs {
            let values = values
                .iter()
                .map(|v| DVec2::new(v[0].to_f64(), v[1].to_f64()))
                .collect();
            let uvs = Uvs::new(values, corners).map_err(|e| invalid(e.to_string()))?;
            mesh.set_uvs(Some(uvs))
                .map_err(|e| invalid(e.to_string()))?;
        }
        if let Some(colors) = self.colors {
            let colors = colors.iter().map(|c| c.map(T::to_f64)).collect();
            mesh.set_colors(Some(colors))
                .map_err(|e| invalid(e.to_string()))?;
        }
        mesh.set_groups(self.groups)
            .map_err(|e| invalid(e.to_string()))?;
        Ok(mesh)
    }
}

/// What a refine-once run produced and measured.
#[derive(Debug)]
pub struct Refined {
    /// `[V, E, F]` of the last level.
    pub vef: [usize; 3],
    /// Building the topology.
    pub refine_topology: Duration,
    /// The first evaluation (of the unmoved base positions: what `-o` writes).
    pub first_evaluation: Duration,
    /// The median of the per-frame evaluations (`None` without frames).
    pub evaluate_median: Option<Duration>,
    /// With UVs: the UV values of the last level, the time the channel's topology took
    /// (part of `refine_topology`, after the surface's: [`SurfaceClock`]) and the time of
    /// their evaluation and index buffer.
    pub uvs: Option<(usize, Duration, Duration)>,
    /// The last level.
    level: LevelBuffers,
}

impl Refined {
    /// Writes the last level (atomically, through [`crate::output::write_atomically`]), its
    /// UVs when they were refined and `options` asks for them, normals when it asks.
    ///
    /// # Errors
    ///
    /// As [`crate::output::write_buffers_obj_file`].
    pub fn write(&self, path: &Path, options: &ObjWriteOptions) -> crate::Result<()> {
        match &self.level {
            LevelBuffers::F32(b) => b.write(path, options),
            LevelBuffers::F64(b) => b.write(path, options),
        }
    }

    /// The last level as a face list (positions, faces, UVs, colors, groups), `f32` values
    /// widened to `f64` exactly: what [`Refined::write`] writes.
    ///
    /// # Errors
    ///
    /// [`halfedge::Error::InvalidOutput`] for buffers that do not fit together (a bug).
    pub fn into_polygon_mesh(self) -> halfedge::Result<PolygonMesh> {
        match self.level {
            LevelBuffers::F32(b) => b.into_polygon_mesh(),
            LevelBuffers::F64(b) => b.into_polygon_mesh(),
        }
    }
}

/// A refine-once run: what to refine, and how.
#[derive(Clone, Copy, Debug)]
pub struct RefineOnce<'a> {
    /// The mesh.
    pub mesh: &'a HalfEdgeMesh,
    /// Its rule.
    pub rule: Rule,
    /// The last level.
    pub levels: u32,
    /// Evaluations after the first, from moved base positions (timed).
    pub frames: u32,
    /// The refinement's options (threads, creases, holes, UVs).
    pub opts: &'a SubdivideOptions<'a>,
    /// Splits the surface's time from the UVs'.
    pub clock: &'a SurfaceClock,
    /// At level 0, the UVs to write (the file's, as read) in place of the layout's values.
    pub as_read: Option<&'a halfedge::uv::Uvs>,
    /// A color per vertex of the mesh, refined with the positions' weights (under the
    /// icosphere rule the midpoint rule's: the weights before the projection).
    pub colors: Option<&'a [[f64; 3]]>,
    /// The groups of the mesh's faces, given to each output face from its base face.
    pub groups: Option<&'a halfedge::groups::FaceGroups>,
    /// Write the limit surface (positions, colors, UVs) in place of the last level's points.
    pub limit: bool,
    /// Keep the limit tangents, for the normals written.
    pub limit_normals: bool,
}

/// Refines `run.mesh` by its rule to its last level once, evaluates its positions in
/// `precision`, then `run.frames` more times from moved base positions (timed; the output
/// keeps the first, unmoved evaluation).
///
/// # Errors
///
/// The refinement's and the evaluation's errors; a position or UV beyond the range of the
/// precision.
pub fn run(run: &RefineOnce<'_>, precision: Precision) -> halfedge::Result<Refined> {
    match precision {
        Precision::F32 => run_in::<f32>(run, LevelBuffers::F32),
        Precision::F64 => run_in::<f64>(run, LevelBuffers::F64),
    }
}

/// When the surface's last level was built: a refinement (and a one-shot subdivision) with
/// UVs reports the surface's levels to the progress callback, then its face-varying channel's,
/// so the first report of the last level splits the surface's work from the UVs'.
#[derive(Debug)]
pub struct SurfaceClock {
    levels: u32,
    done: Mutex<Option<Instant>>,
}

impl SurfaceClock {
    /// A clock for a run to `levels`.
    pub fn new(levels: u32) -> SurfaceClock {
        SurfaceClock {
            levels,
            done: Mutex::new(None),
        }
    }

    /// Records a progress report; `true` while it is the surface's (the channel's reports
    /// come after its last level).
    pub fn report(&self, done: &LevelDone) -> bool {
        let mut slot = self.done.lock().unwrap_or_else(|e| e.into_inner());
        if slot.is_some() {
            return false;
        }
        if done.level == self.levels {
            *slot = Some(Instant::now());
        }
        true
    }

    /// The time from the surface's last level (or from `start`, at level 0, which reports
    /// nothing) to `end`.
    pub fn since_surface(&self, start: Instant, end: Instant) -> Duration {
        let done = *self.done.lock().unwrap_or_else(|e| e.into_inner());
        end.saturating_duration_since(done.unwrap_or(start))
    }
}

/// `keep` stores the last level's buffers in `T`.
fn run_in<T: Scalar>(
    run: &RefineOnce<'_>,
    keep: fn(Buffers<T>) -> LevelBuffers,
) -> halfedge::Result<Refined> {
    let RefineOnce {
        mesh,
        rule,
        levels,
        frames,
        opts,
        clock,
        as_read,
        colors,
        groups,
        limit,
        limit_normals,
    } = *run;
    let t0 = Instant::now();
    let with_limit = opts.with_limit(limit || limit_normals);
    let refinement = Refinement::new(mesh, rule, levels, &with_limit)?;
    let built = Instant::now();
    let refine_topology = built - t0;
    let uv_topology = clock.since_surface(t0, built);
    let (n, faces, corners) = (
        refinement.n_vertices(levels),
        refinement.n_faces(levels),
        refinement.n_corners(levels),
    );
    let degree = refinement.face_degree().filter(|d| matches!(d, 3 | 4));
    let mut indices = vec![0u32; corners];
    let mut offsets = Vec::new();
    match degree {
        Some(3) => refinement.write_triangles(&mut indices)?,
        Some(_) => refinement.write_quads(&mut indices)?,
        None => {
            offsets = vec![0u32; faces + 1];
            refinement.write_polygons(&mut offsets, &mut indices)?;
        }
    }
    let base: Vec<[T; 3]> = mesh
        .positions()
        .iter()
        .map(|p| p.to_array().map(T::from_f64))
        .collect();
    if let Some(v) = base
        .iter()
        .position(|p| p.iter().any(|x| !x.to_f64().is_finite()))
    {
        let p = mesh.positions()[v];
        return Err(halfedge::Error::NonFinitePosition {
            scheme: rule.to_string(),
            level: 0,
            vertex: v as u32,
            origin: format!(
                "the input vertex, beyond the range of {}",
                std::any::type_name::<T>()
            ),
            x: p.x,
            y: p.y,
            z: p.z,
        });
    }
    let mut evaluator = refinement.evaluator::<T, 3>();
    let mut out = vec![[T::ZERO; 3]; n];
    let t = Instant::now();
    // The limit surface's tangents, when its normals are written; its positions in place of
    // the last level's with `limit`.
    let mut tangents = limit_normals.then(|| (vec![[T::ZERO; 3]; n], vec![[T::ZERO; 3]; n]));
    if limit {
        evaluator.evaluate_limit(&base, &mut out, pair(&mut tangents))?;
    } else {
        if limit_normals {
            // The last level's points and the limit's tangents from one refinement.
            let mut position = vec![[T::ZERO; 3]; n];
            let tangents = pair(&mut tangents);
            evaluator.evaluate_with_limit(&base, &mut out, &mut position, tangents)?;
        } else {
            evaluator.evaluate(&base, &mut out)?;
        }
    }
    let first_evaluation = t.elapsed();
    refuse_non_finite(&out, rule, levels)?;
    // The UVs: refined by the same refinement into caller-owned buffers.
    let uvs = match opts.uvs.filter(|_| refinement.has_uvs()) {
        Some(layout) => {
            let t = Instant::now();
            let base: Vec<[T; 2]> = layout
                .values()
                .iter()
                .map(|v| [T::from_f64(v.x), T::from_f64(v.y)])
                .collect();
            // A `vt` beyond the range of `T` (1e39 in `f32`), or sums that overflow: refused
            // before anything is written, as positions are.
            let scheme = rule.to_string();
            let beyond = format!("the input value, beyond the range of {}", type_name::<T>());
            halfedge::subdivide::check_uvs(&scheme, 0, &base, &beyond)?;
            let mut values = vec![[T::ZERO; 2]; refinement.n_uvs(levels)];
            match limit {
                true => refinement.evaluate_limit_uvs(&base, &mut values)?,
                false => refinement.evaluate_uvs(&base, &mut values)?,
            }
            let computed = format!("computed in {}", type_name::<T>());
            halfedge::subdivide::check_uvs(&scheme, levels, &values, &computed)?;
            let mut corners = vec![0u32; refinement.n_corners(levels)];
            refinement.write_uv_indices(&mut corners)?;
            // Level 0 writes the file's UVs as read, except their limit.
            if let Some(read) = as_read.filter(|_| !limit) {
                if read.corners().len() != corners.len() {
                    return Err(halfedge::Error::UvLayoutMismatch {
                        reason: format!(
                            "{} texture-coordinate corners for {} written corners at level 0",
                            read.corners().len(),
                            corners.len()
                        ),
                    });
                }
                values = read
                    .coords()
                    .iter()
                    .map(|v| [T::from_f64(v.x), T::from_f64(v.y)])
                    .collect();
                corners.copy_from_slice(read.corners());
            }
            Some((values, corners, t.elapsed()))
        }
        None => None,
    };
    let colors = match colors {
        Some(base) => Some(refined_colors::<T>(&refinement, run, base)?),
        None => None,
    };
    let groups = match groups {
        Some(groups) => {
            let base = refinement.base_faces(levels)?;
            let groups =
                groups
                    .of_base_faces(base)
                    .map_err(|e| halfedge::Error::InvalidOutput {
                        scheme: rule.to_string(),
                        level: levels,
                        what: e.to_string(),
                    })?;
            Some(groups)
        }
        None => None,
    };
    let evaluate_median = (frames > 0).then(|| -> halfedge::Result<Duration> {
        // The frames' own tangents: the ones written are the unmoved evaluation's.
        let mut frame_tangents =
            (limit && limit_normals).then(|| (vec![[T::ZERO; 3]; n], vec![[T::ZERO; 3]; n]));
        let (mut moved, mut scratch) = (base.clone(), vec![[T::ZERO; 3]; n]);
        let step = perturbation_step(mesh);
        let mut times = Vec::with_capacity(frames as usize);
        for frame in 1..=frames {
            // Cycled, so the base never drifts more than 64 steps from where it was.
            perturb(&base, &mut moved, step * f64::from(frame % 64 + 1));
            let t = Instant::now();
            match limit {
                true => {
                    evaluator.evaluate_limit(&moved, &mut scratch, pair(&mut frame_tangents))?
                }
                false => evaluator.evaluate(&moved, &mut scratch)?,
            }
            times.push(t.elapsed());
        }
        times.sort();
        Ok(times[times.len() / 2])
    });
    let evaluate_median = evaluate_median.transpose()?;
    let uv_summary = uvs
        .as_ref()
        .map(|(values, _, time)| (values.len(), uv_topology, *time));
    let buffers = Buffers {
        positions: out,
        degree,
        offsets,
        indices,
        uvs: uvs.map(|(values, corners, _)| (values, corners)),
        colors,
        groups,
        tangents,
        scheme: rule.to_string(),
        level: levels,
    };
    Ok(Refined {
        vef: [n, refinement.n_edges(levels), faces],
        refine_topology,
        first_evaluation,
        evaluate_median,
        uvs: uv_summary,
        level: keep(buffers),
    })
}

/// The two buffers of `tangents` as the mutable slices an evaluation writes.
fn pair<T: Scalar>(
    tangents: &mut Option<Pair<T>>,
) -> Option<halfedge::refine::TangentBuffersMut<'_, T, 3>> {
    tangents
        .as_mut()
        .map(|(a, b)| (a.as_mut_slice(), b.as_mut_slice()))
}

/// The colors of the last level: `base` (one per vertex of the mesh) refined with the
/// positions' weights ([`Refinement::evaluate_attributes`]: under the icosphere rule those
/// before the projection onto the sphere); refused as positions are when not finite.
fn refined_colors<T: Scalar>(
    refinement: &Refinement,
    run: &RefineOnce<'_>,
    base: &[[f64; 3]],
) -> halfedge::Result<Vec<[T; 3]>> {
    let levels = run.levels;
    let base: Vec<[T; 3]> = base.iter().map(|c| c.map(T::from_f64)).collect();
    let mut out = vec![[T::ZERO; 3]; refinement.n_vertices(levels)];
    match run.limit {
        // The limit of the colors: the positions' limit masks (affine: an affine color field
        // stays the same function of the limit positions).
        true => refinement.evaluate_limit(&base, &mut out, None)?,
        false => refinement.evaluate_attributes(run.mesh, &base, &mut out)?,
    }
    let origin = format!("computed in {}", type_name::<T>());
    halfedge::subdivide::check_colors((&run.rule.to_string(), levels), &out, &origin)?;
    Ok(out)
}

/// The refinement does not check finiteness (the one-shot path does): an `f32` evaluation
/// near `f32::MAX` overflows. Refused as the one-shot path refuses it, naming the vertex.
fn refuse_non_finite<T: Scalar>(out: &[[T; 3]], rule: Rule, levels: u32) -> halfedge::Result<()> {
    match out
        .iter()
        .position(|p| p.iter().any(|x| !x.to_f64().is_finite()))
    {
        None => Ok(()),
        Some(v) => {
            let [x, y, z] = out[v].map(T::to_f64);
            Err(halfedge::Error::NonFinitePosition {
                scheme: rule.to_string(),
                level: levels,
                vertex: v as u32,
                origin: format!("computed in {}", std::any::type_name::<T>()),
                x,
                y,
                z,
            })
        }
    }
}

/// A millionth of the base mesh's bounding-box diagonal: small, but it changes every
/// coordinate, so no frame can reuse another's result.
fn perturbation_step(mesh: &HalfEdgeMesh) -> f64 {
    let (lo, hi) = mesh.positions().iter().fold(
        (DVec3::splat(f64::MAX), DVec3::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let diagonal = (hi - lo).length();
    if diagonal.is_finite() && diagonal > 0.0 {
        diagonal * 1e-6
    } else {
        1e-6
    }
}

/// `moved[i] = base[i] + amount * d(i)`, `d(i)` a fixed pseudo-random vector in `[-1/2, 1/2)^3`.
fn perturb<T: Scalar>(base: &[[T; 3]], moved: &mut [[T; 3]], amount: f64) {
    for (i, (b, m)) in base.iter().zip(moved.iter_mut()).enumerate() {
        for (k, (b, m)) in b.iter().zip(m.iter_mut()).enumerate() {
            let hash = (i as u64 * 3 + k as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 40;
            let d = hash as f64 / (1u64 << 24) as f64 - 0.5;
            *m = T::from_f64(b.to_f64() + amount * d);
        }
    }
}
