//! `subcount.Mesh`: a face list ([`PolygonMesh`]) with numpy arrays in and out (the checks of
//! the arrays a user hands over are `arrays.rs`'); `MeshArg`, a mesh argument.

use std::sync::{Arc, OnceLock};

use halfedge::glam::DVec3;
use halfedge::groups::{FaceGroups, Statement};
use halfedge::tags::Tags;
use halfedge::uv::Uvs;
use halfedge::{PolygonMesh, PolygonParts};
use numpy::{PyArray1, PyReadonlyArrayDyn};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString, PyTuple};

use crate::arrays::{Arrays, Faces};
use crate::errors::{attempt, entry, Failure, Result};
use crate::tags::{options_dict, TagArrays};

/// How messages name a mesh built from arrays (a file's mesh is named by its path).
pub(crate) const ARRAYS_LABEL: &str = "<mesh>";

/// A polygon mesh: vertex positions and faces (a face list, 0-based), with the texture
/// coordinates, vertex colors, materials and groups of its file.
///
/// Mesh(positions, face_vertex_counts, face_vertex_indices, *, uvs=None, uv_indices=None,
/// colors=None, crease_indices=None, crease_lengths=None, crease_sharpnesses=None,
/// corner_indices=None, corner_sharpnesses=None, hole_indices=None, options=None)
///
/// positions: (N, 3) numbers; face_vertex_counts: (F,) integers, each at least 3;
/// face_vertex_indices: one vertex index per corner, face after face; uvs: (K, 2) numbers and
/// uv_indices one index into uvs per corner (both or neither); colors: (N, 3) numbers.
/// A non-numeric dtype (or floats where indices go) raises TypeError; a wrong shape, a
/// non-finite value, a negative or out-of-range index, a face of fewer than 3 corners or an
/// empty mesh raises subcount.InputError naming the array and the index.
///
/// Creases, corners and holes go under USD's names (UsdGeom.Mesh): crease_indices holds
/// chains of vertices, crease_lengths the vertices of each chain (at least 2),
/// crease_sharpnesses one value per chain or one per edge; corner_indices and
/// corner_sharpnesses one per corner; hole_indices the faces that are holes. Sharpness 10 or
/// more is infinitely sharp, as in OpenSubdiv. options is the mesh's own subdivision options
/// (an OBJ file's tags): a dict with the keys "boundary", "crease_method", "triangle_rule",
/// "uv_interpolation" and the command line's names as values ("edge-and-corner", ...);
/// subdivide()'s keywords override them.
///
/// The array properties are read-only (numpy refuses to make them writable): a result's
/// float64 positions, face sizes and corners are the library's own buffers handed over, the
/// others copies made on the first access. positions (N, 3) float64 (float32 for a result
/// of subdivide(..., precision="f32"), as uvs and colors then), face_vertex_counts and
/// face_vertex_indices int32, uvs (K, 2) and uv_indices int32 or None, colors (N, 3) or None;
/// materials and groups: a str or None per face, or None when the mesh has none; mtllib: the
/// material files the OBJ file names; the tags read back under the same names (one 2-vertex
/// chain per crease edge, with its sharpness), and options as a dict of those set.
///
/// >>> m = subcount.Mesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [4], [0, 1, 2, 3],
/// ...                   crease_indices=[0, 1, 2], crease_lengths=[3], crease_sharpnesses=[2.0],
/// ...                   options={"boundary": "edge-and-corner"})
/// >>> m.crease_indices.tolist(), m.crease_sharpnesses.tolist(), m.options
/// ([0, 1, 1, 2], [2.0, 2.0], {'boundary': 'edge-and-corner'})
#[pyclass(module = "subcount", frozen)]
#[derive(Debug)]
pub(crate) struct Mesh {
    /// The face list and what it carries.
    store: Store,
    /// How messages name it: its file's path, or [`ARRAYS_LABEL`].
    pub(crate) label: String,
    /// The values were computed in `f32` (widened exactly): the arrays are float32.
    pub(crate) f32: bool,
    /// `subdivide(..., timings=True)`: the seconds of each part of the call.
    pub(crate) timings: Option<Vec<(&'static str, f64)>>,
    /// The arrays of `positions`, `face_vertex_counts` and `face_vertex_indices`, made on the
    /// first access (read-only, so shared by every later one).
    arrays: [OnceLock<Py<PyAny>>; 3],
}

/// Where a [`Mesh`] keeps its face list.
#[derive(Debug)]
enum Store {
    /// As the library's type (shared with it: handed over without a copy).
    Whole(Arc<PolygonMesh>),
    /// A result whose positions and corners numpy owns (moved, not copied: `Mesh::arrays`),
    /// the rest kept here; the whole face list is put back together (a copy of the arrays)
    /// when the library needs it again.
    Handed {
        /// Without positions, corners and face offsets (the counts' array holds the faces).
        rest: Box<PolygonParts>,
        n_vertices: usize,
        n_faces: usize,
        whole: OnceLock<Arc<PolygonMesh>>,
    },
}

#[pymethods]
impl Mesh {
    #[new]
    #[pyo3(signature = (
        positions, face_vertex_counts, face_vertex_indices, *, uvs=None, uv_indices=None,
        colors=None, crease_indices=None, crease_lengths=None, crease_sharpnesses=None,
        corner_indices=None, corner_sharpnesses=None, hole_indices=None, options=None
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        positions: &Bound<'_, PyAny>,
        face_vertex_counts: &Bound<'_, PyAny>,
        face_vertex_indices: &Bound<'_, PyAny>,
        uvs: Option<&Bound<'_, PyAny>>,
        uv_indices: Option<&Bound<'_, PyAny>>,
        colors: Option<&Bound<'_, PyAny>>,
        crease_indices: Option<&Bound<'_, PyAny>>,
        crease_lengths: Option<&Bound<'_, PyAny>>,
        crease_sharpnesses: Option<&Bound<'_, PyAny>>,
        corner_indices: Option<&Bound<'_, PyAny>>,
        corner_sharpnesses: Option<&Bound<'_, PyAny>>,
        hole_indices: Option<&Bound<'_, PyAny>>,
        options: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Mesh> {
        entry(py, || {
            let built = attempt(|| {
                let arrays = Arrays {
                    positions,
                    faces: Faces::Pair(face_vertex_counts, face_vertex_indices),
                    uvs: match (uvs, uv_indices) {
                        (Some(u), Some(i)) => Some((u, i)),
                        (None, None) => None,
                        _ => {
                            return Err(Failure::Usage(
                                "uvs and uv_indices go together: give both or neither".into(),
                            ))
                        }
                    },
                    colors,
                };
                let mut poly = arrays.polygon_mesh(py)?;
                let tags = TagArrays {
                    crease_indices,
                    crease_lengths,
                    crease_sharpnesses,
                    corner_indices,
                    corner_sharpnesses,
                    hole_indices,
                    options,
                };
                tags.apply(py, &mut poly)?;
                Ok(poly)
            });
            let poly = built.map_err(|f| f.into_pyerr(py))?;
            Ok(Mesh::from_arrays(poly))
        })
    }

