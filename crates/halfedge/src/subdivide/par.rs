//! Filling output arrays, sequentially or with rayon.

use rayon::prelude::*;

/// Below this many elements a pass runs sequentially even when parallelism is on.
const PARALLEL_MIN: usize = 1 << 14;

/// Elements per parallel task when filling half-edge arrays.
const CHUNK: usize = 1 << 13;

/// Appends `f(0), ..., f(n - 1)` to `out`, in parallel when `parallel` and `n` is large.
///
/// With enough capacity in `out` neither path reallocates (rayon's indexed `par_extend` writes
/// in place after reserving exactly `n`).
pub(crate) fn extend<T: Send>(
    out: &mut Vec<T>,
    n: usize,
    parallel: bool,
    f: impl Fn(usize) -> T + Sync + Send,
) {
    if parallel && n >= PARALLEL_MIN {
        out.par_extend((0..n).into_par_iter().map(f));
    } else {
        out.extend((0..n).map(f));
    }
}

/// `f(0), ..., f(n - 1)` in a new vector allocated exactly; `what` names it in an allocation
/// error.
///
/// # Errors
///
/// [`crate::Error::AllocationFailed`] when the system refuses the memory.
pub(crate) fn collect<T: Send>(
    n: usize,
    parallel: bool,
    what: &str,
    f: impl Fn(usize) -> T + Sync + Send,
) -> crate::Result<Vec<T>> {
    let mut out = super::alloc::with_capacity(n, what)?;
    extend(&mut out, n, parallel, f);
    Ok(out)
}

/// Calls `fill((i, chunk))` on the consecutive chunks of `len` elements of `out` (the last
/// may be shorter), in parallel when `parallel` and `out` has at least `parallel_min`
/// elements; on one thread the whole of `out` is one chunk.
pub(crate) fn for_each_chunk<T: Send>(
    out: &mut [T],
    len: usize,
    parallel: bool,
    parallel_min: usize,
    fill: impl Fn((usize, &mut [T])) + Sync + Send,
) {
    if parallel && out.len() >= parallel_min {
        out.par_chunks_mut(len).enumerate().for_each(fill);
    } else {
        fill((0, out));
    }
}

/// `part(range)` on the consecutive ranges of `len` elements of `0..n` (the last may be
/// shorter), in order, in parallel when `parallel` and `n >= parallel_min`; otherwise the one
/// result `part(0..n)`.
pub(crate) fn map_ranges<R: Send>(
    n: usize,
    len: usize,
    parallel: bool,
    parallel_min: usize,
    part: impl Fn(std::ops::Range<usize>) -> R + Sync + Send,
) -> Vec<R> {
    if parallel && n >= parallel_min {
        (0..n.div_ceil(len))
            .into_par_iter()
            .map(|c| part(c * len..((c + 1) * len).min(n)))
            .collect()
    } else {
        vec![part(0..n)]
    }
}

/// One chunk of each of the four half-edge arrays, as zipped by rayon.
type Chunks<'a> = (
    ((&'a mut [u32], &'a mut [u32]), &'a mut [u32]),
    &'a mut [u32],
);

/// The four half-edge arrays (`vertex`, `face`, `next`, `prev`), each of length `n`, with
/// entry `q` of each array from `f(q)`. The arrays are allocated zeroed (no memset: the pages
/// come zeroed from the allocator) and written front to back, in chunks in parallel.
///
/// # Errors
///
/// [`crate::Error::AllocationFailed`] when the system refuses the memory.
pub(crate) fn halfedge_arrays(
    n: usize,
    parallel: bool,
    f: impl Fn(u32) -> [u32; 4] + Sync + Send,
) -> crate::Result<[Vec<u32>; 4]> {
    let [mut vertex, mut face, mut next, mut prev] =
        super::alloc::zeroed_u32::<4>(n, "the half-edge arrays")?;
    let fill = |(chunk, (((v, fa), ne), pr)): (usize, Chunks<'_>)| {
        let base = (chunk * CHUNK) as u32;
        // Zipped iterators: no bounds checks on the four slices.
        let slots = v
            .iter_mut()
            .zip(fa.iter_mut())
            .zip(ne.iter_mut())
            .zip(pr.iter_mut());
        for (q, (((v, fa), ne), pr)) in (base..).zip(slots) {
            [*v, *fa, *ne, *pr] = f(q);
        }
    };
    if parallel && n >= PARALLEL_MIN {
        vertex
            .par_chunks_mut(CHUNK)
            .zip(face.par_chunks_mut(CHUNK))
            .zip(next.par_chunks_mut(CHUNK))
            .zip(prev.par_chunks_mut(CHUNK))
            .enumerate()
            .for_each(fill);
    } else {
        // One thread: the whole arrays are one chunk.
        fill((0, (((&mut vertex, &mut face), &mut next), &mut prev)));
    }
    Ok([vertex, face, next, prev])
}

/// Where a geometry pass writes its values, in output order: a `Vec` it extends or a slice
/// of the right length ([`Slots`]: every evaluation, the one-shot subdivision's included).
pub(crate) trait Sink<T: Send> {
    /// Appends `f(0), ..., f(n - 1)`, in parallel when `parallel` and `n` is large.
    fn append(&mut self, n: usize, parallel: bool, f: impl Fn(usize) -> T + Sync + Send);
}

impl<T: Send> Sink<T> for Vec<T> {
    #[inline]
    fn append(&mut self, n: usize, parallel: bool, f: impl Fn(usize) -> T + Sync + Send) {
        extend(self, n, parallel, f);
    }
}

/// A slice filled front to back (its length is checked by the caller; values past its end
/// are not computed).
pub(crate) struct Slots<'a, T> {
    out: &'a mut [T],
    at: usize,
}

impl<'a, T> Slots<'a, T> {
    pub(crate) fn new(out: &'a mut [T]) -> Self {
        Slots { out, at: 0 }
    }
}

impl<T: Send> Sink<T> for Slots<'_, T> {
    #[inline]
    fn append(&mut self, n: usize, parallel: bool, f: impl Fn(usize) -> T + Sync + Send) {
        let start = self.at.min(self.out.len());
        let end = (start + n).min(self.out.len());
        let dst = &mut self.out[start..end];
        if parallel && dst.len() >= PARALLEL_MIN {
            dst.par_chunks_mut(CHUNK)
                .enumerate()
                .for_each(|(c, chunk)| {
                    let base = c * CHUNK;
                    for (i, x) in chunk.iter_mut().enumerate() {
                        *x = f(base + i);
                    }
                });
        } else {
            for (i, x) in dst.iter_mut().enumerate() {
                *x = f(i);
            }
        }
        self.at += n;
    }
}
