//! The built-in schemes, each derived from what its rule inserts.
//!
//! Notation: `V` vertices, `E` edges, `IE` interior edges (two faces), `BE` boundary edges
//! (one face), `NME` non-manifold edges (three or more faces), `F` faces, `H` the sum of face
//! degrees. A primed count is the count one level later. Every identity a matrix relies on is
//! named in its constructor's documentation, with the level from which each component's
//! closed form holds (`valid_from`, later than 0 only where the matrix has the eigenvalue 0).
//!
//! Use [`builtin`] to look a scheme up by name (aliases included) and [`builtins`] for the
//! list of canonical schemes.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! `catalog.rs` builds every built-in `Scheme`, and each constructor's doc comment derives its
//! matrix from what the rule inserts (the identities it relies on, each component's `valid_from`).
//! `loop` (and its 4:1 aliases), `doo-sabin` and `mid-edge` have a boundary twin (`loop-boundary`,
//! `doo-sabin-boundary`, `mid-edge-boundary`) that `Scheme::for_mesh` / `for_counts` return on a
//! mesh with boundary, so their closed state is unchanged on closed meshes. A `Scheme` has a
//! `StepRule`: one matrix, an optional different first step, or a cycle of matrices
//! (`sqrt3-boundary`). `Plan` is a single scheme or a composition `A:k,B`; `phases()` gives one
//! recurrence per residue class or stage for closed forms. `input.rs` fills a state from typed
//! counts using only documented identities (`CountsInput`) and parses a plain state (`parse_init`,
//! the grammar of `--init`). `custom.rs` parses scheme TOML *text* with line:column errors; its
//! caller owns the path.
//!
//! Owner of scheme names, their matrices and their subdivision rules (the one table: name ->
//! matrix, topology and geometry): `schemes::builtin` / `schemes::builtins` (`catalog.rs`): every
//! built-in carries its `schemes::Rule` (`rule.rs`; re-exported as `halfedge::Rule`), a scheme
//! file gets one from its `topology` key; `Rule::scheme_for` is the way back (the scheme that
//! counts a rule on a mesh); compositions `Plan::parse`. `halfedge::subdivide` takes a `Rule` and
//! knows no scheme name.

use recurrence::IntMatrix;

use crate::class::Hints;
use crate::scheme::{Component, Derivation, SchemeSpec, StepRule};
use crate::{CountsInput, Error, FaceKind, MeshClass, MeshCounts, Result, Rule, Scheme, Stat};

/// Aliases of `loop`: the same topology (4:1 split), different geometry in `halfedge`.
pub const LOOP_ALIASES: [&str; 3] = ["midpoint", "butterfly", "icosphere"];

/// The canonical built-in names (with `tri-split-N` written for the family).
pub const BUILTIN_NAMES: [&str; 13] = [
    "loop",
    "loop-boundary",
    "loop-general",
    "catmull-clark-quad",
    "catmull-clark",
    "catmull-clark-general",
    "sqrt3",
    "sqrt3-boundary",
    "doo-sabin",
    "doo-sabin-boundary",
    "mid-edge",
    "mid-edge-boundary",
    "tri-split-N",
];

/// Looks a built-in scheme up by name.
///
/// Accepts the canonical names, `tri-split-N` for any `N >= 2`, and the aliases `midpoint`,
/// `butterfly`, `icosphere` (Loop topology; [`Scheme::name`] keeps the alias and
/// [`Scheme::canonical_name`] says `loop`) and `ternary` (`tri-split-3`).
///
/// # Errors
///
/// [`Error::UnknownScheme`] listing the built-ins, [`Error::InvalidSplitFactor`] for
/// `tri-split-N` with `N` below 2, not a number or too large.
///
/// ```
/// let s = schemes::builtin("ternary")?;
/// assert_eq!(s.canonical_name(), "tri-split-3");
/// assert!(schemes::builtin("lop").unwrap_err().to_string().contains("loop-boundary"));
/// # Ok::<(), schemes::Error>(())
/// ```
pub fn builtin(name: &str) -> Result<Scheme> {
    let scheme = match name {
        "loop" => loop_scheme(),
        n if LOOP_ALIASES.contains(&n) => loop_scheme(),
        "loop-boundary" => loop_boundary(),
        "loop-general" => loop_general(),
        "catmull-clark-quad" => catmull_clark_quad(),
        "catmull-clark" => catmull_clark(),
        "catmull-clark-general" => catmull_clark_general(),
        "sqrt3" => sqrt3(),
        "sqrt3-boundary" => sqrt3_boundary(),
        "doo-sabin" => doo_sabin(),
        "doo-sabin-boundary" => doo_sabin_boundary(),
        "mid-edge" => mid_edge(),
        "mid-edge-boundary" => mid_edge_boundary(),
        "ternary" => tri_split(3)?,
        n => match n.strip_prefix("tri-split-") {
            Some(factor) => {
                let invalid = |reason: String| Error::InvalidSplitFactor {
                    name: n.to_string(),
                    reason,
                };
                if factor.is_empty() || !factor.bytes().all(|b| b.is_ascii_digit()) {
                    return Err(invalid(format!(
                        "`{factor}` is not a split factor (use tri-split-N with an integer N >= 2)"
                    )));
                }
                let n_split: u64 = factor
                    .parse()
                    .map_err(|_| invalid(format!("split factor {factor} is too large")))?;
                tri_split(n_split).map_err(|e| match e {
                    Error::InvalidSplitFactor { reason, .. } => invalid(reason),
                    other => other,
                })?
            }
            None => {
                return Err(Error::UnknownScheme {
                    name: name.to_string(),
                    known: known_names(),
                })
            }
        },
    };
    let rule = match scheme.canonical_name() {
        _ if name == "midpoint" => Rule::Midpoint,
        _ if name == "butterfly" => Rule::Butterfly,
        _ if name == "icosphere" => Rule::Icosphere,
        "loop" | "loop-boundary" | "loop-general" => Rule::Loop,
        "catmull-clark-quad" | "catmull-clark" | "catmull-clark-general" => Rule::CatmullClark,
        "sqrt3" | "sqrt3-boundary" => Rule::Sqrt3,
        "doo-sabin" | "doo-sabin-boundary" => Rule::DooSabin,
        "mid-edge" | "mid-edge-boundary" => Rule::MidEdge,
        split => match split.strip_prefix("tri-split-").map(str::parse::<u32>) {
            Some(Ok(n)) => Rule::TriSplit(n),
            // Split factors beyond u32 make more faces than any level can hold: counted only.
            _ => return Ok(scheme.renamed(name)),
        },
    };
    let mut scheme = scheme.renamed(name).with_subdivision_rule(rule);
    scheme.boundary_variant = boundary_twin_of(scheme.canonical_name()).is_some();
    Ok(scheme)
}