    /// Vertex positions, (N, 3) float64 (float32 for an f32 result).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || {
            self.cached(py, 0, || match &self.store {
                Store::Whole(poly) if !self.f32 => {
                    // The same bytes, one copy.
                    let flat: &[f64] = bytemuck::cast_slice(&poly.positions);
                    let flat = read_only(PyArray1::from_slice(py, flat).into_any())?;
                    rows(&flat, poly.positions.len(), 3)
                }
                Store::Whole(poly) => {
                    let flat = poly.positions.iter().flat_map(|p| p.to_array());
                    self.floats(py, flat, 3)
                }
                Store::Handed { .. } => {
                    Err(Failure::Bug("a result's positions are made with it".into()).into_pyerr(py))
                }
            })
        })
    }

    /// The number of corners of each face, (F,) int32.
    #[getter]
    fn face_vertex_counts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || {
            self.cached(py, 1, || {
                // One pass into the array numpy takes (a face's corners fit i32: its corners are
                // a slice of the int32 corners).
                let Store::Whole(poly) = &self.store else {
                    return Err(
                        Failure::Bug("a result's counts are made with it".into()).into_pyerr(py)
                    );
                };
                let offsets = poly.face_offsets();
                let (ends, starts) = (&offsets[1..], &offsets[..offsets.len() - 1]);
                let counts: Vec<i32> = ends
                    .iter()
                    .zip(starts)
                    .map(|(&end, &start)| (end - start).min(i32::MAX as usize) as i32)
                    .collect();
                read_only(PyArray1::from_vec(py, counts).into_any())
            })
        })
    }

    /// The vertex of each corner, face after face, int32.
    #[getter]
    fn face_vertex_indices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || {
            self.cached(py, 2, || match &self.store {
                Store::Whole(poly) => int32s(py, poly.face_indices(), "a vertex index"),
                Store::Handed { .. } => {
                    Err(Failure::Bug("a result's corners are made with it".into()).into_pyerr(py))
                }
            })
        })
    }

    /// With `subdivide(..., timings=True)`: the seconds of each part of the call, a dict
    /// (`convert_s`: the arguments into the library's types, `load_s`: the mesh's checks and
    /// options, `prepare_s`: the scheme, the memory guard and the half-edge mesh,
    /// `subdivide_s`: the subdivision, `result_s`: the last level as a face list, `rust_s`: the
    /// library's whole call, freeing included); else None.
    #[getter]
    fn timings<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        entry(py, || {
            let Some(timings) = &self.timings else {
                return Ok(None);
            };
            let dict = PyDict::new(py);
            for (key, seconds) in timings {
                dict.set_item(key, seconds)?;
            }
            Ok(Some(dict))
        })
    }

    /// Texture coordinates, (K, 2), or None.
    #[getter]
    fn uvs<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        entry(py, || {
            let Some(uvs) = self.uvs_stored() else {
                return Ok(None);
            };
            let flat = uvs.coords().iter().flat_map(|v| v.to_array());
            self.floats(py, flat, 2).map(Some)
        })
    }

    /// The texture coordinate of each corner (an index into uvs), int32, or None.
    #[getter]
    fn uv_indices<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        entry(py, || {
            let Some(uvs) = self.uvs_stored() else {
                return Ok(None);
            };
            int32s(py, uvs.corners(), "a texture-coordinate index").map(Some)
        })
    }

    /// Vertex colors, (N, 3), or None.
    #[getter]
    fn colors<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        entry(py, || {
            let Some(colors) = self.colors_stored() else {
                return Ok(None);
            };
            self.floats(py, colors.iter().flatten().copied(), 3)
                .map(Some)
        })
    }

    /// Each face's material (`usemtl`), a str or None, or None when the mesh has none.
    #[getter]
    fn materials(&self, py: Python<'_>) -> PyResult<Option<Vec<Option<String>>>> {
        entry(py, || Ok(self.per_face(Statement::Material)))
    }

    /// Each face's groups (`g`, the names as written), a str or None, or None when the mesh
    /// has none.
    #[getter]
    fn groups(&self, py: Python<'_>) -> PyResult<Option<Vec<Option<String>>>> {
        entry(py, || Ok(self.per_face(Statement::Group)))
    }

    /// The material files the OBJ file names (`mtllib`), in file order.
    #[getter]
    fn mtllib(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        entry(py, || {
            let lines = self.groups_stored().map_or(&[][..], |g| g.mtllib());
            let names = lines.iter().flat_map(|line| {
                let rest = line.trim_start().strip_prefix("mtllib").unwrap_or(line);
                rest.split_whitespace().map(str::to_owned)
            });
            Ok(names.collect())
        })
    }

    /// The crease edges' vertices, one 2-vertex chain per edge (USD's creaseIndices), int32.
    #[getter]
    fn crease_indices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || self.tag_array(py, TagArray::CreaseIndices))
    }

    /// The vertices of each crease chain: 2 per crease edge (USD's creaseLengths), int32.
    #[getter]
    fn crease_lengths<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || self.tag_array(py, TagArray::CreaseLengths))
    }

    /// The sharpness of each crease edge (USD's creaseSharpnesses), float32.
    #[getter]
    fn crease_sharpnesses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || self.tag_array(py, TagArray::CreaseSharpnesses))
    }

    /// The corner vertices (USD's cornerIndices), int32.
    #[getter]
    fn corner_indices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || self.tag_array(py, TagArray::CornerIndices))
    }

    /// The sharpness of each corner (USD's cornerSharpnesses), float32.
    #[getter]
    fn corner_sharpnesses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || self.tag_array(py, TagArray::CornerSharpnesses))
    }

    /// The faces that are holes (USD's holeIndices), int32.
    #[getter]
    fn hole_indices<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        entry(py, || self.tag_array(py, TagArray::HoleIndices))
    }

    /// The mesh's own subdivision options (a file's tags), a dict of those it sets.
    #[getter]
    fn options<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        entry(py, || options_dict(py, self.tags_stored()))
    }

    /// The number of vertices.
    #[getter]
    fn n_vertices(&self, py: Python<'_>) -> PyResult<usize> {
        entry(py, || Ok(self.vertex_count()))
    }

    /// The number of faces.
    #[getter]
    fn n_faces(&self, py: Python<'_>) -> PyResult<usize> {
        entry(py, || Ok(self.face_count()))
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        entry(py, || {
            let mut extras = Vec::new();
            if let Some(uvs) = self.uvs_stored() {
                extras.push(format!(", {} uvs", uvs.coords().len()));
            }
            if self.colors_stored().is_some() {
                extras.push(", colors".to_owned());
            }
            if self.groups_stored().is_some() {
                extras.push(", groups".to_owned());
            }
            if !self.tags_stored().is_empty() {
                extras.push(", tags".to_owned());
            }
            Ok(format!(
                "subcount.Mesh({} vertices, {} faces{})",
                self.vertex_count(),
                self.face_count(),
                extras.concat()
            ))
        })
    }
}

