//! What the differential tests against OpenSubdiv share (`tests/opensubdiv.rs` and the CLI's
//! `crates/subcount/tests/cli/creases.rs`, which includes this file by path): running the
//! repository's driver (`tools/osd-driver`, found through [`DRIVER_VAR`]) and comparing two
//! last levels vertex for vertex (positions matched through a spatial hash, to [`TOLERANCE`]
//! of the base mesh's bounding-box diagonal) and face for face. [`fvar`] runs the driver with
//! its face-varying UV channel (`--fvar MODE`, `--fvar-counts`).

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use halfedge::glam::DVec3;
use halfedge::{io, PolygonMesh};

pub(crate) mod fvar;

/// Positions must agree to this fraction of the base mesh's bounding-box diagonal.
pub(crate) const TOLERANCE: f64 = 1e-12;

/// The environment variable naming the OpenSubdiv driver binary.
pub(crate) const DRIVER_VAR: &str = "SUBCOUNT_OSD_DRIVER";

/// The two schemes compared, with OpenSubdiv's name for each.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Osd {
    Loop,
    Catmark,
}

impl Osd {
    pub(crate) fn driver_name(self) -> &'static str {
        match self {
            Osd::Loop => "loop",
            Osd::Catmark => "catmark",
        }
    }

    /// The scheme's faces at `level` on a base mesh of `faces` faces with `corners` corners.
    pub(crate) fn faces_at(self, faces: usize, corners: usize, level: u32) -> u64 {
        let quads = 4_u64.pow(level.saturating_sub(1));
        match self {
            Osd::Loop => faces as u64 * 4 * quads,
            Osd::Catmark => corners as u64 * quads,
        }
    }
}

/// The OpenSubdiv driver: `$SUBCOUNT_OSD_DRIVER`, a relative value taken from the workspace
/// root; panics, naming the variable and how to build the driver, when it is unset or names no
/// file.
pub(crate) fn driver() -> PathBuf {
    let build = "build it with `tools/osd-driver/build.sh` (needs `apt-get install libosd-dev \
                 g++`) and run with SUBCOUNT_OSD_DRIVER=target/osd-driver/osd_driver";
    let value = std::env::var_os(DRIVER_VAR)
        .filter(|v| !v.is_empty())
        .unwrap_or_else(|| {
            panic!("{DRIVER_VAR} is not set: this test compares with OpenSubdiv through its driver; {build}")
        });
    let manifest_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = manifest_dir.ancestors().nth(2).unwrap_or(manifest_dir);
    let path = root.join(PathBuf::from(value));
    assert!(
        path.is_file(),
        "{DRIVER_VAR}={} names no file ({}): {build}",
        Path::new(&std::env::var_os(DRIVER_VAR).unwrap_or_default()).display(),
        path.display()
    );
    path
}

/// As [`opensubdiv`], with the driver's options `flags` first (`--tags`, `--crease-method M`,
/// `--triangle-rule R`) and the boundary interpolation only when given (else the file's tag,
/// else `edge-only`).
pub(crate) fn opensubdiv_with(
    flags: &[&str],
    scheme: Osd,
    level: u32,
    path: &Path,
    boundary: Option<&str>,
) -> Running {
    let driver = driver();
    let child = Command::new(&driver)
        .args(flags)
        .arg(scheme.driver_name())
        .arg(level.to_string())
        .arg(path)
        .args(boundary)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", driver.display()));
    Running {
        child,
        what: format!(
            "osd_driver {}{} {level} {}",
            flags.iter().map(|f| format!("{f} ")).collect::<String>(),
            scheme.driver_name(),
            path.display()
        ),
    }
}

/// A driver process writing its OBJ.
pub(crate) struct Running {
    child: std::process::Child,
    what: String,
}

impl Running {
    /// What the driver wrote to stdout, once it has finished successfully; panics, with the
    /// command and the driver's stderr, when it fails.
    pub(crate) fn stdout(self) -> (Vec<u8>, String) {
        let output = self
            .child
            .wait_with_output()
            .unwrap_or_else(|e| panic!("{}: {e}", self.what));
        assert!(
            output.status.success(),
            "{} failed: {}",
            self.what,
            String::from_utf8_lossy(&output.stderr)
        );
        (output.stdout, self.what)
    }

    /// The driver's output, once it has finished; panics when it fails.
    pub(crate) fn mesh(self) -> PolygonMesh {
        let (stdout, what) = self.stdout();
        io::read_obj_from(stdout.as_slice(), "osd_driver output")
            .unwrap_or_else(|e| panic!("{what} wrote an unreadable OBJ: {e}"))
    }