/// # `loop`, its aliases, `doo-sabin` and `mid-edge` on meshes with boundary
///
/// `loop` and the 4:1 aliases `midpoint`, `butterfly` and `icosphere` count as `loop` on closed
/// meshes. Their geometry (in `halfedge`) also handles boundaries, so on a mesh with boundary
/// edges and no non-manifold edge they count as `loop-boundary`, the same 4:1 topology, as
/// every peer (OpenSubdiv, OpenMesh, libigl) subdivides a mesh with boundary when asked for
/// Loop: these methods pick the scheme that counts them for the mesh at hand, as `halfedge`'s
/// subdivision does. `doo-sabin` and `mid-edge` do the same with `doo-sabin-boundary` and
/// `mid-edge-boundary` (their boundary rules; on closed meshes they keep their `(V, E, F)`
/// state). Every other scheme is returned unchanged (`sqrt3` refuses a boundary and says to
/// use `sqrt3-boundary`).
impl Scheme {
    /// Whether [`for_mesh`](Self::for_mesh) and [`for_counts`](Self::for_counts) may return
    /// another scheme: true for the built-in `loop` and its 4:1 aliases `midpoint`, `butterfly`
    /// and `icosphere`, and for `doo-sabin` and `mid-edge`.
    ///
    /// ```
    /// assert!(schemes::builtin("butterfly")?.has_boundary_variant());
    /// assert!(schemes::builtin("loop")?.has_boundary_variant());
    /// assert!(schemes::builtin("doo-sabin")?.has_boundary_variant());
    /// assert!(!schemes::builtin("mid-edge-boundary")?.has_boundary_variant());
    /// assert!(!schemes::builtin("loop-boundary")?.has_boundary_variant());
    /// # Ok::<(), schemes::Error>(())
    /// ```
    pub fn has_boundary_variant(&self) -> bool {
        self.boundary_variant
    }

    /// The scheme that counts this one on a mesh with `counts`: for `loop` or a 4:1 alias on
    /// a mesh with boundary edges and no non-manifold edge, `loop-boundary` under the name
    /// asked for ([`canonical_name`](Self::canonical_name) says `loop-boundary`), and
    /// likewise `doo-sabin-boundary` for `doo-sabin` and `mid-edge-boundary` for `mid-edge`;
    /// otherwise a copy of this scheme.
    ///
    /// ```
    /// use schemes::{builtin, MeshCounts};
    ///
    /// let open_square = MeshCounts::from_polygons(&[[0, 1, 2], [0, 2, 3]])?;
    /// let butterfly = builtin("butterfly")?.for_mesh(&open_square);
    /// assert_eq!((butterfly.name(), butterfly.canonical_name()), ("butterfly", "loop-boundary"));
    /// let c = butterfly.counts_at(&open_square, 1)?;
    /// assert_eq!((c.vertices, c.edges, c.faces), (9.into(), 16.into(), 8.into()));
    /// let lp = builtin("loop")?.for_mesh(&open_square);
    /// assert_eq!((lp.name(), lp.canonical_name()), ("loop", "loop-boundary"));
    ///
    /// // On a closed mesh it stays `loop`.
    /// let tetra = MeshCounts::from_polygons(&[[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]])?;
    /// assert_eq!(builtin("butterfly")?.for_mesh(&tetra).canonical_name(), "loop");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn for_mesh(&self, counts: &MeshCounts) -> Scheme {
        if self.has_boundary_variant() && counts.boundary_edges > 0 && counts.nonmanifold_edges == 0
        {
            return self.boundary_twin();
        }
        self.clone()
    }

    /// As [`for_mesh`](Self::for_mesh) for counts typed in: a 4:1 alias counts as
    /// `loop-boundary` when the counts make a valid `loop-boundary` state (by its documented
    /// identities, e.g. `BE = 2E - 3F`) with `BE > 0` and give no non-manifold edge; likewise
    /// `doo-sabin` and `mid-edge` with their boundary twins (whose state needs `IE` and `BE`
    /// or `E` and `BE`: `V`, `E`, `F` alone keep the closed scheme).
    ///
    /// ```
    /// use schemes::{builtin, CountsInput};
    ///
    /// let icosphere = builtin("icosphere")?;
    /// // A 3x3 triangle grid: BE = 2E - 3F = 12.
    /// let grid: CountsInput = "V=16,E=33,F=18".parse()?;
    /// assert_eq!(icosphere.for_counts(&grid).canonical_name(), "loop-boundary");
    /// // The icosahedron is closed (BE = 0), and V, E alone say nothing about a boundary.
    /// for closed in ["V=12,E=30,F=20", "V=12,E=30"] {
    ///     assert_eq!(icosphere.for_counts(&closed.parse()?).canonical_name(), "loop");
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn for_counts(&self, input: &CountsInput) -> Scheme {
        if !self.has_boundary_variant()
            || input
                .get(Stat::NME.short_name())
                .is_some_and(|n| n.sign() != num_bigint::Sign::NoSign)
        {
            return self.clone();
        }
        let Some(boundary) = boundary_twin_of(self.canonical_name()) else {
            return self.clone();
        };
        let be = boundary
            .state_names()
            .iter()
            .position(|n| n == Stat::BE.short_name());
        match (boundary.state_from_input(input), be) {
            (Ok(state), Some(i)) if state[i].sign() == num_bigint::Sign::Plus => {
                self.boundary_twin()
            }
            _ => self.clone(),
        }
    }
}

/// The boundary-aware built-in that counts the built-in `canonical` on a mesh with boundary:
/// `loop-boundary` for `loop`, `doo-sabin-boundary` for `doo-sabin`, `mid-edge-boundary` for
/// `mid-edge`.
fn boundary_twin_of(canonical: &str) -> Option<Scheme> {
    match canonical {
        "loop" => Some(loop_boundary()),
        "doo-sabin" => Some(doo_sabin_boundary()),
        "mid-edge" => Some(mid_edge_boundary()),
        _ => None,
    }
}

impl Scheme {
    /// The boundary-aware twin under this scheme's name, with its rule (a copy of this scheme
    /// when it has none).
    fn boundary_twin(&self) -> Scheme {
        let Some(twin) = boundary_twin_of(self.canonical_name()) else {
            return self.clone();
        };
        let twin = twin.renamed(self.name());
        match self.subdivision_rule() {
            Some(rule) => twin.with_subdivision_rule(rule),
            None => twin,
        }
    }
}

fn known_names() -> String {
    format!(
        "{} (N >= 2); aliases: {}, ternary",
        BUILTIN_NAMES.join(", "),
        LOOP_ALIASES.join(", ")
    )
}

