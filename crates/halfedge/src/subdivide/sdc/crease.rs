//! The scheme-independent crease arithmetic of OpenSubdiv 3.5's `Sdc::Crease`, in `f32` as
//! OpenSubdiv computes it: the vertex rules, the decay of sharpness from level to level
//! (uniform and Chaikin) and the fractional weight of a transition between two rules.
//!
//! Every function takes the sharpness values in the order OpenSubdiv lists them (a vertex's
//! incident edges counter-clockwise from its leading edge), since the sums below run in that
//! order and `f32` addition of three or more terms depends on it.

use crate::tags::{CreaseMethod, INFINITELY_SHARP};

/// The subdivision rule of a vertex (`Sdc::Crease::Rule`): from the number of sharp edges
/// around it (0 smooth, 1 dart, 2 crease, more: corner) unless the vertex itself is sharp
/// (corner).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum VertexRule {
    /// No sharp edge: the smooth mask.
    Smooth,
    /// One sharp edge: the smooth mask too.
    Dart,
    /// Two sharp edges: the crease mask along them.
    Crease,
    /// A sharp vertex or more than two sharp edges: the vertex stays.
    Corner,
}

impl VertexRule {
    /// Smooth and dart vertices take the same (smooth) mask.
    pub(crate) fn is_smooth(self) -> bool {
        matches!(self, VertexRule::Smooth | VertexRule::Dart)
    }
}

/// `Sdc::Crease::IsSharp`.
#[inline]
pub(crate) fn is_sharp(s: f32) -> bool {
    s > 0.0
}

/// `Sdc::Crease::IsSmooth`.
#[inline]
pub(crate) fn is_smooth(s: f32) -> bool {
    s <= 0.0
}

/// `Sdc::Crease::IsInfinite`.
#[inline]
pub(crate) fn is_infinite(s: f32) -> bool {
    s >= INFINITELY_SHARP
}

/// `Sdc::Crease::IsSemiSharp`.
#[inline]
pub(crate) fn is_semi_sharp(s: f32) -> bool {
    0.0 < s && s < INFINITELY_SHARP
}

/// One level of uniform decay (`decrementSharpness`): smooth stays smooth, infinite stays
/// infinite, above 1 loses 1, the rest becomes smooth. The vertex sharpness decays this way
/// under both crease methods.
#[inline]
pub(crate) fn decrement(s: f32) -> f32 {
    if is_smooth(s) {
        0.0
    } else if is_infinite(s) {
        INFINITELY_SHARP
    } else if s > 1.0 {
        s - 1.0
    } else {
        0.0
    }
}

/// The vertex rule from the vertex's sharpness and the number of sharp edges around it
/// (`DetermineVertexVertexRule`).
pub(crate) fn vertex_rule(vertex_sharpness: f32, sharp_edges: usize) -> VertexRule {
    if is_sharp(vertex_sharpness) {
        return VertexRule::Corner;
    }
    match sharp_edges {
        0 => VertexRule::Smooth,
        1 => VertexRule::Dart,
        2 => VertexRule::Crease,
        _ => VertexRule::Corner,
    }
}

/// The rule of a vertex whose incident edges have the sharpness `edges`.
pub(crate) fn vertex_rule_of(vertex_sharpness: f32, edges: &[f32]) -> VertexRule {
    vertex_rule(
        vertex_sharpness,
        edges.iter().filter(|&&s| is_sharp(s)).count(),
    )
}

/// The sharpness of the child of the edge `edges[i]` at its end vertex whose incident edges
/// are `edges` (`SubdivideEdgeSharpnessAtVertex`): uniform decay, or Chaikin's rule (3/4 of
/// the edge's sharpness and 1/4 of the average of the other semi-sharp edges at the vertex,
/// less 1).
pub(crate) fn child_edge_sharpness(method: CreaseMethod, edges: &[f32], i: usize) -> f32 {
    let s = edges[i];
    if method == CreaseMethod::Uniform || edges.len() < 2 {
        return decrement(s);
    }
    if is_smooth(s) {
        return 0.0;
    }
    if is_infinite(s) {
        return INFINITELY_SHARP;
    }
    let mut sum = 0.0f32;
    let mut count = 0u32;
    for &e in edges {
        if is_semi_sharp(e) {
            count += 1;
            sum += e;
        }
    }
    let mut s = s;
    if count > 1 {
        let average = (sum - s) / (count - 1) as f32;
        s = 0.75f32 * s + 0.25f32 * average;
    }
    s -= 1.0;
    if is_sharp(s) {
        s
    } else {
        0.0
    }
}

