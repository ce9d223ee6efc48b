//! Every level's positions are checked before they are returned: a non-finite point (huge
//! coordinates whose weighted sums overflow, a point at the origin that the icosphere rule
//! cannot project onto the sphere) is [`Error::NonFinitePosition`], naming the vertex and the
//! element of the level before it was computed from. Texture coordinates are checked the
//! same way ([`check_uvs`]: [`Error::NonFiniteUv`]), in `f64` here and in `f32` or `f64` by a
//! refinement's caller.

use glam::DVec3;

use super::topo::Topo;
use super::Split;
use crate::error::{Error, Result};
use crate::mesh::HalfEdgeMesh;

/// The level before, as far as naming an origin needs it.
pub(super) enum Before<'a> {
    /// A half-edge mesh: edges are named by their end vertices.
    Mesh(&'a HalfEdgeMesh),
    /// A face list with `vertices` positions and `edges` edges (named by number).
    Counts { vertices: usize, edges: usize },
}

/// Refuses the first non-finite position of level `level`.
pub(super) fn check_positions(
    scheme: &str,
    split: Split,
    level: u32,
    before: &Before<'_>,
    positions: &[DVec3],
) -> Result<()> {
    let Some(v) = positions.iter().position(|p| !p.is_finite()) else {
        return Ok(());
    };
    let p = positions[v];
    Err(Error::NonFinitePosition {
        scheme: scheme.to_string(),
        level,
        vertex: v as u32,
        origin: origin(split, level, before, v),
        x: p.x,
        y: p.y,
        z: p.z,
    })
}

/// What vertex `v` of level `level` is computed from, in the numbering each module documents
/// (old vertices first, then edge points, then face points; one point per half-edge for
/// Doo-Sabin, per edge for mid-edge).
fn origin(split: Split, level: u32, before: &Before<'_>, v: usize) -> String {
    let of = if level == 1 {
        "of the input".to_string()
    } else {
        format!("of level {}", level - 1)
    };
    let (nv, ne) = match before {
        Before::Mesh(m) => (m.n_vertices(), m.n_edges()),
        Before::Counts { vertices, edges } => (*vertices, *edges),
    };
    let edge = |e: usize| match before {
        Before::Mesh(m) => {
            let t = Topo::new(m);
            let h = 2 * e as u32;
            format!("edge ({}, {}) {of}", t.source(h), t.target(h))
        }
        Before::Counts { .. } => format!("edge {e} {of}"),
    };
    match split {
        Split::Tri(..) | Split::Quad if v < nv => format!("from vertex {v} {of}"),
        Split::Tri(n) if v < nv + (n as usize - 1) * ne => {
            format!("on {}", edge((v - nv) / (n as usize - 1)))
        }
        Split::Quad if v < nv + ne => format!("on {}", edge(v - nv)),
        Split::Quad => format!("the point of face {} {of}", v - nv - ne),
        Split::Sqrt3 { boundary: false } if v < nv => format!("from vertex {v} {of}"),
        Split::Sqrt3 { boundary: false } => format!("the centre of face {} {of}", v - nv),
        Split::DualEdges if v < ne => format!("the midpoint of {}", edge(v)),
        Split::DualCorners if v < 2 * ne => match before {
            Before::Mesh(m) => {
                let t = Topo::new(m);
                let h = v as u32;
                if t.is_boundary(h) {
                    format!("on {}", edge(v / 2))
                } else {
                    format!(
                        "the corner of face {} at vertex {} {of}",
                        t.face(h),
                        t.source(h)
                    )
                }
            }
            Before::Counts { .. } => format!("from half-edge {v} {of}"),
        },
        // The kept boundary vertices (mid-edge) and the second Chaikin point of each boundary
        // edge (Doo-Sabin), numbered by the rank of their boundary half-edge.
        Split::DualEdges | Split::DualCorners => match before {
            Before::Mesh(m) => {
                let t = Topo::new(m);
                let first = if split == Split::DualEdges {
                    ne
                } else {
                    2 * ne
                };
                let h = (0..2 * ne as u32)
                    .filter(|&h| t.is_boundary(h))
                    .nth(v - first);
                match h {
                    Some(h) if split == Split::DualEdges => {
                        format!("from boundary vertex {} {of}", t.source(h))
                    }
                    Some(h) => format!("on {}", edge(h as usize / 2)),
                    None => format!("computed from {}", of.trim_start_matches("of ")),
                }
            }
            Before::Counts { .. } => format!("computed from {}", of.trim_start_matches("of ")),
        },
        _ => format!("computed from {}", of.trim_start_matches("of ")),
    }
}

/// Refuses the first non-finite texture coordinate among `values`, the UV values of level
/// `level` (computed in `f32` or `f64`, or converted to it at level 0): `origin` says from
/// what.
///
/// # Errors
///
/// [`Error::NonFiniteUv`] naming the scheme, level and value.
pub fn check_uvs<T: crate::Scalar>(
    scheme: &str,
    level: u32,
    values: &[[T; 2]],
    origin: &str,
) -> Result<()> {
    match first_non_finite(values) {
        None => Ok(()),
        Some((k, [u, v])) => Err(Error::NonFiniteUv {
            scheme: scheme.to_string(),
            level,
            value: k as u32,
            origin: origin.to_string(),
            u,
            v,
        }),
    }
}

/// The first value with a component that is not finite, with its index, in `f64`.
fn first_non_finite<T: crate::Scalar, const N: usize>(
    values: &[[T; N]],
) -> Option<(usize, [f64; N])> {
    let k = values
        .iter()
        .position(|x| x.iter().any(|c| !c.to_f64().is_finite()))?;
    Some((k, values[k].map(T::to_f64)))
}

/// Refuses the first non-finite vertex color among `colors`, those of level `level` of
/// `scheme` (computed in `f32` or `f64`): `origin` says from what.
///
/// # Errors
///
/// [`Error::NonFiniteColor`] naming the scheme, level and vertex.
pub fn check_colors<T: crate::Scalar>(
    (scheme, level): (&str, u32),
    colors: &[[T; 3]],
    origin: &str,
) -> Result<()> {
    let Some((v, [r, g, b])) = first_non_finite(colors) else {
        return Ok(());
    };
    Err(Error::NonFiniteColor {
        scheme: scheme.to_string(),
        level,
        vertex: v as u32,
        origin: origin.to_string(),
        r,
        g,
        b,
    })
}