/// One scheme per canonical name, with `tri-split-2` and `tri-split-3` for the family.
pub fn builtins() -> Vec<Scheme> {
    // Through `builtin`, so every scheme carries its rule exactly as a lookup by name does.
    BUILTIN_NAMES
        .iter()
        .filter(|n| **n != "tri-split-N")
        .copied()
        .chain(["tri-split-2", "tri-split-3"])
        .filter_map(|name| builtin(name).ok())
        .collect()
}

struct Def<'a> {
    name: &'a str,
    description: &'a str,
    state: &'a [Stat],
    rule: StepRule,
    requires: MeshClass,
    produces: FaceKind,
    derive: Vec<(Stat, Derivation)>,
    hints: Hints,
}

fn matrix(rows: &[&[i64]]) -> IntMatrix {
    // Built-in matrices are constants of this file, square by construction.
    IntMatrix::try_from_rows(rows.iter().map(|r| r.to_vec()).collect())
        .unwrap_or_else(|e| unreachable!("built-in matrix: {e}"))
}

fn build(def: Def<'_>) -> Scheme {
    let spec = SchemeSpec {
        name: def.name.to_string(),
        description: def.description.to_string(),
        state: def
            .state
            .iter()
            .map(|s| Component {
                name: s.short_name().to_string(),
                meaning: s.meaning().to_string(),
            })
            .collect(),
        rule: def.rule,
        requires: def.requires,
        produces: Some(def.produces),
        derive: def.derive,
    };
    Scheme::try_from_spec(spec)
        .unwrap_or_else(|e| unreachable!("built-in scheme {}: {e}", def.name))
        .with_hints(def.hints)
}

fn hints(faces: &str, boundary: Option<&str>, nonmanifold: Option<&str>) -> Hints {
    Hints {
        faces: Some(faces.to_string()),
        faces_nonmanifold: Some("catmull-clark-general".into()),
        boundary: boundary.map(String::from),
        nonmanifold: nonmanifold.map(String::from),
    }
}

const CLOSED_TRI: MeshClass = MeshClass {
    faces: FaceKind::Triangles,
    closed: true,
    manifold: true,
};

/// `loop`: the 4:1 triangle split (Loop topology) on closed triangle meshes, in the paper's
/// Theorem 5.1 state `(V, E)`.
///
/// **Rule.** One new vertex per edge; each edge splits into two; each triangle gets three new
/// edges joining its edge points and becomes four triangles.
///
/// **Counts.** `V' = V + E`, `E' = 2E + 3F`, `F' = 4F`. On a closed triangle mesh every edge
/// has two faces and every face three edges, so `2E = 3F`, hence `3F = 2E` and
/// `E' = 2E + 2E = 4E`:
///
/// ```text
/// [V']   [1 1] [V]
/// [E'] = [0 4] [E]        F = 2E/3 (derived)
/// ```
///
/// `valid_from`: 0 for every component (eigenvalues 1 and 4). The identity `2E = 3F` is kept
/// by the step (`2E' = 8E = 3(4F) = 3F'`), so `F = 2E/3` stays an integer.
///
/// **UV values** ([`crate::uv`]): the layout refines as a triangle mesh under the 4:1 split:
/// a value per old value and per layout edge, `UV' = UV + UE`, `UE' = 2 UE + 3 F`,
/// `UBE' = 2 UBE`, `F' = 4 F` (`loop-general`'s matrix on the layout, with its boundary
/// edges); the count is real from level 1 on, level 0 being the used `vt` entries.
pub fn loop_scheme() -> Scheme {
    build(Def {
        name: "loop",
        description:
            "4:1 triangle split (Loop topology) on closed triangle meshes, paper Theorem 5.1",
        state: &[Stat::V, Stat::E],
        rule: StepRule::single(matrix(&[&[1, 1], &[0, 4]])),
        requires: CLOSED_TRI,
        produces: FaceKind::Triangles,
        derive: vec![(Stat::F, Derivation::new(vec![0, 2], 3))],
        hints: hints("catmull-clark", Some("loop-boundary"), Some("loop-general")),
    })
}

/// `loop-boundary`: the 4:1 triangle split on triangle meshes whose edges have one or two
/// faces (boundary allowed), in the paper's Theorem 5.2 state `(V, IE, BE)`.
///
/// **Rule.** As [`loop_scheme`]: one vertex per edge, three new edges inside each face.
///
/// **Counts.** `V' = V + IE + BE`. A boundary edge splits into two boundary edges:
/// `BE' = 2BE`. An interior edge splits into two interior edges, and the three edges added
/// inside each face are interior: `IE' = 2IE + 3F`. Counting face sides,
/// `3F = 2IE + BE`, so `IE' = 4IE + BE`:
///
/// ```text
/// [V' ]   [1 1 1] [V ]
/// [IE'] = [0 4 1] [IE]    E = IE + BE,  F = (2IE + BE)/3 (derived)
/// [BE']   [0 0 2] [BE]
/// ```
///
/// `valid_from`: 0 for every component (eigenvalues 1, 4, 2). The step keeps
/// `3F = 2IE + BE`: `2IE' + BE' = 8IE + 4BE = 4(2IE + BE) = 3F'`.
///
/// **UV values** ([`crate::uv`]): the layout refines as a triangle mesh under the 4:1 split:
/// a value per old value and per layout edge, `UV' = UV + UE`, `UE' = 2 UE + 3 F`,
/// `UBE' = 2 UBE`, `F' = 4 F` (`loop-general`'s matrix on the layout, with its boundary
/// edges); the count is real from level 1 on, level 0 being the used `vt` entries.
pub fn loop_boundary() -> Scheme {
    build(Def {
        name: "loop-boundary",
        description: "4:1 triangle split on triangle meshes with boundary (edges of one or two faces), paper Theorem 5.2",
        state: &[Stat::V, Stat::IE, Stat::BE],
        rule: StepRule::single(matrix(&[&[1, 1, 1], &[0, 4, 1], &[0, 0, 2]])),
        requires: MeshClass {
            faces: FaceKind::Triangles,
            closed: false,
            manifold: true,
        },
        produces: FaceKind::Triangles,
        derive: vec![
            (Stat::E, Derivation::new(vec![0, 1, 1], 1)),
            (Stat::F, Derivation::new(vec![0, 2, 1], 3)),
        ],
        hints: hints("catmull-clark", None, Some("loop-general")),
    })
}

