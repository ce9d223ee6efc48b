//! Stencil tables: every vertex of the last level as a weighted sum of base vertices.

use super::{check_len, Refinement, Scalar, Sparse, Support, Vector};
use crate::{Error, Result};

/// The sizes of a [`StencilTable`], known before it is allocated
/// ([`Refinement::stencil_sizes`](super::Refinement::stencil_sizes)): `rows` stencils (the
/// last level's vertices) of `entries` (index, weight) pairs in all.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct StencilSizes {
    /// The number of stencils: `offsets` has one more entry.
    pub rows: usize,
    /// The number of (index, weight) entries: the length of `indices` and `weights`.
    pub entries: usize,
}

impl StencilSizes {
    /// The bytes of the table's arrays: 4 per offset (`rows + 1` of them), 4 + 8 per entry.
    pub fn bytes(&self) -> u128 {
        4 * (self.rows as u128 + 1) + 12 * self.entries as u128
    }

    /// The table's arrays, empty with exactly these capacities.
    fn allocate(&self) -> Result<(Vec<u32>, Vec<u32>, Vec<f64>)> {
        if u32::try_from(self.entries).is_err() {
            return Err(Error::IndexOverflow {
                what: "stencil entries",
                count: self.entries as u128,
            });
        }
        use crate::subdivide::alloc::with_capacity;
        Ok((
            with_capacity(self.rows + 1, "stencil offsets")?,
            with_capacity(self.entries, "stencil indices")?,
            with_capacity(self.entries, "stencil weights")?,
        ))
    }
}

/// Each vertex of a refinement's last level as a weighted sum of the base vertices
/// ([`Refinement::stencils`](super::Refinement::stencils)), in compressed rows: vertex `i` is
/// `Σ weights[k] * base[indices[k]]` for `k` in `offsets[i]..offsets[i + 1]`, the indices of
/// a row ascending. OpenSubdiv's `Far::StencilTable` (sizes, offsets, indices, weights).
///
/// ```
/// use halfedge::refine::Refinement;
/// use halfedge::subdivide::SubdivideOptions;
/// use halfedge::{shapes, HalfEdgeMesh, Rule};
///
/// let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
/// let r = Refinement::new(&cube, Rule::CatmullClark, 2, &SubdivideOptions::default())?;
/// let table = r.stencils()?;
/// assert_eq!(table.len(), r.n_vertices(2));
/// // Affine: every row sums to 1.
/// for i in 0..table.len() {
///     let (_, weights) = table.row(i);
///     assert!((weights.iter().sum::<f64>() - 1.0).abs() < 1e-12);
/// }
/// let base: Vec<[f64; 3]> = cube.positions().iter().map(|p| p.to_array()).collect();
/// let mut out = vec![[0.0; 3]; table.len()];
/// table.apply(&base, &mut out)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct StencilTable {
    base_vertices: usize,
    offsets: Vec<u32>,
    indices: Vec<u32>,
    weights: Vec<f64>,
}

impl StencilTable {
    /// The table of the sparse sums `rows` over `base_vertices` vertices into arrays
    /// allocated once with the sizes counted beforehand (`sizes`, from the supports); a row
    /// count or an entry count that differs is a bug ([`Error::PredictionMismatch`] under
    /// `scheme`, `level`).
    pub(super) fn from_sums(
        rows: &[Sparse],
        base_vertices: usize,
        sizes: StencilSizes,
        scheme: &str,
        level: u32,
    ) -> Result<StencilTable> {
        let mismatch =
            |what: &'static str, predicted: usize, actual: usize| Error::PredictionMismatch {
                scheme: scheme.to_owned(),
                level,
                what,
                predicted: predicted.into(),
                actual: actual as u64,
            };
        if rows.len() != sizes.rows {
            return Err(mismatch("stencils", sizes.rows, rows.len()));
        }
        let entries: usize = rows.iter().map(|r| r.0.len()).sum();
        if entries != sizes.entries {
            return Err(mismatch("stencil entries", sizes.entries, entries));
        }
        let (mut offsets, mut indices, mut weights) = sizes.allocate()?;
        offsets.push(0u32);
        for row in rows {
            for &(v, w) in &row.0 {
                indices.push(v);
                weights.push(w);
            }
            // At most `entries`, which fits u32 (checked by `allocate`).
            offsets.push(indices.len() as u32);
        }
        Ok(StencilTable {
            base_vertices,
            offsets,
            indices,
            weights,
        })
    }

    /// The sizes of the table ([`StencilSizes`]).
    pub fn sizes(&self) -> StencilSizes {
        StencilSizes {
            rows: self.len(),
            entries: self.n_entries(),
        }
    }

    /// The number of stencils (vertices of the last level).
    pub fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Whether the table has no stencils.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The number of base vertices the stencils read.
    pub fn base_vertices(&self) -> usize {
        self.base_vertices
    }

    /// The total number of (index, weight) entries.
    pub fn n_entries(&self) -> usize {
        self.indices.len()
    }

    /// Row starts: `len() + 1` entries.
    pub fn offsets(&self) -> &[u32] {
        &self.offsets
    }

    /// The base vertex of each entry.
    pub fn indices(&self) -> &[u32] {
        &self.indices
    }

    /// The weight of each entry.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The base vertices and weights of stencil `i`.
    ///
    /// # Panics
    ///
    /// If `i >= len()`.
    pub fn row(&self, i: usize) -> (&[u32], &[f64]) {
        let (a, b) = (self.offsets[i] as usize, self.offsets[i + 1] as usize);
        (&self.indices[a..b], &self.weights[a..b])
    }

    /// `out[i] = Σ weights[k] * base[indices[k]]` over row `i` (weights rounded to `T`, sums
    /// in `T`, in row order), in parallel on rayon's current pool for large tables.
    ///
    /// # Errors
    ///
    /// [`Error::BufferSize`] when `base` does not have [`StencilTable::base_vertices`]
    /// entries or `out` [`StencilTable::len`].
    pub fn apply<T: Scalar, const N: usize>(
        &self,
        base: &[[T; N]],
        out: &mut [[T; N]],
    ) -> Result<()> {
        use rayon::prelude::*;
        check_len("base", self.base_vertices, base.len())?;
        check_len("out", self.len(), out.len())?;
        let row = |(i, o): (usize, &mut [T; N])| {
            let (a, b) = (self.offsets[i] as usize, self.offsets[i + 1] as usize);
            let mut acc = [T::ZERO; N];
            for (&v, &w) in self.indices[a..b].iter().zip(&self.weights[a..b]) {
                let w = T::from_f64(w);
                let p = &base[v as usize];
                for c in 0..N {
                    acc[c] = acc[c] + p[c] * w;
                }
            }
            *o = acc;
        };
        if out.len() >= 1 << 14 {
            out.par_iter_mut().enumerate().for_each(row);
        } else {
            out.iter_mut().enumerate().for_each(row);
        }
        Ok(())
    }
}

