//! Differential tests against OpenSubdiv 3.5: `halfedge`'s Loop and Catmull-Clark output,
//! vertex for vertex and face for face, against `Far::TopologyRefiner` + `PrimvarRefiner`
//! (`VTX_BOUNDARY_EDGE_ONLY`, uniform refinement, positions in `f64`, OBJ tags ignored on both
//! sides) on every shared mesh they apply to: Loop on every triangle mesh, Catmull-Clark on
//! every mesh `halfedge` accepts, at each of levels 1-3 whose output stays within
//! [`MAX_FACES`] (about 2 M faces).
//!
//! The reference is the repository's own driver, `tools/osd-driver/osd_driver.cpp`, which
//! cargo never builds: `tools/osd-driver/build.sh` compiles it (Debian's `libosd-dev`,
//! `-losdCPU`) into `target/osd-driver/osd_driver`, and the tests find it only through the
//! environment variable [`DRIVER_VAR`](osd_support::DRIVER_VAR) (`SUBCOUNT_OSD_DRIVER`), the meshes through
//! `SUBCOUNT_MESHES`. They are `#[ignore = "needs the OpenSubdiv driver"]`; `.ci/run` builds
//! the driver and runs them:
//!
//! ```text
//! tools/osd-driver/build.sh
//! SUBCOUNT_OSD_DRIVER=target/osd-driver/osd_driver SUBCOUNT_MESHES=../shared/meshes \
//!     cargo test -p halfedge --test opensubdiv -- --ignored
//! ```
//!
//! Run with `--ignored` but without either variable, they fail saying what is missing; they
//! never pass untested.
//!
//! OpenSubdiv numbers a level's vertices differently from `halfedge` (see
//! `tools/osd-driver/README.md`), so the correspondence is found by matching positions
//! through a spatial hash: every OpenSubdiv vertex must have exactly one `halfedge` vertex
//! within the tolerance, and the map must be a bijection. Faces are then required to agree
//! one for one under that map: every OpenSubdiv face is a face of `halfedge`, the same
//! vertices in the same cyclic order (the starting corner may differ), as often on both sides.
//! Whether the numberings also coincide is printed, not required.
//!
//! The driver's face-varying UV channel (`--fvar MODE`, `--fvar-counts`) is run through
//! `osd_support::fvar`; its own tests (issue 14's UV value counts, the channel leaving
//! positions and faces alone, the `facevaryinginterpolateboundary` tag, holes) are in
//! `fvar_reference`; the UV value counts `schemes::uv` predicts are compared with its
//! `--fvar-counts` on every shared mesh with UVs in `uv_count_reference`.

mod fvar_reference;
mod limit_reference;
mod osd_support;
mod uv_count_reference;

use std::path::{Path, PathBuf};

use glam::DVec3;
use halfedge::subdivide::{subdivide_to_face_list, Rule, SubdivideOptions};
use halfedge::{io, HalfEdgeMesh, PolygonMesh};

use osd_support::{
    bounding_box_diagonal, compare_levels, driver, opensubdiv_with, without_bare_vertices, Osd,
    Outcome, Running,
};

/// A level is compared when its output has at most this many faces ("about 2 M": the
/// 2,069,536 Catmull-Clark faces of beast.obj at level 3 are in).
const MAX_FACES: u64 = 2_100_000;

/// `halfedge`'s side of a comparison: the test's one call into the subdivision API, kept in
/// this function alone. Loop is Loop's closed rule on a closed mesh and its boundary rule
/// otherwise (what `loop_subdivide` picks), Catmull-Clark has its boundary rules.
fn subdivide_ours(mesh: &HalfEdgeMesh, scheme: Osd, level: u32) -> Result<PolygonMesh, String> {
    // Loop's boundary rules on a mesh with boundary: VTX_BOUNDARY_EDGE_ONLY.
    let name = match scheme {
        Osd::Loop => Rule::Loop,
        Osd::Catmark => Rule::CatmullClark,
    };
    subdivide_to_face_list(mesh, name, level, &SubdivideOptions::default())
        .map(|subdivided| subdivided.mesh)
        .map_err(|e| format!("halfedge {name} level {level}: {e}"))
}

/// The shared meshes folder; these tests fail rather than pass when it is not given.
fn meshes_dir() -> PathBuf {
    testdata::meshes_dir()
}

