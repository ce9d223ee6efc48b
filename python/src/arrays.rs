//! The arrays a user hands over, checked: dtype (numbers, integers), shape, finite values,
//! indices in range; each refusal names the array and the index (`subcount.InputError`), a
//! non-numeric dtype is `TypeError`.

use halfedge::glam::{DVec2, DVec3};
use halfedge::uv::Uvs;
use halfedge::{PolygonMesh, Scalar};
use numpy::{PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::errors::{Failure, Result};

/// The faces a user gives: counts and corners, or an `(F, k)` array.
pub(crate) enum Faces<'a, 'py> {
    /// `face_vertex_counts`, `face_vertex_indices`.
    Pair(&'a Bound<'py, PyAny>, &'a Bound<'py, PyAny>),
    /// `faces`, `(F, k)`.
    Rectangular(&'a Bound<'py, PyAny>),
}

/// The arrays of a mesh a user gives.
pub(crate) struct Arrays<'a, 'py> {
    pub(crate) positions: &'a Bound<'py, PyAny>,
    pub(crate) faces: Faces<'a, 'py>,
    pub(crate) uvs: Option<(&'a Bound<'py, PyAny>, &'a Bound<'py, PyAny>)>,
    pub(crate) colors: Option<&'a Bound<'py, PyAny>>,
}

impl Arrays<'_, '_> {
    /// The checked face list.
    pub(crate) fn polygon_mesh(&self, py: Python<'_>) -> Result<PolygonMesh> {
        let positions = float_rows::<3>(py, self.positions, "positions")?;
        let n = positions.len();
        if n == 0 {
            return Err(Failure::Input(
                "positions is empty: a mesh needs vertices".into(),
            ));
        }
        let (counts, corners, faces_name): (Vec<usize>, Vec<u32>, &str) = match &self.faces {
            Faces::Pair(counts, indices) => {
                let counts = face_counts(py, counts)?;
                let indices = integers(py, indices, "face_vertex_indices", 1)?;
                let total = counts.iter().try_fold(0usize, |a, &c| a.checked_add(c));
                let Some(total) = total else {
                    return Err(Failure::Input(
                        "face_vertex_counts add up to more corners than this machine can address"
                            .into(),
                    ));
                };
                if total != indices.values.len() {
                    return Err(Failure::Input(format!(
                        "face_vertex_counts add up to {total} corners, but face_vertex_indices has {}",
                        indices.values.len()
                    )));
                }
                let corners =
                    vertex_indices(&indices.values, n, &|i| format!("face_vertex_indices[{i}]"))?;
                (counts, corners, "face_vertex_counts")
            }
            Faces::Rectangular(faces) => {
                let faces = integers(py, faces, "faces", 2)?;
                let k = faces.shape[1];
                if k < 3 {
                    return Err(Failure::Input(format!(
                        "faces has shape ({}, {k}): a face has at least 3 corners",
                        faces.shape[0]
                    )));
                }
                let corners = vertex_indices(&faces.values, n, &|i| {
                    format!("faces[{}, {}]", i / k, i % k)
                })?;
                (vec![k; faces.shape[0]], corners, "faces")
            }
        };
        if counts.is_empty() {
            return Err(Failure::Input(format!(
                "{faces_name} is empty: a mesh needs faces"
            )));
        }
        let mut mesh =
            PolygonMesh::with_positions(positions.into_iter().map(DVec3::from_array).collect());
        mesh.reserve_faces(counts.len(), corners.len());
        let mut start = 0;
        for c in counts {
            mesh.push_face(&corners[start..start + c]);
            start += c;
        }
        if let Some((uvs, uv_indices)) = self.uvs {
            let values = float_rows::<2>(py, uvs, "uvs")?;
            let k = values.len();
            let indices = integers(py, uv_indices, "uv_indices", 1)?;
            if indices.values.len() != mesh.n_corners() {
                return Err(Failure::Input(format!(
                    "uv_indices has {} entries for {} corners: one per corner",
                    indices.values.len(),
                    mesh.n_corners()
                )));
            }
            let corners = indices_below(&indices.values, k, "uvs", "texture coordinates", &|i| {
                format!("uv_indices[{i}]")
            })?;
            let coords = values.into_iter().map(DVec2::from_array).collect();
            let uvs = Uvs::new(coords, corners).map_err(|e| Failure::Input(e.to_string()))?;
            mesh.set_uvs(Some(uvs))
                .map_err(|e| Failure::Input(e.to_string()))?;
        }
        if let Some(colors) = self.colors {
            let colors = float_rows::<3>(py, colors, "colors")?;
            if colors.len() != n {
                return Err(Failure::Input(format!(
                    "colors has {} rows for {n} vertices: one per vertex",
                    colors.len()
                )));
            }
            mesh.set_colors(Some(colors))
                .map_err(|e| Failure::Input(e.to_string()))?;
        }
        Ok(mesh)
    }
}

/// `numpy.asarray(obj)`, refusing a dtype whose kind is not in `kinds` (TypeError) and a
/// ragged sequence (InputError).
pub(crate) fn as_array<'py>(
    py: Python<'py>,
    obj: &Bound<'py, PyAny>,
    name: &str,
    kinds: &str,
    expected: &str,
) -> Result<Bound<'py, PyAny>> {
    let numpy = PyModule::import(py, "numpy")?;
    let array = numpy.call_method1("asarray", (obj,)).map_err(|e| {
        if e.is_instance_of::<pyo3::exceptions::PyValueError>(py) {
            Failure::Input(format!(
                "{name} is not a rectangular array: {}",
                e.value(py)
            ))
        } else {
            Failure::Python(e)
        }
    })?;
    let dtype = array.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    // An empty list is float64 to numpy: its emptiness is the error, said by the caller.
    let empty = array.getattr("size")?.extract::<usize>()? == 0;
    if !empty && (kind.len() != 1 || !kinds.contains(kind.as_str())) {
        let dtype_name = dtype.str()?.to_string();
        return Err(Failure::Type(format!(
            "{name} must hold {expected}, not {dtype_name}"
        )));
    }
    Ok(array)
}

