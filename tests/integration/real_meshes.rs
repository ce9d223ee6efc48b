//! Every valid mesh of `SUBCOUNT_MESHES` under the Loop and Catmull-Clark schemes that apply to
//! it: the level-1 counts predicted by the `schemes` crate (and by the closed form) equal the
//! counts of the really subdivided mesh.
//!
//! Tests run unoptimized, so a (mesh, scheme) whose level 1 would have more than
//! [`MAX_FACES`] faces is left to `cargo xtask verify`, which runs every scheme on every
//! shared mesh in release mode (CI runs both); the pairs left to it are printed.

/// The largest level-1 face count subdivided here (`buildings_400k.obj` is above it).
const MAX_FACES: u64 = 500_000;

use halfedge::subdivide::{verify, SubdivideOptions};
use halfedge::{io, HalfEdgeMesh};
use subcount_tests::{applies, measured_state};

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn level_one_of_every_shared_mesh() -> Result<(), Box<dyn std::error::Error>> {
    let dir = testdata::meshes_dir();
    let mut files: Vec<_> = std::fs::read_dir(&dir)?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()?;
    files.retain(|p| p.extension().is_some_and(|e| e == "obj" || e == "off"));
    files.sort();
    assert!(!files.is_empty(), "no mesh in {}", dir.display());
    let opts = SubdivideOptions::default();
    let mut runs = 0;
    for path in &files {
        let polygons = io::read_mesh(path)?;
        let mesh =
            HalfEdgeMesh::try_from(&polygons).map_err(|e| format!("{}: {e}", path.display()))?;
        let counts = mesh.counts();
        let mut ran = false;
        for name in ["loop", "loop-boundary", "catmull-clark"] {
            let scheme = schemes::builtin(name)?;
            if !applies(&scheme, &counts) {
                continue;
            }
            let faces = scheme.counts_at(&counts, 1)?.faces;
            if faces > MAX_FACES.into() {
                eprintln!(
                    "{name} on {}: {faces} faces at level 1, left to `cargo xtask verify`",
                    path.display()
                );
                ran = true;
                continue;
            }
            let reports = verify(&mesh, &scheme, 1, &opts)?;
            assert_eq!(reports.len(), 2);
            assert!(
                reports[1].is_match(),
                "{name} on {}: {:?}",
                path.display(),
                reports[1]
            );
            // The closed form gives the same level-1 state.
            let x0 = scheme.initial_state(&counts)?;
            let measured =
                measured_state(&reports[1], scheme.state_names()).ok_or("state not measured")?;
            assert_eq!(
                scheme.closed_form().evaluate(&x0, 1)?,
                measured,
                "{name} on {}",
                path.display()
            );
            ran = true;
            runs += 1;
        }
        // Every mesh gets catmull-clark at least (any polygon mesh with manifold edges).
        assert!(ran, "no scheme ran on {}", path.display());
    }
    assert!(
        runs >= files.len(),
        "{runs} runs for {} meshes",
        files.len()
    );
    Ok(())
}