    /// What the driver writes of its output: the faces it does not list as holes (its
    /// `# hole F` comments) and the vertices they use, renumbered in order.
    pub(crate) fn written(self) -> (PolygonMesh, usize) {
        let (stdout, what) = self.stdout();
        let text = String::from_utf8_lossy(&stdout);
        let holes: std::collections::HashSet<usize> = text
            .lines()
            .filter_map(|l| l.strip_prefix("# hole "))
            .map(|f| f.trim().parse().expect("a face index"))
            .collect();
        let all = io::read_obj_from(stdout.as_slice(), "osd_driver output")
            .unwrap_or_else(|e| panic!("{what} wrote an unreadable OBJ: {e}"));
        let kept = PolygonMesh::from_faces(
            all.positions.clone(),
            (0..all.n_faces())
                .filter(|f| !holes.contains(f))
                .map(|f| all.face(f).to_vec()),
        );
        (without_bare_vertices(&kept), holes.len())
    }
}

/// The mesh without the vertices no face uses, the others renumbered in order.
pub(crate) fn without_bare_vertices(mesh: &PolygonMesh) -> PolygonMesh {
    let mut used = vec![false; mesh.n_vertices()];
    for &v in mesh.face_indices() {
        used[v as usize] = true;
    }
    let mut new_index = vec![u32::MAX; mesh.n_vertices()];
    let mut positions = Vec::new();
    for (v, &p) in mesh.positions.iter().enumerate() {
        if used[v] {
            new_index[v] = u32::try_from(positions.len()).expect("vertex index fits u32");
            positions.push(p);
        }
    }
    let faces: Vec<Vec<u32>> = mesh
        .faces()
        .map(|face| face.iter().map(|&v| new_index[v as usize]).collect())
        .collect();
    PolygonMesh::from_faces(positions, faces)
}

pub(crate) fn bounding_box_diagonal(positions: &[DVec3]) -> f64 {
    let (lo, hi) = positions.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    (hi - lo).length()
}

/// A uniform grid over positions, cells at least as wide as the search radius, so a point's
/// matches lie in its own cell or next to it: the points sorted by cell, each occupied cell's
/// run found through a hash map (one look-up per cell the search ball touches: with cells much
/// wider than the ball, usually one).
struct SpatialHash<'a> {
    positions: &'a [DVec3],
    cell: f64,
    /// `(cell, point)` for every point, sorted.
    sorted: Vec<([i64; 3], u32)>,
    /// Each occupied cell's run in `sorted`: start and end.
    runs: HashMap<[i64; 3], (u32, u32), BuildHasherDefault<CellHasher>>,
}

impl<'a> SpatialHash<'a> {
    fn new(positions: &'a [DVec3], cell: f64) -> Self {
        let index = |i: usize| u32::try_from(i).expect("vertex index fits u32");
        let mut sorted: Vec<([i64; 3], u32)> = positions
            .iter()
            .enumerate()
            .map(|(i, &p)| (Self::key(p, cell), index(i)))
            .collect();
        sorted.sort_unstable();
        let mut runs = HashMap::with_capacity_and_hasher(sorted.len(), Default::default());
        let mut start = 0;
        for (i, &(key, _)) in sorted.iter().enumerate() {
            if sorted[start].0 != key {
                runs.insert(sorted[start].0, (index(start), index(i)));
                start = i;
            }
        }
        if let Some(&(key, _)) = sorted.get(start) {
            runs.insert(key, (index(start), index(sorted.len())));
        }
        SpatialHash {
            positions,
            cell,
            sorted,
            runs,
        }
    }

    fn key(p: DVec3, cell: f64) -> [i64; 3] {
        // Positions of real meshes divided by a cell of 1e-12 diagonals stay far inside i64.
        let q = (p / cell).floor();
        [q.x as i64, q.y as i64, q.z as i64]
    }

    /// Every indexed point within `radius` of `p` (`radius` at most one cell).
    fn within(&self, p: DVec3, radius: f64) -> Vec<u32> {
        let lo = Self::key(p - DVec3::splat(radius), self.cell);
        let hi = Self::key(p + DVec3::splat(radius), self.cell);
        let mut found = Vec::new();
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    if let Some(&(start, end)) = self.runs.get(&[x, y, z]) {
                        found.extend(
                            self.sorted[start as usize..end as usize]
                                .iter()
                                .map(|&(_, i)| i)
                                .filter(|&i| self.positions[i as usize].distance(p) <= radius),
                        );
                    }
                }
            }
        }
        found
    }
}