/// An `(N, W)` array of finite numbers.
fn float_rows<const W: usize>(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    name: &str,
) -> Result<Vec<[f64; W]>> {
    let values = float_table::<f64>(py, obj, name, W)?;
    let rows = values.chunks_exact(W).map(|r| {
        let mut row = [0.0; W];
        row.copy_from_slice(r);
        row
    });
    Ok(rows.collect())
}

/// An `(N, width)` array of finite numbers as `T`, flattened row by row.
pub(crate) fn float_table<T: Scalar + numpy::Element>(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    name: &str,
    width: usize,
) -> Result<Vec<T>> {
    let array = as_array(py, obj, name, "fiu", "numbers")?;
    let numpy = PyModule::import(py, "numpy")?;
    let array = numpy.call_method1("ascontiguousarray", (array, numpy::dtype::<T>(py)))?;
    let array: PyReadonlyArrayDyn<'_, T> = array.extract()?;
    let shape = array.shape();
    if shape.len() != 2 || shape[1] != width {
        return Err(Failure::Input(format!(
            "{name} has shape {}: expected (N, {width})",
            shape_text(shape)
        )));
    }
    let values = array
        .as_slice()
        .map_err(|e| Failure::Bug(format!("{name}: {e}")))?;
    if let Some(i) = values.iter().position(|x| !x.to_f64().is_finite()) {
        return Err(Failure::Input(format!(
            "{name}[{}, {}] is {}: values must be finite",
            i / width,
            i % width,
            python_float(values[i].to_f64())
        )));
    }
    Ok(values.to_vec())
}

/// A float as Python writes a non-finite one: `nan`, `inf`, `-inf`.
fn python_float(x: f64) -> String {
    if x.is_nan() {
        "nan".to_owned()
    } else {
        x.to_string()
    }
}

/// An integer array, flattened, with its shape.
struct Integers {
    values: Vec<i128>,
    shape: Vec<usize>,
}

/// An integer array of `ndim` dimensions (signed or unsigned, any width).
fn integers(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str, ndim: usize) -> Result<Integers> {
    let array = as_array(py, obj, name, "iu", "integers")?;
    let kind: String = array.getattr("dtype")?.getattr("kind")?.extract()?;
    let numpy = PyModule::import(py, "numpy")?;
    let shape: Vec<usize> = array.getattr("shape")?.extract()?;
    if shape.len() != ndim {
        let expected = if ndim == 1 { "(n,)" } else { "(F, k)" };
        return Err(Failure::Input(format!(
            "{name} has shape {}: expected {expected}",
            shape_text(&shape)
        )));
    }
    let values = if kind == "u" {
        widened::<u64>(&numpy, &array, "uint64", name)?
    } else {
        widened::<i64>(&numpy, &array, "int64", name)?
    };
    Ok(Integers { values, shape })
}

