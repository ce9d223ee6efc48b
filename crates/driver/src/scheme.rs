//! The scheme of a real subdivision: a built-in name or a scheme file
//! ([`SchemeChoice`]), counted as it counts what is written of a mesh, the rule that really
//! subdivides it and the mesh's holes under it ([`choose`]), and whether it runs on the raw
//! face list ([`on_face_list`]).

use std::path::{Path, PathBuf};

use halfedge::holes::HoleSet;
use halfedge::Rule;
use schemes::{MeshCounts, Scheme};

use crate::error::{Error, Result};
use crate::mesh::{refuse_triangle_rule, LoadedMesh};

/// The largest scheme file read, in bytes (a 32-component matrix of 20-digit entries is
/// about 25 KB).
pub const SCHEME_FILE_MAX_BYTES: u64 = 1 << 20;

/// Reads and validates a custom scheme file (at most [`SCHEME_FILE_MAX_BYTES`]).
///
/// # Errors
///
/// [`Error::SchemeFileUnreadable`], [`Error::SchemeFile`].
pub fn load_scheme_file(path: &Path) -> Result<Scheme> {
    let text = halfedge::io::read_text_capped(path, SCHEME_FILE_MAX_BYTES).map_err(|error| {
        Error::SchemeFileUnreadable {
            path: path.to_path_buf(),
            error,
        }
    })?;
    Scheme::from_toml(&text).map_err(|error| Error::SchemeFile {
        path: path.to_path_buf(),
        error: Box::new(error),
    })
}

/// The scheme of `verify` and `subdivide`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SchemeChoice {
    /// A built-in scheme (aliases and `tri-split-N` included).
    Builtin(String),
    /// A scheme file, and the name the user gave it (which must be the file's).
    File {
        /// The TOML file.
        path: PathBuf,
        /// The name given beside it, if any.
        name: Option<String>,
    },
}

impl SchemeChoice {
    /// The scheme of a front end's two options, a built-in `name` (`--scheme`, `scheme=`) and
    /// a scheme `file` (`--scheme-file`, `scheme_file=`; with a name too, the name must be the
    /// file's); `None` when neither is given (each front end words that refusal).
    ///
    /// ```
    /// use driver::SchemeChoice;
    /// assert_eq!(SchemeChoice::from_options(Some("loop".into()), None), Some(SchemeChoice::Builtin("loop".into())));
    /// assert_eq!(SchemeChoice::from_options(None, None), None);
    /// ```
    pub fn from_options(name: Option<String>, file: Option<PathBuf>) -> Option<SchemeChoice> {
        match (file, name) {
            (Some(path), name) => Some(SchemeChoice::File { path, name }),
            (None, Some(name)) => Some(SchemeChoice::Builtin(name)),
            (None, None) => None,
        }
    }

    /// Whether this is a custom scheme (a file).
    pub fn is_custom(&self) -> bool {
        matches!(self, SchemeChoice::File { .. })
    }
}

/// What `verify` and `subdivide` run: the scheme as it counts what is written, its rule, and
/// the holes.
#[derive(Debug)]
pub struct Chosen {
    /// The scheme for the written faces.
    pub scheme: Scheme,
    /// The rule that really subdivides it.
    pub rule: Rule,
    /// The faces that are holes ([`LoadedMesh::holes`]), if any.
    pub holes: Option<HoleSet>,
}

/// The scheme of `choice` as it counts what is written of `mesh` (`loop` and its aliases
/// count as `loop-boundary` on a mesh with boundary: [`Scheme::for_mesh`]; with holes, the
/// statistics of the written faces, so a closed mesh with holes counts with the boundary-aware
/// state), the rule that really subdivides it ([`halfedge::subdivide::checked_rule`]) and the
/// holes. `counts` are the statistics of all faces.
///
/// # Errors
///
/// [`Error::SchemeNotInFile`], a scheme file's errors, the refusals of
/// [`LoadedMesh::holes`] and [`refuse_triangle_rule`], [`Error::NotApplicable`], and a rule
/// that does not apply ([`Error::Geometry`]).
pub fn choose(choice: &SchemeChoice, mesh: &LoadedMesh, counts: &MeshCounts) -> Result<Chosen> {
    let scheme = match choice {
        SchemeChoice::File { path, name } => {
            let custom = load_scheme_file(path)?;
            if let Some(name) = name.as_deref().filter(|n| *n != custom.name()) {
                return Err(Error::SchemeNotInFile {
                    name: name.to_owned(),
                    path: path.clone(),
                    scheme: custom.name().to_owned(),
                });
            }
            custom
        }
        SchemeChoice::Builtin(name) => schemes::builtin(name)?,
    };
    let holes = mesh.holes(
        counts,
        scheme.name(),
        &[(scheme.name(), scheme.subdivision_rule())],
    )?;
    let written = holes.as_ref().map(|h| h.written_counts(&mesh.poly));
    let counts = written.as_ref().unwrap_or(counts);
    let scheme = scheme.for_mesh(counts);
    refuse_triangle_rule(
        mesh.flags().triangle_rule,
        scheme.name(),
        [(scheme.name(), scheme.subdivision_rule())],
    )?;
    scheme
        .initial_state(counts)
        .map_err(|e| mesh.not_applicable(e))?;
    let rule = halfedge::subdivide::checked_rule(&scheme, counts)?;
    Ok(Chosen {
        scheme,
        rule,
        holes,
    })
}

/// Whether to run on the raw face list: a built-in scheme that allows non-manifold input
/// (`loop-general`, `catmull-clark-general`, `tri-split-N`), or a custom one on a mesh with
/// non-manifold edges, when its rule refines each face on its own.
pub fn on_face_list(scheme: &Scheme, rule: Rule, counts: &MeshCounts, custom: bool) -> bool {
    let general = if custom {
        counts.nonmanifold_edges > 0
    } else {
        !scheme.mesh_class().needs_manifold()
    };
    general && rule.refines_faces()
}
