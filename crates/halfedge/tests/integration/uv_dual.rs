//! UVs under the dual rules (Doo-Sabin and mid-edge, closed and with boundary): the corner
//! channel of `halfedge::refine::face_varying` against `schemes::uv`'s recurrences (the
//! distinct values written), its values (affine reproduction on a flat layout without
//! seams, seam edge faces in one chart, each value at one vertex), its buffers and the
//! face list of `subdivide_to_face_list`.

use halfedge::glam::{DVec2, DVec3};
use halfedge::refine::Refinement;
use halfedge::subdivide::{subdivide_to_face_list, SubdivideOptions};
use halfedge::uv::{UvLayout, Uvs};
use halfedge::{io, shapes, stats, Error, HalfEdgeMesh, PolygonMesh, Rule};
use schemes::BigInt;

use super::uv_counts::{grid_with_seams, grid_with_shared_runs, values, written_values};

const DUAL: [Rule; 2] = [Rule::DooSabin, Rule::MidEdge];

/// The refinement of `mesh` by `rule` with its UVs.
fn refine(mesh: &PolygonMesh, rule: Rule, levels: u32) -> (Refinement, UvLayout) {
    let layout = mesh.uv_layout().expect("a layout");
    let half = HalfEdgeMesh::try_from(mesh).expect("manifold");
    let opts = SubdivideOptions::default().with_uvs(&layout);
    let r = Refinement::new(&half, rule, levels, &opts).unwrap_or_else(|e| panic!("{rule}: {e}"));
    (r, layout)
}

/// The positions, the face list and the UV of every corner of the last level.
struct Corners {
    positions: Vec<[f64; 3]>,
    offsets: Vec<u32>,
    vertices: Vec<u32>,
    uv_indices: Vec<u32>,
    uvs: Vec<[f64; 2]>,
}

fn corners(mesh: &PolygonMesh, rule: Rule, levels: u32) -> Corners {
    let (r, layout) = refine(mesh, rule, levels);
    let base: Vec<[f64; 3]> = mesh.positions.iter().map(|p| p.to_array()).collect();
    let mut positions = vec![[0.0; 3]; r.n_vertices(levels)];
    r.evaluate(&base, &mut positions).expect("evaluated");
    let mut offsets = vec![0u32; r.n_faces(levels) + 1];
    let mut vertices = vec![0u32; r.n_corners(levels)];
    r.write_polygons(&mut offsets, &mut vertices)
        .expect("faces");
    let uv_base: Vec<[f64; 2]> = layout.values().iter().map(|v| v.to_array()).collect();
    let mut uvs = vec![[0.0; 2]; r.n_uvs(levels)];
    r.evaluate_uvs(&uv_base, &mut uvs).expect("uvs");
    let mut uv_indices = vec![0u32; r.n_corners(levels)];
    r.write_uv_indices(&mut uv_indices).expect("uv indices");
    Corners {
        positions,
        offsets,
        vertices,
        uv_indices,
        uvs,
    }
}

