//! The limit masks of OpenSubdiv 3.5's `Sdc` schemes (`ComputeVertexLimitMask` with tangents):
//! the limit position of a vertex and two limit tangents as weights of its neighbourhood,
//! from the vertex's rule at the level evaluated. No mesh, no level.
//!
//! A mask has one weight for the vertex, one per ring edge (its other end, the edges listed
//! counter-clockwise from the vertex's leading edge) and, under Catmull-Clark, one per ring
//! face: face `i` lies between edges `i` and `i + 1`, and its weight applies to the face's
//! corner *opposite* the vertex (two corners on from it: the masks assume quads, as
//! OpenSubdiv's `SetFaceWeightsForFaceCenters(false)` says).
//!
//! The tangents are scaled as OpenSubdiv scales them (its notes on consistent magnitudes):
//! the first tangent points along the leading edge, or along the crease towards its first
//! sharp edge; the second across the surface, so that `T1 × T2` is the normal. The weights are
//! computed in `f64` with OpenSubdiv's operations in its order.

use std::f64::consts::PI;

use super::crease::{is_sharp, VertexRule};
use super::masks::{Mask, Scheme};

/// `√3` as OpenSubdiv writes it.
const ROOT3: f64 = 1.732_050_807_568_877_2;

/// The three limit masks of a vertex: its limit position and the two limit tangents. The
/// three have the same number of edge weights; the position may have no face weights where
/// the tangents have some.
#[derive(Clone, Debug, Default)]
pub(crate) struct LimitMasks {
    pub(crate) position: Mask,
    pub(crate) tangent1: Mask,
    pub(crate) tangent2: Mask,
}

impl LimitMasks {
    /// Sets the masks of a vertex of rule `rule` with `sharpness.len()` edges (their
    /// sharpness at the level, in ring order) and `faces` faces.
    pub(crate) fn set(
        &mut self,
        scheme: Scheme,
        rule: VertexRule,
        sharpness: &[f32],
        faces: usize,
    ) {
        let edges = sharpness.len();
        for mask in [&mut self.position, &mut self.tangent1, &mut self.tangent2] {
            mask.vertex = 0.0;
            mask.edges.clear();
            mask.edges.resize(edges, 0.0);
            mask.faces.clear();
        }
        match rule {
            VertexRule::Smooth | VertexRule::Dart => self.smooth(scheme, faces),
            VertexRule::Crease => {
                // The first and last sharp edges of the ring (`GetSharpEdgePairOfCrease`).
                let first = sharpness.iter().position(|&s| is_sharp(s));
                let last = sharpness.iter().rposition(|&s| is_sharp(s));
                match (first, last) {
                    (Some(a), Some(b)) => self.crease(scheme, [a, b], faces),
                    _ => self.corner(scheme),
                }
            }
            VertexRule::Corner => self.corner(scheme),
        }
    }

    /// `assignCornerLimitMask` and `assignCornerLimitTangentMasks`: the vertex stays; the
    /// tangents are differences along the first two edges (scaled by 3 under Loop).
    fn corner(&mut self, scheme: Scheme) {
        self.position.vertex = 1.0;
        // A corner's position has no edge weights; the tangents keep theirs.
        self.position.edges.clear();
        let scale = match scheme {
            Scheme::Loop => 3.0,
            Scheme::CatmullClark => 1.0,
        };
        self.tangent1.vertex = -scale;
        self.tangent2.vertex = -scale;
        if let Some(w) = self.tangent1.edges.get_mut(0) {
            *w = scale;
        }
        if let Some(w) = self.tangent2.edges.get_mut(1) {
            *w = scale;
        }
    }