/// `loop-general`: the 4:1 triangle split on any triangle mesh (boundary, non-manifold
/// edges, any genus), state `(V, E, F)`.
///
/// **Rule.** As [`loop_scheme`]; a non-manifold edge still gets one vertex and splits into two
/// (non-manifold) edges, and each face is split on its own.
///
/// **Counts.** `V' = V + E`, `E' = 2E + 3F`, `F' = 4F`, with no identity needed:
///
/// ```text
/// [V']   [1 1 0] [V]
/// [E'] = [0 2 3] [E]
/// [F']   [0 0 4] [F]
/// ```
///
/// `valid_from`: 0 for every component (eigenvalues 1, 2, 4).
///
/// **UV values** ([`crate::uv`]): the layout refines as a triangle mesh under the 4:1 split:
/// a value per old value and per layout edge, `UV' = UV + UE`, `UE' = 2 UE + 3 F`,
/// `UBE' = 2 UBE`, `F' = 4 F` (`loop-general`'s matrix on the layout, with its boundary
/// edges); the count is real from level 1 on, level 0 being the used `vt` entries.
pub fn loop_general() -> Scheme {
    build(Def {
        name: "loop-general",
        description: "4:1 triangle split on any triangle mesh, non-manifold edges included",
        state: &[Stat::V, Stat::E, Stat::F],
        rule: StepRule::single(matrix(&[&[1, 1, 0], &[0, 2, 3], &[0, 0, 4]])),
        requires: MeshClass {
            faces: FaceKind::Triangles,
            closed: false,
            manifold: false,
        },
        produces: FaceKind::Triangles,
        derive: vec![],
        hints: hints("catmull-clark-general", None, None),
    })
}

/// `catmull-clark-quad`: Catmull-Clark on pure quad meshes, boundary allowed (the paper's
/// Theorem 5.3), state `(V, E, F)`.
///
/// **Rule.** One new vertex per edge and per face; each edge splits into two; each quad gets
/// four edges from its face point to its edge points and becomes four quads.
///
/// **Counts.** `V' = V + E + F`, `E' = 2E + 4F`, `F' = 4F`. These hold on boundary edges too
/// (a boundary edge also gets one edge point and splits in two), and on non-manifold edges,
/// so no identity beyond "every face is a quad" (`H = 4F`) is used:
///
/// ```text
/// [V']   [1 1 1] [V]
/// [E'] = [0 2 4] [E]
/// [F']   [0 0 4] [F]
/// ```
///
/// `valid_from`: 0 for every component (eigenvalues 1, 2, 4).
///
/// **UV values** ([`crate::uv`]): OpenSubdiv's face-varying refinement gives a value per
/// face point, per layout edge and per old value, `UV' = UV + UE + F`, `UE' = 2 UE + H`,
/// `UBE' = 2 UBE`, `F' = H`, `H' = 4 H` (`catmull-clark-general`'s matrix on the layout, with
/// its boundary edges), in every linear-interpolation mode; the count is real from level 1 on,
/// level 0 being the used `vt` entries.
pub fn catmull_clark_quad() -> Scheme {
    build(Def {
        name: "catmull-clark-quad",
        description: "Catmull-Clark on pure quad meshes, boundary allowed, paper Theorem 5.3",
        state: &[Stat::V, Stat::E, Stat::F],
        rule: StepRule::single(matrix(&[&[1, 1, 1], &[0, 2, 4], &[0, 0, 4]])),
        requires: MeshClass {
            faces: FaceKind::Quads,
            closed: false,
            manifold: false,
        },
        produces: FaceKind::Quads,
        derive: vec![],
        hints: Hints {
            faces: Some("catmull-clark".into()),
            faces_nonmanifold: Some("catmull-clark-general".into()),
            boundary: None,
            nonmanifold: None,
        },
    })
}

/// `catmull-clark`: Catmull-Clark on any polygon mesh (triangles, quads, n-gons, mixed)
/// whose edges have one or two faces, state `(V, IE, BE, F, H)` with `H` the sum of face
/// degrees.
///
/// **Rule.** One new vertex per edge and per face; each edge splits into two; a face of
/// degree `n` gets `n` edges from its face point to its edge points and becomes `n` quads.
///
/// **Counts.** `V' = V + IE + BE + F`. Split edges keep their kind: `BE' = 2BE`; the `H` new
/// edges inside faces are interior (each separates two new quads of the same face):
/// `IE' = 2IE + H`. Every corner of every face becomes one quad: `F' = H`, and all faces are
/// quads afterwards: `H' = 4F' = 4H`. This makes the first step (n-gons to quads) linear in
/// this state, so one matrix serves every step:
///
/// ```text
/// [V' ]   [1 1 1 1 0] [V ]
/// [IE']   [0 2 0 0 1] [IE]
/// [BE'] = [0 0 2 0 0] [BE]     E = IE + BE (derived)
/// [F' ]   [0 0 0 0 1] [F ]
/// [H' ]   [0 0 0 0 4] [H ]
/// ```
///
/// The state is redundant on purpose: `H = 2IE + BE` on these meshes, and the step keeps it
/// (`2IE' + BE' = 2(2IE + BE) + 2H = 4H`).
///
/// `valid_from`: 1 for `V` and `F`, 0 for `IE`, `BE`, `H`. The eigenvalue 0 has the
/// eigenvector `(1, 0, 0, -1, 0)`: `F` forgets its initial value (`F(s) = 4^(s-1) H0` for
/// `s >= 1`) and `F0` enters `V` only once, at step 1. The other eigenvalues are 1, 2, 2, 4.
///
/// **UV values** ([`crate::uv`]): OpenSubdiv's face-varying refinement gives a value per
/// face point, per layout edge and per old value, `UV' = UV + UE + F`, `UE' = 2 UE + H`,
/// `UBE' = 2 UBE`, `F' = H`, `H' = 4 H` (`catmull-clark-general`'s matrix on the layout, with
/// its boundary edges), in every linear-interpolation mode; the count is real from level 1 on,
/// level 0 being the used `vt` entries.
pub fn catmull_clark() -> Scheme {
    build(Def {
        name: "catmull-clark",
        description: "Catmull-Clark on any polygon mesh whose edges have one or two faces",
        state: &[Stat::V, Stat::IE, Stat::BE, Stat::F, Stat::H],
        rule: StepRule::single(matrix(&[
            &[1, 1, 1, 1, 0],
            &[0, 2, 0, 0, 1],
            &[0, 0, 2, 0, 0],
            &[0, 0, 0, 0, 1],
            &[0, 0, 0, 0, 4],
        ])),
        requires: MeshClass {
            faces: FaceKind::Polygons,
            closed: false,
            manifold: true,
        },
        produces: FaceKind::Quads,
        derive: vec![(Stat::E, Derivation::new(vec![0, 1, 1, 0, 0], 1))],
        hints: hints("catmull-clark", None, Some("catmull-clark-general")),
    })
}

