//! The corner channel: face-varying values propagated face corner by face corner on the
//! surface's own refinement, for the rules whose new faces straddle old edges and vertices
//! (the dual rules; the [`face_varying`](super::face_varying) module docs, "The corner
//! channel").
//!
//! A rule supplies one [`CornerStep`] per level from the parent level's topology and the
//! value of each of its face corners; this module runs the steps on the levels the
//! [`Refinement`] keeps, numbers the child's corners in the order its faces are written, checks
//! that every value a step creates is used by some corner, and keeps the steps' weight tables
//! (with, for a step that has them, the table of its auxiliary values, evaluated first and
//! numbered after the parent's values) for the evaluation and the last level's corner values
//! for the index buffer.

use super::{check_len, Refinement, Scalar};
use crate::mesh::INVALID;
use crate::subdivide::corner_step::CornerStep;
use crate::subdivide::topo::Topo;
use crate::subdivide::weights::WeightTable;
use crate::{Error, Result, Rule};

/// The corner step of `rule` from level `s` (`t`, its corner values `values` by half-edge:
/// the value of the corner at the source of each half-edge inside its face, `INVALID` on a
/// boundary half-edge; `n_values` values) to level `child = s + 1` (for rules whose steps
/// alternate, as √3's with boundary). A new rule adds its arm here.
///
/// # Errors
///
/// [`Error::UvsNotSupported`] for a rule without a corner rule; [`Error::AllocationFailed`],
/// [`Error::IndexOverflow`].
fn corner_step<'a>(
    rule: Rule,
    t: &'a Topo<'a>,
    values: &'a [u32],
    n_values: usize,
    child: u32,
) -> Result<CornerStep<'a>> {
    match rule {
        // Step B at even steps on a mesh with a boundary, as the surface's refinement.
        Rule::Sqrt3 => crate::subdivide::sqrt3::sqrt3_uv_step(
            t,
            values,
            n_values,
            child % 2 == 0 && !t.is_closed(),
            child,
        ),
        Rule::DooSabin => crate::subdivide::dual::doo_sabin_uv_step(t, values, n_values),
        Rule::MidEdge => crate::subdivide::dual::mid_edge_uv_step(t, values, n_values),
        other => Err(Error::UvsNotSupported {
            rule: other.to_string(),
        }),
    }
}

/// The face-varying channel of a corner rule on a refinement.
#[derive(Debug)]
pub(crate) struct CornerChannel {
    /// The layout's values (level 0).
    n_values: usize,
    /// Level `s` to `s + 1`: the auxiliary values ([`CornerStep::aux`]) and the new values
    /// as weights of the old and the auxiliary ones.
    tables: Vec<(Option<WeightTable>, WeightTable)>,
    /// The value of every corner of the last level, in the order its faces are written.
    last: Vec<u32>,
    /// Whether evaluations may run in parallel.
    parallel: bool,
}

