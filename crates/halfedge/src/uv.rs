//! Texture coordinates (UVs) as face-varying data: a value per face corner, discontinuous
//! across UV seams, as OpenSubdiv, Blender and every renderer carry them.
//!
//! [`Uvs`] is what a file says: the `vt` coordinates and, per face corner, the `vt` it uses
//! (the OBJ reader fills [`PolygonMesh::uvs`](crate::PolygonMesh::uvs) from `f v/vt`).
//! [`UvLayout`] is what subdivision refines: its **values** are the distinct
//! (vertex, `vt`) pairs the corners use, the value OpenSubdiv keeps per pair from level 1 on
//! (one `vt` used at several vertices is one value per vertex); its faces are the mesh's faces
//! with values as corners. A surface edge is a **seam** when its two faces do not agree on
//! the values at both of its ends; a seam edge is two boundary edges of the layout.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Owner of texture coordinates as face-varying data: a `vt` per face corner, the UV layout
//! (values = distinct (vertex, `vt`) pairs, a value per corner): `halfedge::uv` (`uv.rs`: `Uvs`,
//! `UvLayout`, `PartialUvs`); a mesh carries them as `PolygonMesh::uvs` (read from OBJ `vt`; when
//! only some corners have one, `PolygonMesh::partial_uvs` says how many).

use glam::DVec2;

/// The texture coordinates of a face list: the `vt` entries and the `vt` of every face
/// corner, in the order of [`PolygonMesh::face_indices`](crate::PolygonMesh::face_indices).
#[derive(Clone, Debug, PartialEq)]
pub struct Uvs {
    coords: Vec<DVec2>,
    corners: Vec<u32>,
}

/// A [`Uvs`] whose corners do not match its coordinates or its mesh.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum UvError {
    /// A corner names a `vt` entry that does not exist.
    #[error("face corner {corner} uses texture coordinate {index}, but there are {count}")]
    OutOfRange {
        /// The corner (an index into the face corners).
        corner: usize,
        /// The `vt` index it names (0-based).
        index: u32,
        /// The number of `vt` entries.
        count: usize,
    },
    /// The number of corners differs from the mesh's.
    #[error("{given} texture-coordinate corners for a mesh with {expected} face corners")]
    CornerCount {
        /// Corners given.
        given: usize,
        /// Corners of the mesh.
        expected: usize,
    },
}

impl Uvs {
    /// Texture coordinates and the `vt` index (0-based) of each face corner.
    ///
    /// # Errors
    ///
    /// [`UvError::OutOfRange`] for the first corner naming a missing coordinate.
    pub fn new(coords: Vec<DVec2>, corners: Vec<u32>) -> Result<Uvs, UvError> {
        if let Some((corner, &index)) = corners
            .iter()
            .enumerate()
            .find(|(_, &i)| i as usize >= coords.len())
        {
            return Err(UvError::OutOfRange {
                corner,
                index,
                count: coords.len(),
            });
        }
        Ok(Uvs { coords, corners })
    }

    /// What the OBJ reader read: every corner names an existing coordinate.
    pub(crate) fn from_read(coords: Vec<DVec2>, corners: Vec<u32>) -> Uvs {
        debug_assert!(corners.iter().all(|&c| (c as usize) < coords.len()));
        Uvs { coords, corners }
    }

    /// The texture coordinates (`vt` entries), used or not.
    pub fn coords(&self) -> &[DVec2] {
        &self.coords
    }

    /// The `vt` index of every face corner.
    pub fn corners(&self) -> &[u32] {
        &self.corners
    }

    /// The number of `vt` entries no corner uses.
    pub fn unreferenced(&self) -> usize {
        let mut used = vec![false; self.coords.len()];
        for &c in &self.corners {
            used[c as usize] = true;
        }
        used.iter().filter(|&&u| !u).count()
    }

    /// The texture coordinates of the faces `written` keeps, as read: the corners of those
    /// faces (in order) and the `vt` entries they use, in file order, renumbered; entries no
    /// kept corner uses are left out. `face_offsets` delimits each face's corners, as
    /// [`PolygonMesh::face_offsets`](crate::PolygonMesh::face_offsets). Level 0 of a
    /// subdivision writes these, so its `vt` lines are what `table` counts at level 0 (the
    /// `vt` entries the written corners use).
    ///
    /// ```
    /// use halfedge::glam::DVec2;
    /// use halfedge::uv::Uvs;
    ///
    /// let coords = vec![DVec2::ZERO, DVec2::X, DVec2::Y, DVec2::ONE];
    /// // Two triangles; the second is left out, and with it vt 3.
    /// let uvs = Uvs::new(coords, vec![0, 1, 2, 1, 3, 2])?;
    /// let kept = uvs.of_written_faces(&[0, 3, 6], |f| f == 0);
    /// assert_eq!((kept.coords().len(), kept.corners()), (3, &[0, 1, 2][..]));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn of_written_faces(&self, face_offsets: &[usize], written: impl Fn(usize) -> bool) -> Uvs {
        const UNUSED: u32 = u32::MAX;
        let faces = face_offsets
            .windows(2)
            .enumerate()
            .filter(|&(f, _)| written(f));
        let mut map = vec![UNUSED; self.coords.len()];
        for (_, w) in faces.clone() {
            for &c in &self.corners[w[0]..w[1]] {
                map[c as usize] = 0;
            }
        }
        let mut coords = Vec::new();
        for (vt, slot) in map.iter_mut().enumerate() {
            if *slot != UNUSED {
                *slot = coords.len() as u32;
                coords.push(self.coords[vt]);
            }
        }
        let corners = faces
            .flat_map(|(_, w)| self.corners[w[0]..w[1]].iter().map(|&c| map[c as usize]))
            .collect();
        Uvs { coords, corners }
    }

    /// The coordinates and corners.
    pub fn into_parts(self) -> (Vec<DVec2>, Vec<u32>) {
        (self.coords, self.corners)
    }
}

