//! Evaluating data on a [`Refinement`]: `[T; N]` per vertex into the caller's buffers, level
//! by level through the one evaluation dispatch (flattened tables or the rule's kernels).

use super::*;

impl Refinement {
    /// Refines `base` (one entry per vertex of level 0) straight to the last level, into
    /// `out` (one entry per vertex of the last level), in the refinement's threads. The
    /// intermediate levels are allocated for the call; an [`Evaluator`] keeps them.
    ///
    /// # Errors
    ///
    /// [`Error::BufferSize`] when `base` or `out` has the wrong length (nothing is written);
    /// [`Error::AllocationFailed`] for the intermediate levels.
    pub fn evaluate<T: Scalar, const N: usize>(
        &self,
        base: &[[T; N]],
        out: &mut [[T; N]],
    ) -> Result<()> {
        self.evaluator().evaluate(base, out)
    }

    /// An evaluator of `[T; N]` data that keeps its intermediate levels between calls.
    pub fn evaluator<T: Scalar, const N: usize>(&self) -> Evaluator<'_, T, N> {
        self.evaluator_with(Scratch::default())
    }

    /// An evaluator that starts from the buffers another one kept ([`Evaluator::into_scratch`]):
    /// for a caller that cannot hold the evaluator's borrow of the refinement between calls
    /// (a binding's object owning both), no allocation after the first call either.
    pub fn evaluator_with<T: Scalar, const N: usize>(
        &self,
        scratch: Scratch<T, N>,
    ) -> Evaluator<'_, T, N> {
        Evaluator {
            refinement: self,
            scratch: scratch.levels,
            full: scratch.full,
        }
    }

    /// Refines one level: `src` has `n_vertices(level - 1)` entries, `dst` `n_vertices(level)`.
    ///
    /// # Errors
    ///
    /// [`Error::LevelOutOfRange`] unless `1 <= level <= levels`; [`Error::BufferSize`].
    pub fn evaluate_level<T: Scalar, const N: usize>(
        &self,
        level: u32,
        src: &[[T; N]],
        dst: &mut [[T; N]],
    ) -> Result<()> {
        self.check_level(level)?;
        check_len("src", self.n_vertices(level - 1), src.len())?;
        check_len("dst", self.n_vertices(level), dst.len())?;
        if self.written.is_some() && level == self.levels {
            let n = self.computed_vertices(level);
            let mut full =
                crate::subdivide::alloc::filled([T::ZERO; N], n, "the whole last level")?;
            self.run(|| self.fill_level(level, src, &mut full));
            self.gather(&full, dst);
            return Ok(());
        }
        self.run(|| self.fill_level(level, src, dst));
        Ok(())
    }

    pub(super) fn check_level(&self, level: u32) -> Result<()> {
        if level == 0 || level > self.levels {
            return Err(Error::LevelOutOfRange {
                level,
                first: 1,
                levels: self.levels,
            });
        }
        Ok(())
    }

    /// Refines flat data, `stride` entries per vertex (`base`: `stride * n_vertices(0)`,
    /// `out`: `stride * n_vertices(levels)`). Strides 1 to 16 run as `[T; stride]`; wider data
    /// of the linear rules runs component by component (the same values: the rules act on
    /// each component alike).
    ///
    /// # Errors
    ///
    /// [`Error::BufferSize`]; [`Error::UnsupportedStride`] for a stride of 0, or above 16
    /// under the icosphere rule (its projection couples the components).
    pub fn evaluate_strided<T: Scalar>(
        &self,
        base: &[T],
        stride: usize,
        out: &mut [T],
    ) -> Result<()> {
        if stride == 0 {
            return Err(Error::UnsupportedStride {
                rule: self.name.clone(),
                stride,
                reason: "a vertex needs at least one entry",
            });
        }
        let n0 = self.base_vertices();
        let nl = self.n_vertices(self.levels);
        let entries = |n: usize| stride.saturating_mul(n);
        check_len("base", entries(n0), base.len())?;
        check_len("out", entries(nl), out.len())?;
        macro_rules! widths {
            ($($n:literal)*) => {
                match stride {
                    $($n => return self.strided::<T, $n>(base, out),)*
                    _ => {}
                }
            };
        }
        widths!(1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16);
        if !self.rule.is_linear() {
            return Err(Error::UnsupportedStride {
                rule: self.name.clone(),
                stride,
                reason: "the sphere projection needs the whole vector, at most 16 entries",
            });
        }
        let mut evaluator = self.evaluator::<T, 1>();
        let mut column = crate::subdivide::alloc::filled([T::ZERO], n0, "a column of the base")?;
        let mut result = crate::subdivide::alloc::filled([T::ZERO], nl, "a column of the result")?;
        for c in 0..stride {
            for (x, chunk) in column.iter_mut().zip(base.chunks_exact(stride)) {
                *x = [chunk[c]];
            }
            evaluator.evaluate(&column, &mut result)?;
            for (chunk, x) in out.chunks_exact_mut(stride).zip(&result) {
                chunk[c] = x[0];
            }
        }
        Ok(())
    }

    pub(super) fn strided<T: Scalar, const N: usize>(
        &self,
        base: &[T],
        out: &mut [T],
    ) -> Result<()> {
        let n0 = self.base_vertices();
        let nl = self.n_vertices(self.levels);
        let mut packed = crate::subdivide::alloc::with_capacity(n0, "the packed base")?;
        packed.extend(
            base.chunks_exact(N)
                .map(|c| std::array::from_fn::<T, N, _>(|i| c[i])),
        );
        let mut result = crate::subdivide::alloc::filled([T::ZERO; N], nl, "the packed result")?;
        self.evaluate(&packed, &mut result)?;
        for (chunk, x) in out.chunks_exact_mut(N).zip(&result) {
            chunk.copy_from_slice(x);
        }
        Ok(())
    }

    /// The level before `level` (1-based), as the evaluation reads it.
    pub(super) fn before(&self, level: u32) -> Option<LevelRef<'_>> {
        let before = self.topology.get(level as usize - 1)?;
        Some(LevelRef {
            topology: before.topology.as_ref().map(Connectivity::topo),
            step_b: before.step_b.as_ref(),
            fast: before.fast.as_ref(),
        })
    }

    /// Level `level` from `src` (the level before) into `dst`; lengths checked by the caller.
    pub(super) fn fill_level<V: Vector>(&self, level: u32, src: &[V], dst: &mut [V]) {
        if let Some(before) = self.before(level) {
            self.fill_from(&before, src, dst);
        }
    }

    /// The level after `before` from its values `src` into `dst` (exactly its vertices).
    pub(super) fn fill_from<V: Vector>(&self, before: &LevelRef<'_>, src: &[V], dst: &mut [V]) {
        use crate::subdivide::{catmull_clark, dual, sqrt3, trisplit};
        let parallel = self.threads != 1;
        match before.fast {
            Some(Fast::Loop(fast)) => return fast.points(src, &mut Slots::new(dst), parallel),
            Some(Fast::CatmullClark(fast)) => return fast.fill(src, dst, parallel),
            Some(Fast::Linear(fast)) => return fast.points(src, &mut Slots::new(dst), parallel),
            Some(Fast::Creased { weights, .. }) if weights.is_dense() => {
                return weights.points(src, &mut Slots::new(dst), parallel)
            }
            Some(Fast::Creased { base, weights }) => {
                let base = LevelRef {
                    fast: base.as_deref(),
                    ..*before
                };
                self.fill_from(&base, src, dst);
                weights.apply(src, dst, parallel);
                return;
            }
            None => {}
        }
        let Some(t) = before.topology else {
            return;
        };
        if self.split == Split::Quad {
            catmull_clark::cc_fill(&t, src, dst, parallel);
            return;
        }
        let mut out = Slots::new(dst);
        match (self.split, &self.template) {
            (Split::Tri(_), Some(template)) => {
                trisplit::tri_points(&t, src, template, self.rule, &mut out, parallel);
            }
            (Split::Tri(..), None) => {}
            (Split::Quad, _) => {}
            (Split::Sqrt3 { .. }, _) => {
                sqrt3::sqrt3_points(&t, src, before.step_b, &mut out, parallel);
            }
            (Split::DualCorners, _) => dual::doo_sabin_points(&t, src, &mut out, parallel),
            (Split::DualEdges, _) => dual::mid_edge_points(&t, src, &mut out, parallel),
        }
    }

    /// Level `level` from `src` into a new vector (the stencils' sparse sums).
    /// `whole`: the whole last level, also its vertices holes leave unwritten.
    pub(super) fn collect_level<V: Vector>(
        &self,
        level: u32,
        src: &[V],
        whole: bool,
    ) -> Result<Vec<V>> {
        match self.before(level) {
            Some(before) => {
                let n = self.computed_vertices(level);
                let full = self.values_after(&before, src, n, "stencils")?;
                Ok(if level == self.levels && !whole {
                    self.written_of(full)
                } else {
                    full
                })
            }
            None => Ok(Vec::new()),
        }
    }

    /// The `n` values of the level after `before` from its values `src`, in a new vector
    /// allocated exactly and filled by [`Refinement::fill_from`] (the one dispatch of the
    /// rules' evaluation): the geometry of the stencils and of the one-shot subdivision;
    /// `what` names the vector in an allocation failure.
    pub(super) fn values_after<V: Vector>(
        &self,
        before: &LevelRef<'_>,
        src: &[V],
        n: usize,
        what: &str,
    ) -> Result<Vec<V>> {
        let mut out = crate::subdivide::alloc::filled(V::zero(), n, what)?;
        self.fill_from(before, src, &mut out);
        Ok(out)
    }
}

