//! The vertex masks of OpenSubdiv's `Sdc` schemes (`ComputeVertexVertexMask`'s smooth,
//! dart, crease and corner masks, blended by a fractional weight) and the edge masks
//! (`ComputeEdgeVertexMask`: smooth, crease, Catmark's smooth-triangle weights), as weights of
//! a vertex's neighbourhood: no mesh, no level. The refinement walks its levels and applies
//! them (`refine/creases/level.rs`).

use std::f64::consts::PI;

use super::crease::{is_sharp, VertexRule};

/// The crease vertex mask (a boundary or crease vertex, the cubic B-spline): 3/4 of the vertex
/// and 1/8 of each of its two neighbours along the crease.
pub(crate) const CREASE_VERTEX: [f64; 2] = [0.75, 0.125];

/// Loop's smooth edge mask: 3/8 of each end and 1/8 of each vertex opposite the edge.
pub(crate) const LOOP_EDGE: [f64; 2] = [0.375, 0.125];

/// Catmull-Clark's smooth edge mask: 1/4 of each end and of each side's face point.
pub(crate) const CATMULL_CLARK_EDGE: f64 = 0.25;

/// Loop's smooth vertex mask at `valence`: the vertex's weight `1 - n β` and each
/// neighbour's `β`, with Loop's original `β = (5/8 - (3/8 + 1/4 cos(2π/n))²) / n` (`1/16` at
/// valence 6, no cosine). OpenSubdiv computes `cos(2π · (1/n))` and scales by `1/n`: the two
/// differ in the last bit at some valences (5, 10, 12, ...), within the 1e-15 of the
/// differential tests.
#[inline(always)]
pub(crate) fn loop_smooth(valence: usize) -> (f64, f64) {
    if valence == 6 {
        return (0.625, 0.0625);
    }
    let n = valence as f64;
    let c = 3.0 / 8.0 + 0.25 * (2.0 * PI / n).cos();
    let beta = (5.0 / 8.0 - c * c) / n;
    (1.0 - n * beta, beta)
}

/// Catmull-Clark's smooth vertex mask at `valence`: the vertex's weight `(n - 2) / n`, and
/// `1 / n²` for each ring edge's other end and each ring face's centre (OpenSubdiv's
/// `assignSmoothMaskForVertex`).
#[inline(always)]
pub(crate) fn catmull_clark_smooth(valence: usize) -> (f64, f64) {
    let n = valence as f64;
    ((n - 2.0) / n, 1.0 / (n * n))
}

/// The scheme of a crease-aware level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scheme {
    Loop,
    CatmullClark,
}

impl Scheme {
    /// The rule's name.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Scheme::Loop => "loop",
            Scheme::CatmullClark => "catmull-clark",
        }
    }

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
                let [vertex, edge] = CREASE_VERTEX;
                self.vertex = vertex;
                self.edges.resize(n, 0.0);
                self.faces.resize(faces, 0.0);
                let first = sharpness.iter().position(|&s| is_sharp(s));
                let last = sharpness.iter().rposition(|&s| is_sharp(s));
                if let (Some(a), Some(b)) = (first, last) {
                    self.edges[a] = edge;
                    self.edges[b] = edge;
                }
            }
            VertexRule::Smooth | VertexRule::Dart => match scheme {
                Scheme::CatmullClark => {
                    // Valence from the faces (a smooth vertex is interior: as many as edges).
                    let (v, f) = catmull_clark_smooth(faces);
                    self.vertex = v;
                    self.edges.resize(n, f);
                    self.faces.resize(faces, f);
                }
                Scheme::Loop => {
                    let (v, e) = loop_smooth(faces);
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
        Scheme::Loop => (LOOP_EDGE[0], LOOP_EDGE[1]),
        Scheme::CatmullClark if triangles[0] || triangles[1] => {
            let weight = |tri: bool| if tri { 0.470 } else { CATMULL_CLARK_EDGE };
            let fw = 0.5 * (weight(triangles[0]) + weight(triangles[1]));
            (0.5 * (1.0 - 2.0 * fw), fw)
        }
        Scheme::CatmullClark => (CATMULL_CLARK_EDGE, CATMULL_CLARK_EDGE),
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
