//! Filling position arrays, sequentially or with rayon.

use glam::DVec3;
use rayon::prelude::*;

/// Below this many points a pass runs sequentially even when parallelism is on.
const PARALLEL_MIN: usize = 1 << 14;

/// Appends `f(0), ..., f(n - 1)` to `out`, in parallel when `parallel` and `n` is large.
///
/// With enough capacity in `out` neither path reallocates (rayon's indexed `par_extend` writes
/// in place after reserving exactly `n`).
pub(crate) fn extend(
    out: &mut Vec<DVec3>,
    n: usize,
    parallel: bool,
    f: impl Fn(usize) -> DVec3 + Sync + Send,
) {
    if parallel && n >= PARALLEL_MIN {
        out.par_extend((0..n).into_par_iter().map(f));
    } else {
        out.extend((0..n).map(f));
    }
}
