//! The creases, corners, holes and options of `subcount.Mesh` under USD's names
//! (`UsdGeom.Mesh`'s `creaseIndices`, `creaseLengths`, `creaseSharpnesses`, `cornerIndices`,
//! `cornerSharpnesses`, `holeIndices`): arrays in, [`halfedge::tags::Tags`] out, and back.
//!
//! A crease is a chain of vertices (`crease_lengths` of them, at least 2) with one sharpness
//! per chain or one per edge, as USD allows; it is stored as the chain's edges, so a mesh
//! reads back one 2-vertex chain per edge with its own sharpness. The options are the mesh's
//! own (an OBJ file's `t interpolateboundary` tags): `subdivide`'s keywords override them.

use halfedge::tags::{
    BoundaryInterpolation, CreaseMethod, FaceVaryingInterpolation, TagOptions, Tags, TriangleRule,
};
use halfedge::PolygonMesh;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{float_values, index_array};
use crate::errors::{Failure, Result};

/// The keys of `options`, in the order `Mesh.options` lists them.
const OPTION_KEYS: [&str; 4] = [
    "boundary",
    "crease_method",
    "triangle_rule",
    "uv_interpolation",
];

/// The tag arrays a user gives to `subcount.Mesh` (each `None` when not given).
#[derive(Default)]
pub(crate) struct TagArrays<'a, 'py> {
    pub(crate) crease_indices: Option<&'a Bound<'py, PyAny>>,
    pub(crate) crease_lengths: Option<&'a Bound<'py, PyAny>>,
    pub(crate) crease_sharpnesses: Option<&'a Bound<'py, PyAny>>,
    pub(crate) corner_indices: Option<&'a Bound<'py, PyAny>>,
    pub(crate) corner_sharpnesses: Option<&'a Bound<'py, PyAny>>,
    pub(crate) hole_indices: Option<&'a Bound<'py, PyAny>>,
    pub(crate) options: Option<&'a Bound<'py, PyAny>>,
}

impl TagArrays<'_, '_> {
    /// Checks the arrays against `mesh` and sets them as its tags.
    pub(crate) fn apply(&self, py: Python<'_>, mesh: &mut PolygonMesh) -> Result<()> {
        let mut tags = Tags::default();
        self.add_creases(py, mesh.n_vertices(), &mut tags)?;
        self.add_corners(py, mesh.n_vertices(), &mut tags)?;
        if let Some(holes) = self.hole_indices {
            let faces = index_array(
                py,
                holes,
                "hole_indices",
                (mesh.n_faces(), "the mesh", "faces"),
            )?;
            faces.into_iter().for_each(|f| tags.add_hole(f));
        }
        if let Some(options) = self.options {
            tags.options = tag_options(options)?;
        }
        if tags.is_empty() {
            return Ok(());
        }
        mesh.set_tags(tags)
            .map_err(|e| Failure::Input(e.to_string()))
    }

    fn add_creases(&self, py: Python<'_>, n: usize, tags: &mut Tags) -> Result<()> {
        let (indices, lengths, sharpnesses) = match (
            self.crease_indices,
            self.crease_lengths,
            self.crease_sharpnesses,
        ) {
            (None, None, None) => return Ok(()),
            (Some(i), Some(l), Some(s)) => (i, l, s),
            _ => {
                return Err(Failure::Usage(
                    "crease_indices, crease_lengths and crease_sharpnesses go together: give all three or none"
                        .into(),
                ))
            }
        };
        let vertices = index_array(py, indices, "crease_indices", (n, "positions", "vertices"))?;
        let lengths = index_array(py, lengths, "crease_lengths", (usize::MAX, "", ""))?;
        let sharpnesses = float_values(py, sharpnesses, "crease_sharpnesses")?;
        if let Some(i) = lengths.iter().position(|&l| l < 2) {
            return Err(Failure::Input(format!(
                "crease_lengths[{i}] = {}: a crease chain has at least 2 vertices",
                lengths[i]
            )));
        }
        let total: u64 = lengths.iter().map(|&l| u64::from(l)).sum();
        if total != vertices.len() as u64 {
            return Err(Failure::Input(format!(
                "crease_lengths add up to {total} vertices, but crease_indices has {}",
                vertices.len()
            )));
        }
        let edges = vertices.len() - lengths.len();
        let per_edge = match sharpnesses.len() {
            k if k == lengths.len() => false,
            k if k == edges => true,
            k => {
                return Err(Failure::Input(format!(
                    "crease_sharpnesses has {k} values: expected one per chain ({}) or one per edge ({edges})",
                    lengths.len()
                )))
            }
        };
        let (mut start, mut edge) = (0, 0);
        for (chain, &length) in lengths.iter().enumerate() {
            let chain_vertices = &vertices[start..start + length as usize];
            for pair in chain_vertices.windows(2) {
                let at = if per_edge { edge } else { chain };
                let sharpness = sharpnesses[at] as f32;
                tags.add_crease(pair[0], pair[1], sharpness)
                    .map_err(|e| Failure::Input(format!("crease_sharpnesses[{at}]: {e}")))?;
                edge += 1;
            }
            start += length as usize;
        }
        Ok(())
    }

