//! Per-face data across levels (OpenSubdiv's `InterpolateFaceUniform`, with
//! `GetFaceParentFace` chained to the base level): every face of a level gets the value of the
//! face it comes from, in the numbering of each split (the family modules' docs).
//!
//! - 1:N² splits (4:1 included) and Catmull-Clark nest: the children of a face are contiguous
//!   and in the order of their parents (`N²` per triangle; one quad per corner), so a face's
//!   parent is a function of its index and of the base faces' degrees.
//! - √3, Doo-Sabin and mid-edge do not nest: a face that comes from several faces of the
//!   level before (√3's flipped triangles, the dual rules' edge and vertex faces) takes the
//!   least of their values. Chained from the base level, where each face's value is its own
//!   index, that is the lowest-numbered base face it descends from.

use super::topo::Topo;
use super::Split;
use crate::mesh::INVALID;
use crate::Result;

/// The value of each face of the level after `t` (split `split`) from the values `parent` of
/// the faces of `t`: a nesting split's children take their parent's, the others the least of
/// the faces they come from.
pub(crate) fn child_faces(split: Split, t: &Topo<'_>, parent: &[u32]) -> Result<Vec<u32>> {
    let (nv, ne, nf) = (t.nv(), t.ne(), t.nf());
    let value = |f: u32| parent[f as usize];
    let least_around = |v: u32| {
        let mut least = INVALID;
        t.for_outgoing(v, |h| {
            if !t.is_boundary(h) {
                least = least.min(value(t.face(h)));
            }
        });
        least
    };
    let mut out;
    match split {
        Split::Tri(n) => {
            let per_face = (n * n) as usize;
            out = super::alloc::with_capacity(per_face * nf, "base faces")?;
            for &p in parent {
                out.extend(std::iter::repeat(p).take(per_face));
            }
        }
        Split::Quad => {
            out = super::alloc::with_capacity(2 * ne, "base faces")?;
            for f in 0..nf as u32 {
                t.for_face(f, |_| out.push(value(f)));
            }
        }
        Split::Sqrt3 { .. } => {
            // The triangle of face half-edge `g` (corner `3f + k`) lies in `f` and, across an
            // interior edge, in the face of `g`'s twin.
            out = super::alloc::with_capacity(3 * nf, "base faces")?;
            for f in 0..nf as u32 {
                for k in 0..3 {
                    let g = t.triangle_side(f, k);
                    let across = if t.is_boundary(g ^ 1) {
                        INVALID
                    } else {
                        value(t.face(g ^ 1))
                    };
                    out.push(value(f).min(across));
                }
            }
        }
        Split::DualCorners => {
            // The shrunken faces, one quad per edge, one face per vertex.
            out = super::alloc::with_capacity(nf + ne + nv, "base faces")?;
            out.extend_from_slice(&parent[..nf]);
            for e in 0..ne as u32 {
                let side = |h: u32| {
                    if t.is_boundary(h) {
                        INVALID
                    } else {
                        value(t.face(h))
                    }
                };
                out.push(side(2 * e).min(side(2 * e + 1)));
            }
            out.extend((0..nv as u32).map(least_around));
        }
        Split::DualEdges => {
            // The old faces, one face per vertex.
            out = super::alloc::with_capacity(nf + nv, "base faces")?;
            out.extend_from_slice(&parent[..nf]);
            out.extend((0..nv as u32).map(least_around));
        }
    }
    Ok(out)
}

/// The base face of each face of level `level` of a nesting split (`Tri`, `Quad`) on base
/// faces of `degrees`: `N^(2 level)` children per triangle, `degree · 4^(level - 1)` per face
/// under Catmull-Clark; `None` for the other splits, which need the levels' topology
/// ([`child_faces`]).
///
/// # Errors
///
/// [`crate::Error::IndexOverflow`] when the level's faces do not fit `usize`.
pub(crate) fn nested_base_faces(
    split: Split,
    degrees: impl Iterator<Item = usize>,
    level: u32,
) -> Result<Option<Vec<u32>>> {
    let children = |degree: usize| -> u128 {
        match split {
            _ if level == 0 => 1,
            Split::Tri(n) => u128::from(n * n).saturating_pow(level),
            _ => 4u128
                .saturating_pow(level - 1)
                .saturating_mul(degree as u128),
        }
    };
    if !matches!(split, Split::Tri(_) | Split::Quad) {
        return Ok(None);
    }
    let counts: Vec<u128> = degrees.map(children).collect();
    let total = counts.iter().fold(0u128, |a, &c| a.saturating_add(c));
    let too_many = crate::Error::IndexOverflow {
        what: "base faces",
        count: total,
    };
    let total = usize::try_from(total).map_err(|_| too_many)?;
    let mut out = super::alloc::with_capacity(total, "base faces")?;
    for (f, &c) in counts.iter().enumerate() {
        // Each count is at most `total`, which fits usize.
        out.extend(std::iter::repeat(f as u32).take(c as usize));
    }
    Ok(Some(out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::subdivide::{subdivide, SubdivideOptions};
    use crate::{shapes, HalfEdgeMesh, Rule};

    /// The nesting splits' closed forms are the children of each face in the topology the
    /// steps build: `child_faces` chained level by level on the half-edge meshes of
    /// `subdivide` (1:N², 4:1 with boundary, Catmull-Clark on a mixed mesh).
    #[test]
    fn the_nested_closed_forms_are_the_chained_children() {
        let cases = [
            (shapes::icosahedron(), Rule::Loop, Split::Tri(2)),
            (shapes::grid(2, 2).expect("grid"), Rule::Loop, Split::Tri(2)),
            (shapes::icosahedron(), Rule::TriSplit(3), Split::Tri(3)),
            (shapes::mixed(), Rule::CatmullClark, Split::Quad),
        ];
        for (base, rule, split) in cases {
            let mesh = HalfEdgeMesh::try_from_polygon_mesh(&base).expect("a manifold");
            let mut chained: Vec<u32> = (0..mesh.n_faces() as u32).collect();
            for level in 1..=3 {
                let before = subdivide(&mesh, rule, level - 1, &SubdivideOptions::default())
                    .expect("subdivided");
                chained = child_faces(split, &Topo::new(&before), &chained).expect("children");
                let degrees = (0..base.n_faces()).map(|f| base.face(f).len());
                let closed = nested_base_faces(split, degrees, level).expect("fits");
                assert_eq!(Some(&chained), closed.as_ref(), "{rule} level {level}");
            }
        }
    }
}
