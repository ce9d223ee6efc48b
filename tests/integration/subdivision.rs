//! Formulas against real subdivision: every built-in scheme on every generated base mesh it
//! applies to, subdivided for real at levels 0 to 3; every predicted component equals the
//! measured one, and every phase's closed form, evaluated from the measured state at the
//! phase's first level, gives the measured state of the later levels.

use glam::DVec3;
use halfedge::subdivide::{verify, verify_polygons, LevelReport, SubdivideOptions};
use halfedge::{shapes, stats, HalfEdgeMesh, PolygonMesh};
use num_bigint::BigInt;
use schemes::Scheme;
use subcount_tests::{applies, measured_state, BASE_MESHES};

const LEVELS: u32 = 3;

/// The reports match, and the closed forms reproduce the measured states.
fn check_reports(
    scheme: &Scheme,
    mesh: &str,
    reports: &[LevelReport],
) -> Result<(), Box<dyn std::error::Error>> {
    assert_eq!(
        reports.len(),
        LEVELS as usize + 1,
        "{} on {mesh}",
        scheme.name()
    );
    for r in reports {
        assert!(r.is_match(), "{} on {mesh}: {r:?}", scheme.name());
    }
    let names = scheme.state_names();
    let measured: Vec<Vec<BigInt>> = reports
        .iter()
        .map(|r| measured_state(r, names))
        .collect::<Option<_>>()
        .ok_or("a state component was not measured")?;
    let mut checked = 0;
    for phase in scheme.phases() {
        let form = phase.closed_form();
        let Some(x) = measured.get(phase.first_level as usize) else {
            continue;
        };
        for t in 0.. {
            let level = phase.first_level + phase.period * t;
            let Some(want) = measured.get(level as usize) else {
                break;
            };
            assert_eq!(
                &form.evaluate(x, t)?,
                want,
                "{} on {mesh}: closed form of `{}` at level {level}",
                scheme.name(),
                phase.description
            );
            // V, E, F from the closed-form state equal the measured ones.
            let vef = scheme.vef(&form.evaluate(x, t)?)?;
            let r = &reports[level as usize];
            for (name, value) in ["V", "E", "F"].iter().zip(&vef) {
                let m = r.measured.iter().find(|(n, _)| n == name).map(|(_, v)| v);
                assert_eq!(
                    m,
                    Some(value),
                    "{} on {mesh}: {name} at level {level}",
                    scheme.name()
                );
            }
            checked += 1;
        }
    }
    assert!(
        checked > LEVELS,
        "{} on {mesh}: only {checked} levels checked",
        scheme.name()
    );
    Ok(())
}

#[test]
fn every_scheme_on_every_base_mesh() -> Result<(), Box<dyn std::error::Error>> {
    let opts = SubdivideOptions::default();
    let mut runs = Vec::new();
    for scheme in schemes::builtins() {
        for mesh_name in BASE_MESHES {
            let polygons = shapes::from_name(mesh_name)?;
            let counts = stats::face_list_counts(&polygons);
            if !applies(&scheme, &counts) {
                continue;
            }
            let mesh = HalfEdgeMesh::try_from(&polygons)?;
            let reports = verify(&mesh, &scheme, LEVELS, &opts)?;
            check_reports(&scheme, mesh_name, &reports)?;
            runs.push((scheme.name().to_string(), mesh_name));
        }
    }
    // Every scheme ran on at least two meshes, and the classes are respected.
    for scheme in schemes::builtins() {
        let n = runs.iter().filter(|(s, _)| s == scheme.name()).count();
        assert!(n >= 2, "{} ran on {n} base meshes", scheme.name());
    }
    assert!(runs.contains(&("loop".into(), "torus:2")));
    assert!(runs.contains(&("catmull-clark".into(), "mixed")));
    assert!(!runs.contains(&("loop".into(), "grid:3x2")));
    assert!(!runs.contains(&("doo-sabin".into(), "quad-grid:3x2")));
    Ok(())
}

/// Three triangles on one edge and a quad on another: non-manifold edges, which only the
/// face-list path subdivides.
fn books() -> [(&'static str, PolygonMesh); 2] {
    let p = vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::Y,
        DVec3::Z,
        DVec3::NEG_Y,
        DVec3::NEG_Z,
    ];
    let triangles =
        PolygonMesh::from_faces(p.clone(), [[0, 1, 2], [1, 0, 3], [0, 1, 4], [1, 0, 5]]);
    let mixed = PolygonMesh::from_faces(p, vec![vec![0, 1, 2], vec![1, 0, 3], vec![0, 1, 4, 5]]);
    [("triangle book", triangles), ("mixed book", mixed)]
}

#[test]
fn face_list_schemes_on_non_manifold_meshes() -> Result<(), Box<dyn std::error::Error>> {
    let opts = SubdivideOptions::default();
    let mut runs = 0;
    for (mesh_name, polygons) in books() {
        assert!(
            HalfEdgeMesh::try_from(&polygons).is_err(),
            "{mesh_name} is non-manifold"
        );
        let counts = stats::face_list_counts(&polygons);
        assert!(counts.nonmanifold_edges > 0);
        for scheme in schemes::builtins() {
            let usable = applies(&scheme, &counts)
                && !scheme.mesh_class().needs_manifold()
                && scheme.subdivision_rule().is_some_and(|r| r.refines_faces());
            if !usable {
                continue;
            }
            let reports = verify_polygons(&polygons, &scheme, LEVELS, &opts)?;
            check_reports(&scheme, mesh_name, &reports)?;
            runs += 1;
        }
    }
    // loop-general, catmull-clark-general, tri-split-2, tri-split-3 on the triangles;
    // catmull-clark-general on the mixed one.
    assert_eq!(runs, 5);
    Ok(())
}