impl Mesh {
    /// A mesh built from arrays.
    pub(crate) fn from_arrays(poly: PolygonMesh) -> Mesh {
        Mesh::new_with(poly, ARRAYS_LABEL.to_owned(), false)
    }

    /// A mesh named `label` in messages, its values float32 when `f32`.
    pub(crate) fn new_with(poly: impl Into<Arc<PolygonMesh>>, label: String, f32: bool) -> Mesh {
        Mesh {
            store: Store::Whole(poly.into()),
            label,
            f32,
            timings: None,
            arrays: Default::default(),
        }
    }

    /// A result: its positions and corners handed to numpy without a copy (float64 results
    /// whose corners fit int32; others as [`Mesh::new_with`]).
    pub(crate) fn handing_over(
        py: Python<'_>,
        poly: PolygonMesh,
        label: String,
        f32: bool,
    ) -> PyResult<Mesh> {
        // The corners name vertices (the library's output): they fit int32 when the count does.
        let fits = poly.n_vertices() <= i32::MAX as usize;
        if f32 || !fits || std::mem::size_of::<usize>() != 8 {
            return Ok(Mesh::new_with(poly, label, f32));
        }
        let mut rest = poly.into_polygon_parts();
        let n_vertices = rest.positions.len();
        let n_faces = rest.face_offsets.len().saturating_sub(1);
        let positions =
            bytemuck::allocation::try_cast_vec::<DVec3, f64>(std::mem::take(&mut rest.positions));
        let corners =
            bytemuck::allocation::try_cast_vec::<u32, i32>(std::mem::take(&mut rest.face_indices));
        let (positions, corners) = match (positions, corners) {
            (Ok(p), Ok(c)) => (p, c),
            // The allocations do not fit the numpy types' (never for these types): copied.
            (p, c) => {
                rest.positions = bytemuck::allocation::cast_vec(
                    p.unwrap_or_else(|(_, v)| bytemuck::cast_slice(&v).to_vec()),
                );
                rest.face_indices = bytemuck::cast_slice(
                    &c.unwrap_or_else(|(_, v)| bytemuck::cast_slice(&v).to_vec()),
                )
                .to_vec();
                let poly = PolygonMesh::from_polygon_parts(rest)
                    .map_err(|e| Failure::Bug(e.to_string()).into_pyerr(py))?;
                return Ok(Mesh::new_with(poly, label, f32));
            }
        };
        // The face sizes are written over the face offsets' own buffer (no fresh memory), which
        // numpy then owns as uint64, seen as int32 through a view.
        let mut offsets = std::mem::take(&mut rest.face_offsets);
        sizes_over_offsets(&mut offsets);
        let sizes = bytemuck::allocation::try_cast_vec::<usize, u64>(offsets)
            .map_err(|_| Failure::Bug("usize is not 64-bit".into()).into_pyerr(py))?;
        let mesh = Mesh {
            store: Store::Handed {
                rest: Box::new(rest),
                n_vertices,
                n_faces,
                whole: OnceLock::new(),
            },
            label,
            f32,
            timings: None,
            arrays: Default::default(),
        };
        // The buffer's own array is made read-only before the view: numpy then refuses to
        // make either writable (the library reads them back, `Mesh::shared`).
        let flat = read_only(PyArray1::from_vec(py, positions).into_any())?;
        let positions = rows(&flat, n_vertices, 3)?;
        let corners = PyArray1::from_vec(py, corners).into_any();
        let sizes = read_only(PyArray1::from_vec(py, sizes).into_any())?;
        let slice = pyo3::types::PySlice::new(py, 0, n_faces as isize, 1);
        let counts = sizes.call_method1("view", ("int32",))?.get_item(slice)?;
        let _ = mesh.arrays[0].set(positions.unbind());
        let _ = mesh.arrays[1].set(read_only(counts)?.unbind());
        let _ = mesh.arrays[2].set(read_only(corners)?.unbind());
        Ok(mesh)
    }

