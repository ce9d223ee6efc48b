//! The driver's error: what went wrong and where, and the [`Kind`] that classifies it (a
//! front end's exit code, or exception class).
//!
//! Messages name the options by their command-line spelling (`--boundary none`,
//! `--triangle-rule`), the front ends' common vocabulary.

use std::path::PathBuf;

use halfedge::io::escape_controls;
use halfedge::tags::TriangleRule;

/// The driver's result.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What kind of failure: the command line's exit codes 1 to 4.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Kind {
    /// A real subdivision disagreed with the prediction (exit 1).
    Mismatch,
    /// The request is wrong: options that do not go together, a scheme without the mode
    /// asked for (exit 2).
    Usage,
    /// An input file is bad, or the scheme does not apply to the mesh (exit 3).
    Input,
    /// A resource guard refused the work (exit 4).
    Guard,
}

impl Kind {
    /// The kind of a [`schemes::Error`]: problems with what was asked are usage errors; a
    /// scheme that does not apply or a bad scheme file is input; a search that grew too large
    /// is a guard's refusal.
    pub fn of_scheme_error(e: &schemes::Error) -> Kind {
        use schemes::Error as E;
        match e {
            E::NotApplicable { .. }
            | E::SchemeFile { .. }
            | E::NoMeshCounts { .. }
            | E::BadFace { .. }
            | E::NothingFits { .. } => Kind::Input,
            E::SearchTooLarge { .. }
            | E::SearchEstimateTooLarge { .. }
            | E::OutOfFloatRange { .. } => Kind::Guard,
            _ => Kind::Usage,
        }
    }

    /// The kind of a [`halfedge::Error`]: a resource limit is a guard's, a count that
    /// disagrees with its prediction a mismatch, a rule that cannot run on the request a
    /// usage error, anything else about the mesh input.
    pub fn of_geometry_error(e: &halfedge::Error) -> Kind {
        use halfedge::Error as E;
        match e {
            E::Scheme(inner) => Kind::of_scheme_error(inner),
            E::NoSubdivision { .. } | E::NotComposable { .. } => Kind::Usage,
            E::LimitNotSupported { .. } | E::NoLimit => Kind::Usage,
            E::CreasesNotSupported { .. } => Kind::Input,
            _ if e.is_resource_limit() => Kind::Guard,
            E::PredictionMismatch { .. } | E::InvalidOutput { .. } | E::BrokenInvariant { .. } => {
                Kind::Mismatch
            }
            _ => Kind::Input,
        }
    }
}