/// Starts OpenSubdiv's last level of `scheme` at `level` on the mesh file, with the driver's
/// boundary interpolation `boundary` (`edge-only` is `VTX_BOUNDARY_EDGE_ONLY`); [`Running::mesh`]
/// collects it, so `halfedge` can work meanwhile.
fn opensubdiv(scheme: Osd, level: u32, path: &Path, boundary: &str) -> Running {
    opensubdiv_with(&[], scheme, level, path, Some(boundary))
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

/// A base mesh, read once for all its levels. Its half-edge mesh carries no descriptor
/// (`try_from_polygon_mesh`): each comparison passes the tags it means, as the driver's flags do.
struct Base {
    file: String,
    path: PathBuf,
    polygons: PolygonMesh,
    mesh: HalfEdgeMesh,
    /// Whether some vertices are in no face (OpenSubdiv keeps them, `halfedge` drops them).
    has_bare_vertices: bool,
}

impl Base {
    /// The shared mesh `file`; `Err` when it cannot be read or `halfedge` refuses it.
    fn load(file: &str) -> Result<Base, String> {
        let path = meshes_dir().join(file);
        let polygons = io::read_mesh(&path).map_err(|e| format!("{file}: {e}"))?;
        let mesh =
            HalfEdgeMesh::try_from_polygon_mesh(&polygons).map_err(|e| format!("{file}: {e}"))?;
        let mut used = vec![false; polygons.n_vertices()];
        for &v in polygons.face_indices() {
            used[v as usize] = true;
        }
        Ok(Base {
            file: file.to_owned(),
            path,
            has_bare_vertices: used.contains(&false),
            polygons,
            mesh,
        })
    }

    fn is_triangle_mesh(&self) -> bool {
        self.polygons.faces().all(|face| face.len() == 3)
    }

    /// The levels 1-3 whose output under `scheme` has at most [`MAX_FACES`] faces.
    fn levels(&self, scheme: Osd) -> Vec<u32> {
        let (faces, corners) = (self.polygons.n_faces(), self.polygons.n_corners());
        (1..=3)
            .filter(|&level| scheme.faces_at(faces, corners, level) <= MAX_FACES)
            .collect()
    }
}

/// Compares `halfedge` with OpenSubdiv on one mesh, scheme and level; `Err` names the first
/// disagreement (mesh, scheme, level, vertex or face, deviation).
fn compare(base: &Base, scheme: Osd, level: u32, reference: Reference) -> Result<Outcome, String> {
    let file = &base.file;
    let at = format!(
        "{file}, {scheme:?} vs OpenSubdiv {}, level {level}",
        scheme.driver_name()
    );
    let running = opensubdiv(scheme, level, &base.path, reference.boundary);
    let ours = subdivide_ours(&base.mesh, scheme, level);
    // The driver is waited for even when halfedge failed, so no process outlives the test.
    let mut theirs = running.mesh();
    let ours = ours.map_err(|e| format!("{at}: {e}"))?;
    if reference.drop_bare_vertices {
        theirs = without_bare_vertices(&theirs);
    }
    compare_levels(&at, &base.polygons, &ours, &theirs)
}

/// Every `.obj` file directly in the shared meshes folder (`broken/` holds the invalid ones),
/// sorted by name.
fn shared_meshes() -> Vec<String> {
    let dir = meshes_dir();
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| entry.unwrap_or_else(|e| panic!("{}: {e}", dir.display())))
        .filter(|entry| entry.path().is_file())
        .filter_map(|entry| entry.file_name().into_string().ok())
        .filter(|name| name.ends_with(".obj"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "{} holds no .obj file", dir.display());
    files
}

/// Compares `scheme` on every shared mesh it applies to (`applies` says which, given the
/// loaded mesh), at every level [`Base::levels`] allows, prints each deviation and the largest,
/// and fails with all disagreements at once. Returns the `(file, level)` pairs compared.
/// Vertices in no face are taken out of OpenSubdiv's output (see
/// `bare_vertices_are_kept_by_opensubdiv_and_dropped_by_halfedge`).
fn check_every_mesh(scheme: Osd, applies: impl Fn(&Base) -> bool) -> Vec<(String, u32)> {
    driver();
    let mut failures = Vec::new();
    let mut compared = Vec::new();
    let mut largest: Option<(f64, String, u32)> = None;
    for file in shared_meshes() {
        let base = match Base::load(&file) {
            Ok(base) => base,
            Err(message) => {
                // Every file directly in the folder is a valid manifold mesh (its README).
                failures.push(format!(
                    "{message} (a shared mesh every comparison must read)"
                ));
                continue;
            }
        };
        if !applies(&base) {
            eprintln!("{file}: not compared under {scheme:?}");
            continue;
        }
        let reference = Reference {
            drop_bare_vertices: base.has_bare_vertices,
            ..Reference::EDGE_ONLY
        };
        for level in base.levels(scheme) {
            let started = std::time::Instant::now();
            match compare(&base, scheme, level, reference) {
                Ok(outcome) => {
                    eprintln!(
                        "{file} {} level {level}: max deviation {:.3e} of the diagonal{} ({:.2} s)",
                        scheme.driver_name(),
                        outcome.max_deviation,
                        match (outcome.same_vertex_order, outcome.same_face_order) {
                            (true, true) => ", same vertex and face numbering",
                            (true, false) => ", same vertex numbering, faces reordered",
                            (false, true) => ", vertices renumbered, same face order",
                            (false, false) => ", vertices renumbered, faces reordered",
                        },
                        started.elapsed().as_secs_f64()
                    );
                    if largest
                        .as_ref()
                        .map_or(true, |(max, _, _)| outcome.max_deviation > *max)
                    {
                        largest = Some((outcome.max_deviation, file.clone(), level));
                    }
                    compared.push((file.clone(), level));
                }
                Err(message) => failures.push(message),
            }
        }
    }
    if let Some((max, file, level)) = largest {
        eprintln!(
            "{scheme:?}: {} comparisons, largest deviation {max:.3e} of the diagonal ({file}, \
             level {level})",
            compared.len()
        );
    }
    assert!(
        failures.is_empty(),
        "halfedge disagrees with OpenSubdiv:\n{}",
        failures.join("\n")
    );
    compared
}

/// Fails unless every one of `files` was compared at each of levels 1-3.
fn assert_compared_at_every_level(compared: &[(String, u32)], files: &[&str]) {
    for file in files {
        for level in 1..=3 {
            assert!(
                compared.iter().any(|(f, l)| f == file && *l == level),
                "{file} level {level} was not compared"
            );
        }
    }
}

/// Loop on every shared triangle mesh: closed ones with Loop's closed rule (genus 0 to 5,
/// scanned and character models), ones with boundary with its boundary rules against
/// `VTX_BOUNDARY_EDGE_ONLY` (grids with corners, open scans, a genus-2 surface with a hole, a
/// mesh with four boundary loops and coincident vertices along its cuts, a scan with vertices
/// in no face).
#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn loop_matches_opensubdiv_on_every_triangle_mesh() {
    let compared = check_every_mesh(Osd::Loop, Base::is_triangle_mesh);
    assert_compared_at_every_level(
        &compared,
        &[
            "osd_loop_icosahedron.obj",
            "osd_loop_toroidal_tet.obj",
            "3holes.obj",
            "spot_triangulated.obj",
            "planexy.obj",
            "eight_hole.obj",
            "eight_open.obj",
            "face.obj",
            "alligator.obj",
        ],
    );
}

