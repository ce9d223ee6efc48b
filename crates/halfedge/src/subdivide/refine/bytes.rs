//! What a [`Refinement`] occupies: measured ([`Refinement::heap_bytes`]) and predicted from
//! the counts before it is built ([`Refinement::predicted_bytes`] and its crease and
//! face-varying terms).

use num_bigint::BigInt;

use super::*;

impl Refinement {
    /// The bytes the refinement keeps on the heap (see [Memory](Refinement#memory)).
    pub fn heap_bytes(&self) -> usize {
        let levels: usize = self
            .topology
            .iter()
            .map(|l| {
                l.topology.as_ref().map_or(0, Connectivity::bytes)
                    + l.step_b.as_ref().map_or(0, StepB::bytes)
                    + l.fast.as_ref().map_or(0, Fast::bytes)
            })
            .sum();
        let polygons = self
            .polygons
            .as_ref()
            .map_or(0, |p| 4 * (p.offsets.len() + p.indices.len()));
        let written = self
            .written
            .as_ref()
            .map_or(0, |w| 4 * w.kept.len() + w.holes.len());
        let uvs = self.uvs.as_ref().map_or(0, |u| u.heap_bytes());
        let limit = self.limit.as_ref().map_or(0, limit::LimitTable::heap_bytes);
        levels + polygons + written + uvs + limit + 4 * self.base_degrees.len()
    }

    /// The bytes [`Refinement::new`] would keep for `rule` at `levels` on a mesh with
    /// `counts`, before building anything: exact on closed meshes, an upper bound (within a
    /// few percent) with a boundary, where a boundary vertex's ring holds 2 entries instead of
    /// its valence and boundary half-edges have no face corner.
    ///
    /// ```
    /// use halfedge::refine::Refinement;
    /// use halfedge::subdivide::SubdivideOptions;
    /// use halfedge::{shapes, HalfEdgeMesh, Rule};
    ///
    /// let ico = HalfEdgeMesh::try_from(&shapes::icosahedron())?;
    /// let predicted = Refinement::predicted_bytes(Rule::Loop, &ico.counts(), 4)?;
    /// let r = Refinement::new(&ico, Rule::Loop, 4, &SubdivideOptions::default())?;
    /// assert_eq!(predicted, r.heap_bytes().into());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// As the scheme lookup of [`Refinement::new`] ([`Error::Scheme`]).
    pub fn predicted_bytes(rule: Rule, counts: &MeshCounts, levels: u32) -> Result<BigInt> {
        let plan = crate::subdivide::plan(rule, counts)?;
        let mut level = Vec::with_capacity(levels as usize + 1);
        for s in 0..=levels {
            let c = plan.scheme.counts_at(counts, u64::from(s))?;
            let corners = match plan.split {
                _ if s == 0 => BigInt::from(counts.corners),
                Split::Tri(..) | Split::Sqrt3 { .. } => &c.faces * 3u32,
                Split::Quad => &c.faces * 4u32,
                _ => &c.edges * 2u32,
            };
            level.push((c.vertices, c.edges, c.faces, corners));
        }
        let connectivity =
            |(v, e, f, _): &(BigInt, BigInt, BigInt, BigInt)| v * 4u32 + e * 32u32 + f * 4u32;
        let kept = &level[..levels.max(1) as usize];
        let mut bytes = BigInt::from(0u32);
        match plan.split {
            Split::Tri(2) if plan.rule == Rule::Loop && levels > 0 => {
                for (v, e, _, _) in kept {
                    bytes += e * 24u32 + v * 5u32 + 4u32;
                }
                bytes += connectivity(&level[levels as usize - 1]);
            }
            Split::Quad if levels > 0 => {
                for (v, e, f, h) in kept {
                    bytes += e * 32u32 + v * 5u32 + f * 4u32 + h * 4u32 + 8u32;
                }
                bytes += connectivity(&level[levels as usize - 1]);
                // The base faces' degrees (`Refinement::base_faces`).
                bytes += &level[0].2 * 4u32;
            }
            split => {
                for l in kept {
                    bytes += connectivity(l);
                }
                if levels == 0 || !direct(split) {
                    let (_, _, f, h) = &level[levels as usize];
                    bytes += f * 4u32 + h * 4u32 + 4u32;
                }
                if split == (Split::Sqrt3 { boundary: true }) {
                    for (s, (_, _, f, _)) in kept.iter().enumerate() {
                        // Level s is refined by step B when s + 1 is even.
                        if (s + 1) % 2 == 0 {
                            bytes += f * 12u32;
                        }
                    }
                }
            }
        }
        Ok(bytes)
    }

