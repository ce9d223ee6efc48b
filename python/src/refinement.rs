//! `subcount.Refinement`: refine the topology once, evaluate many times (OpenSubdiv's
//! `TopologyRefiner` with `PrimvarRefiner::Interpolate`), through
//! `driver::subdivide::prepare` and `Prepared::refinement` (the checks, guards, options and
//! notes of `subdivide`); positions and UVs evaluated into numpy arrays, given (`out=`, written
//! in place) or allocated, with the GIL released; stencils as a SciPy sparse matrix.

use driver::refinement::KeptRefinement;
use halfedge::Refinement as Refined;
use std::sync::Mutex;

use halfedge::refine::Scratch;
use halfedge::Scalar;
use numpy::{Element, PyArray1, PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{attempt, entry, Failure, Result};
use crate::mesh::int32s;
use crate::options::RunOptions;

/// A mesh's topology refined once to a level, to evaluate positions (and UVs) many times:
/// an animation's frames, a deformer's output, without topology work per frame.
///
/// Refinement(mesh, *, scheme=None, levels, scheme_file=None, boundary=None,
/// crease_method=None, triangle_rule=None, uv_interpolation=None, ignore_tags=False, threads=0,
/// no_uv=False, allow_large=False, limit=False)
///
/// The keywords are subdivide()'s (no precision: evaluate() computes in the dtype of the
/// points it is given); limit=True also keeps the limit surface's masks (loop, catmull-clark:
/// evaluate_limit(), evaluate_uvs(limit=True)). Schemes that run on the raw face list (loop-general,
/// catmull-clark-general, tri-split-N or a non-manifold mesh) keep no refinement:
/// subcount.UsageError.
///
/// >>> cube = subcount.Mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1],
/// ...     [1, 1, 1], [0, 1, 1]], [4] * 6, [0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5,
/// ...     2, 3, 7, 6, 3, 0, 4, 7])
/// >>> r = subcount.Refinement(cube, scheme="catmull-clark", levels=2)
/// >>> r.n_vertices(), r.n_faces(), r.n_vertices(1)
/// (98, 96, 26)
/// >>> out = numpy.empty((r.n_vertices(), 3))
/// >>> _ = r.evaluate(cube.positions * 2.0, out=out)     # a frame, written into out
/// >>> bool(numpy.allclose(out, 2.0 * r.evaluate(cube.positions)))
/// True
/// >>> r.stencils().shape                                 # needs SciPy
/// (98, 8)
#[pyclass(module = "subcount", frozen)]
pub(crate) struct Refinement {
    kept: KeptRefinement,
    /// The vertices of the mesh (the columns of the stencils; rows of evaluate's points).
    n_mesh_vertices: usize,
    /// The memory guard is lifted (for the stencils too).
    allow_large: bool,
    /// The intermediate levels' buffers of the last evaluation, per precision (kept between
    /// frames: no allocation after the first; a concurrent call starts its own).
    scratch64: Mutex<Option<Scratch<f64, 3>>>,
    scratch32: Mutex<Option<Scratch<f32, 3>>>,
}

/// A precision whose evaluation buffers a [`Refinement`] keeps.
trait Kept: Scalar + Element {
    fn slot(r: &Refinement) -> &Mutex<Option<Scratch<Self, 3>>>;
}

impl Kept for f64 {
    fn slot(r: &Refinement) -> &Mutex<Option<Scratch<f64, 3>>> {
        &r.scratch64
    }
}

impl Kept for f32 {
    fn slot(r: &Refinement) -> &Mutex<Option<Scratch<f32, 3>>> {
        &r.scratch32
    }
}

#[pymethods]
impl Refinement {
    #[new]
    #[pyo3(
        signature = (mesh, *, scheme=None, levels, **options),
        text_signature = "(mesh, *, scheme=None, levels, scheme_file=None, boundary=None, crease_method=None, triangle_rule=None, uv_interpolation=None, ignore_tags=False, threads=0, no_uv=False, allow_large=False, limit=False)"
    )]
    fn new(
        py: Python<'_>,
        mesh: &Bound<'_, PyAny>,
        scheme: Option<String>,
        levels: &Bound<'_, PyAny>,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Refinement> {
        entry(py, || {
            let options = RunOptions::from_keywords(py, "Refinement", levels, options)?;
            let allow_large = options.allow_large;
            let run = options.prepared(py, mesh, scheme, |prepared, loaded, notes, _| {
                Ok(Refinement {
                    kept: prepared.refinement(notes)?,
                    n_mesh_vertices: loaded.poly.n_vertices(),
                    allow_large,
                    scratch64: Mutex::new(None),
                    scratch32: Mutex::new(None),
                })
            });
            run.map(|(refinement, _)| refinement)
        })
    }

    /// Whether the refinement keeps the limit surface (made with limit=True).
    #[getter]
    fn limit(&self, py: Python<'_>) -> PyResult<bool> {
        entry(py, || Ok(self.refined().has_limit()))
    }

    /// The last level.
    #[getter]
    fn levels(&self, py: Python<'_>) -> PyResult<u32> {
        entry(py, || Ok(self.refined().levels()))
    }

    /// The scheme as it counts what is written ("loop-boundary" for "loop" on an open mesh).
    #[getter]
    fn scheme(&self, py: Python<'_>) -> PyResult<String> {
        entry(py, || Ok(self.kept.scheme.clone()))
    }

    /// The vertices of a level (default: the last), those of holes included below the last.
    #[pyo3(signature = (level=None))]
    fn n_vertices(&self, py: Python<'_>, level: Option<&Bound<'_, PyAny>>) -> PyResult<usize> {
        entry(py, || Ok(self.refined().n_vertices(self.level(py, level)?)))
    }

    /// The faces of a level (default: the last; at the last, without holes).
    #[pyo3(signature = (level=None))]
    fn n_faces(&self, py: Python<'_>, level: Option<&Bound<'_, PyAny>>) -> PyResult<usize> {
        entry(py, || Ok(self.refined().n_faces(self.level(py, level)?)))
    }

    /// The UV values of a level (default: the last), 0 without UVs.
    #[pyo3(signature = (level=None))]
    fn n_uvs(&self, py: Python<'_>, level: Option<&Bound<'_, PyAny>>) -> PyResult<usize> {
        entry(py, || {
            let level = self.level(py, level)?;
            Ok(match self.refined().has_uvs() {
                true => self.refined().n_uvs(level),
                false => 0,
            })
        })
    }

    /// The last level's face sizes, int32.
    #[getter]
    fn face_vertex_counts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || {
            let (offsets, _) = self.faces().map_err(|f| f.into_pyerr(py))?;
            let counts: Vec<u32> = offsets.windows(2).map(|w| w[1] - w[0]).collect();
            int32s(py, &counts, "a face's corners")
        })
    }

    /// The last level's corners (vertex indices, face after face), int32.
    #[getter]
    fn face_vertex_indices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || {
            let (_, corners) = self.faces().map_err(|f| f.into_pyerr(py))?;
            int32s(py, &corners, "a vertex index")
        })
    }

    /// The UV value of each corner of the last level (indices into evaluate_uvs' rows),
    /// int32, or None without UVs.
    #[getter]
    fn uv_indices<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        entry(py, || {
            if !self.refined().has_uvs() {
                return Ok(None);
            }
            let refined = self.refined();
            let mut indices = vec![0u32; refined.n_corners(refined.levels())];
            let written = refined.write_uv_indices(&mut indices);
            written.map_err(|e| Failure::from(driver::Error::from(e)).into_pyerr(py))?;
            int32s(py, &indices, "a UV index").map(Some)
        })
    }

    /// The UV values evaluate_uvs() starts from by default (the mesh's texture coordinates,
    /// one per value of its UV layout), (K, 2) float64, or None without UVs.
    #[getter]
    fn base_uvs<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        entry(py, || {
            let Some(uvs) = &self.kept.base_uvs else {
                return Ok(None);
            };
            let flat: Vec<f64> = uvs.iter().flatten().copied().collect();
            Ok(Some(
                PyArray1::from_vec(py, flat)
                    .reshape([uvs.len(), 2])?
                    .into_any(),
            ))
        })
    }

    /// Evaluates the last level's positions from `points`, one row per vertex of the mesh
    /// ((N, 3), float64 or float32: computed in that type), into `out` when given (C-contiguous,
    /// writable, (n_vertices(), 3), the same dtype; written in place), else into a new array.
    /// Returns the array written. The GIL is released while it works.
    ///
    /// Raises subcount.InputError for a wrong shape, a non-finite value or an unfit out,
    /// TypeError for a non-numeric dtype or an out of another dtype.
    #[pyo3(signature = (points, out=None))]
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || self.points_of(py, (points, out), Stream::Positions))
    }

    /// Evaluates the last level's UV values from `uvs` ((K, 2), one per value of the UV
    /// layout, float64 or float32; default: base_uvs) into `out` as evaluate() does
    /// ((n_uvs(), 2)); uv_indices names the value of each corner; limit=True gives their limit
    /// instead (OpenSubdiv's LimitFaceVarying; the Refinement made with limit=True).
    /// subcount.UsageError without UVs (or without limit=True for their limit).
    #[pyo3(signature = (uvs=None, out=None, limit=false))]
    fn evaluate_uvs<'py>(
        &self,
        py: Python<'py>,
        uvs: Option<&Bound<'py, PyAny>>,
        out: Option<&Bound<'py, PyAny>>,
        limit: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || {
            if limit {
                attempt(|| self.require_limit()).map_err(|f| f.into_pyerr(py))?;
            }
            let stream = if limit { Stream::LimitUvs } else { Stream::Uvs };
            let work = || {
                let Some(base) = &self.kept.base_uvs else {
                    return Err(Failure::Usage(
                        "this refinement has no UVs (the mesh has none, no_uv=True, or the scheme has no face-varying rule)".into(),
                    ));
                };
                let default;
                let uvs = match uvs {
                    Some(uvs) => uvs,
                    None => {
                        default = self
                            .base_uvs(py)?
                            .unwrap_or_else(|| py.None().into_bound(py));
                        &default
                    }
                };
                let n_out = self.refined().n_uvs(self.refined().levels());
                let rows = (base.len(), "UV value of the layout");
                match is_float32(py, uvs, "uvs")? {
                    true => self.evaluate_in::<f32>(py, uvs, out, rows, n_out, stream),
                    false => self.evaluate_in::<f64>(py, uvs, out, rows, n_out, stream),
                }
            };
            attempt(work).map_err(|f| f.into_pyerr(py))
        })
    }

    /// The limit surface at the last level's vertices (OpenSubdiv's limit masks; the
    /// Refinement made with limit=True), from `points` as evaluate() takes them, into `out`
    /// as evaluate() writes it; with tangents=True, returns (positions, tangent1, tangent2),
    /// three (n_vertices(), 3) arrays (the tangents scaled as OpenSubdiv scales them; their
    /// cross product is the surface's normal). subcount.UsageError without limit=True.
    ///
    /// >>> quad = subcount.Mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [4], [0, 1, 2, 3])
    /// >>> r = subcount.Refinement(quad, scheme="catmull-clark", levels=1, limit=True)
    /// >>> p, t1, t2 = r.evaluate_limit(quad.positions, tangents=True)
    /// >>> p[8].tolist()                                      # the centre (the face's child) stays
    /// [0.5, 0.5, 0.0]
    /// >>> numpy.cross(t1[8], t2[8]).tolist()                 # the normal, up
    /// [0.0, 0.0, 30.25]
    #[pyo3(signature = (points, out=None, tangents=false))]
    fn evaluate_limit<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
        tangents: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || {
            attempt(|| self.require_limit()).map_err(|f| f.into_pyerr(py))?;
            self.points_of(py, (points, out), Stream::Limit(tangents))
        })
    }

    /// The last level's vertices as weighted sums of the mesh's vertices: a
    /// scipy.sparse.csr_array of shape (n_vertices(), N) (OpenSubdiv's StencilTable), so that
    /// `r.stencils() @ points` equals `r.evaluate(points)` up to rounding. Needs SciPy. Refused
    /// (subcount.ResourceError) beyond half the available memory unless the refinement was
    /// made with allow_large; the icosphere rule (not linear) has none (subcount.InputError).
    fn stencils<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || {
            let table = attempt(|| {
                let refined = self.refined();
                let sizes = refined.stencil_sizes().map_err(driver::Error::from)?;
                let available = driver::system::available_bytes();
                let limit = available.map_or(u128::MAX, |a| u128::from(a / 2));
                if sizes.bytes() > limit && !self.allow_large {
                    return Err(Failure::Resource(format!(
                        "the stencils need {} bytes, over half the available memory ({limit} bytes): make the Refinement with allow_large=True to lift the guard",
                        sizes.bytes()
                    )));
                }
                py.detach(|| refined.stencils().map_err(driver::Error::from))
                    .map_err(Failure::from)
            })
            .map_err(|f| f.into_pyerr(py))?;
            let columns: Vec<i64> = table
                .indices()
                .iter()
                .map(|&i| i64::from(self.kept.base_vertices[i as usize]))
                .collect();
            let offsets: Vec<i64> = table.offsets().iter().map(|&o| i64::from(o)).collect();
            let weights = PyArray1::from_slice(py, table.weights());
            let sparse = PyModule::import(py, "scipy.sparse")?;
            let shape = (table.len(), self.n_mesh_vertices);
            let parts = (
                weights,
                PyArray1::from_vec(py, columns),
                PyArray1::from_vec(py, offsets),
            );
            sparse.call_method1("csr_array", (parts, shape))
        })
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        entry(py, || {
            let r = self.refined();
            Ok(format!(
                "subcount.Refinement({}, levels={}: {} vertices, {} faces)",
                self.kept.scheme,
                r.levels(),
                r.n_vertices(r.levels()),
                r.n_faces(r.levels())
            ))
        })
    }
}