/// Everything that can go wrong between a front end and the geometry.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The geometry kernel's error, as it is.
    #[error(transparent)]
    Geometry(#[from] halfedge::Error),
    /// A scheme's error, as it is.
    #[error(transparent)]
    Scheme(#[from] schemes::Error),
    /// An output file the user may not write: it is left as it is.
    #[error("{}: refusing to write over it: {reason}", escape_controls(&path.display().to_string()))]
    WriteProtected {
        /// The file as given.
        path: PathBuf,
        /// Why it may not be written (its mode, or the system's answer).
        reason: String,
    },
    /// The geometry's error about the mesh `mesh` (its file, or `base mesh NAME`), at `place`
    /// (`line 12: `, or empty): invalid as a half-edge mesh, a face a rule refuses, a crease
    /// it cannot resolve.
    #[error("{mesh}: {place}{error}")]
    InMesh {
        /// The mesh's label.
        mesh: String,
        /// `line N: ` of the face concerned, or empty.
        place: String,
        /// The geometry's error.
        error: Box<halfedge::Error>,
    },
    /// A scheme that does not apply to the mesh.
    #[error("{mesh}: {error}")]
    NotApplicable {
        /// The mesh's label.
        mesh: String,
        /// Why.
        error: Box<schemes::Error>,
    },
    /// A face that uses a vertex twice: refused on every path, before any counting.
    #[error("{mesh}: {place}face {face} (vertices {vertices}) repeats vertex {vertex}")]
    RepeatedVertex {
        /// The mesh's label.
        mesh: String,
        /// `line N: `, or empty.
        place: String,
        /// The face (0-based).
        face: usize,
        /// Its vertices, comma-separated.
        vertices: String,
        /// The vertex repeated.
        vertex: u32,
    },
    /// Analysing a mesh (counts, problems, a half-edge build) would not fit half the memory
    /// available.
    #[error("{mesh}: analysing the mesh ({faces} faces, {corners} corners) needs about {need}, more than half of the memory available to this process ({limit} is half)")]
    AnalysisTooLarge {
        /// The mesh's label.
        mesh: String,
        /// Its faces.
        faces: usize,
        /// Its corners.
        corners: usize,
        /// The bytes needed, in words (`297.5 MiB`).
        need: String,
        /// Half the bytes available, in words.
        limit: String,
    },
    /// A composition cannot carry what the mesh has.
    #[error("{mesh}: {error}")]
    NotComposable {
        /// The mesh's label.
        mesh: String,
        /// The geometry's refusal ([`halfedge::Error::NotComposable`]).
        error: Box<halfedge::Error>,
    },
    /// Boundary interpolation `none` on a mesh with boundary under a scheme other than Loop
    /// and Catmull-Clark.
    #[error("{mesh}: {option} is OpenSubdiv's VTX_BOUNDARY_NONE (the faces at the boundary become holes), a mode of loop and catmull-clark; {stage} has no such mode on a mesh with boundary ({boundary_edges} boundary edges): {fix}")]
    BoundaryNone {
        /// The mesh's label.
        mesh: String,
        /// Where `none` came from: the flag or the file's tag.
        option: String,
        /// The scheme (or the composition and its stage) without the mode.
        stage: String,
        /// The mesh's boundary edges.
        boundary_edges: u64,
        /// What to do instead.
        fix: &'static str,
    },
    /// Holes under a scheme whose faces do not nest (or that names no rule).
    #[error("{mesh}: the file's hole tags make {tagged} face{} holes, but {stage}: {why}; holes are counted and written by the 4:1 family (loop, midpoint, butterfly, icosphere), tri-split-N and catmull-clark: use one of them, or --ignore-tags to count the mesh without its tags", if *tagged == 1 { "" } else { "s" })]
    HolesNotNested {
        /// The mesh's label.
        mesh: String,
        /// The faces the file's hole tags make holes.
        tagged: usize,
        /// The scheme (or the composition and its stage).
        stage: String,
        /// Why it cannot have holes.
        why: &'static str,
    },
    /// Catmull-Clark's triangle rule asked of a triangle scheme.
    #[error("--triangle-rule {rule} is Catmull-Clark's rule for triangles (OpenSubdiv's TriangleSubdivision), but {which}: triangle schemes (the Loop family, tri-split-N, sqrt3) have no such choice; drop the flag or use --scheme catmull-clark")]
    TriangleRule {
        /// The rule asked for.
        rule: TriangleRule,
        /// Which scheme (or stage) is a triangle scheme.
        which: String,
    },
    /// A scheme file that cannot be read.
    #[error("cannot read {}: {error}", path.display())]
    SchemeFileUnreadable {
        /// The file.
        path: PathBuf,
        /// Why.
        error: std::io::Error,
    },
    /// A scheme file that does not declare a valid scheme.
    #[error("{}: {error}", path.display())]
    SchemeFile {
        /// The file.
        path: PathBuf,
        /// Why.
        error: Box<schemes::Error>,
    },
    /// A scheme name that is not the scheme file's.
    #[error("--scheme {name} is not the scheme of {} (`{scheme}`)", path.display())]
    SchemeNotInFile {
        /// The name given.
        name: String,
        /// The file.
        path: PathBuf,
        /// The file's scheme.
        scheme: String,
    },
    /// Refining once (`f32`, frames) a scheme that runs on the raw face list.
    #[error("--precision f32 and --frames refine a manifold mesh once: this scheme runs on the raw face list (loop-general, catmull-clark-general, tri-split-N or a non-manifold mesh); use loop, catmull-clark or --precision f64")]
    RefineOnce,
    /// A refinement to keep, asked of a scheme that runs on the raw face list.
    #[error("{scheme} runs on the raw face list (loop-general, catmull-clark-general, tri-split-N or a non-manifold mesh), which keeps no refinement: use loop or catmull-clark")]
    NoRefinement {
        /// The scheme.
        scheme: String,
    },
    /// Counts too long to materialize ([`crate::limits::digits`]).
    #[error("the counts at level {level} would have about {digits:.3e} decimal digits ({bytes} per count); the limit is 10^7 digits: {hint}")]
    TooManyDigits {
        /// The level.
        level: u64,
        /// The digits of the largest count, estimated.
        digits: f64,
        /// Its bytes, in words.
        bytes: String,
        /// What to do instead.
        hint: &'static str,
    },
    /// A table too large to hold ([`crate::limits::table`]).
    #[error("levels {}..={} would make a table of {rows} rows and about {digits:.3e} decimal digits; the limits are 10^7 cells and 10^8 digits: ask for fewer levels", levels.start(), levels.end())]
    TableTooLarge {
        /// The levels asked for.
        levels: std::ops::RangeInclusive<u64>,
        /// The table's rows.
        rows: u128,
        /// Its digits, estimated.
        digits: f64,
    },
    /// A closed form too costly to derive ([`crate::limits::closed_forms`]).
    #[error("{what}: the closed form of a {dim}x{dim} matrix would cost about {cost:.2e} work units (estimated from its size and entries), more than the limit of {} (about 20 components): use `at` or `table` for exact counts (they power the matrix), or --allow-large to compute it anyway", schemes::CLOSED_FORM_LIMIT)]
    ClosedFormTooCostly {
        /// Which recurrence (`--matrix`, `scheme `loop``, a phase).
        what: String,
        /// Its components.
        dim: usize,
        /// The estimated cost.
        cost: f64,
    },
    /// The limit surface (`--limit`, `--normals limit`) asked of a scheme without limit masks.
    #[error("--limit and --normals limit use OpenSubdiv's limit masks, which loop, loop-boundary and catmull-clark have (and scheme files whose topology is one of them) on a manifold mesh; {scheme} has none")]
    LimitNotSupported {
        /// The scheme (or composition).
        scheme: String,
    },
    /// Refining once asked of a composition.
    #[error("--precision f32 and --frames refine one scheme once; {plan} is a composition: use --precision f64")]
    RefineOnceComposition {
        /// The composition.
        plan: String,
    },
}

impl Error {
    /// The kind of failure (a front end's exit code): the guards' refusals, the requests a
    /// scheme cannot serve, and otherwise bad input (a file, a mesh a scheme does not apply to).
    pub fn kind(&self) -> Kind {
        use Error as E;
        match self {
            E::Geometry(e) => Kind::of_geometry_error(e),
            E::Scheme(e) => Kind::of_scheme_error(e),
            E::AnalysisTooLarge { .. } | E::TooManyDigits { .. } => Kind::Guard,
            E::TableTooLarge { .. } | E::ClosedFormTooCostly { .. } => Kind::Guard,
            E::NotComposable { .. } | E::BoundaryNone { .. } => Kind::Usage,
            E::HolesNotNested { .. } | E::TriangleRule { .. } => Kind::Usage,
            E::SchemeNotInFile { .. } | E::RefineOnce | E::NoRefinement { .. } => Kind::Usage,
            E::RefineOnceComposition { .. } | E::LimitNotSupported { .. } => Kind::Usage,
            _ => Kind::Input,
        }
    }

    /// What a front end adds after the message where an option helps, in the command line's
    /// spelling (every front end names its options as the flags): how to lift the memory
    /// guard, how to drop crease input under a rule without creases; empty otherwise.
    ///
    /// ```
    /// let e = driver::Error::from(halfedge::Error::CreasesNotSupported {
    ///     rule: "sqrt3".into(),
    ///     what: "creases and corners",
    /// });
    /// assert!(e.advice().contains("--ignore-tags"));
    /// ```
    pub fn advice(&self) -> &'static str {
        use halfedge::Error as E;
        match self {
            Error::Geometry(E::OverMemoryLimit { .. }) => {
                "; use fewer levels, or --allow-large to try anyway"
            }
            Error::Geometry(E::CreasesNotSupported { .. }) => {
                ": use a Loop or Catmull-Clark scheme, --ignore-tags (for the file's tags), or drop the option flags"
            }
            _ => "",
        }
    }

    /// The geometry's error about a face of the input (a face-list subdivider's refusal)
    /// names the mesh and the face's line ([`Error::InMesh`]); any other stays as it is.
    pub(crate) fn located(e: halfedge::Error, mesh: &crate::LoadedMesh) -> Error {
        match e.face() {
            Some(f) => Error::InMesh {
                mesh: mesh.label().to_owned(),
                place: mesh.face_place(f as usize),
                error: Box::new(e),
            },
            None => Error::Geometry(e),
        }
    }
}