    /// An upper bound of the bytes [`Refinement::new`] keeps for `rule` (Loop or
    /// Catmull-Clark) at `levels` under crease rules ([`sdc`](crate::subdivide::sdc)): as
    /// [`Refinement::predicted_bytes`], with each level's tables bounded by a dense weight
    /// table of full smooth rows (a vertex's distinct neighbours through its faces, an edge's
    /// two faces' corners; a face of more than 32 sides, which an overriding row names by its
    /// child point, counting 4 entries per side rather than its degree: linear in it); within about 15 % of a level whose every row is semi-sharp and
    /// blended with its smooth mask, on quad and triangle meshes. A level whose rows mostly
    /// keep the rule's masks (a few creases, a UV channel's seams) keeps the flattened tables
    /// and its sharp rows ([Memory](Refinement#memory)), far below: about
    /// [`Refinement::predicted_bytes`]. Other rules: as [`Refinement::predicted_bytes`].
    ///
    /// ```
    /// use halfedge::refine::Refinement;
    /// use halfedge::subdivide::{Sharpness, SubdivideOptions};
    /// use halfedge::tags::Tags;
    /// use halfedge::{shapes, HalfEdgeMesh, Rule};
    ///
    /// let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
    /// let mut tags = Tags::default();
    /// tags.add_crease(0, 1, 2.5)?;
    /// let sharpness = Sharpness::from_tags(&cube, &tags)?;
    /// let opts = SubdivideOptions::default().with_sharpness(&sharpness);
    /// let r = Refinement::new(&cube, Rule::CatmullClark, 3, &opts)?;
    /// let bound = Refinement::predicted_bytes_with_creases(Rule::CatmullClark, &cube.counts(), 3)?;
    /// assert!(bound >= r.heap_bytes().into());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// As [`Refinement::predicted_bytes`].
    pub fn predicted_bytes_with_creases(
        rule: Rule,
        counts: &MeshCounts,
        levels: u32,
    ) -> Result<BigInt> {
        Refinement::tables_bound(rule, counts, levels, false)
    }

    /// The bound of a refinement's crease tables under `rule` to `levels`; with
    /// `dense_only_narrow`, for a face-varying channel whose surface has no crease rules (its
    /// sharpness is its corners, seams and boundary, infinitely sharp: override rows of at
    /// most 3 entries): a level with a face of more than 32 sides never gets a dense table, so
    /// each face counts at most 32 entries per side.
    pub(crate) fn tables_bound(
        rule: Rule,
        counts: &MeshCounts,
        levels: u32,
        dense_only_narrow: bool,
    ) -> Result<BigInt> {
        let plan = crate::subdivide::plan(rule, counts)?;
        if levels == 0 || crease_table_bytes(&plan, counts, 0)?.is_none() {
            return Refinement::predicted_bytes(rule, counts, levels);
        }
        let mut bytes = BigInt::from(0u32);
        for s in 0..levels {
            bytes += table_bytes(&plan, counts, s, dense_only_narrow)?.unwrap_or_default();
        }
        // The last parent level keeps its connectivity for the index buffers.
        let c = plan.scheme.counts_at(counts, u64::from(levels - 1))?;
        bytes += &c.vertices * 4u32 + &c.edges * 32u32 + &c.faces * 4u32;
        if plan.split == Split::Quad {
            // The base faces' degrees (`Refinement::base_faces`).
            bytes += BigInt::from(counts.faces) * 4u32;
        }
        Ok(bytes)
    }

    /// An upper bound of what the one-shot subdivision
    /// ([`subdivide`](crate::subdivide::subdivide), [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list))
    /// holds under crease rules, next to the input and level `levels - 1`, while it builds the
    /// weight table of level `levels - 1` (the largest), for `rule` (Loop or Catmull-Clark; 0
    /// for the others, which have no crease rules) at `levels` on a mesh with `counts`: the
    /// table twice (its rows are built in chunks, then copied into the table; bounded as in
    /// [`Refinement::predicted_bytes_with_creases`]), 8 bytes per row (the chunks' row ends)
    /// and the level's sharpness (4 bytes per edge, 8 per vertex). What
    /// [`memory::predicted_peak_bytes_with_creases`](crate::memory::predicted_peak_bytes_with_creases)
    /// weighs against the last level.
    ///
    /// # Errors
    ///
    /// As [`Refinement::predicted_bytes`].
    pub fn one_shot_crease_bytes(rule: Rule, counts: &MeshCounts, levels: u32) -> Result<BigInt> {
        let plan = crate::subdivide::plan(rule, counts)?;
        let Some(last) = levels.checked_sub(1) else {
            return Ok(0u32.into());
        };
        let Some(table) = crease_table_bytes(&plan, counts, last)? else {
            return Ok(0u32.into());
        };
        let c = plan.scheme.counts_at(counts, u64::from(last))?;
        // One row per vertex of the next level.
        let rows = plan.scheme.counts_at(counts, u64::from(levels))?.vertices;
        Ok(table * 2u32 + rows * 8u32 + &c.edges * 4u32 + &c.vertices * 8u32)
    }
}
