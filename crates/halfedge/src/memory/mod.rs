//! Memory for the resource guards: how many bytes a [`HalfEdgeMesh`] occupies, exactly and from
//! predicted counts, and the peak a subdivision will need ([`predicted_peak_bytes`]), so that a
//! subdivision is refused before it is built. These are sizes only: what they are compared with
//! (the bytes this process may still allocate) is read from the system by the front ends'
//! `driver::system`, never here. Refining UVs adds their face-varying
//! channel ([`predicted_uv_bytes`]) to either path's peak.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! `memory.rs`: the bytes of a mesh for given counts, `predicted_peak_bytes` (the peak resident
//! set of a one-shot run from the exact counts, what the CLI's guard compares: the process's 6
//! MiB, the input as face list and half-edge mesh and the arrays that build the latter
//! (`halfedge_build_bytes`; at level 0 the larger of them and the face list written), the last
//! two levels, and the
//! arrays below glibc's 32 MiB mmap threshold of level `L - 2`, freed but still resident; within 5
//! % of `/usr/bin/time -v` on the icosphere and armadillo jobs; the CLI adds what the file's face
//! list holds beyond its counts (`read_extra_bytes`: file lines, `vt`) and the face list copied
//! from a last level built as a half-edge mesh (`face_list_copy_bytes`);
//! `predicted_peak_bytes_with_creases` adds the last parent level's crease weight table while it
//! is built, `Refinement::one_shot_crease_bytes`, against the last level), `hole_filter_bytes` and
//! `refinement_hole_bytes` (what leaving holes out of a one-shot or refined output adds), for
//! the resource guards (`driver::system::available_bytes` is the other side: the least of
//! MemAvailable, RLIMIT_AS minus VmSize and the cgroup limit).
//!
//! Owner of the bytes of a mesh and the predicted peaks of the memory guards (the surface's, and what the UV channel adds:
//! `predicted_uv_bytes` of the layout's `MeshCounts`, `halfedge::stats::uv_layout_counts`):
//! `halfedge::memory`.

use num_bigint::BigInt;
use num_traits::ToPrimitive;
use schemes::{MeshCounts, Scheme};

use crate::{HalfEdgeMesh, PolygonMesh};

mod carried;
mod refinement;
mod uv;

pub use self::carried::{carried_bytes, Carrying};
pub use self::refinement::{predicted_limit_bytes, predicted_refinement_peak_bytes};
pub use self::uv::predicted_uv_bytes;

/// Bytes per vertex: a `DVec3` position (24) and one outgoing half-edge (`u32`, 4).
pub const BYTES_PER_VERTEX: u64 = 24 + 4;
/// Bytes per edge: two half-edges, each with target vertex, face, next and prev (`u32` each).
pub const BYTES_PER_EDGE: u64 = 2 * 4 * 4;
/// Bytes per face: one half-edge (`u32`).
pub const BYTES_PER_FACE: u64 = 4;

impl HalfEdgeMesh {
    /// The bytes of the arrays of a mesh with `vertices`, `edges` and `faces` elements
    /// (exact for this crate's layout; capacity equals length when preallocated).
    ///
    /// ```
    /// use halfedge::HalfEdgeMesh;
    /// let ico = HalfEdgeMesh::try_from(&halfedge::shapes::icosahedron())?;
    /// assert_eq!(ico.heap_bytes() as u128, HalfEdgeMesh::bytes_for(12, 30, 20));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn bytes_for(vertices: u64, edges: u64, faces: u64) -> u128 {
        u128::from(vertices) * u128::from(BYTES_PER_VERTEX)
            + u128::from(edges) * u128::from(BYTES_PER_EDGE)
            + u128::from(faces) * u128::from(BYTES_PER_FACE)
    }

    /// The bytes this mesh's arrays occupy (their lengths; see [`bytes_for`](Self::bytes_for)).
    pub fn heap_bytes(&self) -> usize {
        self.positions.len() * std::mem::size_of::<glam::DVec3>()
            + (self.vertex_halfedge.len()
                + self.halfedge_vertex.len()
                + self.halfedge_face.len()
                + self.halfedge_next.len()
                + self.halfedge_prev.len()
                + self.face_halfedge.len())
                * std::mem::size_of::<u32>()
    }
}