/// `catmull-clark-general`: Catmull-Clark on any polygon mesh, non-manifold edges included,
/// state `(V, E, F, H)`.
///
/// **Counts.** As [`catmull_clark`] without telling edge kinds apart: `V' = V + E + F`,
/// `E' = 2E + H`, `F' = H`, `H' = 4H`:
///
/// ```text
/// [V']   [1 1 1 0] [V]
/// [E'] = [0 2 0 1] [E]
/// [F']   [0 0 0 1] [F]
/// [H']   [0 0 0 4] [H]
/// ```
///
/// `valid_from`: 1 for `V` and `F` (eigenvalue 0, eigenvector `(1, 0, -1, 0)`), 0 for `E`
/// and `H`.
///
/// **UV values** ([`crate::uv`]): OpenSubdiv's face-varying refinement gives a value per
/// face point, per layout edge and per old value, `UV' = UV + UE + F`, `UE' = 2 UE + H`,
/// `UBE' = 2 UBE`, `F' = H`, `H' = 4 H` (`catmull-clark-general`'s matrix on the layout, with
/// its boundary edges), in every linear-interpolation mode; the count is real from level 1 on,
/// level 0 being the used `vt` entries.
pub fn catmull_clark_general() -> Scheme {
    build(Def {
        name: "catmull-clark-general",
        description: "Catmull-Clark on any polygon mesh, non-manifold edges included",
        state: &[Stat::V, Stat::E, Stat::F, Stat::H],
        rule: StepRule::single(matrix(&[
            &[1, 1, 1, 0],
            &[0, 2, 0, 1],
            &[0, 0, 0, 1],
            &[0, 0, 0, 4],
        ])),
        requires: MeshClass::ANY,
        produces: FaceKind::Quads,
        derive: vec![],
        hints: Hints::default(),
    })
}

/// `sqrt3`: Kobbelt's sqrt(3) subdivision on closed triangle meshes, state `(V, E, F)`.
///
/// **Rule.** One new vertex per face, joined to the three corners (three new edges, three
/// triangles per face); then every old edge is flipped.
///
/// **Counts.** Flips change no count: `V' = V + F`, `E' = E + 3F`, `F' = 3F`:
///
/// ```text
/// [V']   [1 0 1] [V]
/// [E'] = [0 1 3] [E]
/// [F']   [0 0 3] [F]
/// ```
///
/// No identity is used (on a closed mesh `2E = 3F` gives `E' = 3E`). The flips need every
/// old edge to have two faces, hence closed meshes; see [`sqrt3_boundary`].
///
/// `valid_from`: 0 for every component (eigenvalues 1, 1, 3; diagonalizable).
///
/// **UV values:** [`crate::uv::uv_scheme`] (`Rule::Sqrt3`): over the layout's values,
/// boundary edges, seam edges `S` and faces, `UV' = UV + 2 S + F` (old values, centroids, two
/// seam midpoints per seam edge), `S' = 3 S`.
pub fn sqrt3() -> Scheme {
    build(Def {
        name: "sqrt3",
        description: "Kobbelt's sqrt(3) subdivision on closed triangle meshes",
        state: &[Stat::V, Stat::E, Stat::F],
        rule: StepRule::single(matrix(&[&[1, 0, 1], &[0, 1, 3], &[0, 0, 3]])),
        requires: CLOSED_TRI,
        produces: FaceKind::Triangles,
        derive: vec![],
        hints: hints("catmull-clark", Some("sqrt3-boundary"), None),
    })
}

/// `sqrt3-boundary`: sqrt(3) with Kobbelt's boundary rule (boundary edges trisected every
/// second step), a periodic scheme of two matrices over `(V, IE, BE, F)`, on triangle meshes
/// whose edges have one or two faces.
///
/// **Rule** (Kobbelt 2000, section 4; the variant of OpenMesh's `Sqrt3T`). Steps alternate,
/// starting with step A at step 1:
///
/// - *Step A* (steps 1, 3, 5, ...): every face, boundary or not, gets a centre vertex joined
///   to its three corners; then every old interior edge is flipped; boundary edges are kept.
///   Afterwards each boundary edge lies in exactly one triangle `(a, b, c)` whose other two
///   edges are spokes (interior), so **every face has at most one boundary edge**, even when
///   the input had faces with two or three boundary edges.
/// - *Step B* (steps 2, 4, ...): each boundary edge is trisected (two new vertices) and its
///   triangle is split into three by joining the opposite vertex to the two new vertices;
///   every other face gets a centre vertex as in step A; then every old interior edge is
///   flipped. After A then B, each boundary edge is split in three (a triadic 1:9 split
///   along the boundary). The flips of step B can leave triangles with two boundary edges
///   (where two fans meet at a boundary vertex); the next step A splits them like any face,
///   which restores the one-boundary-edge property before the next step B.
///
/// The `halfedge` implementation must alternate the same way, counting steps from the input
/// mesh (step B at even step numbers), and treat as "boundary faces" in step B the faces with
/// a boundary edge (one each, by the property above).
///
/// **Counts, step A.** `V' = V + F`, `IE' = IE + 3F` (old interior edges flipped, three
/// interior spokes per face), `BE' = BE`, `F' = 3F`.
///
/// **Counts, step B.** There are `BE` boundary faces (one per boundary edge) and `F - BE`
/// others: `V' = V + 2BE + (F - BE) = V + BE + F`; `BE' = 3BE`; new interior edges are three
/// spokes per interior face and two per boundary face: `IE' = IE + 3(F - BE) + 2BE =
/// IE - BE + 3F`; `F' = 3F`.
///
/// ```text
///        A = [1 0 0 1]        B = [1 0  1 1]
///            [0 1 0 3]            [0 1 -1 3]
///            [0 0 1 0]            [0 0  3 0]
///            [0 0 0 3]            [0 0  0 3]
/// ```
///
/// Both keep `3F = 2IE + BE` (step B: `2IE' + BE' = 2IE + BE + 6F = 9F`). On a closed mesh
/// (`BE = 0`) both reduce to [`sqrt3`]. `E = IE + BE` is derived. Over one period the matrix
/// is `BA` (levels `2t`) or `AB` (levels `2t + 1`); [`Scheme::phases`] gives both.
///
/// `valid_from`: 0 for every component (no eigenvalue 0).
///
/// **UV values:** [`crate::uv::uv_scheme`] (`Rule::Sqrt3`), the same two steps over the
/// layout's values, boundary edges `UBE`, seam edges `S` and faces: step A
/// `UV' = UV + 2 S + F`, step B `UV' = UV + UBE + F`.
pub fn sqrt3_boundary() -> Scheme {
    let a = matrix(&[&[1, 0, 0, 1], &[0, 1, 0, 3], &[0, 0, 1, 0], &[0, 0, 0, 3]]);
    let b = matrix(&[&[1, 0, 1, 1], &[0, 1, -1, 3], &[0, 0, 3, 0], &[0, 0, 0, 3]]);
    build(Def {
        name: "sqrt3-boundary",
        description: "Kobbelt's sqrt(3) with boundary edges trisected every second step (periodic: steps A, B)",
        state: &[Stat::V, Stat::IE, Stat::BE, Stat::F],
        rule: StepRule::try_new(None, vec![a, b])
            .unwrap_or_else(|e| unreachable!("built-in cycle: {e}")),
        requires: MeshClass {
            faces: FaceKind::Triangles,
            closed: false,
            manifold: true,
        },
        produces: FaceKind::Triangles,
        derive: vec![(Stat::E, Derivation::new(vec![0, 1, 1, 0], 1))],
        hints: hints("catmull-clark", None, None),
    })
}