/// A fast hash for grid cells (multiply and rotate over 64-bit words, as rustc's FxHasher, then
/// splitmix64's finalizer): the standard SipHash costs more than the whole rest of a look-up,
/// and no adversary picks the keys.
#[derive(Default)]
struct CellHasher(u64);

impl Hasher for CellHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }

    fn write_u64(&mut self, n: u64) {
        self.0 = (self.0.rotate_left(5) ^ n).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }

    fn finish(&self) -> u64 {
        // splitmix64's finalizer: the multiply-rotate above leaves the low bits, which pick
        // the bucket, depending on the low bits of the input only.
        let mut x = self.0;
        x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        x ^ (x >> 31)
    }
}

/// `to_ours[v]`: the `halfedge` vertex that is OpenSubdiv's vertex `v`.
///
/// A vertex is matched by position when exactly one `halfedge` vertex lies within `tolerance`.
/// Where several do (a seam: distinct vertices at one place), the candidate is the one whose
/// outgoing face edges lead to the matches of `v`'s face neighbours, repeated until nothing
/// changes. Every vertex must end with exactly one match, each `halfedge` vertex used once.
pub(crate) fn correspondence(
    theirs: &PolygonMesh,
    ours: &PolygonMesh,
    tolerance: f64,
) -> Result<Vec<u32>, String> {
    let diagonal = tolerance / TOLERANCE;
    // Cells of 1024 tolerances: the search ball (2 tolerances wide) lies in one cell for
    // about 99.4 % of the points, and at 1e-9 of the diagonal a cell still holds one vertex
    // (the vertices of the compared levels are far further apart).
    let hash = SpatialHash::new(&ours.positions, 1024.0 * tolerance);
    let mut candidates: Vec<Vec<u32>> = Vec::with_capacity(theirs.n_vertices());
    for (v, &p) in theirs.positions.iter().enumerate() {
        let found = hash.within(p, tolerance);
        if found.is_empty() {
            let (nearest, distance) = ours
                .positions
                .iter()
                .enumerate()
                .map(|(i, q)| (i, q.distance(p)))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .expect("the level has vertices");
            return Err(format!(
                "OpenSubdiv vertex {v} at {p} has no halfedge vertex within {TOLERANCE:e} of \
                 the diagonal; the nearest is vertex {nearest} at {}, {:e} of the diagonal away",
                ours.positions[nearest],
                distance / diagonal
            ));
        }
        candidates.push(found);
    }

    if candidates.iter().any(|c| c.len() > 1) {
        // Directed face edges (corner to next corner) on both sides.
        let edges = |mesh: &PolygonMesh| {
            let mut out: Vec<(u32, u32)> = Vec::with_capacity(mesh.n_corners());
            for face in mesh.faces() {
                for (k, &a) in face.iter().enumerate() {
                    out.push((a, face[(k + 1) % face.len()]));
                }
            }
            out
        };
        let ours_edges: std::collections::HashSet<(u32, u32)> = edges(ours).into_iter().collect();
        let theirs_edges = edges(theirs);
        loop {
            let mut progress = false;
            for &(a, b) in &theirs_edges {
                let (a, b) = (a as usize, b as usize);
                for (v, w, forward) in [(a, b, true), (b, a, false)] {
                    if candidates[v].len() > 1 && candidates[w].len() == 1 {
                        let known = candidates[w][0];
                        let before = candidates[v].len();
                        candidates[v].retain(|&c| {
                            let edge = if forward { (c, known) } else { (known, c) };
                            ours_edges.contains(&edge)
                        });
                        progress |= candidates[v].len() < before;
                    }
                }
            }
            if !progress || candidates.iter().all(|c| c.len() <= 1) {
                break;
            }
        }
    }

    let mut taken = vec![false; ours.n_vertices()];
    let mut to_ours = Vec::with_capacity(theirs.n_vertices());
    for (v, found) in candidates.iter().enumerate() {
        let p = theirs.positions[v];
        match found.as_slice() {
            &[i] => {
                if std::mem::replace(&mut taken[i as usize], true) {
                    return Err(format!(
                        "halfedge vertex {i} matches two OpenSubdiv vertices (one is {v})"
                    ));
                }
                to_ours.push(i);
            }
            [] => {
                return Err(format!(
                    "OpenSubdiv vertex {v} at {p} coincides with several halfedge vertices and \
                     none of them has its face neighbours"
                ))
            }
            several => {
                return Err(format!(
                    "OpenSubdiv vertex {v} at {p} is within the tolerance of halfedge vertices \
                     {several:?}, and their face neighbours do not tell them apart"
                ))
            }
        }
    }
    Ok(to_ours)
}
/// What one comparison found.
pub(crate) struct Outcome {
    /// Largest distance between matched vertices, as a fraction of the diagonal.
    pub(crate) max_deviation: f64,
    /// Whether `halfedge` numbers the level's vertices exactly as OpenSubdiv does.
    pub(crate) same_vertex_order: bool,
    /// Whether face `i` is the same vertex cycle on both sides, for every `i`.
    pub(crate) same_face_order: bool,
}