impl PolygonMesh {
    /// The bytes of the arrays of a face list with `vertices` positions (a `DVec3`, 24 bytes
    /// each), `faces` faces (one `usize` offset each, plus one) and `corners` face corners in
    /// all (a `u32` each), as [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list)
    /// builds it (no file lines).
    ///
    /// ```
    /// use halfedge::PolygonMesh;
    /// let cube = halfedge::shapes::cube();
    /// assert_eq!(cube.heap_bytes() as u128, PolygonMesh::bytes_for(8, 6, 24));
    /// ```
    pub fn bytes_for(vertices: u64, faces: u64, corners: u64) -> u128 {
        u128::from(vertices) * 24
            + (u128::from(faces) + 1) * std::mem::size_of::<usize>() as u128
            + u128::from(corners) * 4
    }

    /// The bytes this face list's arrays occupy (their lengths, file lines included; see
    /// [`bytes_for`](Self::bytes_for)).
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(self.positions.as_slice())
            + std::mem::size_of_val(self.face_offsets())
            + std::mem::size_of_val(self.face_indices())
            + self.face_lines_len() * std::mem::size_of::<u64>()
            + self.colors().map_or(0, std::mem::size_of_val)
            + self
                .groups()
                .map_or(0, crate::groups::FaceGroups::heap_bytes)
    }
}

/// The resident bytes of the process itself before it allocates any mesh (code, libraries,
/// stacks, the allocator's arenas): what `subcount subdivide --base icosahedron --levels 0`
/// peaks at, 5.9 MiB measured, rounded up.
pub const PROCESS_BYTES: u64 = 6 << 20;

/// The peak resident memory of a one-shot subdivision of a mesh with `counts` by `scheme` to
/// level `levels`, as `subcount subdivide` runs it (it keeps the face list it read and the
/// half-edge mesh built from it), from the scheme's exact counts; the prediction of the memory
/// guard, the sum of
///
/// - [`PROCESS_BYTES`];
/// - the input, as the face list it was read into ([`PolygonMesh::bytes_for`]; a file's
///   lines and UVs are the caller's: [`read_extra_bytes`]) and as a half-edge mesh
///   ([`HalfEdgeMesh::bytes_for`]), and the transient arrays of building the latter
///   ([`halfedge_build_bytes`]);
/// - the two levels alive at once at the end (levels `levels - 1` and `levels`, the largest
///   two; only level 1 when `levels = 1`): with `last_faces = Some(d)` the last level is a face
///   list of `d`-gons as [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list)
///   builds it, else a half-edge mesh;
/// - from 3 levels on, level `levels - 2` as a half-edge mesh: it is freed while the last
///   level is built, but the allocator keeps the heap blocks of the small early levels
///   resident (glibc carves blocks below its mmap threshold, which rises up to 32 MiB as large
///   blocks are freed, from a heap it does not give back), and the peak resident set counts
///   them. Measured on the 81,920-face icosphere (Loop and Catmull-Clark, 3 levels) and
///   armadillo.obj (2 levels): within 5 % of the peak `/usr/bin/time -v` reports.
///
/// Computed on big integers, so a level far beyond any memory is a number, not an overflow.
/// `levels = 0`: the process, the input and the face list written from its half-edge mesh.
///
/// # Errors
///
/// The scheme's error when `counts` are outside its class ([`Scheme::counts_at`]).
///
/// ```
/// use halfedge::memory::{predicted_peak_bytes, PROCESS_BYTES};
/// use halfedge::{HalfEdgeMesh, PolygonMesh};
/// let ico = HalfEdgeMesh::try_from(&halfedge::shapes::icosahedron())?;
/// let loop_ = schemes::builtin("loop")?;
/// let peak = predicted_peak_bytes(&loop_, &ico.counts(), 3, None)?;
/// // The input as a face list and as a half-edge mesh, level 1 (freed, still resident),
/// // levels 2 and 3.
/// let levels = [(12, 30, 20), (42, 120, 80), (162, 480, 320), (642, 1920, 1280)];
/// let sum: u128 = levels.iter().map(|&(v, e, f)| HalfEdgeMesh::bytes_for(v, e, f)).sum();
/// let input = PolygonMesh::bytes_for(12, 20, 60);
/// assert_eq!(peak, (u128::from(PROCESS_BYTES) + input + sum).into());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn predicted_peak_bytes(
    scheme: &Scheme,
    counts: &MeshCounts,
    levels: u32,
    last_faces: Option<usize>,
) -> Result<BigInt, schemes::Error> {
    let arrays = arrays_peak_bytes(scheme, counts, levels, last_faces)?;
    let c = scheme.counts_at(counts, 0)?;
    // PolygonMesh::bytes_for on big integers.
    let input_faces: BigInt = BigInt::from(24) * &c.vertices
        + BigInt::from(std::mem::size_of::<usize>()) * (&c.faces + 1)
        + BigInt::from(4) * counts.corners;
    let freed = if levels >= 3 {
        heap_resident_bytes(scheme, counts, u64::from(levels) - 2)?
    } else {
        BigInt::from(0)
    };
    // Building the input's half-edge mesh: its transients are freed before the first level
    // (measured: armadillo's levels 1-3 and the 5.5 M-face level 3 read back peak without
    // them), but at level 0 they are the peak unless the face list written from the mesh is
    // larger.
    let transient = if levels == 0 {
        halfedge_build_bytes(counts).max(input_faces.clone())
    } else {
        BigInt::from(0)
    };
    Ok(arrays + input_faces + transient + freed + PROCESS_BYTES)
}