impl CornerChannel {
    /// Runs `rule`'s corner steps on the levels of `r` (its topology built from the mesh
    /// whose corner values `base` are, by half-edge; `n_values` values at level 0).
    pub(crate) fn new(r: &Refinement, rule: Rule, base: Vec<u32>, n_values: usize) -> Result<Self> {
        let levels = r.levels;
        let invalid = |level: u32, what: String| Error::InvalidOutput {
            scheme: r.name.clone(),
            level,
            what,
        };
        let topo = |s: u32| {
            r.topology
                .get(s as usize)
                .and_then(|l| l.topology.as_ref())
                .map(|c| c.topo())
                .ok_or_else(|| invalid(s, "no connectivity kept for the UV corners".into()))
        };
        let polygons = r
            .polygons
            .as_ref()
            .ok_or_else(|| invalid(levels, "no face list kept for the UV corners".into()))?;
        let mut tables = Vec::with_capacity(levels as usize);
        let mut cv = base;
        let mut n = n_values;
        let mut last = Vec::new();
        if levels == 0 {
            // The base corners in the order of the face list (each face from its half-edge).
            let t = topo(0)?;
            last = crate::subdivide::alloc::with_capacity(polygons.indices.len(), "uv corners")?;
            for f in 0..t.nf() as u32 {
                t.for_face(f, |h| last.push(cv[h as usize]));
            }
        }
        for s in 0..levels {
            let child = s + 1;
            let t = topo(s)?;
            let (table, next) = {
                let CornerStep {
                    aux,
                    values: table,
                    corner,
                } = corner_step(rule, &t, &cv, n, child)?;
                let rows = table.rows();
                let mut used = crate::subdivide::alloc::filled(false, rows, "uv values used")?;
                let mut bad = None;
                let mut value = |face: u32, vertex: u32| {
                    let v = corner(face, vertex);
                    match used.get_mut(v as usize) {
                        Some(u) => *u = true,
                        None => {
                            bad.get_or_insert((face, vertex, v));
                        }
                    }
                    v
                };
                let next = if child < levels {
                    let ct = topo(child)?;
                    let mut next =
                        crate::subdivide::alloc::filled(INVALID, 2 * ct.ne(), "uv corners")?;
                    for h in 0..2 * ct.ne() as u32 {
                        if !ct.is_boundary(h) {
                            next[h as usize] = value(ct.face(h), ct.source(h));
                        }
                    }
                    next
                } else {
                    let mut out = crate::subdivide::alloc::with_capacity(
                        polygons.indices.len(),
                        "uv corners",
                    )?;
                    for (f, w) in polygons.offsets.windows(2).enumerate() {
                        for &vertex in &polygons.indices[w[0] as usize..w[1] as usize] {
                            out.push(value(f as u32, vertex));
                        }
                    }
                    out
                };
                if let Some((face, vertex, v)) = bad {
                    return Err(invalid(
                        child,
                        format!("UV value {v} of face {face} at vertex {vertex}, of {rows}"),
                    ));
                }
                if let Some(v) = used.iter().position(|&u| !u) {
                    return Err(invalid(
                        child,
                        format!("UV value {v} of {rows} is used by no corner"),
                    ));
                }
                ((aux, table), next)
            };
            n = table.1.rows();
            tables.push(table);
            if child < levels {
                cv = next;
            } else {
                last = next;
            }
        }
        Ok(CornerChannel {
            n_values,
            tables,
            last,
            parallel: r.threads != 1,
        })
    }

    /// The UV values of level `level` (0 beyond the last level).
    pub(crate) fn n_uvs(&self, level: u32) -> usize {
        match level {
            0 => self.n_values,
            s => self.tables.get(s as usize - 1).map_or(0, |(_, t)| t.rows()),
        }
    }

    pub(crate) fn heap_bytes(&self) -> usize {
        let bytes = |(aux, t): &(Option<WeightTable>, WeightTable)| {
            t.bytes() + aux.as_ref().map_or(0, WeightTable::bytes)
        };
        self.tables.iter().map(bytes).sum::<usize>() + 4 * self.last.len()
    }

    pub(crate) fn evaluate<T: Scalar>(&self, base: &[[T; 2]], out: &mut [[T; 2]]) -> Result<()> {
        let levels = self.tables.len() as u32;
        check_len("uv base", self.n_values, base.len())?;
        check_len("uv out", self.n_uvs(levels), out.len())?;
        if self.tables.is_empty() {
            out.copy_from_slice(base);
            return Ok(());
        }
        let aux_rows = |k: usize| {
            self.tables
                .get(k)
                .and_then(|(aux, _)| aux.as_ref())
                .map_or(0, WeightTable::rows)
        };
        // Each level's values, with room after them for the next step's auxiliary values.
        let mut current: Option<Vec<[T; 2]>> = None;
        for (k, (aux, table)) in self.tables.iter().enumerate() {
            if let Some(aux) = aux {
                let mut src = match current.take() {
                    Some(v) => v,
                    None => {
                        let mut v = crate::subdivide::alloc::with_capacity(
                            base.len() + aux.rows(),
                            "uv level",
                        )?;
                        v.extend_from_slice(base);
                        v
                    }
                };
                let mut sums = crate::subdivide::alloc::with_capacity(aux.rows(), "uv sums")?;
                aux.points(&src, &mut sums, self.parallel);
                src.extend_from_slice(&sums);
                current = Some(src);
            }
            let src = current.as_deref().unwrap_or(base);
            if k + 1 == self.tables.len() {
                table.points(src, &mut super::Slots::new(out), self.parallel);
                break;
            }
            let room = table.rows() + aux_rows(k + 1);
            let mut next = crate::subdivide::alloc::with_capacity(room, "uv level")?;
            table.points(src, &mut next, self.parallel);
            current = Some(next);
        }
        Ok(())
    }

    pub(crate) fn write_indices(&self, out: &mut [u32], expected: usize) -> Result<()> {
        check_len("uv indices", expected, out.len())?;
        // The last level's corners are the refinement's (checked when they were numbered).
        check_len("uv indices", self.last.len(), out.len())?;
        out.copy_from_slice(&self.last);
        Ok(())
    }
}
