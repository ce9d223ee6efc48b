//! Differential tests against OpenSubdiv 3.5: `halfedge`'s Loop and Catmull-Clark output,
//! vertex for vertex and face for face, against `Far::TopologyRefiner` + `PrimvarRefiner`
//! (`VTX_BOUNDARY_EDGE_ONLY`, uniform refinement, positions in `f64`) on shared meshes with
//! boundaries, genus and mixed polygons, levels 1-3.
//!
//! The reference is the repository's own driver, `tools/osd-driver/osd_driver.cpp`, compiled
//! once per test binary with `c++ -O2 -std=c++17 ... -losdCPU` into cargo's temporary folder.
//! The tests are ignored by default (they need Debian's `libosd-dev`, a C++ compiler and the
//! shared meshes); `cargo test -p halfedge --test opensubdiv -- --ignored` runs them, and they
//! fail, saying what is missing, when the compiler, OpenSubdiv or `SUBCOUNT_MESHES` is absent.
//!
//! OpenSubdiv numbers a level's vertices differently from `halfedge` (see
//! `tools/osd-driver/README.md`), so the correspondence is found by matching positions
//! through a spatial hash: every OpenSubdiv vertex must have exactly one `halfedge` vertex
//! within the tolerance, and the map must be a bijection. Faces are then required to agree
//! one for one under that map: every OpenSubdiv face is a face of `halfedge`, the same
//! vertices in the same cyclic order (the starting corner may differ), as often on both sides.
//! Whether the numberings also coincide is printed, not required.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use glam::DVec3;
use halfedge::subdivide::{subdivide_to_face_list, Rule, SubdivideOptions};
use halfedge::{io, HalfEdgeMesh, PolygonMesh};

/// Positions must agree to this fraction of the base mesh's bounding-box diagonal.
const TOLERANCE: f64 = 1e-12;

/// The two schemes compared, with OpenSubdiv's name for each.
#[derive(Clone, Copy, Debug)]
enum Osd {
    Loop,
    Catmark,
}

impl Osd {
    fn driver_name(self) -> &'static str {
        match self {
            Osd::Loop => "loop",
            Osd::Catmark => "catmark",
        }
    }

    /// `halfedge`'s rule: Loop (its boundary rules on a boundary), Catmull-Clark.
    fn rule(self) -> Rule {
        match self {
            Osd::Loop => Rule::Loop,
            Osd::Catmark => Rule::CatmullClark,
        }
    }
}

/// The compiled driver, built once per test binary; `Err` says what is missing.
fn driver() -> &'static Path {
    static DRIVER: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    let built = DRIVER.get_or_init(|| {
        let source =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tools/osd-driver/osd_driver.cpp");
        let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("osd-driver");
        std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        let binary = dir.join("osd_driver");
        let output = Command::new("c++")
            .args(["-O2", "-std=c++17", "-o"])
            .arg(&binary)
            .arg(&source)
            .arg("-losdCPU")
            .output()
            .map_err(|e| {
                format!("cannot run the C++ compiler `c++` ({e}): install g++ to run the OpenSubdiv tests")
            })?;
        if !output.status.success() {
            return Err(format!(
                "compiling {} failed (are OpenSubdiv's headers under /usr/include/opensubdiv and \
                 libosdCPU installed? `apt-get install libosd-dev`):\n{}",
                source.display(),
                String::from_utf8_lossy(&output.stderr)
            ));
        }
        Ok(binary)
    });
    match built {
        Ok(path) => path,
        Err(message) => panic!("{message}"),
    }
}

/// The shared meshes folder; these tests fail rather than pass when it is not given.
fn meshes_dir() -> PathBuf {
    testdata::meshes_dir()
}

/// OpenSubdiv's last level of `scheme` at `level` on the mesh file, with the driver's
/// boundary interpolation `boundary` (`edge-only` is `VTX_BOUNDARY_EDGE_ONLY`).
fn opensubdiv(scheme: Osd, level: u32, path: &Path, boundary: &str) -> PolygonMesh {
    let output = Command::new(driver())
        .arg(scheme.driver_name())
        .arg(level.to_string())
        .arg(path)
        .arg(boundary)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {}: {e}", driver().display()));
    assert!(
        output.status.success(),
        "osd_driver {} {level} {} failed: {}",
        scheme.driver_name(),
        path.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    io::read_obj_from(output.stdout.as_slice(), "osd_driver output")
        .unwrap_or_else(|e| panic!("osd_driver wrote an unreadable OBJ: {e}"))
}

fn bounding_box_diagonal(positions: &[DVec3]) -> f64 {
    let (lo, hi) = positions.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    (hi - lo).length()
}

/// A uniform grid over positions, cells a little wider than the tolerance, so a point's match
/// lies in its own cell or one of the 26 around it.
struct SpatialHash<'a> {
    positions: &'a [DVec3],
    cell: f64,
    cells: HashMap<[i64; 3], Vec<u32>>,
}