/// Compares two last levels (`at` names the comparison), `base` giving the bounding box.
pub(crate) fn compare_levels(
    at: &str,
    base: &PolygonMesh,
    ours: &PolygonMesh,
    theirs: &PolygonMesh,
) -> Result<Outcome, String> {
    if ours.n_vertices() != theirs.n_vertices() || ours.n_faces() != theirs.n_faces() {
        return Err(format!(
            "{at}: halfedge has {} vertices and {} faces, OpenSubdiv {} and {}",
            ours.n_vertices(),
            ours.n_faces(),
            theirs.n_vertices(),
            theirs.n_faces()
        ));
    }

    let diagonal = bounding_box_diagonal(&base.positions);
    let tolerance = TOLERANCE * diagonal;
    let to_ours = correspondence(theirs, ours, tolerance).map_err(|e| format!("{at}: {e}"))?;
    let max_deviation = theirs
        .positions
        .iter()
        .zip(&to_ours)
        .map(|(p, &i)| p.distance(ours.positions[i as usize]))
        .fold(0.0, f64::max);

    // Faces as cycles: each rotated to start at its smallest vertex, orientation kept. The two
    // levels have the same faces when their sorted cycle lists are equal.
    let ours_cycles = Cycles::new(ours.faces().map(|face| face.iter().copied()));
    let theirs_cycles = Cycles::new(
        theirs
            .faces()
            .map(|face| face.iter().map(|&v| to_ours[v as usize])),
    );
    let same_face_order = (0..ours.n_faces()).all(|f| ours_cycles.get(f) == theirs_cycles.get(f));
    let ours_sorted = ours_cycles.sorted();
    let theirs_sorted = theirs_cycles.sorted();
    let same_faces = ours_sorted
        .iter()
        .zip(&theirs_sorted)
        .all(|(&a, &b)| ours_cycles.get(a) == theirs_cycles.get(b));
    if !same_faces {
        // Name the first OpenSubdiv face, in its order, that halfedge lacks (or has fewer
        // times), counting halfedge's cycles.
        let mut unmatched: HashMap<&[u32], usize> = HashMap::with_capacity(ours.n_faces());
        for f in 0..ours.n_faces() {
            *unmatched.entry(ours_cycles.get(f)).or_default() += 1;
        }
        for f in 0..theirs.n_faces() {
            let mapped = theirs_cycles.get(f);
            match unmatched.get_mut(mapped) {
                Some(count) if *count > 0 => *count -= 1,
                _ => {
                    return Err(format!(
                        "{at}: OpenSubdiv face {f} {:?} is halfedge's vertex cycle {mapped:?}, \
                         which is not a face of halfedge's level (or appears there fewer times)",
                        theirs.face(f)
                    ))
                }
            }
        }
        unreachable!("the sorted cycle lists differ, so some OpenSubdiv face is unmatched");
    }

    Ok(Outcome {
        max_deviation: max_deviation / diagonal,
        same_vertex_order: to_ours.iter().enumerate().all(|(v, &i)| v as u32 == i),
        same_face_order,
    })
}

/// Faces as vertex cycles, each rotated to start at its smallest vertex (orientation kept),
/// in one flat array.
pub(crate) struct Cycles {
    vertices: Vec<u32>,
    offsets: Vec<usize>,
}

impl Cycles {
    pub(crate) fn new<F: Iterator<Item = u32>>(faces: impl Iterator<Item = F>) -> Cycles {
        let mut vertices = Vec::new();
        let mut offsets = vec![0];
        for face in faces {
            let start = vertices.len();
            vertices.extend(face);
            let face = &mut vertices[start..];
            let smallest = (0..face.len()).min_by_key(|&i| face[i]).unwrap_or(0);
            face.rotate_left(smallest);
            offsets.push(vertices.len());
        }
        Cycles { vertices, offsets }
    }

    pub(crate) fn get(&self, f: usize) -> &[u32] {
        &self.vertices[self.offsets[f]..self.offsets[f + 1]]
    }

    /// The face indices, sorted by cycle.
    pub(crate) fn sorted(&self) -> Vec<usize> {
        let mut order: Vec<usize> = (0..self.offsets.len() - 1).collect();
        order.sort_unstable_by(|&a, &b| self.get(a).cmp(self.get(b)));
        order
    }
}
