//! Subdivision schemes declared as integer matrices.
//!
//! Every subdivision rule whose counts evolve linearly is a [`Scheme`]: a name, an ordered
//! state of mesh statistics (`V`, `E`, `IE`, `BE`, `F`, `H`, ...), the matrices that advance
//! the state by one level, the [`MeshClass`] it applies to, and how `V`, `E` and `F` follow
//! from the state. From a mesh's [`MeshCounts`] (or counts typed in as [`CountsInput`]) a
//! scheme gives exact counts at any level.
//!
//! - Built-ins: [`builtin`] by name, [`builtins`] for the list; each is derived in the
//!   documentation of its constructor in [`catalog`].
//! - Custom schemes from TOML text: [`Scheme::from_toml`]; export with [`Scheme::to_toml`].
//! - Composition `A:k,B`: [`Plan`].
//! - Counting a plan or a bare matrix (powering or closed form, table columns and rows, size
//!   estimates, digit summaries of huge levels, closed forms with a state substituted):
//!   [`Counter`].
//! - UV values (face-varying texture coordinates) and their recurrences: [`uv`].
//! - Budgets and the paper's eq. (1): [`fit`], [`parse_byte_size`], [`density`].
//!
//! # Built-in schemes
//!
//! | name | state | matrix (rows) | mesh class |
//! |---|---|---|---|
//! | `loop` (`midpoint`, `butterfly`, `icosphere`) | V, E | `[1 1] [0 4]`; F = 2E/3 | closed triangles |
//! | `loop-boundary` | V, IE, BE | `[1 1 1] [0 4 1] [0 0 2]` | triangles, edges of one or two faces |
//! | `loop-general` | V, E, F | `[1 1 0] [0 2 3] [0 0 4]` | any triangle mesh |
//! | `catmull-clark-quad` | V, E, F | `[1 1 1] [0 2 4] [0 0 4]` | any quad mesh |
//! | `catmull-clark` | V, IE, BE, F, H | see [`catalog::catmull_clark`] | polygons, edges of one or two faces |
//! | `catmull-clark-general` | V, E, F, H | `[1 1 1 0] [0 2 0 1] [0 0 0 1] [0 0 0 4]` | any polygon mesh |
//! | `sqrt3` | V, E, F | `[1 0 1] [0 1 3] [0 0 3]` | closed triangles |
//! | `sqrt3-boundary` | V, IE, BE, F | a cycle of two, see [`catalog::sqrt3_boundary`] | triangles, edges of one or two faces |
//! | `doo-sabin` | V, E, F | `[0 2 0] [0 4 0] [1 1 1]` | closed polygons |
//! | `doo-sabin-boundary` | V, IE, BE, F | `[0 2 3 0] [0 4 3 0] [0 0 2 0] [1 1 1 1]` | polygons, edges of one or two faces |
//! | `mid-edge` | V, E, F | `[0 1 0] [0 2 0] [1 0 1]` | closed polygons |
//! | `mid-edge-boundary` | V, IE, BE, F | `[0 1 2 0] [0 2 1 0] [0 0 2 0] [1 0 0 1]` | polygons, edges of one or two faces |
//! | `tri-split-N` (`ternary` = 3) | V, E, F | see [`catalog::tri_split`] | any triangle mesh |
//!
//! The aliases `midpoint`, `butterfly` and `icosphere` (the same 4:1 topology with their own
//! geometry in `halfedge`) count as `loop-boundary` on a mesh with boundary, and `doo-sabin`
//! and `mid-edge` as `doo-sabin-boundary` and `mid-edge-boundary`: [`Scheme::for_mesh`],
//! [`Plan::for_mesh`].
//!
//! # Example: the icosahedron under Loop
//!
//! ```
//! use num_bigint::BigInt;
//! use schemes::{builtin, CountsInput};
//!
//! let scheme = builtin("loop")?;
//! let x0 = scheme.state_from_input(&"V=12,E=30,F=20".parse::<CountsInput>()?)?;
//! let v: Vec<BigInt> = (0..4)
//!     .map(|s| scheme.level_counts(&x0, s).map(|c| c.vertices))
//!     .collect::<Result<_, _>>()?;
//! assert_eq!(v, [12, 42, 162, 642].map(BigInt::from));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Example: a mesh the scheme does not apply to
//!
//! ```
//! use schemes::{builtin, MeshCounts};
//!
//! let open_square = MeshCounts::from_polygons(&[[0, 1, 2], [0, 2, 3]])?;
//! let err = builtin("loop")?.initial_state(&open_square).unwrap_err();
//! assert_eq!(
//!     err.to_string(),
//!     "loop needs a closed mesh, but this mesh has 4 boundary edges; use loop-boundary"
//! );
//! let c = builtin("loop-boundary")?.counts_at(&open_square, 1)?;
//! assert_eq!((c.vertices, c.edges, c.faces), (9.into(), 16.into(), 8.into()));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![deny(missing_docs)]

pub mod catalog;
mod class;
mod counter;
mod counts;
pub mod custom;
mod error;
mod fit;
pub mod holes;
pub mod input;
pub mod output;
mod plan;
mod rule;
mod scheme;
pub mod uv;

pub use crate::catalog::{builtin, builtins};
pub use crate::class::{FaceKind, MeshClass};
pub use crate::counter::{
    log10_abs, specialized_line_from, specialized_lines, Counter, Row, CLOSED_FORM_LIMIT,
    SUMMARY_DIGITS,
};
pub use crate::counts::{first_repeated_vertex, DisjointSets, MeshCounts, Stat};
pub use crate::error::{Error, Result};
pub use crate::fit::{
    density, fit, fit_uv, level_for_area, parse_byte_size, Budget, Density, Fit, MemoryBudget,
};
pub use crate::input::{parse_init, CountsInput, Facts};
pub use crate::plan::{Plan, Stage};
pub use crate::rule::Rule;
pub use crate::scheme::{Component, Derivation, LevelCounts, Phase, Scheme, SchemeSpec, StepRule};
pub use num_bigint::{self, BigInt};
pub use recurrence;