/// A scheme over the state `(V, E, F)` of closed manifold polygon meshes that produces
/// polygons (Doo-Sabin, mid-edge), pointing to its boundary-aware twin (`boundary`) for
/// boundaries and to `catmull-clark-general` for non-manifold edges.
fn closed_polygon_scheme(
    name: &'static str,
    description: &'static str,
    rows: &[&[i64]],
    boundary: &'static str,
) -> Scheme {
    build(Def {
        name,
        description,
        state: &[Stat::V, Stat::E, Stat::F],
        rule: StepRule::single(matrix(rows)),
        requires: MeshClass {
            faces: FaceKind::Polygons,
            closed: true,
            manifold: true,
        },
        produces: FaceKind::Polygons,
        derive: vec![],
        hints: Hints {
            boundary: Some(boundary.into()),
            nonmanifold: Some("catmull-clark-general".into()),
            ..Hints::default()
        },
    })
}

/// A scheme over the state `(V, IE, BE, F)` of manifold polygon meshes with boundary allowed
/// that produces polygons (the boundary-aware Doo-Sabin and mid-edge), `E = IE + BE` derived.
fn boundary_polygon_scheme(
    name: &'static str,
    description: &'static str,
    rows: &[&[i64]],
) -> Scheme {
    build(Def {
        name,
        description,
        state: &[Stat::V, Stat::IE, Stat::BE, Stat::F],
        rule: StepRule::single(matrix(rows)),
        requires: MeshClass {
            faces: FaceKind::Polygons,
            closed: false,
            manifold: true,
        },
        produces: FaceKind::Polygons,
        derive: vec![(Stat::E, Derivation::new(vec![0, 1, 1, 0], 1))],
        hints: Hints {
            nonmanifold: Some("catmull-clark-general".into()),
            ..Hints::default()
        },
    })
}

/// `doo-sabin`: Doo-Sabin subdivision on closed polygon meshes, state `(V, E, F)`.
///
/// **Rule.** Every corner of every face becomes a new vertex (`H` of them). New faces: one per
/// old face (same degree), one quad per old edge, one per old vertex (of its valence).
///
/// **Counts.** `V' = H`, `F' = F + E + V`; each new vertex has degree 4, so `E' = 2V' = 2H`.
/// On a closed mesh `H = 2E` (each edge has two face sides), so `V' = 2E`, `E' = 4E`:
///
/// ```text
/// [V']   [0 2 0] [V]
/// [E'] = [0 4 0] [E]
/// [F']   [1 1 1] [F]
/// ```
///
/// `valid_from`: 1 for `V` and `F` (eigenvalue 0, eigenvector `(1, 0, -1)`: `V(s) =
/// 2 * 4^(s-1) E0` only from `s = 1`), 0 for `E` (`E(s) = 4^s E0`).
///
/// **UV values:** counted by [`crate::uv::uv_scheme`]`(Rule::DooSabin)` over the layout and
/// its seams (`UV(s) = V(s) + 2 * 3^(s-1) * S0` from level 1 on; derived on
/// [`crate::uv::UvScheme`]).
pub fn doo_sabin() -> Scheme {
    closed_polygon_scheme(
        "doo-sabin",
        "Doo-Sabin subdivision on closed polygon meshes",
        &[&[0, 2, 0], &[0, 4, 0], &[1, 1, 1]],
        "doo-sabin-boundary",
    )
}

/// `doo-sabin-boundary`: Doo-Sabin subdivision on polygon meshes whose edges have one or two
/// faces (boundary allowed), state `(V, IE, BE, F)`. `doo-sabin` counts as this scheme on a
/// mesh with boundary edges ([`Scheme::for_mesh`]).
///
/// **Rule** (the boundary treatment that makes the boundary converge to the quadratic B-spline
/// of the boundary polygon, Chaikin's corner cutting, as Doo's and Nasri's boundary rules do:
/// D. Doo, "A subdivision algorithm for smoothing down irregularly shaped polyhedrons", 1978;
/// A. H. Nasri, "Polyhedral subdivision methods for free-form surfaces", ACM TOG 6(1), 1987).
/// As [`doo_sabin`] inside: every corner of every face becomes a new vertex, with one face
/// per old face, one quad per interior edge and one face per interior vertex. On the boundary:
///
/// - each boundary edge `(a, b)` gets two new vertices, its Chaikin points `(3a + b)/4` and
///   `(a + 3b)/4`, and its quad joins the face's two corners on it to these two points;
/// - each boundary vertex gets a face of `k + 2` sides, `k` its number of faces: the `k`
///   face corners at it and the Chaikin points next to it on its two boundary edges. A
///   boundary corner with one face (valence 2) gets a triangle: the corner is cut.
///
/// (CGAL's `DQQ` step instead emits no quad on a border edge and no face on a border vertex,
/// so its surface retreats from the border; counting it would need the number of face corners
/// at boundary vertices, which this state does not carry.)
///
/// **Counts.** Every vertex of a manifold mesh has one fan of faces, so a boundary vertex has
/// two boundary edges and the boundary vertices are as many as the boundary edges (`BV =
/// BE`). New vertices: `H = 2IE + BE` corners and `2BE` Chaikin points, `V' = 2IE + 3BE`.
/// Faces: `F' = F + IE + BE + V`. Edges: the `H` sides of the shrunken faces; two more per
/// interior quad (`2IE`), three more per boundary quad (`3BE`: the two joining the corners to
/// the Chaikin points and the outer one); one more per boundary vertex face (`BE`: the side
/// joining the two Chaikin points), so `E' = 4IE + 5BE`. The outer sides and those last sides
/// are the new boundary, Chaikin's polygon: `BE' = 2BE`, `IE' = 4IE + 3BE`:
///
/// ```text
/// [V' ]   [0 2 3 0] [V ]
/// [IE'] = [0 4 3 0] [IE]     E = IE + BE (derived)
/// [BE']   [0 0 2 0] [BE]
/// [F' ]   [1 1 1 1] [F ]
/// ```
///
/// On a closed mesh (`BE = 0`, `IE = E`) this is [`doo_sabin`]. The new mesh is again
/// manifold with one fan per vertex, so the identity `BV = BE` holds at every level.
///
/// `valid_from`: 1 for `V` and `F` (eigenvalue 0, eigenvector `(1, 0, 0, -1)`), 0 for `IE`
/// and `BE` (eigenvalues 4, 2, 1).
///
/// ```
/// use schemes::{builtin, MeshCounts};
///
/// // One quad: a shrunken quad, four boundary quads and four corner triangles.
/// let quad = MeshCounts::from_polygons(&[[0, 1, 2, 3]])?;
/// let ds = builtin("doo-sabin")?.for_mesh(&quad);
/// assert_eq!(ds.canonical_name(), "doo-sabin-boundary");
/// let c = ds.counts_at(&quad, 1)?;
/// assert_eq!((c.vertices, c.edges, c.faces), (12.into(), 20.into(), 9.into()));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// **UV values:** counted by [`crate::uv::uv_scheme`]`(Rule::DooSabin)` over the layout and
/// its seams (`UV(s) = V(s) + 2 * 3^(s-1) * S0` from level 1 on; derived on
/// [`crate::uv::UvScheme`]).
pub fn doo_sabin_boundary() -> Scheme {
    boundary_polygon_scheme(
        "doo-sabin-boundary",
        "Doo-Sabin subdivision on polygon meshes with boundary (boundary as Chaikin's quadratic B-spline)",
        &[&[0, 2, 3, 0], &[0, 4, 3, 0], &[0, 0, 2, 0], &[1, 1, 1, 1]],
    )
}