    /// The face list as the library takes it (a result's put back together once, from its
    /// arrays).
    pub(crate) fn shared(&self, py: Python<'_>) -> Result<Arc<PolygonMesh>> {
        let (rest, whole) = match &self.store {
            Store::Whole(poly) => return Ok(Arc::clone(poly)),
            Store::Handed { rest, whole, .. } => (rest, whole),
        };
        if let Some(poly) = whole.get() {
            return Ok(Arc::clone(poly));
        }
        let array = |slot: usize| self.arrays[slot].get().map(|a| a.bind(py).clone());
        let (Some(positions), Some(counts), Some(corners)) = (array(0), array(1), array(2)) else {
            return Err(Failure::Bug("a result's arrays are missing".into()));
        };
        let positions: PyReadonlyArrayDyn<'_, f64> = positions.extract()?;
        let counts: PyReadonlyArrayDyn<'_, i32> = counts.extract()?;
        let corners: PyReadonlyArrayDyn<'_, i32> = corners.extract()?;
        let bug = |e: numpy::AsSliceError| Failure::Bug(e.to_string());
        let mut parts = PolygonParts::clone(rest);
        parts.positions = bytemuck::cast_slice(positions.as_slice().map_err(bug)?).to_vec();
        parts.face_indices = bytemuck::cast_slice(corners.as_slice().map_err(bug)?).to_vec();
        let counts = counts.as_slice().map_err(bug)?;
        parts.face_offsets = std::iter::once(0)
            .chain(counts.iter().scan(0usize, |end, &c| {
                *end += c as usize;
                Some(*end)
            }))
            .collect();
        let poly =
            PolygonMesh::from_polygon_parts(parts).map_err(|e| Failure::Bug(e.to_string()))?;
        Ok(Arc::clone(whole.get_or_init(|| Arc::new(poly))))
    }

