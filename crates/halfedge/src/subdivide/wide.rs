//! Wide faces and wide vertex rings: the elements whose rules weigh every corner of the
//! element by a cosine of the angle between corners (Doo-Sabin's face points, the modified
//! butterfly's one-ring stencil). A direct sum per corner costs `n²` per element; above
//! [`DIRECT_MAX`] corners the rules use a few element-wide sums instead ([`Wide::sums`]),
//! since `cos(θ_j - θ_i) = cos θ_i cos θ_j + sin θ_i sin θ_j`: `O(n)` per element.
//!
//! Elements of at most [`DIRECT_MAX`] corners keep the direct sums, so every ordinary mesh's
//! output is what it always was, bit for bit (a wide element's corners agree with the direct
//! sums up to rounding, about `n` ulps).
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Owner of wide faces and vertex rings (more than 32 corners: element-wide sums instead of a sum
//! per corner, so Doo-Sabin and the butterfly stay linear): `halfedge::subdivide`'s `wide.rs`
//! (`Wide`, `Ring`, `DIRECT_MAX`).

use std::f64::consts::PI;

use super::data::Vector;
use super::topo::Topo;

/// The most corners an element may have and still be summed directly: 32 keeps every
/// ordinary mesh's output (the shared meshes' faces have at most 16 sides and their vertices
/// a valence of at most 16), while an element of 33 corners costs at most 33 products per
/// corner, never more than about five times the element-wide form.
pub(crate) const DIRECT_MAX: usize = 32;

/// Which elements: faces (corners in face order, [`Topo::next`]) or the rings of interior
/// vertices (outgoing half-edges clockwise, `next(twin(h))`, as [`Topo::for_outgoing`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Ring {
    Faces,
    Vertices,
}

/// The angle `θ_i = 2πi/n` of corner `i` of an element of `n` corners.
pub(crate) fn angle(n: u32, i: u32) -> f64 {
    2.0 * PI * f64::from(i) / f64::from(n)
}

/// The elements of `t` with more than [`DIRECT_MAX`] corners: `O(corners)` to build, a bit
/// per element to tell the others, `O(log)` per corner of a wide element to find its index;
/// 12 bytes per corner of a wide element, 8 per wide element.
pub(crate) struct Wide {
    ring: Ring,
    /// Each wide element's first half-edge (corner 0) and number of corners.
    elements: Vec<(u32, u32)>,
    /// Each corner of a wide element: (its half-edge, the element's slot, its index from
    /// corner 0), by half-edge.
    corners: Vec<(u32, u32, u32)>,
    /// One bit per element of `t`, set on the wide ones.
    is_wide: Vec<u64>,
}

impl Wide {
    /// The wide elements of `t`; `None` when there is none or the room for them is refused
    /// (the direct sums then serve every element, in quadratic time rather than an abort).
    pub(crate) fn of(t: &Topo<'_>, ring: Ring) -> Option<Wide> {
        let n_elements = match ring {
            Ring::Faces => t.nf(),
            Ring::Vertices => t.nv(),
        };
        let size = |x: u32| match ring {
            Ring::Faces => t.face_degree(x),
            Ring::Vertices if t.is_boundary_vertex(x) => 0,
            Ring::Vertices => t.valence(x),
        };
        let (mut count, mut n_corners) = (0usize, 0usize);
        for x in 0..n_elements as u32 {
            let n = size(x);
            if n > DIRECT_MAX {
                count += 1;
                n_corners += n;
            }
        }
        if count == 0 {
            return None;
        }
        let mut wide = Wide {
            ring,
            elements: Vec::new(),
            corners: Vec::new(),
            is_wide: Vec::new(),
        };
        wide.elements.try_reserve_exact(count).ok()?;
        wide.corners.try_reserve_exact(n_corners).ok()?;
        wide.is_wide
            .try_reserve_exact(n_elements.div_ceil(64))
            .ok()?;
        wide.is_wide.resize(n_elements.div_ceil(64), 0u64);
        for x in 0..n_elements as u32 {
            let n = size(x);
            if n <= DIRECT_MAX {
                continue;
            }
            let slot = wide.elements.len() as u32;
            let first = match ring {
                Ring::Faces => t.face_halfedge(x),
                Ring::Vertices => t.vertex_halfedge(x),
            };
            wide.elements.push((first, n as u32));
            wide.is_wide[x as usize / 64] |= 1 << (x % 64);
            let mut h = first;
            for i in 0..n as u32 {
                wide.corners.push((h, slot, i));
                h = wide.step(t, h);
            }
        }
        wide.corners.sort_unstable_by_key(|c| c.0);
        Some(wide)
    }

    /// The corner after `h` in its element.
    fn step(&self, t: &Topo<'_>, h: u32) -> u32 {
        match self.ring {
            Ring::Faces => t.next(h),
            Ring::Vertices => t.next(h ^ 1),
        }
    }

    /// The number of wide elements.
    pub(crate) fn len(&self) -> usize {
        self.elements.len()
    }

    /// The number of corners of the wide element in slot `slot`.
    pub(crate) fn size(&self, slot: usize) -> u32 {
        self.elements[slot].1
    }

    /// The slot of the element of half-edge `h` (its face, not a boundary half-edge; or its
    /// source) and the index of its corner there, if the element is wide.
    pub(crate) fn corner(&self, t: &Topo<'_>, h: u32) -> Option<(usize, u32)> {
        let x = match self.ring {
            Ring::Faces => t.face(h),
            Ring::Vertices => t.source(h),
        } as usize;
        if self.is_wide.get(x / 64).map_or(0, |w| w & (1 << (x % 64))) == 0 {
            return None;
        }
        let k = self.corners.binary_search_by_key(&h, |c| c.0).ok()?;
        let (_, slot, i) = self.corners[k];
        Some((slot as usize, i))
    }

    /// Calls `f(j, h)` on each corner of the wide element in slot `slot`, from corner 0.
    pub(crate) fn for_corners(&self, t: &Topo<'_>, slot: usize, mut f: impl FnMut(u32, u32)) {
        let (mut h, n) = self.elements[slot];
        for j in 0..n {
            f(j, h);
            h = self.step(t, h);
        }
    }

    /// The element-wide sums of `value` (of each corner's half-edge) in slot `slot`, each
    /// divided by the element's size: the mean, then `Σ cos(kθ_j) v_j` and `Σ sin(kθ_j) v_j`
    /// for `k = 1..=harmonics` (`1 + 2 harmonics` values).
    pub(crate) fn sums<V: Vector>(
        &self,
        t: &Topo<'_>,
        slot: usize,
        harmonics: u32,
        value: impl Fn(u32) -> V,
    ) -> Vec<V> {
        let n = self.size(slot);
        let each = 1.0 / f64::from(n);
        let mut sums: Vec<V> = (0..1 + 2 * harmonics).map(|_| V::zero()).collect();
        self.for_corners(t, slot, |j, h| {
            let v = value(h);
            let mut weights = vec![each];
            for k in 1..=harmonics {
                let (sin, cos) = angle(n, (k * j) % n).sin_cos();
                weights.extend([cos * each, sin * each]);
            }
            for (sum, w) in sums.iter_mut().zip(weights) {
                *sum = std::mem::replace(sum, V::zero()).add(v.clone().scale(w));
            }
        });
        sums
    }
}