impl<'a> SpatialHash<'a> {
    fn new(positions: &'a [DVec3], cell: f64) -> Self {
        let mut cells: HashMap<[i64; 3], Vec<u32>> = HashMap::with_capacity(positions.len());
        for (i, &p) in positions.iter().enumerate() {
            let key = Self::key(p, cell);
            cells
                .entry(key)
                .or_default()
                .push(u32::try_from(i).expect("vertex index fits u32"));
        }
        SpatialHash {
            positions,
            cell,
            cells,
        }
    }

    fn key(p: DVec3, cell: f64) -> [i64; 3] {
        // Positions of real meshes divided by a cell of 1e-11 diagonals stay far inside i64.
        let q = (p / cell).floor();
        [q.x as i64, q.y as i64, q.z as i64]
    }

    /// Every indexed point within `radius` of `p` (`radius` at most one cell).
    fn within(&self, p: DVec3, radius: f64) -> Vec<u32> {
        let [x, y, z] = Self::key(p, self.cell);
        let mut found = Vec::new();
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(list) = self.cells.get(&[x + dx, y + dy, z + dz]) {
                        found.extend(
                            list.iter()
                                .filter(|&&i| self.positions[i as usize].distance(p) <= radius),
                        );
                    }
                }
            }
        }
        found
    }
}