/// The weight of the parent's mask when a vertex's rule changes from one level to the next
/// (`ComputeFractionalWeightAtVertex`): the average of the sharpness values that decay to
/// zero (the vertex's, then its edges' in order), at most 1. Under the uniform method an
/// edge decays when its sharpness is at most 1; under Chaikin when its child is smooth.
pub(crate) fn fractional_weight(
    method: CreaseMethod,
    vertex: f32,
    child_vertex: f32,
    edges: &[f32],
    child_edges: &[f32],
) -> f32 {
    let mut count = 0u32;
    let mut sum = 0.0f32;
    if is_sharp(vertex) && is_smooth(child_vertex) {
        count = 1;
        sum = vertex;
    }
    for (&p, &c) in edges.iter().zip(child_edges) {
        let decays = match method {
            CreaseMethod::Uniform => is_sharp(p) && p <= 1.0,
            CreaseMethod::Chaikin => is_sharp(p) && is_smooth(c),
        };
        if decays {
            sum += p;
            count += 1;
        }
    }
    if count == 0 {
        return 0.0;
    }
    let weight = sum / count as f32;
    if weight > 1.0 {
        1.0
    } else {
        weight
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_decay_subtracts_one_and_keeps_infinite_and_smooth() {
        assert_eq!(decrement(0.0), 0.0);
        assert_eq!(decrement(0.7), 0.0);
        assert_eq!(decrement(1.0), 0.0);
        assert_eq!(decrement(2.5), 1.5);
        assert_eq!(decrement(1.3), 1.3f32 - 1.0);
        assert_eq!(decrement(10.0), 10.0);
        assert_eq!(decrement(37.0), 10.0);
    }

    #[test]
    fn rules_count_sharp_edges_unless_the_vertex_is_sharp() {
        assert_eq!(vertex_rule_of(0.0, &[0.0, 0.0, 0.0]), VertexRule::Smooth);
        assert_eq!(vertex_rule_of(0.0, &[0.5, 0.0, 0.0]), VertexRule::Dart);
        assert_eq!(vertex_rule_of(0.0, &[0.5, 0.0, 10.0]), VertexRule::Crease);
        assert_eq!(vertex_rule_of(0.0, &[0.5, 1.0, 10.0]), VertexRule::Corner);
        assert_eq!(vertex_rule_of(0.1, &[0.0, 0.0]), VertexRule::Corner);
        assert!(VertexRule::Dart.is_smooth() && !VertexRule::Crease.is_smooth());
    }

    #[test]
    fn chaikin_blends_with_the_other_semi_sharp_edges() {
        // chaikin2's chain 0.5, 1.5, 2.5, 3.5: the edge of 1.5 at its end shared with 2.5.
        let at = [1.5f32, 2.5, 0.0, 0.0];
        assert_eq!(
            child_edge_sharpness(CreaseMethod::Chaikin, &at, 0),
            (0.75f32 * 1.5 + 0.25f32 * 2.5) - 1.0
        );
        // Alone at its vertex: uniform decay; infinite neighbours do not count.
        let alone = [1.5f32, 10.0, 0.0];
        assert_eq!(child_edge_sharpness(CreaseMethod::Chaikin, &alone, 0), 0.5);
        assert_eq!(child_edge_sharpness(CreaseMethod::Chaikin, &alone, 1), 10.0);
        assert_eq!(child_edge_sharpness(CreaseMethod::Uniform, &at, 1), 1.5);
        // A blend that falls to zero or below is smooth.
        let low = [0.5f32, 0.5, 0.0];
        assert_eq!(child_edge_sharpness(CreaseMethod::Chaikin, &low, 0), 0.0);
    }

    #[test]
    fn fractional_weights_average_what_decays_and_clamp_at_one() {
        let u = CreaseMethod::Uniform;
        assert_eq!(
            fractional_weight(u, 0.0, 0.0, &[0.5, 0.0, 0.5, 0.0], &[0.0; 4]),
            0.5
        );
        assert_eq!(
            fractional_weight(u, 0.3, 0.0, &[10.0, 10.0], &[10.0, 10.0]),
            0.3
        );
        assert_eq!(
            fractional_weight(u, 0.0, 0.0, &[2.0, 0.0], &[1.0, 0.0]),
            0.0
        );
        // Chaikin: an edge above 1 can decay to zero in one step; the weight is clamped.
        let c = CreaseMethod::Chaikin;
        assert_eq!(
            fractional_weight(c, 0.0, 0.0, &[1.2, 0.0, 1.6], &[0.0; 3]),
            1.0
        );
    }
}
