//! Command-line flags (clap). The names here are a public contract: extend, never rename.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use halfedge::tags::{BoundaryInterpolation, CreaseMethod, FaceVaryingInterpolation, TriangleRule};

/// The value parser of an option enum of `halfedge::tags`: its command-line names (listed in
/// `--help` and in the error for another value), parsed by its `FromStr`.
macro_rules! named_parser {
    ($t:ty) => {
        clap::builder::TypedValueParser::try_map(
            clap::builder::PossibleValuesParser::new(
                <$t>::ALL
                    .iter()
                    .map(|v| clap::builder::PossibleValue::new(v.name())),
            ),
            |s: String| s.parse::<$t>(),
        )
    };
}

/// Parses `--threads`: a whole number from 0 (all cores) to
/// [`driver::limits::MAX_THREADS`] (each thread costs a stack and a start-up, and the geometry
/// passes gain nothing past the number of cores: without a cap, `--threads 100000` spent
/// minutes starting threads).
fn parse_threads(text: &str) -> Result<usize, String> {
    let n: usize = text.parse().map_err(|e| format!("{e}"))?;
    match driver::limits::threads_refusal(n as u64) {
        Some(why) => Err(why),
        None => Ok(n),
    }
}

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
    /// The highest level within a vertex, edge, face or memory budget.
    Fit(FitArgs),
    /// The paper's eq. (1): mean co-volume area and scale factor at a level, or the level for
    /// a target area.
    Density(DensityArgs),
    /// The built-in schemes (or one of them as a TOML template).
    Schemes(SchemesArgs),
    /// A mesh's statistics and the schemes that apply to it.
    Stats(StatsArgs),
    /// Really subdivide a mesh and compare every count with the prediction (exit 1 on a
    /// mismatch).
    Verify(VerifyArgs),
    /// Subdivide a mesh and write it as OBJ or PLY, with its UVs, colors and groups.
    Subdivide(SubdivideArgs),
    /// Draw V, E, F and the state components versus level on a log scale (SVG or PNG).
    Plot(PlotArgs),
}

#[derive(Args, Debug)]
pub(crate) struct PlotArgs {
    #[command(flatten)]
    pub(crate) source: Source,
    /// Levels: N (meaning 0..=N), A..=B or A..B.
    #[arg(
        long,
        default_value = "0..=12",
        value_name = "RANGE",
        allow_hyphen_values = true
    )]
    pub(crate) levels: String,
    /// The image to write (atomically): `.svg` or `.png`, chosen by the extension.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub(crate) output: PathBuf,
}

#[derive(Args, Debug)]
pub(crate) struct StatsArgs {
    #[command(flatten)]
    pub(crate) mesh: MeshSource,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub(crate) format: ReportFormat,
}

#[derive(Args, Debug)]
pub(crate) struct VerifyArgs {
    #[command(flatten)]
    pub(crate) mesh: MeshSource,
    #[command(flatten)]
    pub(crate) scheme: SchemeChoice,
    /// The last level to build (default: the highest whose face count stays within --max-faces).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub(crate) levels: Option<String>,
    /// The size cap used when --levels is not given.
    #[arg(long, value_name = "N", default_value_t = 2_000_000)]
    pub(crate) max_faces: u64,
    /// Threads for the geometry passes (0: all cores).
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = parse_threads)]
    pub(crate) threads: usize,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub(crate) format: ReportFormat,
    /// Lift the memory guard.
    #[arg(long)]
    pub(crate) allow_large: bool,
}