/// `to_ours[v]`: the `halfedge` vertex that is OpenSubdiv's vertex `v`.
///
/// A vertex is matched by position when exactly one `halfedge` vertex lies within `tolerance`.
/// Where several do (a seam: distinct vertices at one place), the candidate is the one whose
/// outgoing face edges lead to the matches of `v`'s face neighbours, repeated until nothing
/// changes. Every vertex must end with exactly one match, each `halfedge` vertex used once.
fn correspondence(
    theirs: &PolygonMesh,
    ours: &PolygonMesh,
    tolerance: f64,
) -> Result<Vec<u32>, String> {
    let diagonal = tolerance / TOLERANCE;
    let hash = SpatialHash::new(&ours.positions, 2.0 * tolerance);
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

/// How OpenSubdiv's side of a comparison is made.
#[derive(Clone, Copy)]
struct Reference {
    /// The driver's boundary interpolation (`edge-only`: `VTX_BOUNDARY_EDGE_ONLY`).
    boundary: &'static str,
    /// Whether vertices in no face are removed from OpenSubdiv's output before comparing.
    drop_bare_vertices: bool,
}

impl Reference {
    /// The reference the project promises to match.
    const EDGE_ONLY: Reference = Reference {
        boundary: "edge-only",
        drop_bare_vertices: false,
    };
}

/// The mesh without the vertices no face uses, the others renumbered in order.
fn without_bare_vertices(mesh: &PolygonMesh) -> PolygonMesh {
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

/// What one comparison found.
struct Outcome {
    /// Largest distance between matched vertices, as a fraction of the diagonal.
    max_deviation: f64,
    /// Whether `halfedge` numbers the level's vertices exactly as OpenSubdiv does.
    same_vertex_order: bool,
    /// Whether face `i` is the same vertex cycle on both sides, for every `i`.
    same_face_order: bool,
}

/// Compares `halfedge` with OpenSubdiv on one mesh, scheme and level; `Err` names the first
/// disagreement (mesh, scheme, level, vertex or face, deviation).
fn compare(file: &str, scheme: Osd, level: u32, reference: Reference) -> Result<Outcome, String> {
    let path = meshes_dir().join(file);
    let base = io::read_mesh(&path).map_err(|e| format!("{file}: {e}"))?;
    let mesh = HalfEdgeMesh::try_from(&base).map_err(|e| format!("{file}: {e}"))?;
    let name = scheme.rule();
    let ours = subdivide_to_face_list(&mesh, name, level, &SubdivideOptions::default())
        .map_err(|e| format!("{file}: halfedge {name} level {level}: {e}"))?
        .mesh;
    let mut theirs = opensubdiv(scheme, level, &path, reference.boundary);
    if reference.drop_bare_vertices {
        theirs = without_bare_vertices(&theirs);
    }
    let at = format!(
        "{file}, {name} vs OpenSubdiv {}, level {level}",
        scheme.driver_name()
    );

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
    let to_ours = correspondence(&theirs, &ours, tolerance).map_err(|e| format!("{at}: {e}"))?;
    let max_deviation = theirs
        .positions
        .iter()
        .zip(&to_ours)
        .map(|(p, &i)| p.distance(ours.positions[i as usize]))
        .fold(0.0, f64::max);

    // Faces as cycles: each rotated to start at its smallest vertex, orientation kept.
    fn cycle(face: impl Iterator<Item = u32>) -> Vec<u32> {
        let mut face: Vec<u32> = face.collect();
        let start = (0..face.len()).min_by_key(|&i| face[i]).unwrap_or(0);
        face.rotate_left(start);
        face
    }
    let mut same_face_order = true;
    let mut unmatched: HashMap<Vec<u32>, usize> = HashMap::with_capacity(ours.n_faces());
    for (f, face) in ours.faces().enumerate() {
        let mine = cycle(face.iter().copied());
        let mapped = cycle(theirs.face(f).iter().map(|&v| to_ours[v as usize]));
        same_face_order &= mine == mapped;
        *unmatched.entry(mine).or_default() += 1;
    }
    for (f, face) in theirs.faces().enumerate() {
        let mapped = cycle(face.iter().map(|&v| to_ours[v as usize]));
        match unmatched.get_mut(&mapped) {
            Some(count) if *count > 0 => *count -= 1,
            _ => {
                return Err(format!(
                    "{at}: OpenSubdiv face {f} {face:?} is halfedge's vertex cycle {mapped:?}, \
                     which is not a face of halfedge's level (or appears there fewer times)"
                ))
            }
        }
    }

    Ok(Outcome {
        max_deviation: max_deviation / diagonal,
        same_vertex_order: to_ours.iter().enumerate().all(|(v, &i)| v as u32 == i),
        same_face_order,
    })
}

/// Runs every case, prints the deviations, and fails with all disagreements at once.
fn check(scheme: Osd, files: &[&str], levels: std::ops::RangeInclusive<u32>) {
    let mut failures = Vec::new();
    for file in files {
        for level in levels.clone() {
            match compare(file, scheme, level, Reference::EDGE_ONLY) {
                Ok(outcome) => eprintln!(
                    "{file} {} level {level}: max deviation {:.3e} of the diagonal{}",
                    scheme.driver_name(),
                    outcome.max_deviation,
                    match (outcome.same_vertex_order, outcome.same_face_order) {
                        (true, true) => ", same vertex and face numbering",
                        (true, false) => ", same vertex numbering, faces reordered",
                        (false, true) => ", vertices renumbered, same face order",
                        (false, false) => ", vertices renumbered, faces reordered",
                    }
                ),
                Err(message) => failures.push(message),
            }
        }
    }
    assert!(
        failures.is_empty(),
        "halfedge disagrees with OpenSubdiv:\n{}",
        failures.join("\n")
    );
}

/// Loop on closed triangle meshes: genus 0 (icosahedron), genus 3 (toroidal tetrahedron, the
/// paper's 3holes), a character model.
#[test]
#[ignore = "needs libosd-dev and SUBCOUNT_MESHES"]
fn loop_on_closed_meshes_matches_opensubdiv() {
    check(
        Osd::Loop,
        &[
            "osd_loop_icosahedron.obj",
            "osd_loop_toroidal_tet.obj",
            "3holes.obj",
            "spot_triangulated.obj",
        ],
        1..=3,
    );
}

/// Loop's boundary rules (`loop-boundary`) against `VTX_BOUNDARY_EDGE_ONLY`: a grid with
/// corners, a genus-2 surface with a hole, an open mesh with four boundary loops (and
/// coincident vertices along its cuts), two scanned open meshes.
#[test]
#[ignore = "needs libosd-dev and SUBCOUNT_MESHES"]
fn loop_on_meshes_with_boundary_matches_opensubdiv() {
    check(
        Osd::Loop,
        &[
            "planexy.obj",
            "eight_hole.obj",
            "eight_open.obj",
            "face.obj",
            "alligator.obj",
        ],
        1..=3,
    );
}

/// Catmull-Clark on closed polygon meshes: quads with genus 1 and 3, a pyramid (triangles
/// and a quad), quad and mixed control meshes of character models, n-gons, a CAD part.
#[test]
#[ignore = "needs libosd-dev and SUBCOUNT_MESHES"]
fn catmull_clark_on_closed_meshes_matches_opensubdiv() {
    check(
        Osd::Catmark,
        &[
            "osd_catmark_cube.obj",
            "osd_catmark_torus.obj",
            "osd_catmark_toroidal_tet.obj",
            "osd_catmark_pyramid.obj",
            "spot_control_mesh.obj",
            "cylinder_ngon.obj",
            "fandisk_quads.obj",
            "blub_control_mesh.obj",
            "penguin_control_mesh.obj",
            "chamfer_cube.obj",
        ],
        1..=3,
    );
}

/// Catmull-Clark with boundaries: OpenSubdiv's mixed-polygon shapes, a grid, open quad
/// meshes (crease tags in the files are ignored on both sides), and triangles.
/// (`osd_catmark_nonman_bareverts` has its own test below: its vertices in no face.)
#[test]
#[ignore = "needs libosd-dev and SUBCOUNT_MESHES"]
fn catmull_clark_on_meshes_with_boundary_matches_opensubdiv() {
    check(
        Osd::Catmark,
        &[
            "osd_catmark_nonquads.obj",
            "osd_catmark_chaikin2.obj",
            "osd_catmark_pawn.obj",
            "osd_catmark_bishop.obj",
            "inspired_mesh_quads_smooth.obj",
            "suzanne.obj",
            "planexy.obj",
            "eight_hole.obj",
        ],
        1..=3,
    );
}

/// The comparison can fail: OpenSubdiv's `VTX_BOUNDARY_EDGE_AND_CORNER` keeps the corners of a
/// grid (boundary vertices of one face) fixed, while `halfedge` smooths them along the
/// boundary, and the test names the vertex that moved.
#[test]
#[ignore = "needs libosd-dev and SUBCOUNT_MESHES"]
fn a_different_boundary_rule_is_told_apart() {
    for scheme in [Osd::Loop, Osd::Catmark] {
        let corners = Reference {
            boundary: "edge-and-corner",
            ..Reference::EDGE_ONLY
        };
        let err = compare("planexy.obj", scheme, 1, corners)
            .err()
            .unwrap_or_else(|| panic!("{scheme:?}: corner rules went unnoticed"));
        assert!(
            err.contains("planexy.obj") && err.contains("has no halfedge vertex within"),
            "{err}"
        );
    }
}

/// Vertices in no face ("bare" vertices, 10 of the 25 in OpenSubdiv's
/// catmark_nonman_bareverts shape): OpenSubdiv keeps each one at every level (a vertex child
/// of itself, at the same place), `halfedge` drops them from level 1 on. Everything else
/// agrees: with the bare vertices taken out of OpenSubdiv's output, the levels match.
///
/// FIXME: a known difference, asserted so a change on either side is noticed; whether
/// `halfedge` should carry unreferenced vertices along is the lead's call.
#[test]
#[ignore = "needs libosd-dev and SUBCOUNT_MESHES"]
fn bare_vertices_are_kept_by_opensubdiv_and_dropped_by_halfedge() {
    let file = "osd_catmark_nonman_bareverts.obj";
    for level in 1..=3 {
        let err = compare(file, Osd::Catmark, level, Reference::EDGE_ONLY)
            .err()
            .unwrap_or_else(|| panic!("level {level}: the bare vertices now agree"));
        let (ours, theirs) = [(45, 55), (153, 163), (561, 571)][level as usize - 1];
        let faces = 8 * 4_u32.pow(level);
        assert!(
            err.ends_with(&format!(
                "halfedge has {ours} vertices and {faces} faces, OpenSubdiv {theirs} and {faces}"
            )),
            "{err}"
        );
        let without = Reference {
            drop_bare_vertices: true,
            ..Reference::EDGE_ONLY
        };
        if let Err(err) = compare(file, Osd::Catmark, level, without) {
            panic!("{err}");
        }
    }
}