/// What an evaluation refines.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Stream {
    Positions,
    Uvs,
    /// The limit surface, with its tangents when `true`.
    Limit(bool),
    /// The limit of the UVs.
    LimitUvs,
}

impl Refinement {
    /// UsageError unless the refinement keeps the limit surface.
    fn require_limit(&self) -> Result<()> {
        match self.refined().has_limit() {
            true => Ok(()),
            false => Err(Failure::Usage(
                "this refinement has no limit surface: make it with limit=True".into(),
            )),
        }
    }

    /// evaluate() and evaluate_limit(): `stream` says which.
    fn points_of<'py>(
        &self,
        py: Python<'py>,
        (points, out): (&Bound<'py, PyAny>, Option<&Bound<'py, PyAny>>),
        stream: Stream,
    ) -> PyResult<Bound<'py, PyAny>> {
        let n_out = self.refined().n_vertices(self.refined().levels());
        let work = || {
            let rows = (self.n_mesh_vertices, "vertex of the mesh");
            match is_float32(py, points, "points")? {
                true => self.evaluate_in::<f32>(py, points, out, rows, n_out, stream),
                false => self.evaluate_in::<f64>(py, points, out, rows, n_out, stream),
            }
        };
        attempt(work).map_err(|f| f.into_pyerr(py))
    }

    fn refined(&self) -> &Refined {
        &self.kept.refinement
    }

    /// A level from 0 to the last (default: the last), or UsageError.
    fn level(&self, py: Python<'_>, level: Option<&Bound<'_, PyAny>>) -> PyResult<u32> {
        let last = self.refined().levels();
        let Some(level) = level else {
            return Ok(last);
        };
        let level = crate::whole_number(level, "level").map_err(|f| f.into_pyerr(py))?;
        match u32::try_from(level) {
            Ok(l) if l <= last => Ok(l),
            _ => Err(Failure::Usage(format!(
                "level {level} is not a level of the refinement (0 to {last})"
            ))
            .into_pyerr(py)),
        }
    }

    /// The last level's face offsets and corners (holes left out).
    fn faces(&self) -> Result<(Vec<u32>, Vec<u32>)> {
        let r = self.refined();
        let (faces, corners) = (r.n_faces(r.levels()), r.n_corners(r.levels()));
        let mut indices = vec![0u32; corners];
        let degree = r.face_degree().filter(|d| matches!(d, 3 | 4));
        let written = match degree {
            Some(3) => r.write_triangles(&mut indices),
            Some(_) => r.write_quads(&mut indices),
            None => {
                let mut offsets = vec![0u32; faces + 1];
                r.write_polygons(&mut offsets, &mut indices)
                    .map_err(driver::Error::from)?;
                return Ok((offsets, indices));
            }
        };
        written.map_err(driver::Error::from)?;
        let d = degree.unwrap_or(3) as u32;
        Ok(((0..=faces as u32).map(|f| f * d).collect(), indices))
    }

    /// Evaluates `stream` in `T` from `base` (`rows.0` rows, named `rows.1`) into `out` (or a
    /// new array of `n_out` rows).
    fn evaluate_in<'py, T: Kept>(
        &self,
        py: Python<'py>,
        base: &Bound<'py, PyAny>,
        out: Option<&Bound<'py, PyAny>>,
        rows: (usize, &str),
        n_out: usize,
        stream: Stream,
    ) -> Result<Bound<'py, PyAny>> {
        let (name, width) = match stream {
            Stream::Positions | Stream::Limit(_) => ("points", 3),
            Stream::Uvs | Stream::LimitUvs => ("uvs", 2),
        };
        let values = crate::arrays::float_table::<T>(py, base, name, width)?;
        if values.len() != rows.0 * width {
            return Err(Failure::Input(format!(
                "{name} has {} rows: expected one per {} ({} rows)",
                values.len() / width,
                rows.1,
                rows.0
            )));
        }
        // The refinement's base vertices are the mesh's vertices some face uses.
        let gathered: Vec<T>;
        let base: &[T] = match stream {
            Stream::Positions | Stream::Limit(_) if self.kept.base_vertices.len() != rows.0 => {
                let kept = self.kept.base_vertices.iter().map(|&v| v as usize * width);
                gathered = kept.flat_map(|i| values[i..i + width].to_vec()).collect();
                &gathered
            }
            _ => &values,
        };
        let array = match out {
            Some(out) => out_array::<T>(py, out, n_out, width)?,
            None => PyArray2::<T>::zeros(py, [n_out, width], false),
        };
        let tangents = match stream {
            Stream::Limit(true) => {
                Some([(); 2].map(|_| PyArray2::<T>::zeros(py, [n_out, 3], false)))
            }
            _ => None,
        };
        {
            let mut tangent_guards = tangents
                .as_ref()
                .map(|[a, b]| (a.readwrite(), b.readwrite()));
            let tangent_slices = match tangent_guards.as_mut() {
                Some((a, b)) => Some((
                    a.as_slice_mut()
                        .map_err(|e| Failure::Input(e.to_string()))?,
                    b.as_slice_mut()
                        .map_err(|e| Failure::Input(e.to_string()))?,
                )),
                None => None,
            };
            let mut guard = array
                .try_readwrite()
                .map_err(|e| Failure::Input(format!("out cannot be written: {e}")))?;
            let slice = guard
                .as_slice_mut()
                .map_err(|e| Failure::Input(format!("out is not C-contiguous: {e}")))?;
            let refined = self.refined();
            py.detach(|| match stream {
                Stream::Positions | Stream::Limit(_) => {
                    // Rows of 3 in place (no packed copy of the input or the output), through
                    // the buffers the last evaluation kept.
                    let (rows, _) = base.as_chunks::<3>();
                    let (out_rows, _) = slice.as_chunks_mut::<3>();
                    let slot = T::slot(self);
                    let kept = slot.lock().map_or(None, |mut s| s.take());
                    let mut evaluator = refined.evaluator_with(kept.unwrap_or_default());
                    let done = match stream {
                        Stream::Limit(_) => {
                            let tangents = tangent_slices
                                .map(|(a, b)| (a.as_chunks_mut::<3>().0, b.as_chunks_mut::<3>().0));
                            evaluator.evaluate_limit(rows, out_rows, tangents)
                        }
                        _ => evaluator.evaluate(rows, out_rows),
                    };
                    if let Ok(mut s) = slot.lock() {
                        *s = Some(evaluator.into_scratch());
                    }
                    done
                }
                Stream::Uvs | Stream::LimitUvs => {
                    let pairs: Vec<[T; 2]> = base.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
                    let mut result = vec![[T::ZERO; 2]; n_out];
                    let done = match stream {
                        Stream::LimitUvs => refined.evaluate_limit_uvs(&pairs, &mut result),
                        _ => refined.evaluate_uvs(&pairs, &mut result),
                    };
                    for (dst, src) in slice.chunks_exact_mut(2).zip(&result) {
                        dst.copy_from_slice(src);
                    }
                    done
                }
            })
            .map_err(driver::Error::from)?;
        }
        match tangents {
            Some([a, b]) => Ok((array, a, b).into_pyobject(py)?.into_any()),
            None => Ok(array.into_any()),
        }
    }
}