/// The scheme of `verify` and `subdivide`: a built-in name, or a scheme file.
#[derive(Args, Debug)]
#[group(required = true, multiple = true)]
pub(crate) struct SchemeChoice {
    /// A built-in scheme (aliases and tri-split-N included), or the --scheme-file scheme's name.
    #[arg(long, value_name = "NAME")]
    pub(crate) scheme: Option<String>,
    /// A custom scheme from a TOML file; its `topology` key names the rule that subdivides it.
    #[arg(long, value_name = "FILE")]
    pub(crate) scheme_file: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub(crate) struct SubdivideArgs {
    #[command(flatten)]
    pub(crate) mesh: MeshSource,
    #[command(flatten)]
    pub(crate) scheme: SchemeChoice,
    /// The final level N.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub(crate) levels: String,
    /// Write the result to this file (atomically): binary PLY for a .ply name, else OBJ.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub(crate) output: Option<PathBuf>,
    /// Threads for the geometry passes (0: all cores, 1: the single-thread path).
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = parse_threads)]
    pub(crate) threads: usize,
    /// Print one line `timings: {...}` on stderr (with UVs refined, uv_s: the seconds spent
    /// on them, after the surface's last level).
    #[arg(long)]
    pub(crate) timings: bool,
    /// Accepted and ignored (every run preallocates from the predicted counts; hidden since
    /// the growing builder left the engine, issue 26).
    #[arg(long, hide = true)]
    pub(crate) no_preallocate: bool,
    /// Lift the memory guard (default limit: half the available memory).
    #[arg(long)]
    pub(crate) allow_large: bool,
    /// The floating-point type the geometry is computed and written in.
    #[arg(long, value_enum, default_value_t)]
    pub(crate) precision: Precision,
    /// Refine the topology once, then evaluate the positions N times from slightly moved base
    /// positions (timed: `--timings` adds refine_topology_s and evaluate_s); -o writes the
    /// unmoved result (N at most 1,000,000).
    #[arg(long, value_name = "N", default_value_t = 0,
          value_parser = clap::value_parser!(u32).range(0..=1_000_000))]
    pub(crate) frames: u32,
    /// How UVs are linearly interpolated under loop and catmull-clark (OpenSubdiv's
    /// FVarLinearInterpolation; none: fully smooth; default: the file's
    /// facevaryinginterpolateboundary tag, else corners-plus1).
    #[arg(long, value_name = "MODE", conflicts_with = "no_uv",
          value_parser = named_parser!(FaceVaryingInterpolation))]
    pub(crate) uv_interpolation: Option<FaceVaryingInterpolation>,
    /// Write the output without texture coordinates (and refine none), even when the mesh
    /// has them.
    #[arg(long)]
    pub(crate) no_uv: bool,
    /// Write vertex normals as vn lines (faces v/vt/vn, or v//vn without UVs): area
    /// (--normals alone) weighs the faces written; limit gives the limit surface's normals
    /// (loop, catmull-clark).
    #[arg(long, value_enum, value_name = "KIND", num_args = 0..=1, default_missing_value = "area")]
    pub(crate) normals: Option<Normals>,
    /// Write the limit surface (OpenSubdiv's limit masks: positions, UVs, colors) instead of
    /// the last level's points (loop, loop-boundary, catmull-clark).
    #[arg(long)]
    pub(crate) limit: bool,
}

/// `subdivide --normals`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Normals {
    /// Area-weighted normals of the faces written.
    Area,
    /// The limit surface's normals (from its two limit tangents).
    Limit,
}

/// `subdivide --precision`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(crate) enum Precision {
    /// 32-bit floats (written with the shortest text that reads back as the same f32).
    F32,
    /// 64-bit floats.
    #[default]
    F64,
}

/// Output formats of `fit` and `density`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(crate) enum ReportFormat {
    /// Plain text.
    #[default]
    Text,
    /// One JSON object.
    Json,
}

/// Output formats of `schemes`.
#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq, Default)]
pub(crate) enum SchemesFormat {
    /// A readable list.
    #[default]
    Text,
    /// An array of objects.
    Json,
    /// The custom-scheme file format (one scheme: give its name).
    Toml,
}

#[derive(Args, Debug)]
pub(crate) struct FitArgs {
    #[command(flatten)]
    pub(crate) source: Source,
    /// At most this many vertices (e.g. 4294967295 for u32 indices).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub(crate) max_vertices: Option<String>,
    /// At most this many edges.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub(crate) max_edges: Option<String>,
    /// At most this many faces.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub(crate) max_faces: Option<String>,
    /// At most this many UV values (needs --mesh with texture coordinates at every corner).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub(crate) max_uv: Option<String>,
    /// A memory budget, e.g. 2GiB (GiB = 2^30 bytes, GB = 10^9 bytes).
    #[arg(long, value_name = "SIZE", allow_hyphen_values = true)]
    pub(crate) memory: Option<String>,
    /// Bytes per vertex for --memory (default 12: three f32).
    #[arg(long, value_name = "N", default_value_t = 12)]
    pub(crate) bytes_per_vertex: u64,
    /// Bytes per edge for --memory (default 0).
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub(crate) bytes_per_edge: u64,
    /// Bytes per face for --memory (default 12: three u32 indices).
    #[arg(long, value_name = "N", default_value_t = 12)]
    pub(crate) bytes_per_face: u64,
    /// Bytes per UV value for --memory (e.g. 8: two f32; default 0, UVs not counted; needs
    /// --mesh with texture coordinates at every corner).
    #[arg(long, value_name = "N")]
    pub(crate) bytes_per_uv: Option<u64>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub(crate) format: ReportFormat,
}

#[derive(Args, Debug)]
pub(crate) struct DensityArgs {
    #[command(flatten)]
    pub(crate) source: Source,
    /// The subdivision level s.
    #[arg(
        long,
        value_name = "S",
        allow_hyphen_values = true,
        conflicts_with = "target_area",
        required_unless_present = "target_area"
    )]
    pub(crate) level: Option<String>,
    /// Find the smallest level whose mean co-volume area is at most this.
    #[arg(long, value_name = "AREA", allow_hyphen_values = true)]
    pub(crate) target_area: Option<f64>,
    /// The sphere radius r.
    #[arg(
        long,
        value_name = "R",
        default_value_t = 1.0,
        allow_hyphen_values = true
    )]
    pub(crate) radius: f64,
    /// The time step tau (for the scale factor phi).
    #[arg(long, value_name = "TAU", allow_hyphen_values = true)]
    pub(crate) tau: Option<f64>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub(crate) format: ReportFormat,
}