/// The cube with every face its own chart (a UV square shifted by 10 per face): every edge is
/// a seam.
fn cube_of_charts() -> PolygonMesh {
    let mut cube = shapes::cube();
    let square = [DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
    let coords: Vec<DVec2> = (0..6)
        .flat_map(|f| square.map(|c| c + DVec2::new(10.0 * f64::from(f), 0.0)))
        .collect();
    cube.set_uvs(Some(Uvs::new(coords, (0..24).collect()).expect("in range")))
        .expect("one vt per corner");
    cube
}

/// A flat `w` x `h` quad grid (triangles when `triangles`) with the affine UVs `uv(p)` and
/// no seam, its vertices moved off the lattice a little.
fn flat_grid(w: u32, h: u32, triangles: bool) -> PolygonMesh {
    let mut mesh = if triangles {
        shapes::grid(w, h)
    } else {
        shapes::quad_grid(w, h)
    }
    .expect("a grid");
    for (i, p) in mesh.positions.iter_mut().enumerate() {
        let k = i as f64;
        *p += DVec3::new(0.13 * (k * 1.7).sin(), 0.11 * (k * 2.3).cos(), 0.0);
    }
    let coords: Vec<DVec2> = mesh.positions.iter().map(|&p| affine(p)).collect();
    let corners: Vec<u32> = mesh.faces().flatten().copied().collect();
    mesh.set_uvs(Some(Uvs::new(coords, corners).expect("in range")))
        .expect("one vt per corner");
    mesh
}

fn affine(p: DVec3) -> DVec2 {
    DVec2::new(0.3 * p.x - 0.2 * p.y + 0.5, 0.1 * p.x + 0.4 * p.y - 0.25)
}

/// A torus (closed, genus 1) whose corners use `vt` chosen by `picks` (0: the vertex's own,
/// else one of three per vertex), so seams fall anywhere.
fn torus_with_seams(picks: &[u8]) -> PolygonMesh {
    let mut mesh = shapes::torus(1).expect("a torus");
    let n = mesh.n_vertices() as u32;
    let corners: Vec<u32> = mesh
        .faces()
        .flatten()
        .enumerate()
        .map(|(i, &v)| u32::from(picks[i % picks.len()]) * n + v)
        .collect();
    let coords: Vec<DVec2> = (0..4 * n)
        .map(|t| DVec2::new(f64::from(t), f64::from(t % 7)))
        .collect();
    mesh.set_uvs(Some(Uvs::new(coords, corners).expect("in range")))
        .expect("one vt per corner");
    mesh
}

#[test]
fn the_cube_of_charts_counts_its_seams() {
    let cube = cube_of_charts();
    let uv = stats::uv_counts(&cube).expect("a layout");
    assert_eq!(uv.seam_edges, 12);
    // Doo-Sabin: V(s) + 2 * 3^(s-1) * 12 with V(s) = 2E(s-1), E(s) = 4^s * 12.
    // Mid-edge: E(s-1) + S(s-1) with S(s) = 2^s * 12, E(s) = 2^s * 12.
    for s in 1..=3u32 {
        let ds = 2 * 12 * 4u64.pow(s - 1) + 2 * 3u64.pow(s - 1) * 12;
        let me = 12 * 2u64.pow(s - 1) + 12 * 2u64.pow(s - 1);
        assert_eq!(
            written_values(&cube, Rule::DooSabin, s),
            Ok(ds),
            "level {s}"
        );
        assert_eq!(written_values(&cube, Rule::MidEdge, s), Ok(me), "level {s}");
        for (rule, n) in [(Rule::DooSabin, ds), (Rule::MidEdge, me)] {
            assert_eq!(
                values(rule, &uv, u64::from(s)..=u64::from(s)),
                [BigInt::from(n)]
            );
        }
    }
}

/// A torus whose UVs are an affine image of its positions, without seams.
fn affine_torus() -> PolygonMesh {
    let mut mesh = shapes::torus(1).expect("a torus");
    let coords: Vec<DVec2> = mesh
        .positions
        .iter()
        .map(|&p| affine(p) + DVec2::new(0.2 * p.z, -0.3 * p.z))
        .collect();
    let corners: Vec<u32> = mesh.faces().flatten().copied().collect();
    mesh.set_uvs(Some(Uvs::new(coords, corners).expect("in range")))
        .expect("one vt per corner");
    mesh
}

/// Without seams the UV values are the vertices from level 1 on, and with UVs an affine image
/// of the positions they stay one: on a closed torus at every level, and on a flat grid
/// under Doo-Sabin at every level (its boundary points are Chaikin's for both), under mid-edge
/// at the edge midpoints of level 1 (its kept boundary vertices keep their UV while their
/// positions move, so later levels differ near the boundary).
#[test]
fn a_layout_without_seams_reproduces_affine_uvs() {
    let torus = affine_torus();
    for rule in DUAL {
        for levels in 1..=3 {
            let c = corners(&torus, rule, levels);
            assert_eq!(c.uvs.len(), c.positions.len(), "{rule} {levels}");
            for (&v, &i) in c.vertices.iter().zip(&c.uv_indices) {
                let p = DVec3::from_array(c.positions[v as usize]);
                let expected = affine(p) + DVec2::new(0.2 * p.z, -0.3 * p.z);
                let uv = DVec2::from_array(c.uvs[i as usize]);
                assert!(
                    (uv - expected).length() < 1e-12,
                    "{rule} level {levels} vertex {v}: {uv} against {expected}"
                );
            }
        }
    }
    for triangles in [false, true] {
        let grid = flat_grid(4, 3, triangles);
        let half = HalfEdgeMesh::try_from(&grid).expect("manifold");
        for rule in DUAL {
            let last = if rule == Rule::MidEdge { 1 } else { 3 };
            for levels in 1..=last {
                let c = corners(&grid, rule, levels);
                assert_eq!(c.uvs.len(), c.positions.len(), "{rule} {levels}");
                let counts = half.counts();
                let scheme = rule.scheme_for(&counts).expect("a scheme");
                let edges_before = scheme
                    .counts_at(&counts, u64::from(levels - 1))
                    .expect("counts")
                    .edges;
                let mut checked = 0;
                for (&v, &i) in c.vertices.iter().zip(&c.uv_indices) {
                    if rule == Rule::MidEdge && BigInt::from(v) >= edges_before {
                        continue;
                    }
                    let p = DVec3::from_array(c.positions[v as usize]);
                    let uv = DVec2::from_array(c.uvs[i as usize]);
                    assert!(
                        (uv - affine(p)).length() < 1e-12,
                        "{rule} level {levels} vertex {v}: {uv} against {}",
                        affine(p)
                    );
                    checked += 1;
                }
                assert!(checked > c.vertices.len() / 2, "{rule} {levels}: {checked}");
            }
        }
    }
}

/// Every UV value sits at one vertex, and at level 1 on the cube of charts every face but the
/// vertex faces (which straddle the charts meeting at their vertex) lies in one chart.
#[test]
fn seam_edge_faces_lie_in_one_chart() {
    let cube = cube_of_charts();
    let (f, e) = (6usize, 12usize);
    for rule in DUAL {
        for levels in 1..=3 {
            let c = corners(&cube, rule, levels);
            let mut vertex_of = vec![u32::MAX; c.uvs.len()];
            for (&v, &i) in c.vertices.iter().zip(&c.uv_indices) {
                let slot = &mut vertex_of[i as usize];
                assert!(*slot == u32::MAX || *slot == v, "{rule}: value {i}");
                *slot = v;
            }
            if levels > 1 {
                continue;
            }
            // Face faces 0..F, Doo-Sabin's edge faces F..F+E, then the vertex faces.
            let one_chart = if rule == Rule::DooSabin { f + e } else { f };
            let mut straddling = 0;
            for (k, w) in c.offsets.windows(2).enumerate() {
                let charts: Vec<i64> = c.uv_indices[w[0] as usize..w[1] as usize]
                    .iter()
                    .map(|&i| (c.uvs[i as usize][0] / 10.0).floor() as i64)
                    .collect();
                let single = charts.iter().all(|&x| x == charts[0]);
                if k < one_chart {
                    assert!(single, "{rule} face {k}: charts {charts:?}");
                } else if !single {
                    straddling += 1;
                }
            }
            // The cube's 8 vertices each meet three charts.
            assert_eq!(straddling, 8, "{rule}");
        }
    }
}

#[test]
fn buffers_of_the_wrong_length_are_refused() {
    let cube = cube_of_charts();
    for rule in DUAL {
        let (r, layout) = refine(&cube, rule, 2);
        assert!(r.has_uvs());
        let base: Vec<[f32; 2]> = layout
            .values()
            .iter()
            .map(|v| v.as_vec2().to_array())
            .collect();
        let mut out = vec![[0f32; 2]; r.n_uvs(2)];
        let err = r.evaluate_uvs(&base[..5], &mut out).unwrap_err();
        assert_eq!(err.to_string(), "uv base buffer has 5 entries, expected 24");
        let err = r.evaluate_uvs(&base, &mut out[1..]).unwrap_err();
        assert!(
            matches!(err, Error::BufferSize { what: "uv out", .. }),
            "{err}"
        );
        let mut indices = vec![0u32; r.n_corners(2) + 1];
        let err = r.write_uv_indices(&mut indices).unwrap_err();
        assert!(
            matches!(
                err,
                Error::BufferSize {
                    what: "uv indices",
                    ..
                }
            ),
            "{err}"
        );
        r.evaluate_uvs(&base, &mut out).expect("f32 values");
        assert!(out.iter().all(|p| p[0].is_finite() && p[1].is_finite()));
    }
}

/// The values do not depend on the threads (the weight tables are evaluated in parallel
/// chunks past 16,384 values).
#[test]
fn uvs_do_not_depend_on_the_threads() {
    let grid = grid_with_seams(60, 40, false, &[0, 0, 1, 0, 2, 0, 0, 3, 0]);
    let half = HalfEdgeMesh::try_from(&grid).expect("manifold");
    let layout = grid.uv_layout().expect("a layout");
    let base: Vec<[f64; 2]> = layout
        .values()
        .iter()
        .enumerate()
        .map(|(i, _)| [(i as f64 * 0.37).sin(), (i as f64 * 0.11).cos()])
        .collect();
    for rule in DUAL {
        let run = |threads: usize| {
            let opts = SubdivideOptions::default()
                .with_threads(threads)
                .with_uvs(&layout);
            let r = Refinement::new(&half, rule, 2, &opts).expect("refined");
            let mut uvs = vec![[0.0; 2]; r.n_uvs(2)];
            r.evaluate_uvs(&base, &mut uvs).expect("evaluated");
            let mut indices = vec![0u32; r.n_corners(2)];
            r.write_uv_indices(&mut indices).expect("indices");
            (uvs, indices)
        };
        let one = run(1);
        assert!(one.0.len() > 16_384, "{rule}: {}", one.0.len());
        assert_eq!(one, run(2), "{rule}");
    }
}

/// Level 0 is the layout itself: its values and its corners.
#[test]
fn level_zero_is_the_layout() {
    let cube = cube_of_charts();
    let layout = cube.uv_layout().expect("a layout");
    for rule in DUAL {
        let c = corners(&cube, rule, 0);
        assert_eq!(c.uv_indices, layout.corners(), "{rule}");
        let values: Vec<[f64; 2]> = layout.values().iter().map(|v| v.to_array()).collect();
        assert_eq!(c.uvs, values, "{rule}");
    }
}

/// The dual rules refuse holes, with UVs as without.
#[test]
fn holes_are_refused_with_uvs_too() {
    let cube = cube_of_charts();
    let half = HalfEdgeMesh::try_from(&cube).expect("manifold");
    let layout = cube.uv_layout().expect("a layout");
    let holes = halfedge::holes::HoleSet::new(cube.n_faces(), [0]).expect("a face");
    for rule in DUAL {
        let opts = SubdivideOptions::default()
            .with_uvs(&layout)
            .with_holes(&holes);
        let err = Refinement::new(&half, rule, 1, &opts).unwrap_err();
        assert!(
            matches!(err, Error::HolesNeedNestedFaces { .. }),
            "{rule}: {err}"
        );
        let err = subdivide_to_face_list(&half, rule, 1, &opts).unwrap_err();
        assert!(
            matches!(err, Error::HolesNeedNestedFaces { .. }),
            "{rule}: {err}"
        );
    }
}

/// `subdivide_to_face_list` carries the refinement's UVs (the same faces, corner for corner).
#[test]
fn the_face_list_carries_the_refinements_uvs() {
    let grid = grid_with_seams(3, 2, false, &[0, 1, 0, 0, 2, 0, 3]);
    for mesh in [grid, cube_of_charts()] {
        let half = HalfEdgeMesh::try_from(&mesh).expect("manifold");
        let layout = mesh.uv_layout().expect("a layout");
        for rule in DUAL {
            let opts = SubdivideOptions::default().with_uvs(&layout);
            let level = subdivide_to_face_list(&half, rule, 2, &opts).expect("subdivided");
            let c = corners(&mesh, rule, 2);
            let uvs = level.mesh.uvs().expect("uvs");
            assert_eq!(uvs.corners(), &c.uv_indices[..], "{rule}");
            let coords: Vec<[f64; 2]> = uvs.coords().iter().map(|p| p.to_array()).collect();
            assert_eq!(coords, c.uvs, "{rule}");
            let faces: Vec<u32> = level.mesh.faces().flatten().copied().collect();
            assert_eq!(faces, c.vertices, "{rule}");
        }
    }
}

/// Measured (distinct values written) against the recurrence at levels 1-3 on a torus with
/// random seams (closed meshes).
#[test]
fn closed_meshes_with_seams_count_their_uv_values() {
    for picks in [
        &[0u8][..],
        &[0, 1],
        &[1, 0, 0, 2, 3],
        &[3, 2, 1, 0, 0, 0, 1],
    ] {
        let mesh = torus_with_seams(picks);
        let uv = stats::uv_counts(&mesh).expect("a layout");
        for rule in DUAL {
            for s in 1..=3u32 {
                let written = written_values(&mesh, rule, s).expect("written");
                assert_eq!(
                    values(rule, &uv, u64::from(s)..=u64::from(s)),
                    [BigInt::from(written)],
                    "{rule} level {s} picks {picks:?} seams {}",
                    uv.seam_edges
                );
            }
        }
    }
}

proptest::proptest! {
    #![proptest_config(proptest::test_runner::Config::with_cases(64))]
    /// The dual rules' UV recurrences count the values the corner channel writes at levels
    /// 1-3, on grids (with boundary) with random seams and shared `vt` and on tori (closed)
    /// with random seams.
    #[test]
    fn dual_uv_recurrences_count_the_written_values(
        w in 1u32..5,
        h in 1u32..4,
        triangles in proptest::bool::ANY,
        picks in proptest::collection::vec(0u8..4, 1..40),
        checker in proptest::collection::vec(proptest::bool::weighted(0.4), 1..8),
    ) {
        let grid = grid_with_shared_runs(w, h, triangles, &picks, &checker);
        for mesh in [grid, torus_with_seams(&picks)] {
            let uv = stats::uv_counts(&mesh).expect("a layout");
            for rule in DUAL {
                for s in 1..=3u32 {
                    let written = written_values(&mesh, rule, s)
                        .map_err(proptest::test_runner::TestCaseError::fail)?;
                    proptest::prop_assert_eq!(
                        values(rule, &uv, u64::from(s)..=u64::from(s)),
                        vec![BigInt::from(written)],
                        "{} level {} seams {}", rule, s, uv.seam_edges
                    );
                }
            }
        }
    }
}

/// Measured (distinct values written) against the recurrence at levels 1-3 on every shared
/// mesh with UVs that the dual rules accept.
#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn dual_uv_counts_on_the_shared_meshes() {
    let dir = testdata::meshes_dir();
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| {
            let name = e.ok()?.file_name().to_string_lossy().into_owned();
            name.ends_with(".obj").then_some(name)
        })
        .collect();
    names.sort();
    let mut checked = Vec::new();
    for name in names {
        let mesh = io::read_obj(dir.join(&name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let Some(uv) = stats::uv_counts(&mesh) else {
            continue;
        };
        let Ok(half) = HalfEdgeMesh::try_from(&mesh) else {
            continue;
        };
        for rule in DUAL {
            let Ok(scheme) = rule.scheme_for(&half.counts()) else {
                continue;
            };
            let levels = if half.n_faces() > 20_000 { 2 } else { 3 };
            let mut row = Vec::new();
            for s in 1..=levels {
                let written = match written_values(&mesh, rule, s) {
                    Ok(n) => n,
                    Err(e) => {
                        // Only a mesh the rule refuses without UVs too (a valence-2 vertex).
                        let plain = Refinement::new(&half, rule, s, &SubdivideOptions::default());
                        assert!(plain.is_err(), "{name}: {e}");
                        break;
                    }
                };
                let predicted = values(rule, &uv, u64::from(s)..=u64::from(s));
                assert_eq!(
                    predicted,
                    [BigInt::from(written)],
                    "{name} {rule} level {s}"
                );
                row.push(written);
            }
            println!(
                "{name} {} seams {}: UV {row:?}",
                scheme.name(),
                uv.seam_edges
            );
            if !row.is_empty() {
                checked.push(format!("{name} {rule}"));
            }
        }
    }
    assert!(checked.len() >= 12, "{checked:?}");
}