/// Catmull-Clark on every shared mesh: quads, OpenSubdiv's mixed-polygon shapes, n-gons, CAD
/// parts, open quad meshes (crease tags in the files are ignored on both sides) and every
/// triangle mesh, closed or with boundary.
#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn catmull_clark_matches_opensubdiv_on_every_mesh() {
    let compared = check_every_mesh(Osd::Catmark, |_| true);
    assert_compared_at_every_level(
        &compared,
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
            "osd_catmark_nonquads.obj",
            "osd_catmark_chaikin2.obj",
            "osd_catmark_pawn.obj",
            "osd_catmark_bishop.obj",
            "inspired_mesh_quads_smooth.obj",
            "suzanne.obj",
            "planexy.obj",
            "eight_hole.obj",
        ],
    );
}

/// The comparison can fail: OpenSubdiv's `VTX_BOUNDARY_EDGE_AND_CORNER` keeps the corners of a
/// grid (boundary vertices of one face) fixed, while `halfedge` smooths them along the
/// boundary, and the test names the vertex that moved.
#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn a_different_boundary_rule_is_told_apart() {
    driver();
    let base = Base::load("planexy.obj").unwrap_or_else(|e| panic!("{e}"));
    for scheme in [Osd::Loop, Osd::Catmark] {
        let corners = Reference {
            boundary: "edge-and-corner",
            ..Reference::EDGE_ONLY
        };
        let err = compare(&base, scheme, 1, corners)
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
#[ignore = "needs the OpenSubdiv driver"]
fn bare_vertices_are_kept_by_opensubdiv_and_dropped_by_halfedge() {
    driver();
    let base = Base::load("osd_catmark_nonman_bareverts.obj").unwrap_or_else(|e| panic!("{e}"));
    assert!(base.has_bare_vertices);
    for level in 1..=3 {
        let err = compare(&base, Osd::Catmark, level, Reference::EDGE_ONLY)
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
        if let Err(err) = compare(&base, Osd::Catmark, level, without) {
            panic!("{err}");
        }
    }
}

// ---------------------------------------------------------------------------------------
// Creases, corners and the Sdc options (issue 13): the crease rules of `Refinement`.
// ---------------------------------------------------------------------------------------

use halfedge::refine::Refinement;
use halfedge::subdivide::Sharpness;
use halfedge::tags::{
    BoundaryInterpolation, CreaseMethod, SubdivisionOptions, Tags, TriangleRule, INFINITELY_SHARP,
};

/// The tags of an OBJ file as OpenSubdiv's shape loader reads them: `crease` (vertex pairs,
/// one sharpness or one per pair), `corner`, `interpolateboundary` (0 none, 1 edge-and-corner,
/// 2 edge-only), `creasemethod` (`normal`, `chaikin`), `smoothtriangles`; holes and other tags
/// are left out (holes do not move vertices). The test's own reader, so these tests do not
/// depend on the library's.
fn read_tags(path: &Path) -> Tags {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut tags = Tags::default();
    for line in text.lines() {
        let mut words = line.split_whitespace();
        if words.next() != Some("t") {
            continue;
        }
        let name = words.next().expect("a tag name");
        let counts: Vec<usize> = words
            .next()
            .expect("tag counts")
            .split('/')
            .map(|n| n.parse().expect("a count"))
            .collect();
        let rest: Vec<&str> = words.collect();
        let ints: Vec<u32> = rest[..counts[0]]
            .iter()
            .map(|w| w.parse().expect("an int"))
            .collect();
        let floats: Vec<f32> = rest[counts[0]..counts[0] + counts[1]]
            .iter()
            .map(|w| w.parse().expect("a float"))
            .collect();
        let strings = &rest[counts[0] + counts[1]..];
        let weight = |k: usize| {
            if floats.len() == 1 {
                floats[0]
            } else {
                floats[k]
            }
        };
        match name {
            "crease" => {
                for (k, pair) in ints.chunks(2).enumerate() {
                    tags.add_crease(pair[0], pair[1], weight(k))
                        .expect("a valid sharpness");
                }
            }
            "corner" => {
                for (k, &v) in ints.iter().enumerate() {
                    tags.add_corner(v, weight(k)).expect("a valid sharpness");
                }
            }
            "interpolateboundary" => {
                tags.options.boundary = Some(match ints[0] {
                    0 => BoundaryInterpolation::None,
                    1 => BoundaryInterpolation::EdgeAndCorner,
                    _ => BoundaryInterpolation::Edge,
                })
            }
            "creasemethod" => {
                tags.options.crease_method = Some(match strings[0] {
                    "chaikin" => CreaseMethod::Chaikin,
                    _ => CreaseMethod::Uniform,
                })
            }
            "smoothtriangles" => {
                tags.options.triangle_rule = Some(match strings[0] {
                    "smooth" => TriangleRule::Smooth,
                    _ => TriangleRule::Catmark,
                })
            }
            _ => {}
        }
    }
    tags
}

/// `halfedge`'s last level with the crease rules: a [`Refinement`] with the tags' sharpness
/// and `options`, evaluated in `f64` and its faces written (and, when `stencils`, the same
/// positions from its stencil table, which must agree to 1e-13 of the diagonal).
fn refine_ours(
    base: &Base,
    scheme: Osd,
    level: u32,
    tags: &Tags,
    options: SubdivisionOptions,
    stencils: bool,
) -> Result<PolygonMesh, String> {
    let rule = match scheme {
        Osd::Loop => Rule::Loop,
        Osd::Catmark => Rule::CatmullClark,
    };
    let sharpness = Sharpness::from_tags_of(&base.polygons, &base.mesh, tags)
        .map_err(|e| format!("sharpness: {e}"))?;
    let opts = SubdivideOptions::default()
        .with_sharpness(&sharpness)
        .with_subdivision(options);
    let r = Refinement::new(&base.mesh, rule, level, &opts).map_err(|e| e.to_string())?;
    let points: Vec<[f64; 3]> = base.mesh.positions().iter().map(|p| p.to_array()).collect();
    let mut out = vec![[0.0; 3]; r.n_vertices(level)];
    r.evaluate(&points, &mut out).map_err(|e| e.to_string())?;
    if stencils {
        let table = r.stencils().map_err(|e| e.to_string())?;
        let mut again = vec![[0.0; 3]; r.n_vertices(level)];
        table
            .apply(&points, &mut again)
            .map_err(|e| e.to_string())?;
        let diagonal = bounding_box_diagonal(base.mesh.positions());
        for (v, (a, b)) in out.iter().zip(&again).enumerate() {
            let d = DVec3::from_array(*a).distance(DVec3::from_array(*b));
            if d > 1e-13 * diagonal {
                return Err(format!(
                    "stencil vertex {v} is {d:e} away from the evaluation"
                ));
            }
        }
    }
    let mut offsets = vec![0u32; r.n_faces(level) + 1];
    let mut indices = vec![0u32; r.n_corners(level)];
    r.write_polygons(&mut offsets, &mut indices)
        .map_err(|e| e.to_string())?;
    let faces: Vec<Vec<u32>> = offsets
        .windows(2)
        .map(|w| indices[w[0] as usize..w[1] as usize].to_vec())
        .collect();
    Ok(PolygonMesh::from_faces(
        out.into_iter().map(DVec3::from_array).collect(),
        faces,
    ))
}

/// One crease comparison: `halfedge` with `tags` and `options` against the driver reading the
/// file's tags (`--tags`), with the options given as flags; `Err` names the first difference.
fn compare_creased(
    base: &Base,
    scheme: Osd,
    level: u32,
    tags: &Tags,
    options: SubdivisionOptions,
) -> Result<Outcome, String> {
    let method = options.crease_method.name();
    let triangles = options.triangle_rule.name();
    let boundary = match options.boundary {
        BoundaryInterpolation::Edge => "edge-only",
        BoundaryInterpolation::EdgeAndCorner => "edge-and-corner",
        BoundaryInterpolation::None => "none",
    };
    let flags = [
        "--tags",
        "--crease-method",
        method,
        "--triangle-rule",
        triangles,
    ];
    let at = format!(
        "{}, {scheme:?} vs OpenSubdiv {} level {level}, boundary {boundary}, {method}, {triangles}",
        base.file,
        scheme.driver_name()
    );
    let running = opensubdiv_with(&flags, scheme, level, &base.path, Some(boundary));
    let ours = refine_ours(base, scheme, level, tags, options, level <= 2);
    let theirs = running.mesh();
    let ours = ours.map_err(|e| format!("{at}: {e}"))?;
    compare_levels(&at, &base.polygons, &ours, &theirs)
}

/// Runs every comparison of `cases` and fails with all disagreements at once.
fn check_creased(cases: &[(&Base, Osd, &Tags, SubdivisionOptions)], levels: &[u32]) {
    driver();
    let mut failures = Vec::new();
    let mut largest = 0.0f64;
    for &(base, scheme, tags, options) in cases {
        for &level in levels {
            match compare_creased(base, scheme, level, tags, options) {
                Ok(outcome) => largest = largest.max(outcome.max_deviation),
                Err(message) => failures.push(message),
            }
        }
    }
    eprintln!(
        "{} crease comparisons, largest deviation {largest:.3e} of the diagonal",
        cases.len() * levels.len()
    );
    assert!(
        failures.is_empty(),
        "halfedge's crease rules disagree with OpenSubdiv:\n{}",
        failures.join("\n")
    );
}

/// The resolved options of a file's tags (edge / uniform / catmark where it says nothing).
fn tag_options(tags: &Tags) -> SubdivisionOptions {
    tags.options.over(SubdivisionOptions::default())
}

/// Every tagged shared mesh with its own tags (OpenSubdiv's creases, Chaikin's rule, its
/// boundary modes), Catmull-Clark on all, Loop on the triangle one, levels 1-3.
#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn crease_rules_match_opensubdiv_on_every_tagged_shared_mesh() {
    let files = [
        ("osd_catmark_bishop.obj", Osd::Catmark),
        ("osd_catmark_pawn.obj", Osd::Catmark),
        ("osd_catmark_chaikin2.obj", Osd::Catmark),
        ("osd_catmark_nonquads.obj", Osd::Catmark),
        ("osd_loop_icosahedron.obj", Osd::Loop),
        ("osd_loop_icosahedron.obj", Osd::Catmark),
    ];
    let bases: Vec<(Base, Osd, Tags)> = files
        .iter()
        .map(|&(file, scheme)| {
            let base = Base::load(file).unwrap_or_else(|e| panic!("{e}"));
            let tags = read_tags(&base.path);
            assert!(!tags.is_empty(), "{file} has no tags");
            (base, scheme, tags)
        })
        .collect();
    let cases: Vec<_> = bases
        .iter()
        .map(|(base, scheme, tags)| (base, *scheme, tags, tag_options(tags)))
        .collect();
    check_creased(&cases, &[1, 2, 3]);
}