/// Evaluates `[T; N]` data on a [`Refinement`], keeping the intermediate levels' buffers
/// between calls (no allocation after the first call).
#[derive(Debug)]
pub struct Evaluator<'r, T: Scalar, const N: usize> {
    refinement: &'r Refinement,
    scratch: [Vec<[T; N]>; 2],
    /// The whole last level, when holes leave only part of it written.
    full: Vec<[T; N]>,
}

/// The buffers an [`Evaluator`] keeps between calls, apart from its refinement
/// ([`Evaluator::into_scratch`], [`Refinement::evaluator_with`]); any refinement's evaluator
/// may take them (they grow to what it needs).
#[derive(Debug)]
pub struct Scratch<T: Scalar, const N: usize> {
    levels: [Vec<[T; N]>; 2],
    full: Vec<[T; N]>,
}

impl<T: Scalar, const N: usize> Default for Scratch<T, N> {
    fn default() -> Self {
        Scratch {
            levels: [Vec::new(), Vec::new()],
            full: Vec::new(),
        }
    }
}

impl<T: Scalar, const N: usize> Evaluator<'_, T, N> {
    /// The buffers this evaluator keeps, to give the next one ([`Refinement::evaluator_with`]).
    pub fn into_scratch(self) -> Scratch<T, N> {
        Scratch {
            levels: self.scratch,
            full: self.full,
        }
    }

    /// As [`Refinement::evaluate`].
    ///
    /// # Errors
    ///
    /// As [`Refinement::evaluate`].
    pub fn evaluate(&mut self, base: &[[T; N]], out: &mut [[T; N]]) -> Result<()> {
        let r = self.refinement;
        let levels = r.levels;
        check_len("base", r.base_vertices(), base.len())?;
        check_len("out", r.n_vertices(levels), out.len())?;
        if levels == 0 {
            match r.written {
                Some(_) => r.gather(base, out),
                None => out.copy_from_slice(base),
            }
            return Ok(());
        }
        let whole = r.computed_vertices(levels);
        if r.written.is_some() {
            reserve(&mut self.full, whole)?;
            let mut full = std::mem::take(&mut self.full);
            self.levels_into(base, &mut full[..whole])?;
            r.gather(&full[..whole], out);
            self.full = full;
        } else {
            self.levels_into(base, out)?;
        }
        Ok(())
    }

    /// The limit surface of `base`, as [`Refinement::evaluate_limit`], the last level in
    /// the evaluator's buffers.
    ///
    /// # Errors
    ///
    /// As [`Refinement::evaluate_limit`].
    pub fn evaluate_limit(
        &mut self,
        base: &[[T; N]],
        position: &mut [[T; N]],
        tangents: Option<super::limit::TangentBuffersMut<'_, T, N>>,
    ) -> Result<()> {
        self.limit_into(base, None, position, tangents)
    }

    /// [`Refinement::evaluate`] into `points` and [`Refinement::evaluate_limit`] into
    /// `position` (and the tangents) from one refinement of the levels: the last level's
    /// points and the surface's limit (its normals) of the same frame.
    ///
    /// # Errors
    ///
    /// As [`Refinement::evaluate_limit`]; [`Error::BufferSize`] for `points`.
    pub fn evaluate_with_limit(
        &mut self,
        base: &[[T; N]],
        points: &mut [[T; N]],
        position: &mut [[T; N]],
        tangents: Option<super::limit::TangentBuffersMut<'_, T, N>>,
    ) -> Result<()> {
        self.limit_into(base, Some(points), position, tangents)
    }

    /// The limit of `base`, and the last level's written points into `points` when given.
    fn limit_into(
        &mut self,
        base: &[[T; N]],
        points: Option<&mut [[T; N]]>,
        position: &mut [[T; N]],
        tangents: Option<super::limit::TangentBuffersMut<'_, T, N>>,
    ) -> Result<()> {
        let r = self.refinement;
        let table = r.limit_table()?;
        let levels = r.levels;
        check_len("base", r.base_vertices(), base.len())?;
        let n = r.n_vertices(levels);
        check_len("limit position", n, position.len())?;
        if let Some(points) = &points {
            check_len("out", n, points.len())?;
        }
        if let Some((a, b)) = &tangents {
            check_len("limit tangent", n, a.len())?;
            check_len("limit tangent", n, b.len())?;
        }
        let rows = r.limit_rows();
        let parallel = r.threads != 1;
        let whole = r.computed_vertices(levels);
        let mut full = std::mem::take(&mut self.full);
        let level = if levels == 0 {
            base
        } else {
            reserve(&mut full, whole)?;
            self.levels_into(base, &mut full[..whole])?;
            &full[..whole]
        };
        if let Some(points) = points {
            match r.written {
                Some(_) => r.gather(level, points),
                None => points.copy_from_slice(level),
            }
        }
        r.run(|| table.apply(level, rows, position, tangents, parallel));
        self.full = full;
        Ok(())
    }

    /// Refines `base` level by level (the intermediate levels in the evaluator's buffers)
    /// into `last`, the whole last level (`levels >= 1`).
    fn levels_into(&mut self, base: &[[T; N]], last: &mut [[T; N]]) -> Result<()> {
        let r = self.refinement;
        let levels = r.levels;
        let need = |parity: u32| {
            (1..levels)
                .filter(|s| s % 2 == parity)
                .map(|s| r.n_vertices(s))
                .max()
                .unwrap_or(0)
        };
        let [a, b] = &mut self.scratch;
        reserve(a, need(1))?;
        reserve(b, need(0))?;
        let (a, b): (&mut [[T; N]], &mut [[T; N]]) = (a, b);
        r.run(|| {
            // Odd levels go to `a`, even ones to `b`.
            for s in 1..levels {
                let (n, m) = (r.n_vertices(s), r.n_vertices(s - 1));
                if s % 2 == 1 {
                    let input = if s == 1 { base } else { &b[..m] };
                    r.fill_level(s, input, &mut a[..n]);
                } else {
                    r.fill_level(s, &a[..m], &mut b[..n]);
                }
            }
            let m = r.n_vertices(levels - 1);
            let input = match levels {
                1 => base,
                l if (l - 1) % 2 == 1 => &a[..m],
                _ => &b[..m],
            };
            r.fill_level(levels, input, last);
        });
        Ok(())
    }
}

/// Grows `buffer` to at least `n` entries (fallibly).
fn reserve<T: Scalar, const N: usize>(buffer: &mut Vec<[T; N]>, n: usize) -> Result<()> {
    if buffer.len() < n {
        buffer
            .try_reserve_exact(n - buffer.len())
            .map_err(|e| Error::AllocationFailed {
                what: "intermediate level data".into(),
                bytes: n as u128 * std::mem::size_of::<[T; N]>() as u128,
                reason: e.to_string(),
            })?;
        buffer.resize(n, [T::ZERO; N]);
    }
    Ok(())
}