/// `mid-edge`: Peters and Reif's mid-edge subdivision on closed polygon meshes, state
/// `(V, E, F)`.
///
/// **Rule.** One new vertex at the midpoint of each edge. New faces: one per old face
/// (joining its edge midpoints, same degree) and one per old vertex (of its valence); each new
/// edge joins two midpoints of consecutive edges of a face.
///
/// **Counts.** `V' = E`, `F' = F + V`, `E' = H = 2E` (one new edge per face corner; on a
/// closed mesh `H = 2E`):
///
/// ```text
/// [V']   [0 1 0] [V]
/// [E'] = [0 2 0] [E]
/// [F']   [1 0 1] [F]
/// ```
///
/// `valid_from`: 1 for `V` and `F` (eigenvalue 0, eigenvector `(1, 0, -1)`), 0 for `E`.
///
/// **UV values:** counted by [`crate::uv::uv_scheme`]`(Rule::MidEdge)` over the layout and
/// its seams (`UV(s+1) = E(s) + S(s) + BE(s)`, `S(s) = 2^s S0`, from level 1 on; derived on
/// [`crate::uv::UvScheme`]).
pub fn mid_edge() -> Scheme {
    closed_polygon_scheme(
        "mid-edge",
        "Peters-Reif mid-edge subdivision on closed polygon meshes",
        &[&[0, 1, 0], &[0, 2, 0], &[1, 0, 1]],
        "mid-edge-boundary",
    )
}

/// `mid-edge-boundary`: Peters and Reif's mid-edge subdivision on polygon meshes whose edges
/// have one or two faces (boundary allowed), state `(V, IE, BE, F)`. `mid-edge` counts as
/// this scheme on a mesh with boundary edges ([`Scheme::for_mesh`]).
///
/// **Rule** (J. Peters, U. Reif, "The simplest subdivision scheme for smoothing polyhedra",
/// ACM TOG 16(4), 1997, inside; on the boundary the cubic B-spline border masks of
/// Catmull-Clark and Loop, as CGAL's `PQQ`/`PTQ` `border_node`: edge point the midpoint,
/// vertex point `(a + 6v + b)/8`). As [`mid_edge`] inside: one vertex at the midpoint of each
/// edge, one face per old face on the midpoints of its edges, one face per interior vertex on
/// the midpoints of its edges. Each boundary vertex `v` is kept as a vertex (moved to
/// `(a + 6v + b)/8`, `a` and `b` its boundary neighbours), and its face has `k + 2` sides, `k`
/// its number of faces: `v` and the midpoints of its `k + 1` edges. A boundary corner with one
/// face (valence 2) gets a triangle. The boundary polygon is thus refined by the cubic
/// B-spline rule (its vertices and its edge midpoints), and the kept vertices are corners
/// with one face at the next level.
///
/// **Counts.** Every vertex of a manifold mesh has one fan of faces, so the boundary vertices
/// are as many as the boundary edges (`BV = BE`). `V' = E + BE = IE + 2BE`; one face per old
/// face and per old vertex, `F' = F + V`; edges: one per face corner (`H = 2IE + BE`, joining
/// the midpoints of its two sides) and two per boundary vertex (joining it to the midpoints of
/// its boundary edges, the new boundary): `BE' = 2BE`, `IE' = 2IE + BE`:
///
/// ```text
/// [V' ]   [0 1 2 0] [V ]
/// [IE'] = [0 2 1 0] [IE]     E = IE + BE (derived)
/// [BE']   [0 0 2 0] [BE]
/// [F' ]   [1 0 0 1] [F ]
/// ```
///
/// On a closed mesh (`BE = 0`, `IE = E`) this is [`mid_edge`]. The new mesh is again manifold
/// with one fan per vertex, so `BV = BE` holds at every level.
///
/// `valid_from`: 1 for `V` and `F` (eigenvalue 0, eigenvector `(1, 0, 0, -1)`), 0 for `IE`
/// and `BE` (eigenvalue 2 twice, in one Jordan block: `IE(s) = 2^s IE0 + s 2^(s-1) BE0`).
///
/// ```
/// use schemes::{builtin, MeshCounts};
///
/// // One quad: the quad of its midpoints and four corner triangles.
/// let quad = MeshCounts::from_polygons(&[[0, 1, 2, 3]])?;
/// let me = builtin("mid-edge")?.for_mesh(&quad);
/// assert_eq!(me.canonical_name(), "mid-edge-boundary");
/// let c = me.counts_at(&quad, 1)?;
/// assert_eq!((c.vertices, c.edges, c.faces), (8.into(), 12.into(), 5.into()));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// **UV values:** counted by [`crate::uv::uv_scheme`]`(Rule::MidEdge)` over the layout and
/// its seams (`UV(s+1) = E(s) + S(s) + BE(s)`, `S(s) = 2^s S0`, from level 1 on; derived on
/// [`crate::uv::UvScheme`]).
pub fn mid_edge_boundary() -> Scheme {
    boundary_polygon_scheme(
        "mid-edge-boundary",
        "Peters-Reif mid-edge subdivision on polygon meshes with boundary (boundary as a cubic B-spline)",
        &[&[0, 1, 2, 0], &[0, 2, 1, 0], &[0, 0, 2, 0], &[1, 0, 0, 1]],
    )
}