/// A generated test mesh with its tags, written as an OBJ with OpenSubdiv's `t` lines into the
/// system's temporary folder (one file per mesh and process, removed on drop).
struct Generated {
    base: Base,
    tags: Tags,
}

impl Generated {
    fn new(name: &str, polygons: PolygonMesh, tags: Tags) -> Generated {
        use std::fmt::Write as _;
        let mut text = String::new();
        for p in &polygons.positions {
            writeln!(text, "v {} {} {}", p.x, p.y, p.z).expect("a string");
        }
        for face in polygons.faces() {
            text.push('f');
            for &v in face {
                write!(text, " {}", v + 1).expect("a string");
            }
            text.push('\n');
        }
        for c in tags.creases() {
            writeln!(text, "t crease 2/1/0 {} {} {}", c.a, c.b, c.sharpness).expect("a string");
        }
        for c in tags.corners() {
            writeln!(text, "t corner 1/1/0 {} {}", c.vertex, c.sharpness).expect("a string");
        }
        for f in tags.holes() {
            writeln!(text, "t hole 1/0/0 {f}").expect("a string");
        }
        let path = std::env::temp_dir().join(format!(
            "subcount-creases-{}-{name}.obj",
            std::process::id()
        ));
        std::fs::write(&path, text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mesh = HalfEdgeMesh::try_from_polygon_mesh(&polygons)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        Generated {
            base: Base {
                file: name.to_owned(),
                path,
                polygons,
                mesh,
                has_bare_vertices: false,
            },
            tags,
        }
    }
}

impl Drop for Generated {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.base.path);
    }
}

