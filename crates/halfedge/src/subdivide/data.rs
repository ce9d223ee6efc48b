//! The vertex data the geometry kernels combine: [`Scalar`] (`f32`, `f64`) and the crate's
//! [`Vector`] trait, implemented for `DVec3` (the one-shot positions), for `[T; N]` (any
//! caller data) and for [`Sparse`] (a weighted sum of base vertices, from which the stencil
//! tables are read).
//!
//! Every operation is componentwise and in the order the kernel writes it (no fused
//! multiply-add, no reassociation), so `[f64; 3]` and `DVec3` give the same bits.

use glam::DVec3;

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// A floating-point type vertex data can be refined in: `f32` or `f64` (sealed).
///
/// The weights of the rules are computed in `f64` and converted to the scalar type; the
/// arithmetic then runs in the scalar type, componentwise.
pub trait Scalar:
    sealed::Sealed
    + Copy
    + Send
    + Sync
    + PartialEq
    + PartialOrd
    + std::fmt::Debug
    + Default
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
    + std::ops::Div<Output = Self>
    + 'static
{
    /// Zero.
    const ZERO: Self;
    /// The `f64` weight `w` in this type (rounded for `f32`).
    fn from_f64(w: f64) -> Self;
    /// This value as `f64` (exact).
    fn to_f64(self) -> f64;
    /// The square root.
    fn sqrt(self) -> Self;
    /// The absolute value.
    fn abs(self) -> Self;
    /// Above this magnitude a squared length may overflow (the sphere projection rescales).
    #[doc(hidden)]
    const SQUARE_SAFE_MAX: Self;
    /// Below this magnitude (and above zero) a squared length may vanish.
    #[doc(hidden)]
    const SQUARE_SAFE_MIN: Self;
}

/// The items of [`Scalar`] both float types write alike: zero, the square-safe bounds
/// `max` and `min`, and their inherent `sqrt` and `abs`.
macro_rules! float_scalar_items {
    ($t:ident, max: $max:literal, min: $min:literal) => {
        const ZERO: $t = 0.0;
        const SQUARE_SAFE_MAX: $t = $max;
        const SQUARE_SAFE_MIN: $t = $min;
        #[inline(always)]
        fn sqrt(self) -> $t {
            $t::sqrt(self)
        }
        #[inline(always)]
        fn abs(self) -> $t {
            $t::abs(self)
        }
    };
}

