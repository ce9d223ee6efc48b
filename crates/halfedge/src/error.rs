//! The error type of the `halfedge` crate.

use std::fmt;
use std::path::PathBuf;

use crate::text::escape_controls;

/// A `Result` whose error defaults to this crate's [`Error`].
pub type Result<T = (), E = Error> = std::result::Result<T, E>;

/// A list of indices (the vertices of a face, or the faces on an edge), displayed as
/// `4, 9, 4`; lists longer than 8 are shortened.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FaceVertices(pub Vec<u32>);

impl fmt::Display for FaceVertices {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const SHOWN: usize = 8;
        for (i, v) in self.0.iter().take(SHOWN).enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{v}")?;
        }
        if self.0.len() > SHOWN {
            write!(f, ", ... ({} vertices)", self.0.len())?;
        }
        Ok(())
    }
}

/// What is wrong with one line of a mesh file (see [`Error::Parse`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ParseError {
    /// A token that should be a number is not one.
    #[error("`{token}` is not a valid {expected}")]
    InvalidNumber {
        /// The offending token (shortened when long).
        token: String,
        /// What was expected there ("coordinate", "vertex index", ...).
        expected: &'static str,
    },
    /// A coordinate is NaN or infinite.
    #[error("coordinate `{token}` is not finite")]
    NonFiniteCoordinate {
        /// The offending token.
        token: String,
    },
    /// A vertex line with fewer than three coordinates.
    #[error("vertex has {found} coordinates, expected 3")]
    MissingCoordinates {
        /// How many coordinates the line has.
        found: usize,
    },
    /// An OBJ face index of 0 (OBJ indices start at 1; negative ones count back).
    #[error("face index 0 is not valid (OBJ indices start at 1)")]
    IndexZero,
    /// A face index that does not fit the index type.
    #[error("face index `{token}` is too large")]
    IndexTooLarge {
        /// The offending token.
        token: String,
    },
    /// A face index that refers past the vertices read so far (or before the first one).
    #[error("face index {index} is out of range (the file has {vertices} vertices)")]
    IndexOutOfRange {
        /// The index as written in the file.
        index: i64,
        /// Number of vertices defined before this line (OBJ) or in the file (OFF).
        vertices: u64,
    },
    /// A texture-coordinate line (`vt u v [w]`) with fewer than two values.
    #[error("texture coordinate has {found} values, expected u v (and an optional w)")]
    MissingTexCoords {
        /// How many values the line has.
        found: usize,
    },
    /// A face corner's texture-coordinate index (`v/vt`, `v/vt/vn`) that is not a non-zero
    /// integer (one too large is [`ParseError::TexCoordIndexTooLarge`]).
    #[error("corner {corner}: `{token}` is not a valid texture coordinate index (expected a non-zero integer; negative ones count back)")]
    InvalidTexCoordIndex {
        /// The corner on the face line (1-based).
        corner: usize,
        /// The index as written (shortened when long).
        token: String,
    },
    /// A face corner's texture-coordinate index whose magnitude does not fit the index type
    /// (as [`ParseError::IndexTooLarge`] for a face index).
    #[error("corner {corner}: texture coordinate index `{token}` is too large")]
    TexCoordIndexTooLarge {
        /// The corner on the face line (1-based).
        corner: usize,
        /// The index as written (shortened when long).
        token: String,
    },
    /// A face corner's texture-coordinate index that refers past the `vt` lines of the file
    /// (or, negative, before the first one).
    #[error("corner {corner}: texture coordinate index {index} is out of range (the file has {count} texture coordinates)")]
    TexCoordIndexOutOfRange {
        /// The corner on the face line (1-based).
        corner: usize,
        /// The index as written in the file.
        index: i64,
        /// Number of `vt` lines before this line (negative indices) or in the file.
        count: u64,
    },
    /// A face with fewer than three corners.
    #[error("face has {corners} vertices, at least 3 are needed")]
    FaceTooSmall {
        /// Number of corners on the line.
        corners: usize,
    },
    /// The line is not text (binary data or invalid UTF-8).
    #[error("not a text line (binary data?)")]
    NotText,
    /// A line longer than [`crate::io::MAX_LINE_BYTES`] (continuations included).
    #[error("line is longer than {limit} bytes")]
    LineTooLong {
        /// The limit in bytes.
        limit: usize,
    },
    /// A malformed statement not covered by another variant (an OFF header, a short face).
    #[error("{what}")]
    Malformed {
        /// What is wrong.
        what: String,
    },
    /// An OFF file ended before all its vertices and faces.
    #[error("the file ends early: {what}")]
    UnexpectedEnd {
        /// What was still expected.
        what: String,
    },
    /// Extra tokens where none are allowed.
    #[error("unexpected `{token}`")]
    UnexpectedToken {
        /// The offending token.
        token: String,
    },
    /// An OBJ tag line without a name or without value counts (the grammar is
    /// `t NAME nInts/nFloats/nStrings ints floats strings`).
    #[error("a tag line needs a name and value counts (expected t NAME nInts/nFloats/nStrings, e.g. t crease 2/1/0 0 1 10)")]
    TagIncomplete,
    /// An OBJ tag line whose value counts are malformed.
    #[error("`{token}` is not a tag's value counts (expected t NAME nInts/nFloats/nStrings, e.g. t crease 2/1/0 0 1 10)")]
    TagCounts {
        /// The token where the counts should be.
        token: String,
    },
    /// A tag line with more or fewer values than its counts declare.
    #[error("tag `{name}` declares {declared} values but the line has {found}")]
    TagValueCount {
        /// The tag.
        name: String,
        /// nInts + nFloats + nStrings (three `u64` counts: their sum may pass `u64::MAX`).
        declared: u128,
        /// The values on the line.
        found: u64,
    },
    /// A known tag with counts its meaning does not allow (an odd number of crease
    /// integers, a float count that is neither 1 nor one per pair or vertex, ...).
    #[error("tag `{name}` has {counts} values: expected {expected}")]
    TagForm {
        /// The tag.
        name: String,
        /// The counts as written, `nInts/nFloats/nStrings` (shortened when long).
        counts: String,
        /// What the tag takes.
        expected: &'static str,
    },
    /// An option tag with a value outside its range.
    #[error("tag `{name}`: `{value}` is not a valid value (expected {expected})")]
    TagOption {
        /// The tag.
        name: String,
        /// The value (shortened when long).
        value: String,
        /// The valid values and their meaning.
        expected: &'static str,
    },
    /// A sharpness that is negative, NaN or infinite.
    #[error("tag `{name}`: sharpness `{token}` is not valid (expected a finite number >= 0)")]
    TagSharpness {
        /// The tag.
        name: String,
        /// The value as written (shortened when long).
        token: String,
    },
    /// A tag's vertex or face index beyond 32 bits.
    #[error("tag `{name}`: index `{token}` is too large")]
    TagIndexTooLarge {
        /// The tag.
        name: String,
        /// The index as written (shortened when long).
        token: String,
    },
    /// A tag that names a vertex, face or edge the file's mesh does not have.
    #[error(transparent)]
    Tag(#[from] crate::tags::TagError),
    /// A PLY face's vertex index that is negative or not below the file's vertex count.
    #[error("vertex index {index} is out of range (the file has {vertices} vertices)")]
    VertexIndexOutOfRange {
        /// The index as stored in the file.
        index: i64,
        /// The vertices the header declares.
        vertices: u64,
    },
    /// A PLY list whose count is negative or larger than the reader accepts.
    #[error("list count {count} is not valid (expected 0 to {limit})")]
    ListCount {
        /// The count as stored in the file.
        count: i64,
        /// The largest count accepted.
        limit: u64,
    },
}

