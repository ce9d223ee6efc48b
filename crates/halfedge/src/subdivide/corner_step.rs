//! One step of a corner rule (the face-varying data of √3, Doo-Sabin and mid-edge: a value
//! per face corner), as the topology steps write it ([`CornerStep`]), and the seams of corner
//! values: the types the rules' UV steps return, below the refinement that runs them.

use crate::mesh::INVALID;
use crate::subdivide::topo::Topo;
use crate::subdivide::weights::WeightTable;
use crate::Result;

/// One step of a corner rule, from level `s` (the parent) to level `s + 1` (the child).
pub(crate) struct CornerStep<'a> {
    /// Auxiliary values, linear combinations of the parent level's values computed before the
    /// child's and numbered after the parent's (`n_values + k` for row `k`): a rule whose
    /// rows would each span a whole large face (Doo-Sabin's) writes the face-wide sums once
    /// here and short rows over them, so the tables stay linear in the corners.
    pub(crate) aux: Option<WeightTable>,
    /// The child level's values: row `i` is value `i`, an affine combination (weights
    /// summing to 1) of the parent level's values, then the auxiliary ones.
    pub(crate) values: WeightTable,
    /// The value of the child's face corner of face `face` at vertex `vertex` (child ids, in
    /// the rule's numbering of faces and vertices): a face visits a vertex once, so the pair
    /// names the corner whatever the order the step writes the face's half-edges in.
    pub(crate) corner: Box<dyn Fn(u32, u32) -> u32 + Send + Sync + 'a>,
}

/// Whether the interior edge of half-edge `h` is a seam of the corner values `cv` (by
/// half-edge): its two faces disagree at either end. Surface boundary edges are not seams.
pub(crate) fn is_seam(t: &Topo<'_>, cv: &[u32], h: u32) -> bool {
    let g = h ^ 1;
    !t.is_boundary(h)
        && !t.is_boundary(g)
        && (cv[h as usize] != cv[t.next(g) as usize] || cv[t.next(h) as usize] != cv[g as usize])
}

/// The rank of every seam edge of `t` among the seam edges in increasing order (`INVALID`
/// on the other edges), and their number.
pub(crate) fn seam_ranks(t: &Topo<'_>, cv: &[u32]) -> Result<(Vec<u32>, usize)> {
    let mut rank = crate::subdivide::alloc::filled(INVALID, t.ne(), "seam ranks")?;
    let mut next = 0u32;
    for e in 0..t.ne() as u32 {
        if is_seam(t, cv, 2 * e) {
            rank[e as usize] = next;
            next += 1;
        }
    }
    Ok((rank, next as usize))
}