/// The transient arrays of building the input's half-edge mesh from its face list (the
/// crate's `build.rs`), alive next to the face list and the half-edge arrays: each corner's
/// side (8 bytes) and half-edge (4), and per vertex its bucket's start (then its
/// component), its last corner, its new number and, in a mesh of quads (about as many faces
/// as vertices), a face's vertex across from its smallest (16). Freed once the mesh is
/// built; [`predicted_peak_bytes`] counts them at level 0 (or the face list written, if
/// larger). Without them `subdivide --levels 0` of a 314 MB quad grid
/// peaked at 2.2 times the prediction.
///
/// ```
/// use halfedge::memory::halfedge_build_bytes;
/// let cube = halfedge::stats::face_list_counts(&halfedge::shapes::cube());
/// assert_eq!(halfedge_build_bytes(&cube), (12 * 24 + 16 * 8).into());
/// ```
pub fn halfedge_build_bytes(counts: &MeshCounts) -> BigInt {
    BigInt::from(12) * counts.corners + BigInt::from(16) * counts.vertices
}

/// What the face list `poly` holds as it was read beyond the arrays
/// [`PolygonMesh::bytes_for`] counts from its statistics (what [`predicted_peak_bytes`]
/// counts for the input): the file line of each face (8 bytes), positions no face uses (24
/// each), its UVs, `vt` and the `vt` of each corner (16 and 4 bytes), its vertex colors (24
/// bytes a vertex), its groups ([`crate::groups::FaceGroups::heap_bytes`], 4 bytes a face
/// and the names) and the reader's buffers (2 MiB, when read from an OBJ file). The caller
/// adds it to a prediction made from the counts alone.
///
/// ```
/// use halfedge::memory::read_extra_bytes;
/// // A generated mesh: no file lines, no UVs.
/// assert_eq!(read_extra_bytes(&halfedge::shapes::cube()), 0);
/// ```
pub fn read_extra_bytes(poly: &PolygonMesh) -> u128 {
    let mut used = vec![false; poly.positions.len()];
    for &v in poly.face_indices() {
        if let Some(u) = used.get_mut(v as usize) {
            *u = true;
        }
    }
    let unreferenced = used.iter().filter(|&&u| !u).count() as u64;
    let uvs = poly.uvs().map_or(0, |u| {
        16 * u.coords().len() as u128 + 4 * u.corners().len() as u128
    });
    let colors = poly.colors().map_or(0, |c| 24 * c.len() as u128);
    let groups = poly.groups().map_or(0, |g| g.heap_bytes() as u128);
    // A file read leaves the reader's chunk buffers behind (1 MiB of lines and the line
    // being assembled across chunks).
    let reader = match poly.face_lines_len() {
        0 => 0,
        _ => READ_BUFFER_BYTES,
    };
    8 * poly.face_lines_len() as u128
        + 24 * u128::from(unreferenced)
        + uvs
        + colors
        + groups
        + reader
}