/// The integers of `array` as `dtype` (`T`), contiguous, widened to `i128` (so that unsigned
/// and signed values compare with the bounds alike).
fn widened<T: numpy::Element + Copy + Into<i128>>(
    numpy: &Bound<'_, PyModule>,
    array: &Bound<'_, PyAny>,
    dtype: &str,
    name: &str,
) -> Result<Vec<i128>> {
    let array = numpy.call_method1("ascontiguousarray", (array, dtype))?;
    let array: PyReadonlyArrayDyn<'_, T> = array.extract()?;
    let slice = array
        .as_slice()
        .map_err(|e| Failure::Bug(format!("{name}: {e}")))?;
    Ok(slice.iter().map(|&x| x.into()).collect())
}

/// The face sizes: each at least 3.
fn face_counts(py: Python<'_>, obj: &Bound<'_, PyAny>) -> Result<Vec<usize>> {
    let counts = integers(py, obj, "face_vertex_counts", 1)?;
    let mut out = Vec::with_capacity(counts.values.len());
    for (i, &c) in counts.values.iter().enumerate() {
        if c < 0 {
            return Err(Failure::Input(format!(
                "face_vertex_counts[{i}] = {c} is negative"
            )));
        }
        if c < 3 {
            return Err(Failure::Input(format!(
                "face_vertex_counts[{i}] = {c}: a face has at least 3 corners"
            )));
        }
        let c = usize::try_from(c)
            .map_err(|_| Failure::Input(format!("face_vertex_counts[{i}] = {c} is too large")))?;
        out.push(c);
    }
    Ok(out)
}

/// A 1-D integer array (`name`) of indices each below `bound.0`, the rows of `bound.1`
/// (`bound.2`, as messages name them).
pub(crate) fn index_array(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    name: &str,
    (n, array, what): (usize, &str, &str),
) -> Result<Vec<u32>> {
    let values = integers(py, obj, name, 1)?.values;
    indices_below(&values, n, array, what, &|i| format!("{name}[{i}]"))
}

/// A 1-D array of numbers (`name`), as float64.
pub(crate) fn float_values(py: Python<'_>, obj: &Bound<'_, PyAny>, name: &str) -> Result<Vec<f64>> {
    let array = as_array(py, obj, name, "fiu", "numbers")?;
    let numpy = PyModule::import(py, "numpy")?;
    let array = numpy.call_method1("ascontiguousarray", (array, "float64"))?;
    let array: PyReadonlyArrayDyn<'_, f64> = array.extract()?;
    if array.shape().len() != 1 {
        return Err(Failure::Input(format!(
            "{name} has shape {}: expected (n,)",
            shape_text(array.shape())
        )));
    }
    let values = array
        .as_slice()
        .map_err(|e| Failure::Bug(format!("{name}: {e}")))?;
    Ok(values.to_vec())
}

/// Vertex indices, each below the `n` vertices.
fn vertex_indices(values: &[i128], n: usize, place: &dyn Fn(usize) -> String) -> Result<Vec<u32>> {
    indices_below(values, n, "positions", "vertices", place)
}

/// Indices each from 0 to below `n` (the rows of `array`, `what`); `place` names entry `i`.
fn indices_below(
    values: &[i128],
    n: usize,
    array: &str,
    what: &str,
    place: &dyn Fn(usize) -> String,
) -> Result<Vec<u32>> {
    let mut out = Vec::with_capacity(values.len());
    for (i, &v) in values.iter().enumerate() {
        if v < 0 {
            return Err(Failure::Input(format!("{} = {v} is negative", place(i))));
        }
        match u32::try_from(v) {
            Ok(x) if (x as usize) < n => out.push(x),
            _ => {
                return Err(Failure::Input(format!(
                    "{} = {v} is out of range: {array} has {n} {what}",
                    place(i)
                )))
            }
        }
    }
    Ok(out)
}

/// A shape as Python writes it: `(3,)`, `(4, 2)`.
fn shape_text(shape: &[usize]) -> String {
    match shape {
        [one] => format!("({one},)"),
        _ => {
            let parts: Vec<String> = shape.iter().map(ToString::to_string).collect();
            format!("({})", parts.join(", "))
        }
    }
}
