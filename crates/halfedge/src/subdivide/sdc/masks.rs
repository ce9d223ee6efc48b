//! The vertex masks of OpenSubdiv's `Sdc` schemes (`ComputeVertexVertexMask`'s smooth,
//! dart, crease and corner masks, blended by a fractional weight) and the edge masks
//! (`ComputeEdgeVertexMask`: smooth, crease, Catmark's smooth-triangle weights), as weights of
//! a vertex's neighbourhood: no mesh, no level. The refinement walks its levels and applies
//! them (`refine/creases/level.rs`).

use std::f64::consts::PI;

use super::crease::{is_sharp, VertexRule};

/// The scheme of a crease-aware level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scheme {
    Loop,
    CatmullClark,
}

impl Scheme {
    /// The crease-aware scheme of `rule`: Loop and Catmull-Clark have one, other rules none.
    pub(crate) fn of(rule: crate::Rule) -> Option<Scheme> {
        match rule {
            crate::Rule::Loop => Some(Scheme::Loop),
            crate::Rule::CatmullClark => Some(Scheme::CatmullClark),
            _ => None,
        }
    }
}

/// A vertex mask (`Sdc`'s vertex, edge and face weights): one weight for the vertex, one per
/// ring edge (its opposite vertex) and one per ring face (its centre; Catmull-Clark only).
#[derive(Clone, Debug, Default)]
pub(crate) struct Mask {
    /// The vertex's own weight.
    pub(crate) vertex: f64,
    /// One weight per ring edge (its opposite vertex).
    pub(crate) edges: Vec<f64>,
    /// One weight per ring face (its centre).
    pub(crate) faces: Vec<f64>,
}

impl Mask {
    /// Sets the mask of `rule` for a vertex of `sharpness.len()` edges and `faces` faces.
    pub(crate) fn set(
        &mut self,
        rule: VertexRule,
        scheme: Scheme,
        sharpness: &[f32],
        faces: usize,
    ) {
        let n = sharpness.len();
        self.edges.clear();
        self.faces.clear();
        match rule {
            VertexRule::Corner => {
                self.vertex = 1.0;
                self.edges.resize(n, 0.0);
                self.faces.resize(faces, 0.0);
            }
            VertexRule::Crease => {
                // 3/4 of the vertex and 1/8 of each of the two sharp edges (the first and last
                // sharp ones in the ring: `GetSharpEdgePairOfCrease`).
                self.vertex = 0.75;
                self.edges.resize(n, 0.0);
                self.faces.resize(faces, 0.0);
                let first = sharpness.iter().position(|&s| is_sharp(s));
                let last = sharpness.iter().rposition(|&s| is_sharp(s));
                if let (Some(a), Some(b)) = (first, last) {
                    self.edges[a] = 0.125;
                    self.edges[b] = 0.125;
                }
            }
            VertexRule::Smooth | VertexRule::Dart => match scheme {
                Scheme::CatmullClark => {
                    // Valence from the faces (a smooth vertex is interior: as many as edges).
                    let valence = faces as f64;
                    let f = 1.0 / (faces * faces) as f64;
                    self.vertex = (valence - 2.0) / valence;
                    self.edges.resize(n, f);
                    self.faces.resize(faces, f);
                }
                Scheme::Loop => {
                    let (e, v) = if faces == 6 {
                        (0.0625, 0.625)
                    } else {
                        let valence = faces as f64;
                        let inv = 1.0 / valence;
                        let cos = (PI * 2.0 * inv).cos();
                        let beta = 0.25 * cos + 0.375;
                        let e = (0.625 - beta * beta) * inv;
                        (e, 1.0 - e * valence)
                    };
                    self.vertex = v;
                    self.edges.resize(n, e);
                    self.faces.resize(faces, 0.0);
                }
            },
        }
    }

    /// `self * p + child * (1 - p)` (`CombineVertexVertexMasks`).
    pub(crate) fn blend(&mut self, child: &Mask, p: f64) {
        let c = 1.0 - p;
        self.vertex = p * self.vertex + c * child.vertex;
        for (x, y) in self.edges.iter_mut().zip(&child.edges) {
            *x = p * *x + c * y;
        }
        for (x, y) in self.faces.iter_mut().zip(&child.faces) {
            *x = p * *x + c * y;
        }
    }
}

/// The mask of an edge's child vertex whose children are not both sharp
/// (`ComputeEdgeVertexMask`): the weight of each end vertex and of each side (Loop: the vertex
/// opposite the edge; Catmull-Clark: the face's centre). The smooth mask, with Catmark's
/// smooth-triangle weights where `triangles` marks a side that is a triangle under that rule
/// (in Hbr's order of operations), blended with the crease mask (the midpoint) by the edge's
/// `sharpness` when it is sharp (a crease that becomes smooth).
pub(crate) fn edge_mask(scheme: Scheme, sharpness: f32, triangles: [bool; 2]) -> (f64, [f64; 2]) {
    let (mut vw, fw) = match scheme {
        Scheme::Loop => (0.375, 0.125),
        Scheme::CatmullClark if triangles[0] || triangles[1] => {
            let weight = |tri: bool| if tri { 0.470 } else { 0.25 };
            let fw = 0.5 * (weight(triangles[0]) + weight(triangles[1]));
            (0.5 * (1.0 - 2.0 * fw), fw)
        }
        Scheme::CatmullClark => (0.25, 0.25),
    };
    let mut fw = [fw, fw];
    if is_sharp(sharpness) {
        let p = f64::from(sharpness);
        let c = 1.0 - p;
        vw = p * 0.5 + c * vw;
        fw = [fw[0] * c, fw[1] * c];
    }
    (vw, fw)
}
