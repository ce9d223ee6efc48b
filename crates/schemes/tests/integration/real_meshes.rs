//! Every built-in scheme on the statistics of the real meshes in `$SUBCOUNT_MESHES`
//! (`stats.json`): applicability decided correctly, Euler characteristic kept, and equivalent
//! schemes agreeing on V, E, F. (Real subdivision is checked by the `halfedge` crate.)

use std::collections::BTreeMap;

use num_bigint::BigInt;
use schemes::{builtins, Error, MeshCounts};

fn load() -> Vec<(String, MeshCounts)> {
    let path = testdata::mesh("stats.json");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let num = |v: &serde_json::Value, k: &str| v[k].as_u64().unwrap_or_else(|| panic!("{k}"));
    let mut out = Vec::new();
    for (name, s) in json.as_object().unwrap() {
        if name.starts_with("broken/") {
            continue; // meshes a validating loader rejects
        }
        let (e, be, nme) = (
            num(s, "E"),
            num(s, "boundary_edges"),
            num(s, "nonmanifold_edges"),
        );
        let faces_by_degree: BTreeMap<u32, u64> = s["face_degrees"]
            .as_object()
            .unwrap()
            .iter()
            .map(|(d, n)| (d.parse().unwrap(), n.as_u64().unwrap()))
            .collect();
        out.push((
            name.clone(),
            MeshCounts {
                vertices: num(s, "V") - num(s, "unreferenced_vertices"),
                edges: e,
                interior_edges: e - be - nme,
                boundary_edges: be,
                nonmanifold_edges: nme,
                faces: num(s, "F"),
                corners: num(s, "corners"),
                faces_by_degree,
                boundary_loops: num(s, "boundary_loops"),
                components: num(s, "components"),
                euler_characteristic: s["chi_used_vertices"].as_i64().unwrap(),
                unreferenced_vertices: num(s, "unreferenced_vertices"),
            },
        ));
    }
    out
}

#[test]
#[ignore = "needs SUBCOUNT_MESHES"]
fn builtins_on_real_mesh_statistics() {
    let meshes = load();
    assert!(meshes.len() >= 40, "{} meshes", meshes.len());
    let mut applied = 0;
    for (name, m) in &meshes {
        m.check_identities()
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let tri = m.faces_by_degree.keys().all(|&d| d == 3);
        let quad = m.faces_by_degree.keys().all(|&d| d == 4);
        let manifold = m.nonmanifold_edges == 0;
        let closed = manifold && m.boundary_edges == 0;
        let mut vef_by_topology: BTreeMap<String, Vec<[BigInt; 3]>> = BTreeMap::new();
        for s in builtins() {
            let class = s.mesh_class();
            let applies = match class.faces.degree() {
                Some(3) => tri,
                Some(4) => quad,
                _ => true,
            } && (!class.closed || closed)
                && (!class.needs_manifold() || manifold);
            match s.initial_state(m) {
                Ok(x0) => {
                    assert!(applies, "{} accepted {name}", s.name());
                    applied += 1;
                    let mut seq = Vec::new();
                    for level in 0..=3 {
                        let c = s.level_counts(&x0, level).unwrap();
                        let chi = &c.vertices - &c.edges + &c.faces;
                        assert_eq!(
                            chi,
                            BigInt::from(m.euler_characteristic),
                            "{} on {name} at {level}",
                            s.name()
                        );
                        seq.push([c.vertices, c.edges, c.faces]);
                    }
                    let family = match s.name() {
                        "loop" | "loop-boundary" | "loop-general" | "tri-split-2" => "loop",
                        "catmull-clark" | "catmull-clark-general" | "catmull-clark-quad" => "cc",
                        "sqrt3" | "sqrt3-boundary" => "sqrt3",
                        other => other,
                    }
                    .to_string();
                    vef_by_topology.entry(family).or_default().extend(seq);
                }
                Err(Error::NotApplicable { .. }) => {
                    assert!(!applies, "{} refused {name}", s.name())
                }
                Err(e) => panic!("{} on {name}: {e}", s.name()),
            }
        }
        for (family, runs) in vef_by_topology {
            // Runs of 4 levels from equivalent schemes must be identical.
            let first: Vec<_> = runs[..4].to_vec();
            for chunk in runs.chunks(4) {
                assert_eq!(chunk, &first[..], "{family} on {name}");
            }
        }
    }
    assert!(applied > 200, "{applied} scheme/mesh pairs applied");
}