    /// The crease masks along the sharp edges `ends` (ring indices, `ends[0] < ends[1]`): the
    /// position is the cubic B-spline's limit (2/3, 1/6, 1/6) under both schemes.
    fn crease(&mut self, scheme: Scheme, ends: [usize; 2], faces: usize) {
        let [a, b] = ends;
        self.position.vertex = 2.0 / 3.0;
        self.position.edges[a] = 1.0 / 6.0;
        self.position.edges[b] = 1.0 / 6.0;
        let interior = b - a - 1;
        let (t1, t2) = (&mut self.tangent1, &mut self.tangent2);
        match scheme {
            Scheme::Loop => {
                t1.edges[a] = 1.5;
                t1.edges[b] = -1.5;
                match interior {
                    0 => one_face(t2, ends),
                    1 => {
                        t2.vertex = -3.0;
                        t2.edges[a + 1] = 3.0;
                    }
                    2 => {
                        let half = ROOT3 * 0.5;
                        t2.vertex = -ROOT3;
                        t2.edges[a] = -half;
                        t2.edges[b] = -half;
                        t2.edges[a + 1] = ROOT3;
                        t2.edges[a + 2] = ROOT3;
                    }
                    _ => {
                        let theta = PI / (interior + 1) as f64;
                        let c = -3.0 * theta.sin();
                        t2.edges[a] = c;
                        t2.edges[b] = c;
                        let e = -3.0 * 2.0 * (theta.cos() - 1.0);
                        for i in 1..=interior {
                            t2.edges[a + i] = e * (i as f64 * theta).sin();
                        }
                    }
                }
            }
            Scheme::CatmullClark => {
                t1.faces.resize(faces, 0.0);
                t2.faces.resize(faces, 0.0);
                t1.edges[a] = 0.5;
                t1.edges[b] = -0.5;
                match interior {
                    0 => one_face(t2, ends),
                    1 => {
                        t2.vertex = -4.0 / 6.0;
                        t2.edges[a] = -1.0 / 6.0;
                        t2.edges[a + 1] = 4.0 / 6.0;
                        t2.edges[b] = -1.0 / 6.0;
                        t2.faces[a] = 1.0 / 6.0;
                        t2.faces[a + 1] = 1.0 / 6.0;
                    }
                    _ => {
                        // Biermann et al.'s irregular crease.
                        let k = (interior + 1) as f64;
                        let theta = PI / k;
                        let (sin, cos) = (theta.sin(), theta.cos());
                        let denominator = 1.0 / (k * (3.0 + cos));
                        let r = (cos + 1.0) / sin;
                        t2.vertex = 4.0 * r * (cos - 1.0) * denominator;
                        let crease = -r * (1.0 + 2.0 * cos) * denominator;
                        t2.edges[a] = crease;
                        t2.edges[b] = crease;
                        t2.faces[a] = sin * denominator;
                        let mut next = sin;
                        for i in 1..=interior {
                            let this = next;
                            next = ((i + 1) as f64 * theta).sin();
                            t2.edges[a + i] = 4.0 * this * denominator;
                            t2.faces[a + i] = (this + next) * denominator;
                        }
                    }
                }
            }
        }
    }

    /// The smooth (and dart) masks at a vertex of `valence` faces (OpenSubdiv's constants at
    /// the regular valences, its formulas elsewhere).
    fn smooth(&mut self, scheme: Scheme, valence: usize) {
        self.smooth_by(scheme, valence, true);
    }

    /// [`LimitMasks::smooth`], by the general formulas at every valence unless `regular`.
    fn smooth_by(&mut self, scheme: Scheme, valence: usize, regular: bool) {
        let n = valence as f64;
        match scheme {
            Scheme::Loop => {
                let (v, e) = if regular && valence == 6 {
                    (0.5, 1.0 / 12.0)
                } else {
                    let inverse = 1.0 / n;
                    let cos = (PI * 2.0 * inverse).cos();
                    let beta = 0.25 * cos + 0.375;
                    let gamma = (0.625 - beta * beta) * inverse;
                    let e = 1.0 / (n + 3.0 / (8.0 * gamma));
                    (1.0 - e * n, e)
                };
                self.position.vertex = v;
                self.position.edges.fill(e);
                if regular && valence == 6 {
                    let half = 0.5 * ROOT3;
                    self.tangent1
                        .edges
                        .copy_from_slice(&[1.0, 0.5, -0.5, -1.0, -0.5, 0.5]);
                    self.tangent2
                        .edges
                        .copy_from_slice(&[0.0, half, half, 0.0, -half, -half]);
                } else {
                    let alpha = 2.0 * PI / n;
                    for i in 0..valence {
                        let angle = alpha * i as f64;
                        self.tangent1.edges[i] = angle.cos();
                        self.tangent2.edges[i] = angle.sin();
                    }
                }
            }
            Scheme::CatmullClark => {
                if valence == 2 {
                    self.corner(scheme);
                    return;
                }
                for mask in [&mut self.position, &mut self.tangent1, &mut self.tangent2] {
                    mask.faces.resize(valence, 0.0);
                }
                let (v, e, f) = if regular && valence == 4 {
                    (4.0 / 9.0, 1.0 / 9.0, 1.0 / 36.0)
                } else {
                    let f = 1.0 / (n * (n + 5.0));
                    let e = 4.0 * f;
                    (1.0 - n * (e + f), e, f)
                };
                self.position.vertex = v;
                self.position.edges.fill(e);
                self.position.faces.fill(f);
                let (t1, t2) = (&mut self.tangent1, &mut self.tangent2);
                if regular && valence == 4 {
                    t1.edges.copy_from_slice(&[4.0, 0.0, -4.0, 0.0]);
                    t1.faces.copy_from_slice(&[1.0, -1.0, -1.0, 1.0]);
                    t2.edges.copy_from_slice(&[0.0, 4.0, 0.0, -4.0]);
                    t2.faces.copy_from_slice(&[1.0, 1.0, -1.0, -1.0]);
                } else {
                    let theta = 2.0 * PI / n;
                    let cos = theta.cos();
                    let lambda = 5.0 / 16.0
                        + (1.0 / 16.0) * (cos + (theta * 0.5).cos() * (2.0 * (9.0 + cos)).sqrt());
                    let face_scale = 1.0 / (4.0 * lambda - 1.0);
                    for i in 0..valence {
                        let this = (i as f64 * theta).cos();
                        let next = ((i + 1) as f64 * theta).cos();
                        t1.edges[i] = 4.0 * this;
                        t1.faces[i] = face_scale * (this + next);
                    }
                    // The second tangent is the first rotated by one sector.
                    for i in 0..valence {
                        let from = (i + valence - 1) % valence;
                        t2.edges[i] = t1.edges[from];
                        t2.faces[i] = t1.faces[from];
                    }
                }
            }
        }
    }
}