    fn add_corners(&self, py: Python<'_>, n: usize, tags: &mut Tags) -> Result<()> {
        let (indices, sharpnesses) = match (self.corner_indices, self.corner_sharpnesses) {
            (None, None) => return Ok(()),
            (Some(i), Some(s)) => (i, s),
            _ => {
                return Err(Failure::Usage(
                    "corner_indices and corner_sharpnesses go together: give both or neither"
                        .into(),
                ))
            }
        };
        let vertices = index_array(py, indices, "corner_indices", (n, "positions", "vertices"))?;
        let sharpnesses = float_values(py, sharpnesses, "corner_sharpnesses")?;
        if sharpnesses.len() != vertices.len() {
            return Err(Failure::Input(format!(
                "corner_sharpnesses has {} values for {} corner_indices: one per corner",
                sharpnesses.len(),
                vertices.len()
            )));
        }
        for (at, (&v, &s)) in vertices.iter().zip(&sharpnesses).enumerate() {
            tags.add_corner(v, s as f32)
                .map_err(|e| Failure::Input(format!("corner_sharpnesses[{at}]: {e}")))?;
        }
        Ok(())
    }
}

/// The `options` dict: keys from [`OPTION_KEYS`], values the command line's names.
fn tag_options(options: &Bound<'_, PyAny>) -> Result<TagOptions> {
    let dict = options.cast::<PyDict>().map_err(|_| {
        Failure::Type(format!(
            "options must be a dict, not {}",
            options
                .get_type()
                .name()
                .map_or_else(|_| "?".into(), |n| n.to_string())
        ))
    })?;
    let mut out = TagOptions::default();
    for (key, value) in dict.iter() {
        let key: String = key
            .extract()
            .map_err(|_| Failure::Type("options' keys must be str".into()))?;
        let value: String = value
            .extract()
            .map_err(|_| Failure::Type(format!("options[{key:?}] must be a str")))?;
        let name = format!("options[{key:?}]");
        let value = Some(value.as_str());
        match key.as_str() {
            "boundary" => out.boundary = named::<BoundaryInterpolation>(value, &name)?,
            "crease_method" => out.crease_method = named::<CreaseMethod>(value, &name)?,
            "triangle_rule" => out.triangle_rule = named::<TriangleRule>(value, &name)?,
            "uv_interpolation" => {
                out.face_varying = named::<FaceVaryingInterpolation>(value, &name)?;
            }
            _ => {
                return Err(Failure::Usage(format!(
                    "options has an unknown key {key:?}: expected {}",
                    OPTION_KEYS.join(", ")
                )))
            }
        }
    }
    Ok(out)
}

/// The mesh's options as a dict (only those it sets).
pub(crate) fn options_dict<'py>(py: Python<'py>, tags: &Tags) -> PyResult<Bound<'py, PyDict>> {
    let o = &tags.options;
    let dict = PyDict::new(py);
    let values = [
        o.boundary.map(|v| v.name()),
        o.crease_method.map(|v| v.name()),
        o.triangle_rule.map(|v| v.name()),
        o.face_varying.map(|v| v.name()),
    ];
    for (key, value) in OPTION_KEYS.iter().zip(values) {
        if let Some(value) = value {
            dict.set_item(key, value)?;
        }
    }
    Ok(dict)
}

/// An option by its command-line name (`FromStr` of `halfedge::tags`' enums): the names it
/// accepts in the message otherwise.
pub(crate) fn named<T>(value: Option<&str>, name: &str) -> Result<Option<T>>
where
    T: std::str::FromStr,
    T::Err: std::fmt::Display,
{
    value
        .map(|v| {
            v.parse::<T>()
                .map_err(|e| Failure::Usage(format!("invalid {name}: {e}")))
        })
        .transpose()
}
