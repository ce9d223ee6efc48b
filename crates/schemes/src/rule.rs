//! The geometric subdivision rules: which real subdivision a scheme stands for.
//!
//! A [`Scheme`] says how many vertices, edges and faces a rule makes; a [`Rule`] names the
//! rule itself, the thing `halfedge` runs (its topology and its geometry). The built-in table
//! ([`builtin`](crate::builtin)) maps every name to both: `butterfly` is the Loop matrix with
//! [`Rule::Butterfly`], `loop-boundary` the boundary-aware Loop matrix with [`Rule::Loop`]. A
//! custom scheme gets a rule from the `topology` key of its file
//! ([`Scheme::from_toml`](crate::Scheme::from_toml)).
//!
//! [`Rule::scheme_for`] goes the other way: the built-in scheme that counts a rule on a given
//! mesh (Loop on a mesh with boundary is counted by `loop-boundary`, on a non-manifold face
//! list by `loop-general`), which is what `halfedge` sizes its output arrays from.

use std::fmt;

use crate::{builtin, MeshCounts, Result, Scheme};

/// A subdivision rule: a topology (how faces split) and a geometry (where points go).
///
/// ```
/// use schemes::{builtin, MeshCounts, Rule};
///
/// assert_eq!(builtin("butterfly")?.subdivision_rule(), Some(Rule::Butterfly));
/// assert_eq!(builtin("ternary")?.subdivision_rule(), Some(Rule::TriSplit(3)));
/// assert_eq!(Rule::TriSplit(3).to_string(), "tri-split-3");
///
/// // Loop on an open square is counted by the boundary-aware matrix.
/// let open_square = MeshCounts::from_polygons(&[[0, 1, 2], [0, 2, 3]])?;
/// assert_eq!(Rule::Loop.scheme_for(&open_square)?.canonical_name(), "loop-boundary");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
/// Not `non_exhaustive`: `halfedge` matches every rule, so a new one cannot be forgotten.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Rule {
    /// Loop: 4:1 triangle split, Loop's weights; on a boundary the cubic B-spline of the
    /// boundary polygon (edges sharp, corners smooth: OpenSubdiv's `VTX_BOUNDARY_EDGE_ONLY`).
    Loop,
    /// 4:1 triangle split with the edge midpoints; old vertices stay.
    Midpoint,
    /// The modified butterfly scheme (interpolating), 4:1 split.
    Butterfly,
    /// 4:1 split with the edge midpoints projected on the unit sphere (not linear).
    Icosphere,
    /// 1:N² triangle split with points on the flat triangles (`N >= 2`).
    TriSplit(u32),
    /// Catmull-Clark on any polygon mesh, with boundary rules.
    CatmullClark,
    /// Kobbelt's √3 (on a boundary: his alternating boundary steps).
    Sqrt3,
    /// Doo-Sabin (on a boundary: Chaikin's quadratic B-spline boundary,
    /// [`doo_sabin_boundary`](crate::catalog::doo_sabin_boundary)).
    DooSabin,
    /// Peters-Reif mid-edge (on a boundary: the cubic B-spline boundary,
    /// [`mid_edge_boundary`](crate::catalog::mid_edge_boundary)).
    MidEdge,
}

impl Rule {
    /// The built-in rules, `TriSplit(3)` standing for the family.
    pub const ALL: [Rule; 9] = [
        Rule::Loop,
        Rule::Midpoint,
        Rule::Butterfly,
        Rule::Icosphere,
        Rule::TriSplit(3),
        Rule::CatmullClark,
        Rule::Sqrt3,
        Rule::DooSabin,
        Rule::MidEdge,
    ];

    /// Whether every new point is a fixed linear combination of old points, so that a stencil
    /// table exists: all rules but [`Rule::Icosphere`] (its projection on the sphere).
    pub fn is_linear(self) -> bool {
        self != Rule::Icosphere
    }

    /// Whether the rule works on triangles only (the 4:1 family, 1:N², √3).
    pub fn needs_triangles(self) -> bool {
        !matches!(self, Rule::CatmullClark | Rule::DooSabin | Rule::MidEdge)
    }

    /// Whether the rule's topology is a refinement of each face on its own (4:1, 1:N²,
    /// Catmull-Clark), so that it also runs on non-manifold face lists.
    pub fn refines_faces(self) -> bool {
        !matches!(self, Rule::Sqrt3 | Rule::DooSabin | Rule::MidEdge)
    }

