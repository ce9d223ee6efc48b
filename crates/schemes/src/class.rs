//! [`MeshClass`]: what a scheme requires of its input mesh, and the refusal when a mesh does
//! not qualify.

use std::fmt;

use crate::{Error, MeshCounts, Result};

/// The kind of faces a scheme accepts or produces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum FaceKind {
    /// Every face is a triangle (`H = 3F`).
    Triangles,
    /// Every face is a quad (`H = 4F`).
    Quads,
    /// Faces of any degree >= 3.
    Polygons,
}

impl FaceKind {
    /// The face degree when fixed (3 or 4).
    pub fn degree(self) -> Option<u32> {
        match self {
            FaceKind::Triangles => Some(3),
            FaceKind::Quads => Some(4),
            FaceKind::Polygons => None,
        }
    }

    /// The word used in TOML `requires`/`produces` and in messages: `triangles`, `quads`,
    /// `polygons`.
    pub fn keyword(self) -> &'static str {
        match self {
            FaceKind::Triangles => "triangles",
            FaceKind::Quads => "quads",
            FaceKind::Polygons => "polygons",
        }
    }

    fn noun(self) -> &'static str {
        match self {
            FaceKind::Triangles => "triangle",
            FaceKind::Quads => "quad",
            FaceKind::Polygons => "polygon",
        }
    }
}

/// The meshes a scheme applies to.
///
/// `closed` means no boundary and no non-manifold edges (`BE = 0` and `NME = 0`); `manifold`
/// means every edge has one or two faces (`NME = 0`), boundary allowed. `closed` implies
/// `manifold`.
///
/// ```
/// use schemes::{FaceKind, MeshClass};
/// let c = MeshClass { faces: FaceKind::Triangles, closed: true, manifold: true };
/// assert_eq!(c.to_string(), "closed triangle mesh");
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct MeshClass {
    /// The faces required.
    pub faces: FaceKind,
    /// No boundary edges and no non-manifold edges.
    pub closed: bool,
    /// Every edge has one or two faces.
    pub manifold: bool,
}

impl MeshClass {
    /// Any polygon mesh: no requirement at all.
    pub const ANY: MeshClass = MeshClass {
        faces: FaceKind::Polygons,
        closed: false,
        manifold: false,
    };

    /// Whether `closed` or `manifold` rules out non-manifold edges.
    pub fn needs_manifold(&self) -> bool {
        self.closed || self.manifold
    }

    /// The requirement keywords as used in TOML `requires`, e.g. `["triangles", "closed"]`.
    pub fn keywords(&self) -> Vec<&'static str> {
        let mut out = Vec::new();
        if self.faces != FaceKind::Polygons {
            out.push(self.faces.keyword());
        }
        if self.closed {
            out.push("closed");
        } else if self.manifold {
            out.push("manifold");
        }
        out
    }
}

impl fmt::Display for MeshClass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let noun = self.faces.noun();
        if self.closed {
            write!(f, "closed {noun} mesh")
        } else if self.manifold {
            write!(
                f,
                "{noun} mesh with edges of one or two faces (boundary allowed)"
            )
        } else {
            write!(
                f,
                "any {noun} mesh (boundary and non-manifold edges allowed)"
            )
        }
    }
}

/// Schemes to suggest when a mesh does not qualify.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Hints {
    /// When the faces are of the wrong kind (on a manifold mesh).
    pub(crate) faces: Option<String>,
    /// When the faces are of the wrong kind and there are non-manifold edges.
    pub(crate) faces_nonmanifold: Option<String>,
    /// When a closed-mesh scheme meets boundary edges.
    pub(crate) boundary: Option<String>,
    /// When a manifold scheme meets non-manifold edges.
    pub(crate) nonmanifold: Option<String>,
}

fn use_(name: &Option<String>) -> Option<String> {
    name.as_ref().map(|n| format!("use {n}"))
}

/// Checks `counts` against `class`; the refusal names what is wrong and what to use instead.
pub(crate) fn check_counts(
    scheme: &str,
    class: &MeshClass,
    hints: &Hints,
    counts: &MeshCounts,
) -> Result {
    let refuse = |needs: String, found: String, hint: Option<String>| {
        Err(Error::NotApplicable {
            scheme: scheme.to_string(),
            needs,
            found,
            hint,
        })
    };
    if let Some(degree) = class.faces.degree() {
        let needs = format!("a {} mesh", class.faces.noun());
        let hint = if counts.nonmanifold_edges > 0 {
            use_(&hints.faces_nonmanifold)
        } else {
            use_(&hints.faces)
        };
        match counts.faces_not_of_degree(degree) {
            Some(others) if !others.is_empty() => {
                let parts: Vec<String> = others
                    .iter()
                    .enumerate()
                    .map(|(i, (d, n))| {
                        if i == 0 {
                            format!("{n} face{} of degree {d}", plural(*n))
                        } else {
                            format!("{n} of degree {d}")
                        }
                    })
                    .collect();
                return refuse(
                    needs,
                    format!("this mesh has {}", parts.join(" and ")),
                    hint,
                );
            }
            Some(_) => {}
            None => {
                return refuse(
                    needs,
                    format!(
                    "the face degrees are not known (faces_by_degree is empty and H={} for F={})",
                    counts.corners, counts.faces
                ),
                    hint,
                )
            }
        }
    }
    if class.needs_manifold() && counts.nonmanifold_edges > 0 {
        return refuse(
            "every edge to have one or two faces".into(),
            format!(
                "this mesh has {} non-manifold edge{} (three or more faces)",
                counts.nonmanifold_edges,
                plural(counts.nonmanifold_edges)
            ),
            use_(&hints.nonmanifold),
        );
    }
    if class.closed && counts.boundary_edges > 0 {
        return refuse(
            "a closed mesh".into(),
            format!(
                "this mesh has {} boundary edge{}",
                counts.boundary_edges,
                plural(counts.boundary_edges)
            ),
            use_(&hints.boundary),
        );
    }
    Ok(())
}

pub(crate) fn plural(n: u64) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}