/// The cross tangent of a crease vertex of one face (both schemes): the average of the two
/// crease edges' differences, scaled by 3.
fn one_face(t2: &mut Mask, [a, b]: [usize; 2]) {
    t2.vertex = -6.0;
    t2.edges[a] = 3.0;
    t2.edges[b] = 3.0;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn masks(scheme: Scheme, rule: VertexRule, sharpness: &[f32], faces: usize) -> LimitMasks {
        let mut m = LimitMasks::default();
        m.set(scheme, rule, sharpness, faces);
        m
    }

    fn sum(mask: &Mask) -> f64 {
        mask.vertex + mask.edges.iter().sum::<f64>() + mask.faces.iter().sum::<f64>()
    }

    #[test]
    fn positions_are_affine_and_tangents_differences() {
        for scheme in [Scheme::Loop, Scheme::CatmullClark] {
            for n in 2..12 {
                let smooth = vec![0.0f32; n];
                let mut crease = smooth.clone();
                crease[0] = 10.0;
                crease[n - 1] = 10.0;
                for (rule, sharpness, faces) in [
                    (VertexRule::Smooth, &smooth, n),
                    (VertexRule::Crease, &crease, n - 1),
                    (VertexRule::Corner, &crease, n - 1),
                ] {
                    if rule == VertexRule::Smooth && n < 3 {
                        continue;
                    }
                    let m = masks(scheme, rule, sharpness, faces);
                    assert!(
                        (sum(&m.position) - 1.0).abs() < 1e-14,
                        "{scheme:?} {rule:?} {n}"
                    );
                    assert!(sum(&m.tangent1).abs() < 1e-13, "{scheme:?} {rule:?} {n}");
                    assert!(sum(&m.tangent2).abs() < 1e-13, "{scheme:?} {rule:?} {n}");
                    assert_eq!(m.tangent1.edges.len(), m.tangent2.edges.len());
                    assert_eq!(m.tangent1.faces.len(), m.tangent2.faces.len());
                }
            }
        }
    }

    #[test]
    fn the_regular_constants_are_the_general_formulas_there() {
        for (scheme, valence) in [(Scheme::Loop, 6), (Scheme::CatmullClark, 4)] {
            let (mut special, mut general) = (LimitMasks::default(), LimitMasks::default());
            for (m, regular) in [(&mut special, true), (&mut general, false)] {
                m.set(scheme, VertexRule::Smooth, &vec![0.0; valence], valence);
                m.smooth_by(scheme, valence, regular);
            }
            let pairs = [
                (&special.position, &general.position),
                (&special.tangent1, &general.tangent1),
                (&special.tangent2, &general.tangent2),
            ];
            for (a, b) in pairs {
                assert!((a.vertex - b.vertex).abs() < 1e-15, "{scheme:?}");
                for (x, y) in a
                    .edges
                    .iter()
                    .zip(&b.edges)
                    .chain(a.faces.iter().zip(&b.faces))
                {
                    assert!((x - y).abs() < 1e-14, "{scheme:?}: {x} vs {y}");
                }
                assert_eq!(
                    (a.edges.len(), a.faces.len()),
                    (b.edges.len(), b.faces.len())
                );
            }
        }
    }

    #[test]
    fn regular_masks_are_the_b_spline_limits() {
        // Loop at valence 6 and Catmull-Clark at valence 4: the box-spline and bicubic
        // B-spline limits; the general formulas agree with them there.
        let loop6 = masks(Scheme::Loop, VertexRule::Smooth, &[0.0; 6], 6);
        assert_eq!(loop6.position.vertex, 0.5);
        let cc4 = masks(Scheme::CatmullClark, VertexRule::Smooth, &[0.0; 4], 4);
        assert_eq!(cc4.position.vertex, 4.0 / 9.0);
        assert_eq!(cc4.position.faces, vec![1.0 / 36.0; 4]);
        let n = 4.0f64;
        let f = 1.0 / (n * (n + 5.0));
        assert!((1.0 - n * 5.0 * f - 4.0 / 9.0).abs() < 1e-15);
        // A crease: the cubic B-spline limit under both schemes.
        let mut sharp = [0.0f32; 4];
        sharp[0] = 10.0;
        sharp[2] = 10.0;
        let c = masks(Scheme::CatmullClark, VertexRule::Crease, &sharp, 4);
        assert_eq!(c.position.vertex, 2.0 / 3.0);
        assert_eq!(c.position.edges, vec![1.0 / 6.0, 0.0, 1.0 / 6.0, 0.0]);
        assert_eq!(c.tangent1.edges, vec![0.5, 0.0, -0.5, 0.0]);
    }
}