    fn uvs_stored(&self) -> Option<&Uvs> {
        match &self.store {
            Store::Whole(poly) => poly.uvs(),
            Store::Handed { rest, .. } => rest.uvs.as_ref(),
        }
    }

    fn colors_stored(&self) -> Option<&[[f64; 3]]> {
        match &self.store {
            Store::Whole(poly) => poly.colors(),
            Store::Handed { rest, .. } => rest.colors.as_deref(),
        }
    }

    fn groups_stored(&self) -> Option<&FaceGroups> {
        match &self.store {
            Store::Whole(poly) => poly.groups(),
            Store::Handed { rest, .. } => rest.groups.as_ref(),
        }
    }

    /// One of the tags' arrays under USD's name (read back: one 2-vertex chain per crease
    /// edge, with its own sharpness).
    fn tag_array<'py>(&self, py: Python<'py>, array: TagArray) -> PyResult<Bound<'py, PyAny>> {
        let tags = self.tags_stored();
        let (creases, corners) = (tags.creases(), tags.corners());
        match array {
            TagArray::CreaseIndices => {
                let ends: Vec<u32> = creases.iter().flat_map(|c| [c.a, c.b]).collect();
                int32s(py, &ends, "a vertex index")
            }
            TagArray::CreaseLengths => int32s(py, &vec![2; creases.len()], "a crease length"),
            TagArray::CreaseSharpnesses => float32s(py, creases.iter().map(|c| c.sharpness)),
            TagArray::CornerIndices => {
                let vertices: Vec<u32> = corners.iter().map(|c| c.vertex).collect();
                int32s(py, &vertices, "a vertex index")
            }
            TagArray::CornerSharpnesses => float32s(py, corners.iter().map(|c| c.sharpness)),
            TagArray::HoleIndices => int32s(py, tags.holes(), "a face index"),
        }
    }

    fn tags_stored(&self) -> &Tags {
        match &self.store {
            Store::Whole(poly) => poly.tags(),
            Store::Handed { rest, .. } => &rest.tags,
        }
    }

    fn vertex_count(&self) -> usize {
        match &self.store {
            Store::Whole(poly) => poly.n_vertices(),
            Store::Handed { n_vertices, .. } => *n_vertices,
        }
    }

    fn face_count(&self) -> usize {
        match &self.store {
            Store::Whole(poly) => poly.n_faces(),
            Store::Handed { n_faces, .. } => *n_faces,
        }
    }

    /// Array `slot`, made by `make` on the first access.
    fn cached<'py>(
        &self,
        py: Python<'py>,
        slot: usize,
        make: impl FnOnce() -> PyResult<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        if let Some(array) = self.arrays[slot].get() {
            return Ok(array.bind(py).clone());
        }
        let array = make()?;
        let kept = self.arrays[slot].get_or_init(|| array.clone().unbind());
        Ok(kept.bind(py).clone())
    }

    /// `(rows, width)` values as a read-only float64 (float32 for an f32 result) array.
    fn floats<'py>(
        &self,
        py: Python<'py>,
        values: impl Iterator<Item = f64>,
        width: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let flat = if self.f32 {
            // Widened from f32: narrowing back is exact.
            let v: Vec<f32> = values.map(|x| x as f32).collect();
            PyArray1::from_vec(py, v).into_any()
        } else {
            let v: Vec<f64> = values.collect();
            PyArray1::from_vec(py, v).into_any()
        };
        let n = flat.len()? / width;
        rows(&read_only(flat)?, n, width)
    }

    /// The value of `statement` per face, or `None` without groups.
    fn per_face(&self, statement: Statement) -> Option<Vec<Option<String>>> {
        let groups = self.groups_stored()?;
        let values = (0..self.face_count()).map(|f| groups.value(f, statement).map(str::to_owned));
        Some(values.collect())
    }
}