/// The buffers an OBJ read holds beside the face list ([`read_extra_bytes`]).
const READ_BUFFER_BYTES: u128 = 2 << 20;

/// [`predicted_peak_bytes`] of `rule`'s counting scheme ([`Rule::scheme_for`](crate::Rule::scheme_for))
/// when the one-shot subdivision runs under crease rules (a sharpness or options that change
/// something: [`SubdivideOptions::sharpness`](crate::subdivide::SubdivideOptions::sharpness)).
/// The last parent level's weight table is built, and used, before the last level exists and
/// dropped before its faces are built, so the peak has, next to the input and level
/// `levels - 1`, the larger of the last level and what building the table holds
/// ([`Refinement::one_shot_crease_bytes`](crate::Refinement::one_shot_crease_bytes)) plus the
/// last level's positions. For rules without crease rules it is [`predicted_peak_bytes`].
/// Linear in a face's degree: a face of more than 32 sides counts 4 table entries per side
/// (an overriding row names it by its child point), not its degree. Measured on an
/// 80,000-gon with creases on every edge at Catmull-Clark level 1 (release): a 23 MB peak,
/// 44 MB predicted (307 GB while a face counted `d²` entries per side).
/// Measured on osd_catmark_pawn.obj at Catmull-Clark level 5 (debug build, one thread): a
/// peak of 123 MB, 149 MB predicted (an upper bound: the table's bound is up to 15 % over and
/// is counted twice, its chunk not all resident); without its creases 59 MB and 53 MB.
///
/// ```
/// use halfedge::memory::{predicted_peak_bytes, predicted_peak_bytes_with_creases};
/// use halfedge::Rule;
/// let cube = halfedge::stats::face_list_counts(&halfedge::shapes::cube());
/// let cc = schemes::builtin("catmull-clark")?;
/// let plain = predicted_peak_bytes(&cc, &cube, 3, Some(4))?;
/// let creased = predicted_peak_bytes_with_creases(Rule::CatmullClark, &cube, 3, Some(4))?;
/// assert!(creased > plain);
/// let sqrt3 = schemes::builtin("sqrt3")?;
/// let ico = halfedge::stats::face_list_counts(&halfedge::shapes::icosahedron());
/// assert_eq!(
///     predicted_peak_bytes_with_creases(Rule::Sqrt3, &ico, 3, None)?,
///     predicted_peak_bytes(&sqrt3, &ico, 3, None)?
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// [`Error::Scheme`](crate::Error::Scheme) when the rule does not apply.
pub fn predicted_peak_bytes_with_creases(
    rule: crate::Rule,
    counts: &MeshCounts,
    levels: u32,
    last_faces: Option<usize>,
) -> crate::Result<BigInt> {
    let scheme = rule.scheme_for(counts)?;
    let peak = predicted_peak_bytes(&scheme, counts, levels, last_faces)?;
    let table = crate::Refinement::one_shot_crease_bytes(rule, counts, levels)?;
    if levels == 0 || table == BigInt::from(0) {
        return Ok(peak);
    }
    let last = last_level_bytes(&scheme, counts, levels, last_faces)?;
    let positions = BigInt::from(24) * scheme.counts_at(counts, u64::from(levels))?.vertices;
    let crease_side = table + positions;
    Ok(if crease_side > last {
        peak + crease_side - last
    } else {
        peak
    })
}

/// glibc's largest mmap threshold (`DEFAULT_MMAP_THRESHOLD_MAX` on 64-bit targets): a block
/// at least this large is always mapped on its own and unmapped when freed.
const MMAP_THRESHOLD_MAX: u64 = 32 << 20;

/// The arrays of the half-edge mesh of level `s` that stay resident once freed: the ones
/// below [`MMAP_THRESHOLD_MAX`] (positions, then the connectivity of
/// [`connectivity_resident_bytes`]: vertex half-edges, the four half-edge arrays, face
/// half-edges).
fn heap_resident_bytes(
    scheme: &Scheme,
    counts: &MeshCounts,
    s: u64,
) -> Result<BigInt, schemes::Error> {
    let c = scheme.counts_at(counts, s)?;
    Ok(below_mmap_threshold([(BigInt::from(24) * &c.vertices, 1)]) + connectivity_resident(&c))
}

