//! A [`PolygonMesh`] taken apart into its arrays and put back together: for a binding that
//! hands the arrays to another owner without a copy (numpy) and rebuilds a mesh from them
//! when the library needs one.

use glam::DVec3;

use super::{ColorError, PartialColors, PolygonMesh, Uncarried};
use crate::groups::{FaceGroups, GroupsError};
use crate::tags::{IgnoredTag, TagError, Tags};
use crate::uv::{PartialUvs, UvError, Uvs};

/// Everything a [`PolygonMesh`] holds, as owned values ([`PolygonMesh::into_polygon_parts`],
/// [`PolygonMesh::from_polygon_parts`]; [`PolygonMesh::into_parts`] gives the face list alone).
/// A plain record: a field added with a new part of the mesh is a breaking change, as the
/// part itself is.
#[derive(Clone, Debug, Default)]
pub struct PolygonParts {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Face `f` is `face_indices[face_offsets[f]..face_offsets[f + 1]]` (`[0]` without faces).
    pub face_offsets: Vec<usize>,
    /// The corners, face after face.
    pub face_indices: Vec<u32>,
    /// The file line of each face (empty for a mesh not read from a file).
    pub face_lines: Vec<u64>,
    /// Creases, corners, holes and options.
    pub tags: Tags,
    /// The file's tags that were not interpreted.
    pub ignored_tags: Vec<IgnoredTag>,
    /// Texture coordinates, one per corner.
    pub uvs: Option<Uvs>,
    /// How many corners of the file had a `vt`, when only some had.
    pub partial_uvs: Option<PartialUvs>,
    /// Materials, objects, groups and smoothing groups, per face.
    pub groups: Option<FaceGroups>,
    /// Vertex colors, one per vertex.
    pub colors: Option<Vec<[f64; 3]>>,
    /// How many vertices of the file had a color, when only some had.
    pub partial_colors: Option<PartialColors>,
    /// The kinds of the file's lines no output carries.
    pub uncarried: Vec<Uncarried>,
}

/// Parts that do not make a mesh ([`PolygonMesh::from_polygon_parts`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PartsError {
    /// The face offsets do not start at 0, decrease, or do not end at the number of corners.
    #[error("the face offsets must start at 0, never decrease and end at the {corners} corners")]
    FaceOffsets {
        /// The number of corners.
        corners: usize,
    },
    /// File lines given, but not one per face.
    #[error("{lines} file lines for {faces} faces")]
    FaceLines {
        /// The lines given.
        lines: usize,
        /// The faces.
        faces: usize,
    },
    /// The texture coordinates do not fit the corners.
    #[error(transparent)]
    Uvs(#[from] UvError),
    /// The groups do not fit the faces.
    #[error(transparent)]
    Groups(#[from] GroupsError),
    /// The colors do not fit the vertices.
    #[error(transparent)]
    Colors(#[from] ColorError),
    /// A tag names what the mesh does not have.
    #[error(transparent)]
    Tags(#[from] TagError),
}

impl PolygonMesh {
    /// The mesh taken apart, every array moved out (no copy).
    pub fn into_polygon_parts(self) -> PolygonParts {
        PolygonParts {
            positions: self.positions,
            face_offsets: self.face_offsets,
            face_indices: self.face_indices,
            face_lines: self.face_lines,
            tags: self.tags,
            ignored_tags: self.ignored_tags,
            uvs: self.uvs,
            partial_uvs: self.partial_uvs,
            groups: self.groups,
            colors: self.colors,
            partial_colors: self.partial_colors,
            uncarried: self.uncarried,
        }
    }

    /// A mesh from its parts, checked as the setters check them: the offsets, the file lines,
    /// then [`set_uvs`](Self::set_uvs), [`set_groups`](Self::set_groups),
    /// [`set_colors`](Self::set_colors) and [`set_tags`](Self::set_tags). Corners are not
    /// checked against the positions (no face list is; a half-edge mesh checks them).
    ///
    /// # Errors
    ///
    /// The first part that does not fit ([`PartsError`]).
    ///
    /// ```
    /// let mesh = halfedge::shapes::cube();
    /// let parts = mesh.clone().into_polygon_parts();
    /// assert_eq!(halfedge::PolygonMesh::from_polygon_parts(parts)?, mesh);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_polygon_parts(parts: PolygonParts) -> Result<PolygonMesh, PartsError> {
        let PolygonParts {
            positions,
            mut face_offsets,
            face_indices,
            face_lines,
            tags,
            ignored_tags,
            uvs,
            partial_uvs,
            groups,
            colors,
            partial_colors,
            uncarried,
        } = parts;
        if face_offsets.is_empty() {
            face_offsets.push(0);
        }
        let corners = face_indices.len();
        let ordered = face_offsets.windows(2).all(|w| w[0] <= w[1]);
        if face_offsets[0] != 0 || !ordered || face_offsets.last() != Some(&corners) {
            return Err(PartsError::FaceOffsets { corners });
        }
        let faces = face_offsets.len() - 1;
        if !face_lines.is_empty() && face_lines.len() != faces {
            return Err(PartsError::FaceLines {
                lines: face_lines.len(),
                faces,
            });
        }
        let mut mesh = PolygonMesh::from_raw_parts(positions, face_offsets, face_indices);
        mesh.set_uvs(uvs)?;
        mesh.set_groups(groups)?;
        mesh.set_colors(colors)?;
        mesh.set_tags(tags)?;
        mesh.face_lines = face_lines;
        mesh.ignored_tags = ignored_tags;
        mesh.partial_uvs = partial_uvs;
        mesh.partial_colors = partial_colors;
        mesh.uncarried = uncarried;
        Ok(mesh)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn parts_round_trip_and_refuse_what_does_not_fit() {
        let mesh = shapes::cube();
        let parts = mesh.clone().into_polygon_parts();
        assert_eq!(PolygonMesh::from_polygon_parts(parts.clone()), Ok(mesh));
        let mut bad = parts.clone();
        bad.face_offsets[3] = 100;
        let refused = PolygonMesh::from_polygon_parts(bad);
        assert_eq!(refused, Err(PartsError::FaceOffsets { corners: 24 }));
        let mut lines = parts.clone();
        lines.face_lines = vec![1, 2];
        let refused = PolygonMesh::from_polygon_parts(lines);
        assert_eq!(refused, Err(PartsError::FaceLines { lines: 2, faces: 6 }));
        let mut colors = parts;
        colors.colors = Some(vec![[0.0; 3]; 3]);
        let refused = PolygonMesh::from_polygon_parts(colors);
        assert!(matches!(refused, Err(PartsError::Colors(_))), "{refused:?}");
    }
}