#[derive(Args, Debug)]
pub(crate) struct SchemesArgs {
    /// Show only this scheme (required with --format toml).
    #[arg(value_name = "NAME")]
    pub(crate) name: Option<String>,
    /// Output format.
    #[arg(long, value_enum, default_value_t)]
    pub(crate) format: SchemesFormat,
}

/// Where the recurrence and its initial state come from.
#[derive(Args, Debug, Clone, Default)]
pub(crate) struct Source {
    /// The recurrence matrix, e.g. `[[1,1,0],[0,2,3],[0,0,4]]`.
    // The help text is spelled out: clap prints doc comments as they are, and rustdoc would
    // read the bracketed example as links.
    #[arg(
        long,
        value_name = "ROWS",
        help = "The recurrence matrix, e.g. '[[1,1,0],[0,2,3],[0,0,4]]'"
    )]
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

/// A mesh to read statistics from: a file or a generated base mesh, with the subdivision
/// options that override its OpenSubdiv tags.
#[derive(Args, Debug, Clone, Default)]
pub(crate) struct MeshSource {
    /// A mesh file (OBJ, OFF or PLY).
    #[arg(long, value_name = "FILE")]
    pub(crate) mesh: Option<PathBuf>,
    /// A generated base mesh: tetrahedron, octahedron, icosahedron, cube, torus:G,
    /// icosahedron-holes:K, grid:WxH, quad-grid:WxH, mixed.
    #[arg(long, value_name = "NAME")]
    pub(crate) base: Option<String>,
    /// Boundary interpolation (default: the file's interpolateboundary tag, else edge).
    #[arg(long, value_name = "MODE", value_parser = named_parser!(BoundaryInterpolation))]
    pub(crate) boundary: Option<BoundaryInterpolation>,
    /// How semi-sharp creases decay (default: the file's creasemethod tag, else uniform).
    #[arg(long, value_name = "METHOD", value_parser = named_parser!(CreaseMethod))]
    pub(crate) crease_method: Option<CreaseMethod>,
    /// Catmull-Clark's rule for triangles (default: the file's smoothtriangles tag, else
    /// catmark); not with a triangle scheme.
    #[arg(long, value_name = "RULE", value_parser = named_parser!(TriangleRule))]
    pub(crate) triangle_rule: Option<TriangleRule>,
    /// Do not read the file's OpenSubdiv tags (t lines): creases, corners, holes, options.
    #[arg(long)]
    pub(crate) ignore_tags: bool,
    /// A face list in memory in place of a file, and how messages name it (the Python
    /// bindings' meshes: [`crate::run_captured`]).
    #[arg(skip)]
    pub(crate) memory: Option<MemoryMesh>,
}

/// A mesh handed over in memory, and its label.
pub(crate) type MemoryMesh = (std::sync::Arc<halfedge::PolygonMesh>, String);

impl MeshSource {
    /// Whether a mesh is given (`--mesh`, `--base`, or one in memory).
    pub(crate) fn is_given(&self) -> bool {
        self.mesh.is_some() || self.base.is_some() || self.memory.is_some()
    }

    /// Whether a subdivision option flag (--boundary, --crease-method, --triangle-rule,
    /// --ignore-tags) is given, and the first one's name.
    pub(crate) fn option_flag(&self) -> Option<&'static str> {
        [
            (self.boundary.is_some(), "--boundary"),
            (self.crease_method.is_some(), "--crease-method"),
            (self.triangle_rule.is_some(), "--triangle-rule"),
            (self.ignore_tags, "--ignore-tags"),
        ]
        .into_iter()
        .find_map(|(given, name)| given.then_some(name))
    }
}

impl Command {
    /// Gives the command's mesh source a mesh in memory ([`MeshSource::memory`]).
    pub(crate) fn set_memory_mesh(&mut self, mesh: MemoryMesh) {
        let source = match self {
            Command::Table(a) => &mut a.source.mesh,
            Command::At(a) => &mut a.source.mesh,
            Command::Formula(a) => &mut a.source.mesh,
            Command::Fit(a) => &mut a.source.mesh,
            Command::Density(a) => &mut a.source.mesh,
            Command::Plot(a) => &mut a.source.mesh,
            Command::Stats(a) => &mut a.mesh,
            Command::Verify(a) => &mut a.mesh,
            Command::Subdivide(a) => &mut a.mesh,
            Command::Schemes(_) => return,
        };
        source.memory = Some(mesh);
    }
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
    #[arg(
        long,
        default_value = "8",
        value_name = "RANGE",
        allow_hyphen_values = true
    )]
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
    /// Lift the resource guard (closed forms of at most about 20 components).
    #[arg(long)]
    pub(crate) allow_large: bool,
}
