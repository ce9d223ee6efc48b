//! Varying data (OpenSubdiv's `PrimvarRefiner::InterpolateVarying`): per-vertex data refined
//! linearly over the faces, whatever the rule does to positions. A varying refinement is a
//! [`Refinement`] with the topology of the rule's split and the weights of its linear rule:
//!
//! | split | varying weights |
//! |---|---|
//! | 4:1 (Loop, midpoint, butterfly, icosphere) | the midpoint rule: edge points at the midpoints, old vertices kept |
//! | 1:N² | `tri-split-N`: points on the flat triangles |
//! | Catmull-Clark | bilinear: face points at the centroids, edge points at the midpoints, old vertices kept |
//!
//! It numbers vertices and faces as the refinement it comes from ([`Refinement::varying`],
//! holes included), so its evaluation fills the same buffers. √3, Doo-Sabin and mid-edge have no varying rule
//! (OpenSubdiv has none for them either).

use super::creases::{Creases, Linear};
use super::{Refinement, Result, Rule, Scalar, Split, SubdivideOptions};
use crate::holes::HoleSet;
use crate::tags::SubdivisionOptions;
use crate::{Error, HalfEdgeMesh};

impl Refinement {
    /// The varying refinement of this one (module docs): evaluate it
    /// ([`Refinement::evaluate`], [`Refinement::evaluator`]) to refine any per-vertex data
    /// linearly, into buffers numbered as this refinement's. `mesh` is this refinement's level
    /// 0 (the mesh it was built from). Creases and the boundary options do not apply (varying
    /// data ignores them, as in OpenSubdiv); its threads and holes do.
    ///
    /// # Errors
    ///
    /// [`Error::BufferSize`] for a mesh of another size than level 0;
    /// [`Error::NoSubdivision`] for √3, Doo-Sabin and mid-edge; as [`Refinement::new`].
    ///
    /// ```
    /// use halfedge::subdivide::SubdivideOptions;
    /// use halfedge::{shapes, HalfEdgeMesh, Refinement, Rule};
    ///
    /// let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
    /// let r = Refinement::new(&cube, Rule::CatmullClark, 1, &SubdivideOptions::default())?;
    /// let varying = r.varying(&cube)?;
    /// let base: Vec<[f64; 3]> = cube.positions().iter().map(|p| p.to_array()).collect();
    /// let mut out = vec![[0.0; 3]; varying.n_vertices(1)];
    /// varying.evaluate(&base, &mut out)?;
    /// // Bilinear: the old vertices stay where they are.
    /// assert!(base.iter().all(|p| out.contains(p)));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn varying(&self, mesh: &HalfEdgeMesh) -> Result<Refinement> {
        let (levels, rule) = (self.levels(), self.rule());
        let base_faces = self
            .written
            .as_ref()
            .map_or(self.n_faces(0), |w| w.holes.len());
        for (what, given, expected) in [
            (
                "the mesh's vertices",
                mesh.n_vertices(),
                self.base_vertices(),
            ),
            ("the mesh's faces", mesh.n_faces(), base_faces),
        ] {
            if given != expected {
                return Err(Error::BufferSize {
                    what,
                    given,
                    expected,
                });
            }
        }
        let holes = match &self.written {
            Some(w) => {
                let faces = (0..w.holes.len() as u32).filter(|&f| w.holes[f as usize]);
                Some(HoleSet::new(mesh.n_faces(), faces)?)
            }
            None => None,
        };
        let plain = SubdivideOptions {
            threads: self.threads,
            holes: holes.as_ref(),
            descriptor: false,
            ..SubdivideOptions::default()
        };
        let split = super::super::plan(rule, &mesh.counts())?.split;
        let none = || Ok(None);
        match split {
            Split::Tri(2) => {
                Refinement::with_creases(mesh, Rule::Midpoint, levels, &plain, none, None)
            }
            Split::Tri(n) => {
                Refinement::with_creases(mesh, Rule::TriSplit(n), levels, &plain, none, None)
            }
            Split::Quad => {
                // Every vertex a corner and every edge point a midpoint: bilinear.
                let (edges, vertices) = (vec![0.0; mesh.n_edges()], vec![0.0; mesh.n_vertices()]);
                let rule = Rule::CatmullClark;
                let options = SubdivisionOptions::default();
                let creases =
                    || Creases::for_channel(mesh, rule, &edges, &vertices, &options, Linear::All);
                Refinement::with_creases(mesh, rule, levels, &plain, creases, None)
            }
            Split::Sqrt3 { .. } | Split::DualCorners | Split::DualEdges => {
                Err(Error::NoSubdivision {
                    scheme: rule.to_string(),
                    reason: "varying data is refined linearly over the faces of a primal split \
                             (the 4:1 and 1:N² splits, Catmull-Clark), which this rule is not"
                        .into(),
                })
            }
        }
    }

    /// Refines per-vertex attributes (vertex colors, weights) with the positions' weights:
    /// [`Refinement::evaluate`], except under the icosphere rule, whose projection onto the
    /// sphere is for positions only: there the weights before it, the varying refinement's
    /// ([`Refinement::varying`] of `mesh`, this refinement's level 0).
    ///
    /// # Errors
    ///
    /// As [`Refinement::evaluate`] and, for the icosphere, [`Refinement::varying`].
    pub fn evaluate_attributes<T: Scalar, const N: usize>(
        &self,
        mesh: &HalfEdgeMesh,
        base: &[[T; N]],
        out: &mut [[T; N]],
    ) -> Result<()> {
        match self.rule() {
            Rule::Icosphere => self.varying(mesh)?.evaluate(base, out),
            _ => self.evaluate(base, out),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::holes::HoleSet;
    use crate::shapes;

    fn evaluate(r: &Refinement, base: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let mut out = vec![[0.0; 3]; r.n_vertices(r.levels())];
        r.evaluate(base, &mut out).expect("evaluated");
        out
    }

    fn faces(r: &Refinement) -> (Vec<u32>, Vec<u32>) {
        let levels = r.levels();
        let mut offsets = vec![0u32; r.n_faces(levels) + 1];
        let mut indices = vec![0u32; r.n_corners(levels)];
        r.write_polygons(&mut offsets, &mut indices)
            .expect("polygons");
        (offsets, indices)
    }

    /// Level by level, every vertex of a varying refinement is the centroid of the parent
    /// vertices it comes from (a vertex itself, an edge's two ends, a face's corners), in the
    /// numbering of the rule's refinement; an affine field stays affine.
    #[test]
    fn varying_points_are_vertices_midpoints_and_centroids() {
        let mixed = HalfEdgeMesh::try_from(&shapes::mixed()).expect("mesh");
        let ico = HalfEdgeMesh::try_from(&shapes::icosahedron()).expect("mesh");
        let grid = HalfEdgeMesh::try_from(&shapes::grid(2, 3).expect("grid")).expect("mesh");
        let opts = SubdivideOptions::default();
        for (mesh, rule) in [
            (&mixed, Rule::CatmullClark),
            (&grid, Rule::CatmullClark),
            (&ico, Rule::Loop),
            (&grid, Rule::Loop),
            (&ico, Rule::Butterfly),
            (&ico, Rule::TriSplit(3)),
        ] {
            let base: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
            let smooth = Refinement::new(mesh, rule, 1, &opts).expect("refinement");
            let varying = smooth.varying(mesh).expect("varying");
            assert_eq!(
                faces(&varying),
                faces(&smooth),
                "{rule}: the rule's numbering"
            );
            let out = evaluate(&varying, &base);
            // Old vertices keep their ids and places.
            assert_eq!(&out[..base.len()], &base[..], "{rule}");
            // The edge points: midpoints (4:1, Catmull-Clark), the points at k/N (1:N²).
            let (nv, ne) = (mesh.n_vertices(), mesh.n_edges());
            for e in 0..ne {
                let h = crate::HalfedgeId((2 * e) as u32);
                let a = mesh.position(mesh.from_vertex(h));
                let b = mesh.position(mesh.to_vertex(h));
                match rule {
                    Rule::TriSplit(3) => {
                        for k in 0..2 {
                            let want = a + (b - a) * ((k + 1) as f64 / 3.0);
                            let got = glam::DVec3::from_array(out[nv + 2 * e + k]);
                            assert!((got - want).length() < 1e-12, "{rule} edge {e}");
                        }
                    }
                    _ => {
                        let got = glam::DVec3::from_array(out[nv + e]);
                        assert!((got - (a + b) / 2.0).length() < 1e-12, "{rule} edge {e}");
                    }
                }
            }
            if rule == Rule::CatmullClark {
                // Face points after the edge points: the centroids.
                for f in mesh.faces() {
                    let corners: Vec<glam::DVec3> =
                        mesh.face_vertices(f).map(|v| mesh.position(v)).collect();
                    let centroid = corners.iter().sum::<glam::DVec3>() / corners.len() as f64;
                    let got = glam::DVec3::from_array(out[nv + ne + f.idx()]);
                    assert!((got - centroid).length() < 1e-12, "{rule} face {f:?}");
                }
            }
        }
        let sqrt3 = Refinement::new(&ico, Rule::Sqrt3, 1, &opts).expect("refinement");
        let err = sqrt3.varying(&ico).unwrap_err();
        assert!(err.to_string().contains("varying data"), "{err}");
        // Holes: the written part, as the rule's refinement writes it.
        let holes = HoleSet::new(mixed.n_faces(), [0]).expect("a face");
        let opts = opts.with_holes(&holes);
        let smooth = Refinement::new(&mixed, Rule::CatmullClark, 2, &opts).expect("r");
        let varying = smooth.varying(&mixed).expect("v");
        assert_eq!(faces(&varying), faces(&smooth));
        // Another mesh than level 0 is refused.
        let err = smooth.varying(&ico).unwrap_err();
        assert!(matches!(err, Error::BufferSize { .. }), "{err}");
    }
}