/// The total of `(bytes, copies)` arrays whose size is below [`MMAP_THRESHOLD_MAX`]: what
/// stays resident of them once freed.
fn below_mmap_threshold<const N: usize>(arrays: [(BigInt, u32); N]) -> BigInt {
    let limit = BigInt::from(MMAP_THRESHOLD_MAX);
    arrays
        .into_iter()
        .filter(|(bytes, _)| *bytes < limit)
        .map(|(bytes, n)| bytes * n)
        .sum()
}

/// The connectivity arrays of a level with counts `c` (4 bytes per vertex and per face, four
/// arrays of 8 bytes per edge) that stay resident once freed.
fn connectivity_resident(c: &schemes::LevelCounts) -> BigInt {
    below_mmap_threshold([
        (BigInt::from(4) * &c.vertices, 1),
        (BigInt::from(8) * &c.edges, 4),
        (BigInt::from(4) * &c.faces, 1),
    ])
}

/// The bytes of the half-edge mesh of level `s` of `scheme` ([`HalfEdgeMesh::bytes_for`]).
fn halfedge_bytes(scheme: &Scheme, counts: &MeshCounts, s: u64) -> Result<BigInt, schemes::Error> {
    let c = scheme.counts_at(counts, s)?;
    Ok(BigInt::from(BYTES_PER_VERTEX) * &c.vertices
        + BigInt::from(BYTES_PER_EDGE) * &c.edges
        + BigInt::from(BYTES_PER_FACE) * &c.faces)
}

/// The arrays alive at the peak of a one-shot subdivision: the input half-edge mesh and levels
/// `levels - 1` and `levels` (see [`predicted_peak_bytes`]).
fn arrays_peak_bytes(
    scheme: &Scheme,
    counts: &MeshCounts,
    levels: u32,
    last_faces: Option<usize>,
) -> Result<BigInt, schemes::Error> {
    let bytes = |s: u64| halfedge_bytes(scheme, counts, s);
    let input = bytes(0)?;
    if levels == 0 {
        return Ok(input);
    }
    let last = last_level_bytes(scheme, counts, levels, last_faces)?;
    Ok(if levels == 1 {
        input + last
    } else {
        input + bytes(u64::from(levels) - 1)? + last
    })
}

/// The bytes of the last level of a one-shot subdivision (`levels >= 1`): a face list of
/// `d`-gons with `last_faces = Some(d)`, else a half-edge mesh.
fn last_level_bytes(
    scheme: &Scheme,
    counts: &MeshCounts,
    levels: u32,
    last_faces: Option<usize>,
) -> Result<BigInt, schemes::Error> {
    Ok(match last_faces {
        Some(degree) => {
            // PolygonMesh::bytes_for on big integers: 24 per position, one `usize` per face
            // offset (one more than the faces), 4 per corner.
            let c = scheme.counts_at(counts, u64::from(levels))?;
            BigInt::from(24) * &c.vertices
                + BigInt::from(std::mem::size_of::<usize>()) * (&c.faces + 1)
                + BigInt::from(4 * degree) * &c.faces
        }
        None => halfedge_bytes(scheme, counts, u64::from(levels))?,
    })
}

/// What writing a last level built as a half-edge mesh (`last_faces` `None` in
/// [`predicted_peak_bytes`]: √3, the dual rules, the general subdividers) adds to the peak of
/// [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list): its face list, made
/// while the mesh is alive (at most `2E` corners). 0 at level 0 (counted there already).
///
/// ```
/// use halfedge::memory::face_list_copy_bytes;
/// let cube = halfedge::stats::face_list_counts(&halfedge::shapes::cube());
/// let ds = schemes::builtin("doo-sabin")?;
/// // Level 1: 24 vertices, 48 edges, 26 faces.
/// assert_eq!(face_list_copy_bytes(&ds, &cube, 1)?, (24 * 24 + 8 * 27 + 4 * 96).into());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// As [`predicted_peak_bytes`].
pub fn face_list_copy_bytes(
    scheme: &Scheme,
    counts: &MeshCounts,
    levels: u32,
) -> Result<BigInt, schemes::Error> {
    if levels == 0 {
        return Ok(BigInt::from(0));
    }
    let c = scheme.counts_at(counts, u64::from(levels))?;
    Ok(BigInt::from(24) * &c.vertices
        + BigInt::from(std::mem::size_of::<usize>()) * (&c.faces + 1)
        + BigInt::from(8) * &c.edges)
}