impl Scalar for f64 {
    float_scalar_items!(f64, max: 1e150, min: 1e-150);
    #[inline(always)]
    fn from_f64(w: f64) -> f64 {
        w
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
}

impl Scalar for f32 {
    float_scalar_items!(f32, max: 1e18, min: 1e-18);
    #[inline(always)]
    fn from_f64(w: f64) -> f32 {
        w as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        f64::from(self)
    }
}

/// What the geometry kernels combine: a value per vertex with the operations of an affine
/// combination. Weights are `f64`.
pub(crate) trait Vector: Clone + Send + Sync {
    /// The zero value (the start of a sum).
    fn zero() -> Self;
    /// `self + o`, componentwise.
    fn add(self, o: Self) -> Self;
    /// `self - o`, componentwise.
    fn sub(self, o: Self) -> Self;
    /// `self * w`, componentwise.
    fn scale(self, w: f64) -> Self;
    /// `self / w`, componentwise.
    fn div(self, w: f64) -> Self;
    /// The point on the unit sphere in the direction of `self` (not linear: never asked of
    /// [`Sparse`], whose caller refuses the icosphere rule first).
    fn project_to_sphere(self) -> Self;
}

impl Vector for DVec3 {
    #[inline(always)]
    fn zero() -> Self {
        DVec3::ZERO
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self + o
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self - o
    }
    #[inline(always)]
    fn scale(self, w: f64) -> Self {
        self * w
    }
    #[inline(always)]
    fn div(self, w: f64) -> Self {
        self / w
    }
    /// Where `p`'s squared length would overflow (coordinates beyond about 1e154) or vanish
    /// (below about 1e-154, subnormals included), it is first divided by its largest
    /// coordinate, so the direction stays exact; other points take glam's `normalize`
    /// unchanged. A point at the origin has no direction: NaN, which the level's finiteness
    /// check refuses, naming the edge.
    #[inline]
    fn project_to_sphere(self) -> Self {
        let largest = self.abs().max_element();
        if largest > 1e150 || (largest < 1e-150 && largest > 0.0) {
            (self / largest).normalize()
        } else {
            self.normalize()
        }
    }
}

impl<T: Scalar, const N: usize> Vector for [T; N] {
    #[inline(always)]
    fn zero() -> Self {
        [T::ZERO; N]
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        std::array::from_fn(|i| self[i] + o[i])
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        std::array::from_fn(|i| self[i] - o[i])
    }
    #[inline(always)]
    fn scale(self, w: f64) -> Self {
        let w = T::from_f64(w);
        std::array::from_fn(|i| self[i] * w)
    }
    #[inline(always)]
    fn div(self, w: f64) -> Self {
        let w = T::from_f64(w);
        std::array::from_fn(|i| self[i] / w)
    }
    /// As for `DVec3` (glam's `normalize`: `p * (1 / sqrt((x x + y y) + z z))`), with the
    /// rescaling thresholds of the scalar type.
    #[inline]
    fn project_to_sphere(self) -> Self {
        // glam's max_element (a NaN coordinate gives NaN either way).
        let mut largest = self.first().map_or(T::ZERO, |x| x.abs());
        for x in self.iter().skip(1) {
            if x.abs() > largest {
                largest = x.abs();
            }
        }
        let p = if largest > T::SQUARE_SAFE_MAX
            || (largest < T::SQUARE_SAFE_MIN && largest > T::ZERO)
        {
            std::array::from_fn(|i| self[i] / largest)
        } else {
            self
        };
        let mut dot = T::ZERO;
        for (i, x) in p.iter().enumerate() {
            dot = if i == 0 { *x * *x } else { dot + *x * *x };
        }
        let recip = T::from_f64(1.0) / dot.sqrt();
        std::array::from_fn(|i| p[i] * recip)
    }
}

/// A weighted sum of base vertices, sorted by vertex: what a kernel computes when every base
/// vertex is its own unit vector. The stencil tables are read from it.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Sparse(pub(crate) Vec<(u32, f64)>);

impl Sparse {
    /// Base vertex `v` with weight 1.
    pub(crate) fn unit(v: u32) -> Sparse {
        Sparse(vec![(v, 1.0)])
    }