/// Why a mesh read from a file has no texture coordinates although some of its face corners
/// name a `vt`: only `with_vt` of its `corners` face corners do, so there is no UV layout
/// (a layout needs a value at every corner). Reading such a file is not an error; the mesh
/// records this in [`PolygonMesh::partial_uvs`](crate::PolygonMesh::partial_uvs).
///
/// ```
/// let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\nf 2 4 3\n";
/// let mesh = halfedge::io::read_obj_from(text.as_bytes(), "half.obj")?;
/// assert!(mesh.uvs().is_none());
/// let partial = mesh.partial_uvs().expect("some corners have a vt");
/// assert_eq!((partial.with_vt, partial.corners), (3, 6));
/// assert_eq!(partial.to_string(), "3 of 6 face corners have texture coordinates: no UV layout");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PartialUvs {
    /// The face corners that name a `vt` (at least one, fewer than `corners`).
    pub with_vt: usize,
    /// All face corners of the mesh.
    pub corners: usize,
}

impl std::fmt::Display for PartialUvs {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} of {} face corners have texture coordinates: no UV layout",
            self.with_vt, self.corners
        )
    }
}

/// The UV layout of a mesh: its values (the distinct (vertex, `vt`) pairs the corners use,
/// numbered in order of first use) and, per face corner, its value.
///
/// ```
/// use glam::DVec2;
/// use halfedge::uv::{UvLayout, Uvs};
///
/// // Two triangles sharing the edge 0-2; the second uses its own vt at vertex 2: a seam.
/// let faces = [0u32, 1, 2, 0, 2, 3];
/// let uvs = Uvs::new(vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y, DVec2::splat(0.5)],
///                    vec![0, 1, 2, 0, 4, 3])?;
/// let layout = UvLayout::new(&faces, &uvs);
/// assert_eq!(layout.n_values(), 5);
/// assert_eq!(layout.corners(), [0, 1, 2, 0, 3, 4]);
/// assert_eq!(layout.value_vertex(3), 2);
/// assert_eq!(layout.values()[3], DVec2::splat(0.5));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct UvLayout {
    /// The UV of each value.
    values: Vec<DVec2>,
    /// The vertex of each value.
    vertices: Vec<u32>,
    /// The `vt` index of each value.
    vts: Vec<u32>,
    /// The value of each face corner.
    corners: Vec<u32>,
}

impl UvLayout {
    /// The layout of the face corners `face_indices` (vertex indices, face after face, as
    /// [`PolygonMesh::face_indices`](crate::PolygonMesh::face_indices)) with the texture
    /// coordinates `uvs` (one `vt` per corner).
    ///
    /// # Panics
    ///
    /// When `uvs` does not have one corner per entry of `face_indices`
    /// ([`PolygonMesh::set_uvs`](crate::PolygonMesh::set_uvs) checks it).
    pub fn new(face_indices: &[u32], uvs: &Uvs) -> UvLayout {
        assert_eq!(face_indices.len(), uvs.corners.len(), "one vt per corner");
        let mut ids = std::collections::HashMap::with_capacity(uvs.corners.len());
        let mut layout = UvLayout {
            values: Vec::new(),
            vertices: Vec::new(),
            vts: Vec::new(),
            corners: Vec::with_capacity(face_indices.len()),
        };
        for (&v, &t) in face_indices.iter().zip(&uvs.corners) {
            let next = layout.vertices.len() as u32;
            let id = *ids.entry((v, t)).or_insert(next);
            if id == next {
                layout.values.push(uvs.coords[t as usize]);
                layout.vertices.push(v);
                layout.vts.push(t);
            }
            layout.corners.push(id);
        }
        layout
    }

    /// The number of values (the UV values at level 0).
    pub fn n_values(&self) -> usize {
        self.values.len()
    }

    /// The UV of each value: the base buffer of a face-varying evaluation.
    pub fn values(&self) -> &[DVec2] {
        &self.values
    }

    /// The value of each face corner, in face-corner order.
    pub fn corners(&self) -> &[u32] {
        &self.corners
    }

    /// The vertex value `value` belongs to.
    pub fn value_vertex(&self, value: u32) -> u32 {
        self.vertices[value as usize]
    }

    /// The `vt` index value `value` was read from.
    pub fn value_vt(&self, value: u32) -> u32 {
        self.vts[value as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_vt_at_two_vertices_is_two_values() {
        let faces = [0u32, 1, 2, 2, 1, 3];
        let uvs = Uvs::new(vec![DVec2::ZERO; 2], vec![0, 0, 1, 1, 0, 1]).unwrap();
        let layout = UvLayout::new(&faces, &uvs);
        // Pairs (0,0) (1,0) (2,1) (3,1): vertex 1 and 2 agree in both faces.
        assert_eq!(layout.n_values(), 4);
        assert_eq!(layout.corners(), [0, 1, 2, 2, 1, 3]);
        assert_eq!(uvs.unreferenced(), 0);
    }

    #[test]
    fn out_of_range_corner_is_named() {
        let err = Uvs::new(vec![DVec2::ZERO], vec![0, 3]).unwrap_err();
        assert_eq!(
            err.to_string(),
            "face corner 1 uses texture coordinate 3, but there are 1"
        );
    }
}