/// The bytes leaving holes out of the last level adds to [`predicted_peak_bytes`] (the face
/// list is compacted in place, [`crate::holes`]): the new number of every vertex of the
/// whole level and the old index of each kept one (4 bytes each per vertex), which faces
/// descend from holes (1 byte per face); and, for a last level built as a half-edge mesh
/// (`last_faces` `None`), the face list it becomes (at most `2 E` corners).
///
/// ```
/// use halfedge::memory::hole_filter_bytes;
/// let cube = halfedge::stats::face_list_counts(&halfedge::shapes::cube());
/// let cc = schemes::builtin("catmull-clark")?;
/// // Level 1: 26 vertices, 24 faces.
/// assert_eq!(hole_filter_bytes(&cc, &cube, 1, Some(4))?, (8 * 26 + 24).into());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
///
/// As [`predicted_peak_bytes`].
pub fn hole_filter_bytes(
    scheme: &Scheme,
    counts: &MeshCounts,
    levels: u32,
    last_faces: Option<usize>,
) -> Result<BigInt, schemes::Error> {
    let c = scheme.counts_at(counts, u64::from(levels))?;
    let mut bytes = BigInt::from(8) * &c.vertices + &c.faces;
    if last_faces.is_none() {
        bytes += BigInt::from(24) * &c.vertices
            + BigInt::from(std::mem::size_of::<usize>()) * (&c.faces + 1)
            + BigInt::from(8) * &c.edges;
    }
    Ok(bytes)
}

/// What holes add to [`predicted_refinement_peak_bytes`] (a refinement that writes only the
/// faces that are not holes): the whole last level's corners and offsets, built once before the
/// written faces are kept, and the kept face list (each at most `2E` corners and `F + 1`
/// offsets of 4 bytes), the map of written vertices (4 bytes each), the whole last level's
/// values in the evaluator (`3 * scalar_bytes` per vertex) and the transient mask and map of
/// [`hole_filter_bytes`]. An upper bound.
///
/// # Errors
///
/// The scheme's error when it does not apply to `counts`.
pub fn refinement_hole_bytes(
    scheme: &Scheme,
    counts: &MeshCounts,
    levels: u32,
    scalar_bytes: usize,
) -> Result<BigInt, schemes::Error> {
    let c = scheme.counts_at(counts, u64::from(levels))?;
    let face_list = BigInt::from(4) * (BigInt::from(2) * &c.edges + &c.faces + 1);
    Ok(BigInt::from(2) * face_list
        + BigInt::from(4 + 3 * scalar_bytes) * &c.vertices
        + hole_filter_bytes(scheme, counts, levels, Some(4))?)
}

/// The memory guard of real subdivision: [`predicted_peak_bytes`] of `scheme` to `levels`,
/// refused with [`Error::OverMemoryLimit`](crate::Error::OverMemoryLimit) when it exceeds `limit` (e.g. `driver::system::peak_limit`).
///
/// # Errors
///
/// [`Error::OverMemoryLimit`](crate::Error::OverMemoryLimit), or [`Error::Scheme`](crate::Error::Scheme) when the scheme does not apply.
///
/// ```
/// use halfedge::memory::check_peak;
/// let ico = halfedge::stats::face_list_counts(&halfedge::shapes::icosahedron());
/// let lp = schemes::builtin("loop")?;
/// assert!(check_peak(&lp, &ico, 5, None, 1 << 30).is_ok());
/// let err = check_peak(&lp, &ico, 12, None, 1 << 30).unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "loop to level 12 needs about 25.8 GiB of memory (levels 11 and 12 with the input), more than the limit of 1.0 GiB (half the available memory)"
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn check_peak(
    scheme: &Scheme,
    counts: &MeshCounts,
    levels: u32,
    last_faces: Option<usize>,
    limit: u128,
) -> crate::Result<BigInt> {
    let need = predicted_peak_bytes(scheme, counts, levels, last_faces)?;
    within_limit(need, scheme.name(), levels, limit)
}