/// Whether `array`'s dtype is float32 (everything else numeric evaluates in float64).
fn is_float32(py: Python<'_>, array: &Bound<'_, PyAny>, name: &str) -> Result<bool> {
    let numpy = PyModule::import(py, "numpy")?;
    let array = crate::arrays::as_array(py, array, name, "fiu", "numbers")?;
    Ok(array.getattr("dtype")?.eq(numpy.getattr("float32")?)?)
}

/// The caller's `out`: a writable, C-contiguous `T` array of shape `(n, width)`.
fn out_array<'py, T: Element>(
    py: Python<'py>,
    out: &Bound<'py, PyAny>,
    n: usize,
    width: usize,
) -> Result<Bound<'py, PyArray2<T>>> {
    let dtype = numpy::dtype::<T>(py);
    let array = out.cast::<PyArray2<T>>().map_err(|_| {
        let what = out
            .getattr("dtype")
            .and_then(|d| d.str().map(|s| s.to_string()))
            .unwrap_or_else(|_| out.get_type().to_string());
        let shape = out
            .getattr("shape")
            .map_or(String::new(), |s| s.to_string());
        match out.getattr("ndim").and_then(|d| d.extract::<usize>()) {
            Ok(2) => Failure::Type(format!("out must be a {dtype} array, not {what}")),
            Ok(_) => Failure::Input(format!("out has shape {shape}: expected ({n}, {width})")),
            Err(_) => Failure::Type(format!("out must be a numpy array, not {what}")),
        }
    })?;
    let shape = array.shape();
    if shape != [n, width] {
        return Err(Failure::Input(format!(
            "out has shape ({}, {}): expected ({n}, {width})",
            shape[0], shape[1]
        )));
    }
    if !array.is_c_contiguous() {
        return Err(Failure::Input(
            "out is not C-contiguous: pass numpy.empty(...) or an ascontiguousarray".into(),
        ));
    }
    Ok(array.clone())
}