    fn merge(self, o: Sparse, sign: f64) -> Sparse {
        if o.0.is_empty() {
            return self;
        }
        if self.0.is_empty() && sign == 1.0 {
            return o;
        }
        let mut out = Vec::with_capacity(self.0.len() + o.0.len());
        let (mut i, mut j) = (0, 0);
        let (a, b) = (&self.0, &o.0);
        while i < a.len() && j < b.len() {
            match a[i].0.cmp(&b[j].0) {
                std::cmp::Ordering::Less => {
                    out.push(a[i]);
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    out.push((b[j].0, sign * b[j].1));
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    out.push((a[i].0, a[i].1 + sign * b[j].1));
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend(b[j..].iter().map(|&(v, w)| (v, sign * w)));
        Sparse(out)
    }
}

impl Vector for Sparse {
    fn zero() -> Self {
        Sparse(Vec::new())
    }
    fn add(self, o: Self) -> Self {
        self.merge(o, 1.0)
    }
    fn sub(self, o: Self) -> Self {
        self.merge(o, -1.0)
    }
    fn scale(mut self, w: f64) -> Self {
        self.0.iter_mut().for_each(|(_, x)| *x *= w);
        self
    }
    fn div(mut self, w: f64) -> Self {
        self.0.iter_mut().for_each(|(_, x)| *x /= w);
        self
    }
    fn project_to_sphere(self) -> Self {
        // Not linear: `Refinement::stencils` refuses the icosphere rule before any kernel runs.
        self
    }
}

/// The base vertices a [`Sparse`] sum reads, without its weights: the kernels run on it to
/// count a stencil table's entries before the table is allocated
/// ([`Refinement::stencil_sizes`](super::Refinement::stencil_sizes)). `add` and `sub` unite
/// the sorted vertex lists, as [`Sparse`] merges them (it keeps every vertex of either
/// operand, a weight that cancels to zero included); `scale` and `div` keep the list.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Support(pub(crate) Vec<u32>);

impl Support {
    /// Base vertex `v`.
    pub(crate) fn unit(v: u32) -> Support {
        Support(vec![v])
    }

    fn unite(self, o: Support) -> Support {
        if o.0.is_empty() {
            return self;
        }
        if self.0.is_empty() {
            return o;
        }
        let mut out = Vec::with_capacity(self.0.len() + o.0.len());
        let (mut i, mut j) = (0, 0);
        let (a, b) = (&self.0, &o.0);
        while i < a.len() && j < b.len() {
            match a[i].cmp(&b[j]) {
                std::cmp::Ordering::Less => {
                    out.push(a[i]);
                    i += 1;
                }
                std::cmp::Ordering::Greater => {
                    out.push(b[j]);
                    j += 1;
                }
                std::cmp::Ordering::Equal => {
                    out.push(a[i]);
                    i += 1;
                    j += 1;
                }
            }
        }
        out.extend_from_slice(&a[i..]);
        out.extend_from_slice(&b[j..]);
        Support(out)
    }
}

impl Vector for Support {
    fn zero() -> Self {
        Support(Vec::new())
    }
    fn add(self, o: Self) -> Self {
        self.unite(o)
    }
    fn sub(self, o: Self) -> Self {
        self.unite(o)
    }
    fn scale(self, _: f64) -> Self {
        self
    }
    fn div(self, _: f64) -> Self {
        self
    }
    fn project_to_sphere(self) -> Self {
        // Not linear: `Refinement::stencil_sizes` refuses the icosphere rule first.
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_match_dvec3_to_the_bit() {
        let p = DVec3::new(0.1, -2.5e-3, 7.25);
        let q = DVec3::new(1.0 / 3.0, 1e-7, -0.6);
        let (a, b) = (p.to_array(), q.to_array());
        assert_eq!(p.add(q).scale(0.375).to_array(), a.add(b).scale(0.375));
        assert_eq!(p.sub(q).div(3.0).to_array(), a.sub(b).div(3.0));
        for x in [
            p,
            q,
            DVec3::new(3e200, -1e200, 0.0),
            DVec3::new(1e-300, 0.0, 2e-301),
        ] {
            assert_eq!(
                x.project_to_sphere().to_array(),
                x.to_array().project_to_sphere()
            );
        }
        let f = [1e30f32, 0.0, -2e30];
        let s = f.project_to_sphere();
        assert!((s[0] * s[0] + s[2] * s[2] - 1.0).abs() < 1e-6, "{s:?}");
    }

    #[test]
    fn sparse_sums_merge_by_vertex() {
        let s = Sparse::unit(3)
            .add(Sparse::unit(1).scale(2.0))
            .sub(Sparse::unit(3).div(4.0));
        assert_eq!(s.0, [(1, 2.0), (3, 0.75)]);
    }

    #[test]
    fn supports_unite_as_sparse_sums_merge() {
        // A weight that cancels stays an entry of the sparse sum, and of its support.
        let s = Sparse::unit(3)
            .add(Sparse::unit(1).scale(2.0))
            .sub(Sparse::unit(3))
            .add(Sparse::zero().sub(Sparse::unit(0)));
        assert_eq!(s.0, [(0, -1.0), (1, 2.0), (3, 0.0)]);
        let support = Support::unit(3)
            .add(Support::unit(1).scale(2.0))
            .sub(Support::unit(3))
            .add(Support::zero().sub(Support::unit(0)));
        assert_eq!(support.0, [0, 1, 3]);
    }
}