/// The peak that reading a face list's statistics adds to the face list itself: its counts
/// ([`crate::stats::face_list_counts`]: every side sorted), its problems
/// ([`crate::stats::face_list_problems`]: repeated faces, orientation) and the half-edge mesh
/// built from it. Measured with `subcount stats` (peak resident size less the face list's
/// [`PolygonMesh::heap_bytes`]): 29 bytes per corner on 2 M triangles over 3 vertices (176
/// MB), 43 on `buildings_400k` (1.2 M corners, 400 k faces, 200 k vertices: 52 MB); taken
/// here as 32 bytes per corner, face and vertex (192 and 58 MB). Every command that reads a mesh is refused (exit 4) before this analysis when
/// the face list and this do not fit half the memory available.
///
/// ```
/// use halfedge::memory::face_list_analysis_bytes;
/// assert_eq!(face_list_analysis_bytes(&halfedge::shapes::cube()), 32 * (24 + 6 + 8));
/// ```
pub fn face_list_analysis_bytes(mesh: &PolygonMesh) -> u128 {
    32 * (mesh.n_corners() as u128 + mesh.n_faces() as u128 + mesh.n_vertices() as u128)
}

/// `need` if it is at most `limit`, else [`Error::OverMemoryLimit`](crate::Error::OverMemoryLimit)
/// naming `scheme` and `levels` (the test of [`check_peak`], for any prediction).
///
/// # Errors
///
/// [`Error::OverMemoryLimit`](crate::Error::OverMemoryLimit).
pub fn within_limit(need: BigInt, scheme: &str, levels: u32, limit: u128) -> crate::Result<BigInt> {
    if need > BigInt::from(limit) {
        return Err(crate::Error::OverMemoryLimit {
            scheme: scheme.to_owned(),
            levels,
            need: human_bytes(need.to_f64().unwrap_or(f64::INFINITY)),
            limit: human_bytes(limit as f64),
        });
    }
    Ok(need)
}