/// `tri-split-N`: the 1:N^2 triangle split on any triangle mesh, state `(V, E, F)`
/// (`tri-split-2` is the Loop topology, `tri-split-3` is `ternary`).
///
/// **Rule.** Each edge gets `N - 1` new vertices and splits into `N` edges; each triangle gets
/// `(N - 1)(N - 2)/2` interior vertices and `3N(N - 1)/2` interior edges (a triangle cut into
/// `N^2` has `3N(N + 1)/2` edges, `3N` of them on its sides) and becomes `N^2` triangles.
///
/// **Counts.**
///
/// ```text
/// [V']   [1  N-1  (N-1)(N-2)/2] [V]
/// [E'] = [0  N    3N(N-1)/2   ] [E]
/// [F']   [0  0    N^2         ] [F]
/// ```
///
/// No identity is used. Check (paper ref. \[12\]): the icosahedron (12, 30, 20) gets
/// `12 + 30(N - 1) + 10(N - 1)(N - 2) = 10N^2 + 2` vertices after one step.
///
/// `valid_from`: 0 for every component (eigenvalues 1, N, N^2).
///
/// **UV values** ([`crate::uv`]): UVs are linear within each face, so the layout refines
/// as a triangle mesh under this matrix: `UV' = UV + (N-1) UE + (N-1)(N-2)/2 F`,
/// `UE' = N UE + 3N(N-1)/2 F`, `UBE' = N UBE`, `F' = N^2 F`; the count is real from level 1
/// on, level 0 being the used `vt` entries.
///
/// # Errors
///
/// [`Error::InvalidSplitFactor`] when `n < 2` or an entry would overflow `i64`.
pub fn tri_split(n: u64) -> Result<Scheme> {
    let name = format!("tri-split-{n}");
    let invalid = |reason: &str| Error::InvalidSplitFactor {
        name: name.clone(),
        reason: reason.to_string(),
    };
    if n < 2 {
        return Err(invalid("the split factor N must be at least 2"));
    }
    let n = i64::try_from(n).map_err(|_| invalid("the split factor is too large"))?;
    let big = || invalid("the split factor is too large (matrix entries beyond i64)");
    let nn = n.checked_mul(n).ok_or_else(big)?;
    let interior_vertices = (n - 1).checked_mul(n - 2).ok_or_else(big)? / 2;
    let interior_edges = (n - 1)
        .checked_mul(n)
        .and_then(|x| x.checked_mul(3))
        .ok_or_else(big)?
        / 2;
    let m = matrix(&[
        &[1, n - 1, interior_vertices],
        &[0, n, interior_edges],
        &[0, 0, nn],
    ]);
    let description = format!("1:{nn} triangle split ({n} segments per edge) on any triangle mesh");
    Ok(build(Def {
        name: &name,
        description: &description,
        state: &[Stat::V, Stat::E, Stat::F],
        rule: StepRule::single(m),
        requires: MeshClass {
            faces: FaceKind::Triangles,
            closed: false,
            manifold: false,
        },
        produces: FaceKind::Triangles,
        derive: vec![],
        hints: hints("catmull-clark", None, None),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn counts(faces: &[&[u32]]) -> MeshCounts {
        MeshCounts::from_polygons(faces).expect("valid faces")
    }

    /// The rule of `halfedge`'s subdivision: `loop` and its aliases count as `loop-boundary`
    /// exactly when the mesh has boundary edges and no non-manifold edge; the refusals keep the
    /// name asked for and say what to use.
    #[test]
    fn aliases_follow_the_mesh() {
        let open = counts(&[&[0, 1, 2], &[0, 2, 3]]);
        let closed = counts(&[&[0, 2, 1], &[0, 1, 3], &[1, 2, 3], &[2, 0, 3]]);
        // Three triangles on one edge (NME = 1) and boundary edges.
        let fin = counts(&[&[0, 1, 2], &[1, 0, 3], &[0, 1, 4]]);
        let open_quads = counts(&[&[0, 1, 2, 3]]);
        for alias in ["loop"].into_iter().chain(LOOP_ALIASES) {
            let s = builtin(alias).expect("built-in");
            assert_eq!(s.for_mesh(&open).canonical_name(), "loop-boundary");
            assert_eq!(s.for_mesh(&open).subdivision_rule(), s.subdivision_rule());
            assert_eq!(s.for_mesh(&open).name(), alias);
            assert_eq!(s.for_mesh(&closed).canonical_name(), "loop");
            let err = s.for_mesh(&fin).initial_state(&fin).unwrap_err();
            assert_eq!(s.for_mesh(&fin).canonical_name(), "loop");
            assert!(
                err.to_string().starts_with(&format!("{alias} needs ")),
                "{err}"
            );
            let err = s
                .for_mesh(&open_quads)
                .initial_state(&open_quads)
                .unwrap_err();
            assert_eq!(
                err.to_string(),
                format!("{alias} needs a triangle mesh, but this mesh has 1 face of degree 4; use catmull-clark")
            );
        }
        for name in ["loop-boundary", "loop-general", "tri-split-2", "ternary"] {
            let s = builtin(name).expect("built-in");
            assert!(!s.has_boundary_variant(), "{name}");
            assert_eq!(s.for_mesh(&open), s, "{name}");
        }
    }

    #[test]
    fn aliases_follow_typed_counts() {
        let s = builtin("midpoint").expect("built-in");
        let resolve = |text: &str| {
            let input: CountsInput = text.parse().expect("valid counts");
            s.for_counts(&input).canonical_name().to_string()
        };
        assert_eq!(resolve("V=16,E=33,F=18"), "loop-boundary");
        assert_eq!(resolve("V=16,IE=21,BE=12"), "loop-boundary");
        assert_eq!(resolve("V=16,E=33,F=18,NME=0"), "loop-boundary");
        // Closed, unknown boundary, a non-manifold edge, or counts that contradict.
        for text in [
            "V=12,E=30,F=20",
            "V=12,E=30",
            "V=16,E=33,F=18,NME=1",
            "V=16,E=33,F=18,BE=5",
        ] {
            assert_eq!(resolve(text), "loop", "{text}");
        }
    }
}