    /// The built-in scheme that counts this rule on a mesh with `counts`: the 4:1 family is
    /// `loop` on closed meshes, `loop-boundary` on meshes with boundary edges and
    /// `loop-general` on non-manifold face lists; Catmull-Clark is `catmull-clark`, or
    /// `catmull-clark-general` with non-manifold edges; √3 is `sqrt3` or `sqrt3-boundary`;
    /// Doo-Sabin and mid-edge are `doo-sabin` and `mid-edge` on closed meshes,
    /// `doo-sabin-boundary` and `mid-edge-boundary` with boundary edges;
    /// `TriSplit(n)` is `tri-split-n`. The scheme keeps the rule's name.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidSplitFactor`](crate::Error::InvalidSplitFactor) for `TriSplit(n)` with
    /// `n < 2`.
    pub fn scheme_for(self, counts: &MeshCounts) -> Result<Scheme> {
        let nonmanifold = counts.nonmanifold_edges > 0;
        let boundary = counts.boundary_edges > 0;
        let canonical = match self {
            Rule::Loop | Rule::Midpoint | Rule::Butterfly | Rule::Icosphere => {
                if nonmanifold {
                    "loop-general"
                } else if boundary {
                    "loop-boundary"
                } else {
                    "loop"
                }
            }
            Rule::TriSplit(n) => return builtin(&format!("tri-split-{n}")),
            Rule::CatmullClark if nonmanifold => "catmull-clark-general",
            Rule::CatmullClark => "catmull-clark",
            Rule::Sqrt3 if boundary => "sqrt3-boundary",
            Rule::Sqrt3 => "sqrt3",
            Rule::DooSabin if boundary && !nonmanifold => "doo-sabin-boundary",
            Rule::DooSabin => "doo-sabin",
            Rule::MidEdge if boundary && !nonmanifold => "mid-edge-boundary",
            Rule::MidEdge => "mid-edge",
        };
        Ok(builtin(canonical)?.renamed(&self.to_string()))
    }
}

impl fmt::Display for Rule {
    /// The rule's built-in name: `loop`, `butterfly`, `tri-split-4`, `catmull-clark`, ...
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Rule::Loop => f.write_str("loop"),
            Rule::Midpoint => f.write_str("midpoint"),
            Rule::Butterfly => f.write_str("butterfly"),
            Rule::Icosphere => f.write_str("icosphere"),
            Rule::TriSplit(n) => write!(f, "tri-split-{n}"),
            Rule::CatmullClark => f.write_str("catmull-clark"),
            Rule::Sqrt3 => f.write_str("sqrt3"),
            Rule::DooSabin => f.write_str("doo-sabin"),
            Rule::MidEdge => f.write_str("mid-edge"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every built-in name has a rule, and the rule's own name looks up a scheme with the same
    /// rule (the table is consistent in both directions).
    #[test]
    fn every_builtin_has_a_rule_and_back() {
        let names = crate::catalog::BUILTIN_NAMES
            .iter()
            .map(|n| n.replace("tri-split-N", "tri-split-5"))
            .chain(["midpoint", "butterfly", "icosphere", "ternary"].map(String::from));
        for name in names {
            let scheme = builtin(&name).expect("built-in");
            let rule = scheme
                .subdivision_rule()
                .unwrap_or_else(|| panic!("{name}"));
            assert_eq!(
                builtin(&rule.to_string())
                    .expect("rule name")
                    .subdivision_rule(),
                Some(rule),
                "{name}"
            );
        }
        for scheme in crate::builtins() {
            assert!(scheme.subdivision_rule().is_some(), "{}", scheme.name());
        }
        for rule in Rule::ALL {
            assert_eq!(
                builtin(&rule.to_string())
                    .expect("built-in")
                    .subdivision_rule(),
                Some(rule)
            );
        }
    }

    #[test]
    fn schemes_follow_the_mesh() {
        let closed = MeshCounts::from_polygons(&[[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]])
            .expect("tetrahedron");
        let open = MeshCounts::from_polygons(&[[0, 1, 2], [0, 2, 3]]).expect("square");
        let book = MeshCounts::from_face_list([[0, 1, 2], [1, 0, 3], [0, 1, 4]], 5);
        let canonical = |rule: Rule, c: &MeshCounts| {
            rule.scheme_for(c)
                .expect("scheme")
                .canonical_name()
                .to_owned()
        };
        assert_eq!(canonical(Rule::Butterfly, &closed), "loop");
        assert_eq!(canonical(Rule::Loop, &open), "loop-boundary");
        assert_eq!(canonical(Rule::Midpoint, &book), "loop-general");
        assert_eq!(
            canonical(Rule::CatmullClark, &book),
            "catmull-clark-general"
        );
        assert_eq!(canonical(Rule::Sqrt3, &open), "sqrt3-boundary");
        assert_eq!(canonical(Rule::TriSplit(4), &open), "tri-split-4");
        assert_eq!(
            Rule::Icosphere.scheme_for(&open).expect("scheme").name(),
            "icosphere"
        );
        assert!(Rule::TriSplit(1).scheme_for(&open).is_err());
    }
}