/// An `n` x `n` grid of quads over a bumpy height field (so no rule is exact by symmetry),
/// vertex `(i, j)` numbered `j (n + 1) + i`; split into triangles along one diagonal when
/// `triangles`.
fn bumpy_grid(n: u32, triangles: bool) -> PolygonMesh {
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let positions = (0..=n)
        .flat_map(|j| (0..=n).map(move |i| (i, j)))
        .map(|(i, j)| {
            let (x, y) = (f64::from(i), f64::from(j));
            DVec3::new(
                x + 0.1 * y.sin(),
                y,
                0.3 * (1.3 * x).sin() * (0.7 * y).cos(),
            )
        })
        .collect();
    let mut mesh = PolygonMesh::with_positions(positions);
    for j in 0..n {
        for i in 0..n {
            let [a, b, c, d] = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            if triangles {
                mesh.push_face(&[a, b, c]);
                mesh.push_face(&[a, c, d]);
            } else {
                mesh.push_face(&[a, b, c, d]);
            }
        }
    }
    mesh
}

/// Tags on a 4 x 4 grid: a boundary-to-boundary chain along row 2 of every kind of sharpness
/// (0.5, 1.3, 2.7, infinite), a chain along row 1 ending in an infinitely sharp corner and a
/// semi-sharp one, an isolated semi-sharp edge (a dart at each end), a semi-sharp corner on
/// the row-2 chain and one on a boundary corner of the grid.
fn grid_tags() -> Tags {
    let id = |i: u32, j: u32| j * 5 + i;
    let mut tags = Tags::default();
    for (i, s) in [0.5, 1.3, 2.7, INFINITELY_SHARP].into_iter().enumerate() {
        let i = i as u32;
        tags.add_crease(id(i, 2), id(i + 1, 2), s).expect("valid");
    }
    tags.add_crease(id(1, 1), id(2, 1), 0.5).expect("valid");
    tags.add_crease(id(2, 1), id(3, 1), 1.3).expect("valid");
    tags.add_corner(id(1, 1), INFINITELY_SHARP).expect("valid");
    tags.add_corner(id(3, 1), 1.3).expect("valid");
    tags.add_crease(id(1, 3), id(2, 3), 2.7).expect("valid");
    tags.add_corner(id(3, 2), 0.5).expect("valid");
    tags.add_corner(id(0, 0), 0.5).expect("valid");
    tags
}

/// Tags where three and four semi-sharp edges meet at one vertex (the sums of `f32`
/// sharpness run in OpenSubdiv's edge order): a star at the grid's centre, its edges 0.3,
/// 0.7, 0.9 and 1.7, and a T of 0.2, 2.2, 1.1 at vertex (1, 3).
fn star_tags() -> Tags {
    let id = |i: u32, j: u32| j * 5 + i;
    let mut tags = Tags::default();
    let c = id(2, 2);
    for (v, s) in [
        (id(3, 2), 0.3),
        (id(2, 3), 0.7),
        (id(1, 2), 0.9),
        (id(2, 1), 1.7),
    ] {
        tags.add_crease(c, v, s).expect("valid");
    }
    let t = id(1, 3);
    for (v, s) in [(id(0, 3), 0.2), (id(2, 3), 2.2), (id(1, 4), 1.1)] {
        tags.add_crease(t, v, s).expect("valid");
    }
    tags
}

/// Every combination of boundary mode and crease method (triangle rule `catmark`).
fn all_modes() -> Vec<SubdivisionOptions> {
    let mut out = Vec::new();
    for &boundary in BoundaryInterpolation::ALL {
        for &method in CreaseMethod::ALL {
            out.push(
                SubdivisionOptions::default()
                    .with_boundary(boundary)
                    .with_crease_method(method),
            );
        }
    }
    out
}

