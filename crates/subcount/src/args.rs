//! Command-line flags (clap). The names here are a public contract: extend, never rename.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

/// How big will a subdivision surface be? Exact counts, closed forms and real subdivision.
#[derive(Parser, Debug)]
#[command(name = "subcount", version, about, long_about = None)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand, Debug)]
pub(crate) enum Command {
    /// Counts per level (default: the icosahedron under 4:1 subdivision, levels 0..=8).
    Table(TableArgs),
    /// Exact counts at one (huge) level.
    At(AtArgs),
    /// Closed forms of the recurrence, from its exact eigen-decomposition.
    Formula(FormulaArgs),
}

/// Where the recurrence and its initial state come from.
#[derive(Args, Debug, Clone, Default)]
pub(crate) struct Source {
    /// The recurrence matrix, e.g. '[[1,1,0],[0,2,3],[0,0,4]]'.
    #[arg(long, value_name = "ROWS")]
    pub(crate) matrix: Option<String>,
    /// Component names in state order, e.g. V,E,F (default x0, x1, ...).
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    pub(crate) names: Option<Vec<String>>,
    /// Initial values in state order, e.g. 12,30,20.
    #[arg(long, value_name = "VALUES", allow_hyphen_values = true)]
    pub(crate) init: Option<String>,
    /// A built-in scheme (`subcount schemes` lists them), or a composition `A:k,B`.
    #[arg(long, value_name = "NAME")]
    pub(crate) scheme: Option<String>,
    /// A custom scheme from a TOML file (usable by name inside --scheme compositions).
    #[arg(long, value_name = "FILE")]
    pub(crate) scheme_file: Option<PathBuf>,
    /// Initial mesh counts, e.g. V=12,E=30,F=20 (keys: V, E, IE, BE, NME, F, H or state names).
    #[arg(long, value_name = "KEY=VALUE,...", allow_hyphen_values = true)]
    pub(crate) counts: Option<String>,
    #[command(flatten)]
    pub(crate) mesh: MeshSource,
}

/// A mesh to read statistics from: a file or a generated base mesh.
#[derive(Args, Debug, Clone, Default)]
pub(crate) struct MeshSource {
    /// A mesh file (OBJ or OFF).
    #[arg(long, value_name = "FILE")]
    pub(crate) mesh: Option<PathBuf>,
    /// A generated base mesh: tetrahedron, octahedron, icosahedron, cube, torus:G,
    /// icosahedron-holes:K, grid:WxH, quad-grid:WxH, mixed.
    #[arg(long, value_name = "NAME")]
    pub(crate) base: Option<String>,
}

/// Output formats of `table`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(crate) enum TableFormat {
    /// Aligned columns.
    #[default]
    Text,
    /// An array of objects, one per level.
    Json,
    /// Comma-separated values with a header line.
    Csv,
}

/// Output formats of `at`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(crate) enum AtFormat {
    /// One line per component.
    #[default]
    Text,
    /// One object.
    Json,
}

/// Output formats of `formula`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(crate) enum FormulaFormat {
    /// Plain text, grouped by initial component like the paper.
    #[default]
    Text,
    /// LaTeX.
    Latex,
    /// A compilable Rust function with checked i128 arithmetic.
    Rust,
    /// An array of objects, one per component.
    Json,
}

#[derive(Args, Debug)]
pub(crate) struct TableArgs {
    #[command(flatten)]
    pub(crate) source: Source,
    /// Levels: N (meaning 0..=N), A..=B or A..B.
    #[arg(long, default_value = "8", value_name = "RANGE", allow_hyphen_values = true)]
    pub(crate) levels: String,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub(crate) format: TableFormat,
}

#[derive(Args, Debug)]
pub(crate) struct AtArgs {
    #[command(flatten)]
    pub(crate) source: Source,
    /// The level.
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub(crate) level: String,
    /// Print per component the digit count and the first and last 20 digits.
    #[arg(long)]
    pub(crate) summary: bool,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub(crate) format: AtFormat,
    /// Lift the resource guard (at most 10^7 decimal digits per count).
    #[arg(long)]
    pub(crate) allow_large: bool,
}

#[derive(Args, Debug)]
pub(crate) struct FormulaArgs {
    #[command(flatten)]
    pub(crate) source: Source,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub(crate) format: FormulaFormat,
}