/// `1.5 GiB`-style rendering of a byte count (binary units, one decimal).
///
/// ```
/// use halfedge::memory::human_bytes;
/// assert_eq!(human_bytes(512.0), "512 bytes");
/// assert_eq!(human_bytes(1536.0), "1.5 KiB");
/// assert_eq!(human_bytes(f64::INFINITY), "10^30+ bytes");
/// ```
pub fn human_bytes(bytes: f64) -> String {
    if !bytes.is_finite() || bytes > 1e30 {
        return "10^30+ bytes".to_string();
    }
    const UNITS: [&str; 7] = ["bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut v = bytes;
    let mut unit = 0;
    while v >= 1024.0 && unit + 1 < UNITS.len() {
        v /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{v:.0} bytes")
    } else if v >= 1024.0 {
        format!("{:.3e} {}", v, UNITS[unit])
    } else {
        format!("{v:.1} {}", UNITS[unit])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_predicted_peak_is_what_subdivision_allocates() {
        use crate::subdivide::{subdivide, subdivide_to_face_list, SubdivideOptions};
        let opts = SubdivideOptions::default();
        let bytes = |m: &HalfEdgeMesh| BigInt::from(m.heap_bytes());
        let shapes = [
            ("cube", crate::shapes::cube(), crate::Rule::CatmullClark),
            ("mixed", crate::shapes::mixed(), crate::Rule::CatmullClark),
            (
                "icosahedron",
                crate::shapes::icosahedron(),
                crate::Rule::Loop,
            ),
            (
                "grid",
                crate::shapes::grid(3, 2).expect("grid"),
                crate::Rule::Loop,
            ),
        ];
        for (name, poly, rule) in shapes {
            let mesh = HalfEdgeMesh::try_from(&poly).expect("a valid shape");
            let scheme = rule.scheme_for(&mesh.counts()).expect("scheme");
            let level = |s: u32| subdivide(&mesh, rule, s, &opts).expect("level");
            let degree = crate::subdivide::direct_face_degree(rule);
            // The input as read: a face list without file lines, so heap_bytes is exact.
            let input = BigInt::from(poly.heap_bytes()) + bytes(&mesh) + PROCESS_BYTES;
            for levels in 0..=4 {
                let arrays = |last| arrays_peak_bytes(&scheme, &mesh.counts(), levels, last);
                let peak = |last| predicted_peak_bytes(&scheme, &mesh.counts(), levels, last);
                let last = level(levels);
                let faces = subdivide_to_face_list(&mesh, rule, levels, &opts).expect("faces");
                // The two levels alive at the end (only the input at level 0).
                let before = match levels {
                    0 => BigInt::from(0),
                    1 => bytes(&mesh),
                    _ => bytes(&mesh) + bytes(&level(levels - 1)),
                };
                let (as_mesh, as_faces) = if levels == 0 {
                    (bytes(&mesh), bytes(&mesh))
                } else {
                    (
                        &before + bytes(&last),
                        &before + BigInt::from(faces.mesh.heap_bytes()),
                    )
                };
                assert_eq!(arrays(None).expect("arrays"), as_mesh, "{name} {levels}");
                if levels > 0 {
                    assert_eq!(arrays(degree).expect("faces"), as_faces, "{name} {levels}");
                }
                // Level levels - 2, freed while the last is built: small arrays, all resident.
                let freed = match levels {
                    0..=2 => BigInt::from(0),
                    _ => bytes(&level(levels - 2)),
                };
                // Level 0 is written from a face list of the input, after the build's
                // transients are freed.
                let build = halfedge_build_bytes(&mesh.counts());
                let transient = match levels {
                    0 => build.max(BigInt::from(poly.heap_bytes())),
                    _ => BigInt::from(0),
                };
                let expected =
                    &input - bytes(&mesh) + arrays(None).expect("arrays") + freed + transient;
                assert_eq!(peak(None).expect("peak"), expected, "{name} {levels}");
            }
        }
        // Far beyond any memory: a number, not an overflow.
        let cube = HalfEdgeMesh::try_from(&crate::shapes::cube()).expect("cube");
        let cc = schemes::builtin("catmull-clark").expect("catmull-clark");
        let peak = |levels| predicted_peak_bytes(&cc, &cube.counts(), levels, None);
        assert!(peak(60).expect("60") > BigInt::from(u128::MAX));
    }

    #[test]
    fn only_the_small_arrays_of_a_freed_level_stay_resident() {
        // Level 7 of the icosahedron under Loop: 163,842 vertices (3.9 MB of positions),
        // 491,520 edges, 327,680 faces: every array below 32 MiB. Level 10: 10,485,762
        // vertices (252 MB of positions, 42 MB of vertex half-edges), 31,457,280 edges (252 MB
        // per half-edge array) and 20,971,520 faces (84 MB of face half-edges): none.
        let ico = HalfEdgeMesh::try_from(&crate::shapes::icosahedron()).expect("ico");
        let lp = schemes::builtin("loop").expect("loop");
        let counts = ico.counts();
        let resident = |s| heap_resident_bytes(&lp, &counts, s).expect("resident");
        assert_eq!(
            resident(7),
            BigInt::from(HalfEdgeMesh::bytes_for(163_842, 491_520, 327_680))
        );
        assert_eq!(resident(10), BigInt::from(0));
        // Level 9: 2,621,442 vertices: positions 63 MB (mapped), vertex half-edges 10.5 MB
        // (resident); 7,864,320 edges: 63 MB per half-edge array (mapped); 5,242,880 faces:
        // 21 MB (resident).
        assert_eq!(resident(9), BigInt::from(4 * 2_621_442 + 4 * 5_242_880));
    }

    #[test]
    fn the_predicted_peak_refuses_counts_outside_the_scheme() {
        let cube = HalfEdgeMesh::try_from(&crate::shapes::cube()).expect("cube");
        let loop_ = schemes::builtin("loop").expect("loop");
        let err = predicted_peak_bytes(&loop_, &cube.counts(), 1, None).unwrap_err();
        assert!(err.to_string().contains("triangle"), "{err}");
    }
}
