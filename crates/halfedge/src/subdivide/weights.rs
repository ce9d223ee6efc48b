//! Sparse weight tables: child vertices as weights of the parent's ([`WeightTable`]), what
//! the crease rules and the face-varying corner channels give, applied to any
//! [`Vector`](crate::subdivide::data::Vector) data. Below the rules' kernels and the
//! refinement, which both fill and read them.

use crate::mesh::INVALID;
use crate::subdivide::data::Vector;
use crate::subdivide::par::Sink;
use crate::{Error, Result};

/// A level's child vertices as sparse weights of the parent's vertices: every child vertex
/// (a dense table, rows in child order), or only the child vertices whose crease mask is not
/// the one of the level's [`Base`] (the rows overriding it, in ascending child order).
#[derive(Debug, Default)]
pub(crate) struct WeightTable {
    /// The child vertex of each row, ascending; `None` for a dense table (row `r` is child `r`).
    pub(crate) rows: Option<Vec<u32>>,
    /// Row `r` is entries `offsets[r]..offsets[r + 1]`.
    pub(crate) offsets: Vec<u32>,
    /// The parent vertex of each entry.
    pub(crate) index: Vec<u32>,
    /// The weight of each entry.
    pub(crate) weight: Vec<f64>,
}

/// Rows per task when the overriding rows are evaluated in parallel.
const APPLY_CHUNK: usize = 1 << 12;

impl WeightTable {
    /// Bytes held.
    pub(crate) fn bytes(&self) -> usize {
        4 * (self.offsets.len() + self.index.len() + self.rows.as_ref().map_or(0, Vec::len))
            + 8 * self.weight.len()
    }

    /// The number of rows.
    pub(crate) fn rows(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// An empty table with room for `rows` rows and `entries` weights, rows then pushed one
    /// by one ([`WeightTable::push_row`]): a face-varying corner channel's new values
    /// ([`face_varying`](crate::refine::face_varying)).
    ///
    /// # Errors
    ///
    /// [`Error::AllocationFailed`].
    pub(crate) fn with_room(rows: usize, entries: usize) -> Result<WeightTable> {
        let what = "a face-varying weight table";
        let mut offsets = crate::subdivide::alloc::with_capacity(rows + 1, what)?;
        offsets.push(0);
        Ok(WeightTable {
            rows: None,
            offsets,
            index: crate::subdivide::alloc::with_capacity(entries, what)?,
            weight: crate::subdivide::alloc::with_capacity(entries, what)?,
        })
    }

    /// Appends `row` (parent index, weight) as the next row, equal indices merged, and
    /// clears it.
    ///
    /// # Errors
    ///
    /// [`Error::IndexOverflow`] past `u32::MAX` entries.
    pub(crate) fn push_row(&mut self, row: &mut Vec<(u32, f64)>) -> Result<()> {
        merge_row(row, &mut self.index, &mut self.weight);
        let end = u32::try_from(self.index.len()).map_err(|_| Error::IndexOverflow {
            what: "face-varying weight table entries",
            count: self.index.len() as u128,
        })?;
        self.offsets.push(end);
        Ok(())
    }

    /// Whether the table has a row for every child vertex.
    pub(crate) fn is_dense(&self) -> bool {
        self.rows.is_none()
    }

    /// Row `r` from the parent's data `src`; an index past `src` is a child vertex of
    /// `child` (a wide face's point, computed by the base rule before the overriding rows).
    #[inline]
    fn row<V: Vector>(&self, r: usize, src: &[V], child: &[V]) -> V {
        let (a, b) = (self.offsets[r] as usize, self.offsets[r + 1] as usize);
        let mut sum = V::zero();
        for (&i, &w) in self.index[a..b].iter().zip(&self.weight[a..b]) {
            let i = i as usize;
            let value = match src.get(i) {
                Some(v) => v.clone(),
                None => child[i].clone(),
            };
            sum = sum.add(value.scale(w));
        }
        sum
    }

    /// The child vertices of a dense table from the parent's data `src`, appended to `out`.
    pub(crate) fn points<V: Vector>(&self, src: &[V], out: &mut impl Sink<V>, parallel: bool) {
        out.append(self.rows(), parallel, |r| self.row(r, src, &[]));
    }

    /// Overwrites the child vertices of the rows of a sparse table in `dst` (the whole child
    /// level, its other vertices computed by the base rule) from the parent's data `src` and
    /// the face points of `dst` (a wide face's, never overridden).
    pub(crate) fn apply<V: Vector>(&self, src: &[V], dst: &mut [V], parallel: bool) {
        let Some(rows) = &self.rows else {
            return;
        };
        if parallel && rows.len() >= 2 * APPLY_CHUNK {
            use rayon::prelude::*;
            let child = &*dst;
            let values: Vec<V> = (0..rows.len())
                .into_par_iter()
                .with_min_len(APPLY_CHUNK)
                .map(|k| self.row(k, src, child))
                .collect();
            for (&r, v) in rows.iter().zip(values) {
                if let Some(d) = dst.get_mut(r as usize) {
                    *d = v;
                }
            }
        } else {
            for (k, &r) in rows.iter().enumerate() {
                let value = self.row(k, src, dst);
                if let Some(d) = dst.get_mut(r as usize) {
                    *d = value;
                }
            }
        }
    }
}

/// What computes the child vertices a sparse [`WeightTable`] has no row for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Base {
    /// The rule's own kernels (smooth Loop or Catmull-Clark, the boundary's crease rule).
    Rule,
    /// Linear interpolation: vertices stay, edge points are midpoints, face points centroids
    /// (a face-varying channel under `all`).
    Linear,
}

/// Appends `row` to `index` and `weight`, equal vertices merged (sorted by vertex), and
/// clears it.
pub(crate) fn merge_row(row: &mut Vec<(u32, f64)>, index: &mut Vec<u32>, weight: &mut Vec<f64>) {
    row.sort_by_key(|&(v, _)| v);
    let mut last = INVALID;
    for &(v, w) in row.iter() {
        if v == last {
            if let Some(x) = weight.last_mut() {
                *x += w;
            }
        } else {
            index.push(v);
            weight.push(w);
            last = v;
        }
    }
    row.clear();
}