/// Values as a read-only int32 array; `what` names them when one does not fit.
pub(crate) fn int32s<'py>(
    py: Python<'py>,
    values: &[u32],
    what: &str,
) -> PyResult<Bound<'py, PyAny>> {
    if let Some(&x) = values.iter().max().filter(|&&x| x > i32::MAX as u32) {
        return Err(Failure::Resource(format!(
            "{what} {x} does not fit the int32 arrays of subcount.Mesh"
        ))
        .into_pyerr(py));
    }
    // Every value fits: the same bytes, one copy.
    let v: &[i32] = bytemuck::cast_slice(values);
    read_only(PyArray1::from_slice(py, v).into_any())
}

/// Values as a read-only float32 array.
fn float32s<'py>(
    py: Python<'py>,
    values: impl Iterator<Item = f32>,
) -> PyResult<Bound<'py, PyAny>> {
    read_only(PyArray1::from_iter(py, values).into_any())
}

/// Writes each face's size (its corners, an `i32`: they are a slice of the int32 corners) over
/// the face offsets' own bytes: size `f` goes to bytes `4f..4f + 4`, before every offset still
/// to be read (offsets `f + 1` and on are bytes `8f + 8` and on), so one forward pass needs no
/// other memory. 64-bit `usize` only.
fn sizes_over_offsets(offsets: &mut [usize]) {
    let bytes: &mut [u8] = bytemuck::cast_slice_mut(offsets);
    let offset = |bytes: &[u8], k: usize| {
        let mut word = [0u8; 8];
        word.copy_from_slice(&bytes[8 * k..8 * k + 8]);
        u64::from_ne_bytes(word)
    };
    let faces = (bytes.len() / 8).saturating_sub(1);
    let mut start = if faces > 0 { offset(bytes, 0) } else { 0 };
    for f in 0..faces {
        let end = offset(bytes, f + 1);
        let size = (end - start).min(i32::MAX as u64) as i32;
        bytes[4 * f..4 * f + 4].copy_from_slice(&size.to_ne_bytes());
        start = end;
    }
}

/// A read-only flat array as `(n, width)` rows (a view of it, read-only too: numpy refuses to
/// make it writable while its base is not).
fn rows<'py>(flat: &Bound<'py, PyAny>, n: usize, width: usize) -> PyResult<Bound<'py, PyAny>> {
    read_only(flat.call_method1("reshape", ((n, width),))?)
}

