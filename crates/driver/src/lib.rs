//! What every front end of subcount (the `subcount` command line, the Python package) calls
//! between the user and the geometry, so that none of them re-implements it:
//!
//! - [`load`] reads a mesh ([`MeshSource`]: a file or a generated base mesh) within the memory
//!   the system allows, and resolves its subdivision options: an option the user gave
//!   ([`OptionFlags`]) wins over the file's OpenSubdiv tag, the tag over the default
//!   ([`resolve_options`]). [`LoadedMesh`] holds the refusals every command shares (a face
//!   repeating a vertex, holes under a scheme whose faces do not nest, boundary `none` where
//!   only Loop and Catmull-Clark have it, [`refuse_triangle_rule`]).
//! - [`subdivide::prepare`] and [`subdivide::Prepared::run`] run a real subdivision (the path,
//!   the UV layout, the memory guard), [`verify::start`] a verification, [`compose::start`] a
//!   composition of schemes.
//! - [`limits`] refuses exact counts, tables and closed forms too large to materialize.
//! - [`system`] reads what the system tells about this process's memory (`/proc`,
//!   `RLIMIT_AS`, cgroups); [`output`] replaces output files atomically and removes a
//!   temporary file on a signal.
//!
//! The geometry kernel (`halfedge`) reads no system state and writes into any `Write`: it
//! predicts sizes, this crate compares them with the system's limits.
//!
//! Notes for the user (a tag not read, an option a rule does not apply) go to a [`Notes`]
//! sink, in order; errors are one [`Error`] each, classified by [`Kind`].
//!
//! ```
//! use driver::{load, MeshSource, OptionFlags, SchemeChoice};
//! use driver::subdivide::{prepare, SubdivideJob};
//!
//! let mesh = load(&MeshSource::Base("icosahedron".into()), &OptionFlags::default())?;
//! let mut notes = Vec::new();
//! let scheme = SchemeChoice::Builtin("loop".into());
//! let prepared = prepare(&mesh, &scheme, &SubdivideJob::new(2), None, &mut |n| notes.push(n))?;
//! assert_eq!(prepared.final_faces(), 320);
//! let level = prepared.run(&|_level| {}, &mut |n| notes.push(n))?;
//! assert_eq!(level.counts(), [162, 480, 320]);
//! assert!(notes.is_empty());
//! # Ok::<(), driver::Error>(())
//! ```

pub mod compose;
mod error;
pub mod guard;
pub mod limits;
mod mesh;
pub mod output;
pub mod refined;
pub mod refinement;
mod scheme;
pub mod subdivide;
pub mod system;
pub mod verify;

pub use error::{Error, Kind, Result};
pub use mesh::{
    load, load_polygon_mesh, refuse_triangle_rule, resolve_options, LoadedMesh, MeshSource,
    OptionFlags,
};
pub use scheme::{
    choose, load_scheme_file, on_face_list, Chosen, SchemeChoice, SCHEME_FILE_MAX_BYTES,
};

/// Where the driver's notes to the user go, one line each (`note: ...`, `warning: ...`), in
/// the order they arise: the command line prints them on stderr.
pub type Notes<'a> = &'a mut dyn FnMut(String);
