//! Vertex normals of a face list: area-weighted, from each polygon's area vector.
//!
//! A polygon's **area vector** is half the sum of the cross products of its consecutive
//! corners (Newell's method, taken relative to its first corner so that a mesh far from the
//! origin loses no precision): its length is the polygon's area when it is planar, its
//! direction the normal its corner order gives by the right-hand rule, and a non-planar
//! polygon gets the normal of its best-fitting plane. A vertex's normal is the unit vector
//! along the sum of the area vectors of the faces around it (a face using the vertex twice
//! counts twice), so large faces weigh more than small ones. Where that sum has no direction
//! (a vertex no face uses, or only faces of zero area, or faces cancelling exactly) the
//! normal is `+Z` ([`FALLBACK`]).
//!
//! These are the normals the OBJ writers write as `vn` when asked
//! ([`crate::io::ObjWriteOptions::normals`]): a subdivided surface needs new normals, so the
//! reader never carries a file's `vn`.
//!
//! ```
//! use halfedge::glam::DVec3;
//! use halfedge::normals::{area_vector, vertex_normals};
//!
//! // A unit square in the xy plane, counter-clockwise: area 1 along +z.
//! let square = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
//! assert_eq!(area_vector(square), DVec3::Z);
//! // Two faces of a cube's corner: the shared vertices' normals lean between them.
//! let positions = [DVec3::ZERO, DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y, DVec3::new(1.0, 0.0, -1.0), DVec3::new(0.0, 0.0, -1.0)];
//! let normals = vertex_normals(&positions, [[0u32, 1, 2, 3], [0, 5, 4, 1]]);
//! assert_eq!(normals[2], DVec3::Z);
//! assert!((normals[0] - DVec3::new(0.0, -1.0, 1.0).normalize()).length() < 1e-15);
//! ```
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Owner of vertex normals (a polygon's area vector by Newell's method, area-weighted vertex
//! normals, the `+Z` fallback): `halfedge::normals` (`normals.rs`: `area_vector`,
//! `vertex_normals`, `vertex_normals_by`); the writers call it for `vn`.

use glam::DVec3;

/// The normal of a vertex whose faces' area vectors sum to no direction (or that no face
/// uses): `+Z`.
pub const FALLBACK: DVec3 = DVec3::Z;

/// The area vector of the polygon with corners `points` in order (see the
/// [module docs](self)); zero for fewer than three corners.
pub fn area_vector(points: impl IntoIterator<Item = DVec3>) -> DVec3 {
    let mut points = points.into_iter();
    let Some(first) = points.next() else {
        return DVec3::ZERO;
    };
    let mut sum = DVec3::ZERO;
    let mut previous = DVec3::ZERO;
    for p in points {
        let d = p - first;
        sum += previous.cross(d);
        previous = d;
    }
    0.5 * sum
}

/// The area-weighted unit normal of every vertex of `positions` under `faces` (each a list
/// of 0-based vertex indices), [`FALLBACK`] where the area vectors around a vertex sum to
/// zero (or to something not finite).
///
/// # Panics
///
/// When a face names a vertex beyond `positions` (the writers check their faces first).
pub fn vertex_normals<F>(positions: &[DVec3], faces: F) -> Vec<DVec3>
where
    F: IntoIterator,
    F::Item: AsRef<[u32]>,
{
    vertex_normals_by(positions.len(), |v| positions[v as usize], faces)
}

/// [`vertex_normals`] of `n_vertices` vertices whose positions `position` gives (positions
/// in caller-owned `f32` or `f64` buffers, without a copy as `DVec3`).
///
/// # Panics
///
/// When a face names a vertex `>= n_vertices`, or as `position` does.
pub fn vertex_normals_by<F>(
    n_vertices: usize,
    position: impl Fn(u32) -> DVec3,
    faces: F,
) -> Vec<DVec3>
where
    F: IntoIterator,
    F::Item: AsRef<[u32]>,
{
    let mut sums = vec![DVec3::ZERO; n_vertices];
    for face in faces {
        let face = face.as_ref();
        let area = area_vector(face.iter().map(|&v| position(v)));
        for &v in face {
            sums[v as usize] += area;
        }
    }
    for n in &mut sums {
        *n = n.try_normalize().unwrap_or(FALLBACK);
    }
    sums
}

/// The unit normal of the limit surface from its two limit tangents `t1` and `t2`
/// ([`Refinement::evaluate_limit`](crate::Refinement::evaluate_limit)): `t1 × t2` normalized,
/// flipped where needed so that it does not point against `area` (the area-weighted normal of
/// the vertex, [`vertex_normals`]); `area` itself where the tangents are degenerate
/// (`|t1 × t2| < 1e-12 |t1| |t2|`, or not finite: a corner whose tangents are parallel).
/// Never NaN when `area` is not.
///
/// ```
/// use halfedge::glam::DVec3;
/// use halfedge::normals::limit_normal;
/// assert_eq!(limit_normal(DVec3::X, DVec3::Y, DVec3::Z), DVec3::Z);
/// // Against the area normal: flipped.
/// assert_eq!(limit_normal(DVec3::Y, DVec3::X, DVec3::Z), DVec3::Z);
/// // Parallel tangents: the area normal.
/// assert_eq!(limit_normal(DVec3::X, 2.0 * DVec3::X, DVec3::Y), DVec3::Y);
/// ```
pub fn limit_normal(t1: DVec3, t2: DVec3, area: DVec3) -> DVec3 {
    let cross = t1.cross(t2);
    let length = cross.length();
    let degenerate =
        !(length.is_finite() && length > 0.0) || length < 1e-12 * t1.length() * t2.length();
    if degenerate {
        return area;
    }
    let n = cross / length;
    if n.dot(area) < 0.0 {
        -n
    } else {
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn area_vectors_of_planar_and_degenerate_polygons() {
        let triangle = [
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 3.0, 0.0),
        ];
        assert_eq!(area_vector(triangle), DVec3::new(0.0, 0.0, 3.0));
        // Reversed corners: the opposite normal.
        let reversed: Vec<DVec3> = triangle.iter().rev().copied().collect();
        assert_eq!(area_vector(reversed), DVec3::new(0.0, 0.0, -3.0));
        // Far from the origin, the same area (relative to the first corner: no cancellation).
        let far = DVec3::splat(1e12);
        assert_eq!(
            area_vector(triangle.map(|p| p + far)),
            DVec3::new(0.0, 0.0, 3.0)
        );
        // A pentagon in the plane x = 1 with a notch: area by the shoelace formula, 3.
        let pentagon = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (1.0, 1.0), (0.0, 2.0)]
            .map(|(y, z)| DVec3::new(1.0, y, z));
        assert_eq!(area_vector(pentagon), DVec3::new(3.0, 0.0, 0.0));
        // Collinear corners, two corners, nothing: zero.
        assert_eq!(
            area_vector([DVec3::ZERO, DVec3::X, 2.0 * DVec3::X]),
            DVec3::ZERO
        );
        assert_eq!(area_vector([DVec3::ZERO, DVec3::X]), DVec3::ZERO);
        assert_eq!(area_vector([]), DVec3::ZERO);
    }

    #[test]
    fn normals_are_area_weighted_with_a_fallback() {
        // A big triangle along +z and a small one along +x share the edge 0-1.
        let positions = [
            DVec3::ZERO,
            DVec3::Y,
            DVec3::new(-3.0, 0.0, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(7.0, 7.0, 7.0),
        ];
        let faces = [[0u32, 1, 2], [0, 1, 3]];
        let big = area_vector(faces[0].map(|v| positions[v as usize]));
        let small = area_vector(faces[1].map(|v| positions[v as usize]));
        assert_eq!(
            (big, small),
            (DVec3::new(0.0, 0.0, 1.5), DVec3::new(0.5, 0.0, 0.0))
        );
        let normals = vertex_normals(&positions, faces);
        let shared = DVec3::new(0.5, 0.0, 1.5).normalize();
        assert_eq!(normals[0], shared);
        assert_eq!(normals[1], shared);
        assert_eq!(normals[2], DVec3::Z);
        assert_eq!(normals[3], DVec3::X);
        // Vertex 4 is in no face: the fallback.
        assert_eq!(normals[4], FALLBACK);
        // Faces of zero area, and two faces cancelling: the fallback too.
        let flat = vertex_normals(&positions, [[0u32, 1, 1]]);
        assert_eq!(flat[0], FALLBACK);
        let cancelling = vertex_normals(&positions, [[0u32, 1, 2], [0, 2, 1]]);
        assert_eq!(cancelling[0], FALLBACK);
        assert!(normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-15));
        let by = vertex_normals_by(5, |v| positions[v as usize], faces);
        assert_eq!(by, normals);
    }
}