/// Everything that can go wrong loading, validating or subdividing a mesh.
///
/// Vertex and face numbers in validation errors are 0-based indices into the face list
/// ([`crate::PolygonMesh`]); file errors name the file and its 1-based line.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// Reading or writing a file failed (writing: the front ends' `driver::output`).
    #[error("{}: {source}", escape_controls(&path.display().to_string()))]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// A mesh file larger than the memory this process may allocate, refused before it is
    /// read (a resource guard: see [`Error::is_resource_limit`]).
    #[error("{}: the file is {size} bytes, more than the {limit} bytes of memory available to this process", escape_controls(&path.display().to_string()))]
    FileTooLarge {
        /// The file.
        path: PathBuf,
        /// Its size in bytes.
        size: u64,
        /// The bytes available ([`crate::io::ReadOptions::available_bytes`]).
        limit: u64,
    },
    /// A mesh file whose faces and vertices need more memory than a reader may fill (half
    /// of [`crate::io::ReadOptions::available_bytes`]), refused where the reader got to (a resource
    /// guard).
    #[error("{file}: line {line}: the mesh read so far needs more than {limit} bytes of memory, half of what is available to this process")]
    MeshTooLarge {
        /// The file name.
        file: String,
        /// The line being read.
        line: u64,
        /// The budget in bytes.
        limit: u64,
    },
    /// A line of a mesh file could not be read.
    #[error("{file}: line {line}: {kind}")]
    Parse {
        /// The file name (as given for error messages).
        file: String,
        /// 1-based line number.
        line: u64,
        /// What is wrong.
        kind: ParseError,
    },
    /// A mesh file with no faces.
    #[error("{file}: the file has no faces")]
    NoFaces {
        /// The file name.
        file: String,
    },
    /// A mesh file whose format cannot be told from its extension.
    #[error("{}: unknown mesh format (expected .obj, .off or .ply)", escape_controls(&path.display().to_string()))]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// A face refers to a vertex that does not exist.
    #[error("face {face} (vertices {vertices}) refers to vertex {vertex}, but the mesh has {n_vertices} vertices")]
    VertexOutOfRange {
        /// The face.
        face: u32,
        /// Its vertices.
        vertices: FaceVertices,
        /// The missing vertex.
        vertex: u32,
        /// Number of vertices of the mesh.
        n_vertices: usize,
    },
    /// A face with fewer than three vertices.
    #[error("face {face} (vertices {vertices}) has {degree} vertices, at least 3 are needed")]
    FaceTooSmall {
        /// The face.
        face: u32,
        /// Its vertices.
        vertices: FaceVertices,
        /// Its number of vertices.
        degree: usize,
    },
    /// A face that uses a vertex twice (a degenerate face).
    #[error("face {face} (vertices {vertices}) repeats vertex {vertex}")]
    RepeatedVertex {
        /// The face.
        face: u32,
        /// Its vertices.
        vertices: FaceVertices,
        /// The repeated vertex.
        vertex: u32,
    },
    /// Two faces on the same set of vertices (duplicate or back-to-back faces).
    #[error("faces {first} and {second} have the same vertices ({vertices})")]
    DuplicateFace {
        /// The first face.
        first: u32,
        /// The second face.
        second: u32,
        /// The vertices of the first face.
        vertices: FaceVertices,
    },
    /// An edge shared by more than two faces.
    #[error("edge ({a}, {b}) is shared by {count} faces ({faces}): non-manifold edge")]
    NonManifoldEdge {
        /// One end of the edge.
        a: u32,
        /// The other end.
        b: u32,
        /// How many faces share it.
        count: usize,
        /// The faces (the first few).
        faces: FaceVertices,
    },
    /// Two faces traverse an edge in the same direction: one of them is flipped.
    #[error("faces {first} and {second} both use edge {a} -> {b} in the same direction: inconsistent orientation (flip one of them)")]
    InconsistentOrientation {
        /// Start of the directed edge.
        a: u32,
        /// End of the directed edge.
        b: u32,
        /// The first face.
        first: u32,
        /// The second face.
        second: u32,
    },
    /// The faces cannot be oriented consistently at all (a Moebius strip, a Klein bottle).
    #[error("the surface is not orientable: flipping faces cannot make the orientation consistent (the component of face {face} contains an orientation-reversing loop through edge ({a}, {b}))")]
    NonOrientable {
        /// A face of the non-orientable component.
        face: u32,
        /// One end of an edge where the orientation conflict closes.
        a: u32,
        /// The other end.
        b: u32,
    },
    /// A vertex whose faces form several separate fans (a pinched or bow-tie vertex).
    #[error("vertex {vertex} is non-manifold: its faces form {fans} separate fans")]
    NonManifoldVertex {
        /// The vertex.
        vertex: u32,
        /// Number of fans around it.
        fans: usize,
    },
    /// A vertex position with a NaN or infinite coordinate.
    #[error("vertex {vertex} has a non-finite coordinate ({x}, {y}, {z})")]
    NonFiniteCoordinate {
        /// The vertex.
        vertex: u32,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
        /// Its z coordinate.
        z: f64,
    },
    /// More elements than `u32` handles can address.
    #[error("too many {what} ({count}): handles are 32-bit")]
    TooManyElements {
        /// Which elements ("vertices", "half-edges", ...).
        what: &'static str,
        /// How many there would be.
        count: u64,
    },
    /// A base mesh name that is not known.
    #[error("unknown base mesh `{name}` (known: tetrahedron, octahedron, icosahedron, cube, torus:G, icosahedron-holes:K, grid:WxH, quad-grid:WxH, mixed)")]
    UnknownShape {
        /// The name as given.
        name: String,
    },
    /// A base mesh parameter that is malformed or out of range.
    #[error("base mesh `{name}`: {what}")]
    InvalidShapeParameter {
        /// The name as given.
        name: String,
        /// What is wrong.
        what: String,
    },
    /// A structural invariant of a [`crate::HalfEdgeMesh`] does not hold (a bug).
    #[error("internal error: broken half-edge invariant: {what} (please report this)")]
    BrokenInvariant {
        /// The violated invariant.
        what: String,
    },
    /// A subdivision scheme's counts (from the `schemes` crate): unknown name, mesh outside
    /// the scheme's class, impossible counts.
    #[error(transparent)]
    Scheme(#[from] schemes::Error),
    /// The memory guard: the two largest levels of a subdivision would need more than the
    /// limit ([`crate::memory::check_peak`]).
    #[error("{scheme} to level {levels} needs about {need} of memory (levels {prev} and {levels} with the input), more than the limit of {limit} (half the available memory)", prev = levels.saturating_sub(1))]
    OverMemoryLimit {
        /// The scheme.
        scheme: String,
        /// The last level.
        levels: u32,
        /// The predicted peak, e.g. `19.3 GiB`.
        need: String,
        /// The limit, e.g. `1.0 GiB`.
        limit: String,
    },
    /// A scheme without a real subdivision: a matrix whose file names no `topology`, or a
    /// rule that cannot run on this input (√3, Doo-Sabin and mid-edge on a raw face list).
    #[error("no real subdivision for scheme `{scheme}`: {reason}")]
    NoSubdivision {
        /// The scheme.
        scheme: String,
        /// Why, and what to do.
        reason: String,
    },
    /// A hole names a face the mesh does not have.
    #[error("hole face {face} is out of range (the mesh has {n_faces} faces)")]
    HoleOutOfRange {
        /// The face index (0-based).
        face: u32,
        /// The number of faces.
        n_faces: usize,
    },
    /// Holes under a rule whose faces do not nest, so that a hole has no descendants.
    #[error("holes need a rule whose faces nest (the 4:1 family, tri-split-N, Catmull-Clark); {rule} does not")]
    HolesNeedNestedFaces {
        /// The rule.
        rule: schemes::Rule,
    },
    /// The mesh is in the scheme's class for counting but the subdivision itself cannot run
    /// on it (e.g. a vertex of valence 2 for a dual scheme).
    #[error("{scheme} cannot subdivide this mesh: {reason}")]
    SchemeNotApplicable {
        /// The scheme.
        scheme: String,
        /// What is wrong, naming the element.
        reason: String,
    },
    /// The subdivision built a different number of elements than the scheme predicted (a bug).
    #[error("internal error: {scheme} level {level}: predicted {predicted} {what}, built {actual} (please report this)")]
    PredictionMismatch {
        /// The scheme.
        scheme: String,
        /// The level being built.
        level: u32,
        /// Which count ("vertices", "edges", "faces", a capacity).
        what: &'static str,
        /// The predicted count.
        predicted: num_bigint::BigInt,
        /// What the subdivision built.
        actual: u64,
    },
    /// A composition of schemes (`loop:1,sqrt3`) asked to carry what one rule defines alone
    /// (creases and corners, holes) from one stage to the next.
    #[error("{scheme}: a composition does not carry {what} from one stage to the next; use one scheme, or drop them (--ignore-tags for the file's tags)")]
    NotComposable {
        /// The composition.
        scheme: String,
        /// What it would have to carry.
        what: String,
    },
    /// The subdivision built an inconsistent mesh (a bug).
    #[error("internal error: {scheme} level {level}: {what} (please report this)")]
    InvalidOutput {
        /// The scheme.
        scheme: String,
        /// The level being built.
        level: u32,
        /// What is inconsistent.
        what: String,
    },
    /// A subdivision level whose mesh does not fit 32-bit handles.
    #[error(
        "{scheme} level {level} would have {count} {what}: more than 32-bit handles can address"
    )]
    TooLarge {
        /// The scheme.
        scheme: String,
        /// The level.
        level: u32,
        /// Which elements.
        what: &'static str,
        /// The predicted count.
        count: num_bigint::BigInt,
    },
    /// A generated base mesh larger than half the memory this process may allocate (as
    /// given to [`crate::shapes::from_name_within`]), refused before it is built.
    #[error("base mesh `{name}` would need {bytes} bytes of memory, more than the limit of {limit} bytes (half the memory available to this process)")]
    ShapeTooLarge {
        /// The name as given.
        name: String,
        /// The bytes its face list would need.
        bytes: u128,
        /// The limit in bytes.
        limit: u64,
    },
    /// The system refused memory for a large buffer (`try_reserve` failed): the process's
    /// limits are tighter than the guards estimated.
    #[error("cannot allocate {bytes} bytes for {what}: {reason}")]
    AllocationFailed {
        /// What the buffer is for.
        what: String,
        /// Its size in bytes.
        bytes: u128,
        /// The allocator's answer.
        reason: String,
    },
    /// A subdivision step computed a position that is not finite (an overflow of huge
    /// coordinates, a projection of a point at the origin): refused, nothing is returned.
    #[error("{scheme} level {level}: vertex {vertex} ({origin}) would be at ({x}, {y}, {z}), not a finite point")]
    NonFinitePosition {
        /// The scheme.
        scheme: String,
        /// The level being built.
        level: u32,
        /// The vertex of that level.
        vertex: u32,
        /// What it is computed from, naming the element of the level before.
        origin: String,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
        /// Its z coordinate.
        z: f64,
    },
    /// A subdivision computed a vertex color that is not finite (an overflow of huge color
    /// values, or a value beyond the range of `f32`): refused, nothing is written.
    #[error("{scheme} level {level}: the color of vertex {vertex} ({origin}) would be ({r}, {g}, {b}), not finite")]
    NonFiniteColor {
        /// The scheme.
        scheme: String,
        /// The level.
        level: u32,
        /// The vertex of that level.
        vertex: u32,
        /// What it is computed from.
        origin: String,
        /// Its red value.
        r: f64,
        /// Its green value.
        g: f64,
        /// Its blue value.
        b: f64,
    },
    /// A subdivision step computed a texture coordinate that is not finite (an overflow of
    /// huge `vt` values, or a value beyond the range of `f32`): refused, nothing is written.
    #[error("{scheme} level {level}: UV value {value} ({origin}) would be at ({u}, {v}), not a finite point")]
    NonFiniteUv {
        /// The scheme.
        scheme: String,
        /// The level being built.
        level: u32,
        /// The UV value of that level (an index into its texture coordinates).
        value: u32,
        /// What it is computed from.
        origin: String,
        /// Its u coordinate.
        u: f64,
        /// Its v coordinate.
        v: f64,
    },
    /// A caller's buffer of the wrong length for a refinement
    /// ([`crate::refine::Refinement`]): nothing is written.
    #[error("{what} buffer has {given} entries, expected {expected}")]
    BufferSize {
        /// Which buffer (`base`, `out`, `src`, `dst`, `triangle indices`, ...).
        what: &'static str,
        /// The length it must have.
        expected: usize,
        /// The length given.
        given: usize,
    },
    /// A refinement level outside `1..=levels` (or `0..=levels` for the sizes).
    #[error("level {level} is out of range: the refinement has levels {first}..={levels}")]
    LevelOutOfRange {
        /// The level asked for.
        level: u32,
        /// The first valid level.
        first: u32,
        /// The last level of the refinement.
        levels: u32,
    },
    /// An index buffer of fixed face degree asked of a level with other faces (triangles of a
    /// quad mesh, quads of a mixed one).
    #[error(
        "{what} need faces of {wanted} vertices, but face {face} of the last level has {degree}"
    )]
    FaceDegreeMismatch {
        /// What was asked (`triangles`, `quads`).
        what: &'static str,
        /// The face degree that buffer holds.
        wanted: usize,
        /// The first face of another degree.
        face: usize,
        /// Its degree.
        degree: usize,
    },
    /// An index buffer whose entries would not fit `u32`.
    #[error("{count} {what} do not fit 32-bit indices")]
    IndexOverflow {
        /// What the indices count (`face corners`, `vertices`).
        what: &'static str,
        /// How many there are.
        count: u128,
    },
    /// Stencils asked of a rule that is not a fixed linear combination of the base vertices.
    #[error("no stencils for {rule}: rule is not linear: {reason}")]
    NotLinear {
        /// The rule.
        rule: String,
        /// What makes it non-linear.
        reason: &'static str,
    },
    /// A stride that a rule coupling the components cannot evaluate (the sphere projection
    /// needs the whole vector in one `[T; N]`, N up to 16).
    #[error("{rule} cannot evaluate data of stride {stride}: {reason}")]
    UnsupportedStride {
        /// The rule.
        rule: String,
        /// The stride given.
        stride: usize,
        /// Why.
        reason: &'static str,
    },
    /// A crease or corner names a vertex the mesh does not have.
    #[error("{what} names vertex {vertex}, but the mesh has {vertices} vertices")]
    TagVertexOutOfRange {
        /// `crease` or `corner`.
        what: &'static str,
        /// The vertex named (0-based).
        vertex: u32,
        /// The vertices of the mesh.
        vertices: usize,
    },
    /// A crease whose two vertices no edge of the mesh joins.
    #[error("crease ({a}, {b}) is not an edge of the mesh")]
    CreaseNotAnEdge {
        /// One vertex of the crease (0-based, as given).
        a: u32,
        /// The other.
        b: u32,
    },
    /// The limit surface asked of a rule without limit masks (Loop and Catmull-Clark have them).
    #[error("the limit surface is computed under Loop and Catmull-Clark, not {rule}")]
    LimitNotSupported {
        /// The rule.
        rule: String,
    },
    /// Catmull-Clark's limit masks next to a face that is not a quad (level 0 only, so `face`
    /// is a face of the input, of `sides` sides): they weigh the corner opposite the vertex.
    #[error("face {face} has {sides} sides: Catmull-Clark's limit masks need quads around a vertex (every face after one level is one; evaluate the limit at level 1 or more)")]
    LimitNeedsQuads {
        /// The face.
        face: u32,
        /// Its sides.
        sides: usize,
    },
    /// The limit surface asked of a refinement built without it.
    #[error("the refinement was built without the limit surface (SubdivideOptions::limit)")]
    NoLimit,
    /// Creases, corners or crease options for a rule that has no crease rules.
    #[error("creases apply to Loop and Catmull-Clark, not {rule} ({what} given)")]
    CreasesNotSupported {
        /// The rule.
        rule: String,
        /// What was given (`creases and corners`, ...).
        what: &'static str,
    },
    /// A [`Sharpness`](crate::subdivide::Sharpness) resolved on another mesh.
    #[error(
        "the sharpness covers {edges} edges and {vertices} vertices, the mesh has {mesh_edges} \
         and {mesh_vertices}"
    )]
    SharpnessMismatch {
        /// Edges of the sharpness.
        edges: usize,
        /// Vertices of the sharpness.
        vertices: usize,
        /// Edges of the mesh.
        mesh_edges: usize,
        /// Vertices of the mesh.
        mesh_vertices: usize,
    },
    /// UVs asked of a rule that does not refine them (every built-in rule refines them: a
    /// rule without a face-varying step, or OpenSubdiv's channel asked of another rule).
    #[error("UVs are not refined under {rule} (no face-varying rule)")]
    UvsNotSupported {
        /// The rule.
        rule: String,
    },
    /// A UV layout ([`crate::uv::UvLayout`]) that is not of the mesh refined.
    #[error("the UV layout does not match the mesh: {reason}")]
    UvLayoutMismatch {
        /// What differs (corners, or a value used at two vertices).
        reason: String,
    },
    /// UVs evaluated on a refinement built without a UV layout
    /// ([`SubdivideOptions::uvs`](crate::subdivide::SubdivideOptions::uvs)).
    #[error("the refinement has no UVs (build it with SubdivideOptions::with_uvs)")]
    NoUvs,
    /// The thread pool for parallel subdivision could not be created.
    #[error("cannot start {threads} threads for subdivision: {reason}")]
    ThreadPool {
        /// Threads requested.
        threads: usize,
        /// The reason given by rayon.
        reason: String,
    },
    /// A value in the data of a PLY file (after its header) that could not be read, named by
    /// its element, the element's 0-based index and, when the problem is one value's, its
    /// property: ``bunny.ply: vertex 7, property `y`: coordinate `inf` is not finite``. (A
    /// problem in the header is [`Error::Parse`], naming the header line.)
    #[error("{file}: {element} {index}{}: {kind}", ply_property(property.as_deref()))]
    PlyData {
        /// The file name (as given for error messages).
        file: String,
        /// The element's name (`vertex`, `face`, ...; control characters escaped).
        element: String,
        /// The element's 0-based index among the elements of its kind.
        index: u64,
        /// The property, when the problem is one of its values.
        property: Option<String>,
        /// What is wrong (boxed: the variant stays as small as [`Error::Parse`]).
        kind: Box<ParseError>,
    },
}