/// Generated grids with creases, corners, darts, chains ending in corners and semi-sharp
/// values (0.5, 1.3, 2.7 and infinite), each boundary mode, uniform and Chaikin: Catmull-Clark
/// on quads and triangles, Loop on triangles, levels 1-3. One grid also has holes (a face at
/// the boundary, two adjacent ones, all four around an interior vertex) on OpenSubdiv's side
/// only: uniform refinement still refines and positions every vertex of a hole face, so the
/// surface is the same (holes only say what is not drawn).
#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn crease_rules_match_opensubdiv_on_generated_grids() {
    let grids = generated_grids("");
    check_creased(&grid_cases(&grids), &[1, 2, 3]);
}

/// The generated grids of the crease and limit comparisons, their files named from `prefix`:
/// quads and triangles with [`grid_tags`], both with [`star_tags`], quads with holes too.
fn generated_grids(prefix: &str) -> [Generated; 5] {
    let mut with_holes = grid_tags();
    for f in [0, 5, 6, 10, 9] {
        with_holes.add_hole(f);
    }
    [
        ("quads", false, grid_tags()),
        ("triangles", true, grid_tags()),
        ("star", false, star_tags()),
        ("star-tri", true, star_tags()),
        ("holes", false, with_holes),
    ]
    .map(|(name, triangles, tags)| {
        Generated::new(&format!("{prefix}{name}"), bumpy_grid(4, triangles), tags)
    })
}

/// Every comparison of [`generated_grids`]: each boundary mode and crease method,
/// Catmull-Clark on every grid, Loop on the triangle ones.
fn grid_cases(grids: &[Generated; 5]) -> Vec<(&Base, Osd, &Tags, SubdivisionOptions)> {
    let [quads, triangles, star, star_tri, holes] = grids;
    let mut cases = Vec::new();
    for options in all_modes() {
        for (g, scheme) in [
            (quads, Osd::Catmark),
            (triangles, Osd::Catmark),
            (triangles, Osd::Loop),
            (star, Osd::Catmark),
            (star_tri, Osd::Loop),
            (holes, Osd::Catmark),
        ] {
            cases.push((&g.base, scheme, &g.tags, options));
        }
    }
    cases
}

/// Closed meshes: a cube (Catmull-Clark) and an icosahedron (Loop and Catmull-Clark) with a
/// loop of creases around one face, a chain ending in corners and semi-sharp corners, uniform
/// and Chaikin.
#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn crease_rules_match_opensubdiv_on_closed_meshes() {
    let closed_tags = |mesh: &PolygonMesh| {
        let mut tags = Tags::default();
        let face = mesh.face(0);
        let sharpness = [1.3, 2.7, 0.5, INFINITELY_SHARP];
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            tags.add_crease(a, b, sharpness[k % 4]).expect("valid");
        }
        // A chain across the next face, ending in corners.
        let next = mesh.face(1);
        tags.add_crease(next[1], next[2], 0.5).expect("valid");
        tags.add_corner(next[2], 2.7).expect("valid");
        tags.add_corner(face[0], 0.5).expect("valid");
        tags
    };
    let cube = halfedge::shapes::cube();
    let ico = halfedge::shapes::icosahedron();
    let cube = Generated::new("cube", cube.clone(), closed_tags(&cube));
    let ico = Generated::new("icosahedron", ico.clone(), closed_tags(&ico));
    let mut cases = Vec::new();
    for &method in CreaseMethod::ALL {
        let options = SubdivisionOptions::default().with_crease_method(method);
        cases.push((&cube.base, Osd::Catmark, &cube.tags, options));
        cases.push((&ico.base, Osd::Loop, &ico.tags, options));
        cases.push((&ico.base, Osd::Catmark, &ico.tags, options));
    }
    check_creased(&cases, &[1, 2, 3]);
}

/// Catmark's smooth-triangle rule (`TRI_SUB_SMOOTH`) on meshes mixing triangles with quads and
/// n-gons, with and without creases, and each boundary mode.
#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn smooth_triangles_match_opensubdiv() {
    let mut mixed = halfedge::shapes::mixed();
    for (v, p) in mixed.positions.iter_mut().enumerate() {
        p.z = 0.2 * (v as f64).sin();
    }
    let mut creased = Tags::default();
    creased.add_crease(3, 4, 1.3).expect("valid");
    creased.add_crease(4, 10, 0.5).expect("valid");
    creased.add_corner(9, 2.7).expect("valid");
    let plain = Generated::new("mixed", mixed.clone(), Tags::default());
    let with_creases = Generated::new("mixed-creased", mixed, creased);
    let pyramid = Base::load("osd_catmark_pyramid.obj").unwrap_or_else(|e| panic!("{e}"));
    let nonquads = Base::load("osd_catmark_nonquads.obj").unwrap_or_else(|e| panic!("{e}"));
    let none = Tags::default();
    let nonquad_tags = read_tags(&nonquads.path);
    let mut cases = Vec::new();
    for &boundary in BoundaryInterpolation::ALL {
        let options = SubdivisionOptions::default()
            .with_boundary(boundary)
            .with_triangle_rule(TriangleRule::Smooth);
        cases.push((&plain.base, Osd::Catmark, &plain.tags, options));
        cases.push((
            &with_creases.base,
            Osd::Catmark,
            &with_creases.tags,
            options,
        ));
        cases.push((&nonquads, Osd::Catmark, &nonquad_tags, options));
    }
    let smooth = SubdivisionOptions::default().with_triangle_rule(TriangleRule::Smooth);
    cases.push((&pyramid, Osd::Catmark, &none, smooth));
    check_creased(&cases, &[1, 2, 3]);
}