impl Refinement {
    /// The last level's vertices as weighted sums of the base vertices, for the linear rules (every
    /// rule but [`Rule::Icosphere`](crate::Rule::Icosphere)): the form GPU evaluators consume
    /// (OpenSubdiv's `Far::StencilTable`). Computed by running the rules' kernels level by level on
    /// sparse sums, after the table's sizes are counted ([`Refinement::stencil_sizes`]); its arrays
    /// are allocated once, exactly, and filled.
    ///
    /// # Errors
    ///
    /// [`Error::NotLinear`] for [`Rule::Icosphere`](crate::Rule::Icosphere);
    /// [`Error::IndexOverflow`] beyond `u32` entries; [`Error::AllocationFailed`].
    pub fn stencils(&self) -> Result<StencilTable> {
        let sizes = self.stencil_sizes()?;
        let current = self.last_level_sums(Sparse::unit, false)?;
        let n0 = self.base_vertices();
        StencilTable::from_sums(&current, n0, sizes, &self.name, self.levels)
    }

    /// The sizes of [`Refinement::stencils`]' table before anything of it is allocated: its
    /// rows (the last level's vertices) and its entries, counted by running the rules' kernels
    /// level by level on the supports of the sums (their base vertices, without weights).
    ///
    /// ```
    /// use halfedge::refine::Refinement;
    /// use halfedge::subdivide::SubdivideOptions;
    /// use halfedge::{shapes, HalfEdgeMesh, Rule};
    ///
    /// let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
    /// let r = Refinement::new(&cube, Rule::CatmullClark, 2, &SubdivideOptions::default())?;
    /// let sizes = r.stencil_sizes()?;
    /// assert_eq!(sizes.rows, r.n_vertices(2));
    /// assert_eq!(sizes, r.stencils()?.sizes());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::NotLinear`] for [`Rule::Icosphere`](crate::Rule::Icosphere);
    /// [`Error::AllocationFailed`].
    pub fn stencil_sizes(&self) -> Result<StencilSizes> {
        if !self.rule.is_linear() {
            return Err(Error::NotLinear {
                rule: self.name.clone(),
                reason: "the sphere projection",
            });
        }
        let current = self.last_level_sums(Support::unit, false)?;
        Ok(StencilSizes {
            rows: current.len(),
            entries: current.iter().map(|r| r.0.len()).sum(),
        })
    }

    /// The written vertices of the last level as sums `V` of the base vertices (`unit(i)` is
    /// base vertex `i`), level by level through the rules' kernels.
    pub(super) fn last_level_sums<V: Vector>(
        &self,
        unit: impl Fn(u32) -> V,
        whole: bool,
    ) -> Result<Vec<V>> {
        let n0 = self.base_vertices() as u32;
        let mut current: Vec<V> = (0..n0).map(unit).collect();
        for s in 1..=self.levels {
            current = self.run(|| self.collect_level(s, &current, whole))?;
        }
        if self.levels == 0 && !whole {
            current = self.written_of(current);
        }
        Ok(current)
    }
}