/// `, property `NAME`` for [`Error::PlyData`] (nothing without a property).
fn ply_property(property: Option<&str>) -> String {
    property.map_or(String::new(), |p| format!(", property `{p}`"))
}

impl Error {
    /// Whether this is a refusal by a resource guard (memory or 32-bit handles), rather than
    /// bad input or a bug: [`Error::FileTooLarge`], [`Error::MeshTooLarge`],
    /// [`Error::ShapeTooLarge`], [`Error::AllocationFailed`], [`Error::TooLarge`],
    /// [`Error::TooManyElements`].
    pub fn is_resource_limit(&self) -> bool {
        matches!(
            self,
            Error::FileTooLarge { .. }
                | Error::MeshTooLarge { .. }
                | Error::ShapeTooLarge { .. }
                | Error::AllocationFailed { .. }
                | Error::OverMemoryLimit { .. }
                | Error::TooLarge { .. }
                | Error::TooManyElements { .. }
        )
    }

    /// The face a validation error is about (for two faces, the later one), as an index into
    /// the face list; map it to a file line with [`crate::PolygonMesh::face_line`].
    pub fn face(&self) -> Option<u32> {
        match self {
            Error::VertexOutOfRange { face, .. }
            | Error::FaceTooSmall { face, .. }
            | Error::RepeatedVertex { face, .. }
            | Error::NonOrientable { face, .. }
            | Error::LimitNeedsQuads { face, .. } => Some(*face),
            Error::DuplicateFace { second, .. } | Error::InconsistentOrientation { second, .. } => {
                Some(*second)
            }
            Error::NonManifoldEdge { faces, .. } => faces.0.last().copied(),
            _ => None,
        }
    }
}