/// The crease comparison can fail: the pawn's 120 creases (sharpness 6) left out of
/// `halfedge`'s side, or Chaikin's rule asked of one side only, are told apart.
#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn missing_creases_are_told_apart() {
    driver();
    let pawn = Base::load("osd_catmark_pawn.obj").unwrap_or_else(|e| panic!("{e}"));
    let tags = read_tags(&pawn.path);
    let flags = ["--tags"];
    let running = opensubdiv_with(&flags, Osd::Catmark, 1, &pawn.path, None);
    let ours = refine_ours(
        &pawn,
        Osd::Catmark,
        1,
        &Tags::default(),
        SubdivisionOptions::default(),
        false,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let err = compare_levels(
        "pawn without creases",
        &pawn.polygons,
        &ours,
        &running.mesh(),
    )
    .err()
    .expect("the creases went unnoticed");
    assert!(err.contains("has no halfedge vertex within"), "{err}");

    let chaikin = Base::load("osd_catmark_chaikin2.obj").unwrap_or_else(|e| panic!("{e}"));
    let tags_chaikin = read_tags(&chaikin.path);
    assert_eq!(
        tags_chaikin.options.crease_method,
        Some(CreaseMethod::Chaikin)
    );
    let uniform = SubdivisionOptions::default();
    let err = (1..=3)
        .map(|level| compare_creased(&chaikin, Osd::Catmark, level, &tags_chaikin, uniform))
        .find_map(Result::err);
    // The driver was told `uniform` too (flags win over the file's tag): both agree.
    assert!(err.is_none(), "{err:?}");
    let running = opensubdiv_with(&flags, Osd::Catmark, 2, &chaikin.path, None);
    let ours = refine_ours(&chaikin, Osd::Catmark, 2, &tags_chaikin, uniform, false)
        .unwrap_or_else(|e| panic!("{e}"));
    let err = compare_levels(
        "chaikin2 as uniform",
        &chaikin.polygons,
        &ours,
        &running.mesh(),
    )
    .err()
    .expect("Chaikin's rule went unnoticed");
    assert!(err.contains("has no halfedge vertex within"), "{err}");
    drop(tags);

    // Smooth triangles on one side only.
    let pyramid = Base::load("osd_catmark_pyramid.obj").unwrap_or_else(|e| panic!("{e}"));
    let smooth = ["--tags", "--triangle-rule", "smooth"];
    let running = opensubdiv_with(&smooth, Osd::Catmark, 1, &pyramid.path, None);
    let none = Tags::default();
    let ours = refine_ours(
        &pyramid,
        Osd::Catmark,
        1,
        &none,
        SubdivisionOptions::default(),
        false,
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let err = compare_levels("pyramid", &pyramid.polygons, &ours, &running.mesh())
        .err()
        .expect("the smooth triangle rule went unnoticed");
    assert!(err.contains("has no halfedge vertex within"), "{err}");
}

/// Holes against OpenSubdiv's (`holeIndices`, read by the driver from the file's `t hole`
/// tags, and `VTX_BOUNDARY_NONE`, which makes every face at a boundary vertex a hole): the
/// written part of `halfedge`'s last level (hole faces, their descendants and the vertices
/// only they use left out) against OpenSubdiv's faces not tagged as holes, vertex for vertex
/// to 1e-12 of the diagonal and face for face. Generated meshes: bumpy quad and triangle
/// grids with a single hole, adjacent holes, holes at the boundary and a vertex surrounded by
/// holes; a closed cube and icosahedron with holes; the grids under boundary `none`, also with
/// infinitely sharp and semi-sharp boundary creases (which keep or do not keep faces). Loop and
/// Catmull-Clark, levels 1-3.
#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn holes_match_opensubdiv_on_generated_meshes() {
    use halfedge::holes::{boundary_faces, HoleSet};
    driver();
    let lift = |mut mesh: PolygonMesh| {
        for (i, p) in mesh.positions.iter_mut().enumerate() {
            let t = i as f64;
            *p += DVec3::new(
                0.05 * (t * 0.7).sin(),
                0.03 * (t * 1.3).cos(),
                0.2 * (t * 0.9).sin(),
            );
        }
        mesh
    };
    let quads = bumpy_grid(4, false);
    let triangles = bumpy_grid(4, true);
    // Vertex (2, 2) = 12 is interior: quads 5, 6, 9, 10 around it; its six triangles.
    let around = |mesh: &PolygonMesh, v: u32| -> Vec<u32> {
        (0..mesh.n_faces() as u32)
            .filter(|&f| mesh.face(f as usize).contains(&v))
            .collect()
    };
    let cases: Vec<(&str, PolygonMesh, Osd, Vec<Vec<u32>>)> = vec![
        (
            "quads",
            quads.clone(),
            Osd::Catmark,
            vec![
                vec![5],
                vec![5, 6],
                vec![0, 3, 12],
                around(&quads, 12),
                vec![5, 10],
            ],
        ),
        (
            "triangles",
            triangles.clone(),
            Osd::Loop,
            vec![
                vec![10],
                vec![10, 11],
                vec![0, 1, 7],
                around(&triangles, 12),
            ],
        ),
        (
            "triangles",
            triangles.clone(),
            Osd::Catmark,
            vec![vec![10, 11], around(&triangles, 12)],
        ),
        (
            "cube",
            lift(halfedge::shapes::cube()),
            Osd::Catmark,
            vec![vec![0], vec![0, 2]],
        ),
        (
            "icosahedron",
            lift(halfedge::shapes::icosahedron()),
            Osd::Loop,
            vec![
                vec![3],
                vec![3, 4],
                around(&halfedge::shapes::icosahedron(), 0),
            ],
        ),
    ];
    let mut failures = Vec::new();
    let (mut compared, mut largest, mut hole_faces) = (0usize, 0.0f64, 0usize);
    let mut check = |g: &Generated,
                     scheme: Osd,
                     holes: &HoleSet,
                     sharpness: Option<&Sharpness>,
                     boundary: &str| {
        let rule = match scheme {
            Osd::Loop => Rule::Loop,
            Osd::Catmark => Rule::CatmullClark,
        };
        for level in 1..=3 {
            let at = format!(
                "{} holes {:?}, {rule} vs OpenSubdiv {} level {level}, boundary {boundary}",
                g.base.file,
                holes.faces(),
                scheme.driver_name()
            );
            let running = opensubdiv_with(&["--tags"], scheme, level, &g.base.path, Some(boundary));
            let mut opts = SubdivideOptions::default().with_holes(holes);
            if let Some(sharpness) = sharpness {
                opts = opts.with_sharpness(sharpness);
            }
            let ours = subdivide_to_face_list(&g.base.mesh, rule, level, &opts);
            let (theirs, n_holes) = running.written();
            hole_faces += n_holes;
            compared += 1;
            match ours
                .map_err(|e| format!("{at}: {e}"))
                .and_then(|ours| compare_levels(&at, &g.base.polygons, &ours.mesh, &theirs))
            {
                Ok(outcome) => largest = largest.max(outcome.max_deviation),
                Err(message) => failures.push(message),
            }
        }
    };
    for (name, mesh, scheme, hole_sets) in &cases {
        for (k, faces) in hole_sets.iter().enumerate() {
            let mut tags = Tags::default();
            for &f in faces {
                tags.add_hole(f);
            }
            let g = Generated::new(&format!("holes-{name}-{k}"), mesh.clone(), tags);
            let holes = HoleSet::new(mesh.n_faces(), faces.iter().copied()).expect("in range");
            check(&g, *scheme, &holes, None, "edge-only");
        }
    }
    // VTX_BOUNDARY_NONE: the faces at the boundary are OpenSubdiv's holes, and ours.
    for (name, mesh, scheme) in [
        ("quads", &quads, Osd::Catmark),
        ("triangles", &triangles, Osd::Loop),
        ("triangles", &triangles, Osd::Catmark),
    ] {
        let g = Generated::new(&format!("none-{name}"), mesh.clone(), Tags::default());
        let holes = HoleSet::new(mesh.n_faces(), boundary_faces(mesh)).expect("in range");
        check(&g, scheme, &holes, None, "none");
    }
    // VTX_BOUNDARY_NONE with creased boundaries: a vertex whose boundary edges are all
    // infinitely sharp keeps its faces (the whole boundary at 10; the bottom row at 10, so the
    // faces at its inner vertices stay; the bottom row at 9.99, not infinite: all holes).
    let (bottom, ring) = {
        let id = |i: u32, j: u32| j * 5 + i;
        let bottom: Vec<(u32, u32)> = (0..4).map(|i| (id(i, 0), id(i + 1, 0))).collect();
        let mut ring = bottom.clone();
        ring.extend((0..4).map(|i| (id(i, 4), id(i + 1, 4))));
        ring.extend((0..4).map(|j| (id(0, j), id(0, j + 1))));
        ring.extend((0..4).map(|j| (id(4, j), id(4, j + 1))));
        (bottom, ring)
    };
    let mut kept_by_creases = 0;
    for (name, mesh, scheme) in [
        ("quads", &quads, Osd::Catmark),
        ("triangles", &triangles, Osd::Loop),
        ("triangles", &triangles, Osd::Catmark),
    ] {
        for (k, (edges, sharpness)) in [(&ring, 10.0), (&bottom, 10.0), (&bottom, 9.99)]
            .into_iter()
            .enumerate()
        {
            let mut tags = Tags::default();
            for &(a, b) in edges {
                tags.add_crease(a, b, sharpness).expect("a valid sharpness");
            }
            let g = Generated::new(
                &format!("none-creased-{name}-{k}"),
                mesh.clone(),
                tags.clone(),
            );
            let faces = halfedge::holes::boundary_faces_with(mesh, &tags);
            kept_by_creases += boundary_faces(mesh).len() - faces.len();
            let holes = HoleSet::new(mesh.n_faces(), faces).expect("in range");
            let sharp = Sharpness::from_tags(&g.base.mesh, &tags).expect("edges of the mesh");
            check(&g, scheme, &holes, Some(&sharp), "none");
        }
    }
    assert!(kept_by_creases > 0, "no creased boundary kept a face");
    // Holes beside creases and a corner: the crease row y = 2 (vertices 10-14) runs along the
    // hole's corner 12, semi-sharp then infinitely sharp; vertex 0 a corner.
    for (name, mesh, scheme, hole) in [
        ("quads", &quads, Osd::Catmark, 5),
        ("triangles", &triangles, Osd::Loop, 10),
        ("triangles", &triangles, Osd::Catmark, 10),
    ] {
        let mut tags = Tags::default();
        tags.add_hole(hole);
        for (a, b, s) in [(10, 11, 1.5), (11, 12, 1.5), (12, 13, 10.0), (13, 14, 10.0)] {
            tags.add_crease(a, b, s).expect("a valid sharpness");
        }
        tags.add_corner(0, 2.5).expect("a valid sharpness");
        let g = Generated::new(&format!("creased-holes-{name}"), mesh.clone(), tags.clone());
        let sharpness = Sharpness::from_tags(&g.base.mesh, &tags).expect("edges of the mesh");
        let holes = HoleSet::new(mesh.n_faces(), [hole]).expect("in range");
        check(&g, scheme, &holes, Some(&sharpness), "edge-only");
    }
    eprintln!(
        "{compared} hole comparisons ({hole_faces} OpenSubdiv hole faces), largest deviation {largest:.3e} of the diagonal"
    );
    assert!(hole_faces > 0, "the driver listed no hole faces");
    assert!(
        failures.is_empty(),
        "halfedge's holes disagree with OpenSubdiv:\n{}",
        failures.join("\n")
    );
}