/// Marks an array read-only (`setflags(write=False)`): the mesh's arrays are copies, and
/// writing into one would change nothing.
pub(crate) fn read_only(array: Bound<'_, PyAny>) -> PyResult<Bound<'_, PyAny>> {
    let kwargs = PyDict::new(array.py());
    kwargs.set_item("write", false)?;
    array.call_method("setflags", (), Some(&kwargs))?;
    Ok(array)
}

/// The mesh argument of `subdivide` and `write_mesh`: a path, a `subcount.Mesh`, or
/// `(positions, faces)`.
pub(crate) enum MeshArg {
    /// A file, read by the driver (`driver::load`).
    Path(std::path::PathBuf),
    /// A face list in memory, and how messages name it.
    Poly(Arc<PolygonMesh>, String),
}

impl MeshArg {
    /// Reads the argument (a `Mesh`'s face list is shared, not copied: it never changes).
    pub(crate) fn extract(py: Python<'_>, obj: &Bound<'_, PyAny>) -> Result<MeshArg> {
        if let Ok(mesh) = obj.cast::<Mesh>() {
            let mesh = mesh.get();
            return Ok(MeshArg::Poly(mesh.shared(py)?, mesh.label.clone()));
        }
        if obj.is_instance_of::<PyString>() || is_path_like(py, obj)? {
            let path: std::path::PathBuf = obj.extract()?;
            return Ok(MeshArg::Path(path));
        }
        if let Ok(tuple) = obj.cast::<PyTuple>() {
            if tuple.len() == 2 {
                let positions = tuple.get_item(0)?;
                let faces = tuple.get_item(1)?;
                // A pair (counts, corners) is two 1-D sequences of different lengths (the
                // corners outnumber the faces); ((0, 1, 2), (0, 2, 3)) is two triangles.
                let numpy = PyModule::import(py, "numpy")?;
                let length = |item: PyResult<Bound<'_, PyAny>>| -> Option<usize> {
                    let item = item.ok()?;
                    let ndim: usize = numpy.call_method1("ndim", (&item,)).ok()?.extract().ok()?;
                    (ndim == 1).then(|| item.len().ok()).flatten()
                };
                let pair = faces.cast::<PyTuple>().ok().filter(|t| {
                    t.len() == 2
                        && matches!(
                            (length(t.get_item(0)), length(t.get_item(1))),
                            (Some(a), Some(b)) if a != b
                        )
                });
                let poly = match pair {
                    Some(pair) => {
                        let (counts, indices) = (pair.get_item(0)?, pair.get_item(1)?);
                        let arrays = Arrays {
                            positions: &positions,
                            faces: Faces::Pair(&counts, &indices),
                            uvs: None,
                            colors: None,
                        };
                        arrays.polygon_mesh(py)?
                    }
                    None => {
                        let arrays = Arrays {
                            positions: &positions,
                            faces: Faces::Rectangular(&faces),
                            uvs: None,
                            colors: None,
                        };
                        arrays.polygon_mesh(py)?
                    }
                };
                return Ok(MeshArg::Poly(Arc::new(poly), ARRAYS_LABEL.to_owned()));
            }
        }
        let type_name = obj.get_type().name()?.to_string();
        Err(Failure::Type(format!(
            "mesh must be a path, a subcount.Mesh or (positions, faces), not {type_name}"
        )))
    }
}

impl MeshArg {
    /// The mesh through the driver's checks and notes, with `flags` (a file is read).
    pub(crate) fn load(self, flags: &driver::OptionFlags) -> driver::Result<driver::LoadedMesh> {
        match self {
            MeshArg::Path(path) => driver::load(&driver::MeshSource::File(path), flags),
            MeshArg::Poly(poly, label) => driver::load_polygon_mesh(poly, &label, flags),
        }
    }
}

/// Whether `obj` is an `os.PathLike`.
fn is_path_like(py: Python<'_>, obj: &Bound<'_, PyAny>) -> PyResult<bool> {
    let path_like = PyModule::import(py, "os")?.getattr("PathLike")?;
    obj.is_instance(&path_like)
}

/// The tags' arrays a `Mesh` shows under USD's names.
#[derive(Clone, Copy)]
enum TagArray {
    CreaseIndices,
    CreaseLengths,
    CreaseSharpnesses,
    CornerIndices,
    CornerSharpnesses,
    HoleIndices,
}
