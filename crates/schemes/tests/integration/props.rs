//! Property tests: random closed triangle meshes give the same counts under every Loop state.

use num_bigint::BigInt;
use proptest::prelude::*;
use schemes::{builtin, CountsInput, MeshCounts};

/// Counts of a closed triangle mesh: F even, E = 3F/2, V = E - F + chi with chi even and
/// at most 2 per component (genus g: chi = 2 - 2g), V >= 4.
fn closed_triangle_mesh() -> impl Strategy<Value = MeshCounts> {
    (2u64..100_000, 0u64..50).prop_filter_map("needs V >= 4", |(half_f, genus)| {
        let faces = 2 * half_f;
        let edges = 3 * half_f;
        let chi = 2 - 2 * i64::try_from(genus).ok()?;
        let vertices = u64::try_from(i64::try_from(edges - faces).ok()? + chi).ok()?;
        (vertices >= 4).then(|| MeshCounts {
            vertices,
            edges,
            interior_edges: edges,
            faces,
            corners: 3 * faces,
            faces_by_degree: [(3, faces)].into(),
            components: 1,
            euler_characteristic: chi,
            ..MeshCounts::default()
        })
    })
}

proptest! {
    #[test]
    fn loop_states_agree(mesh in closed_triangle_mesh()) {
        mesh.check_identities().unwrap();
        let schemes = ["loop", "loop-boundary", "loop-general", "tri-split-2"].map(|n| builtin(n).unwrap());
        for level in 0..=8u64 {
            let counts: Vec<[BigInt; 3]> = schemes
                .iter()
                .map(|s| {
                    let c = s.counts_at(&mesh, level).unwrap();
                    [c.vertices, c.edges, c.faces]
                })
                .collect();
            prop_assert_eq!(&counts[0], &counts[1]);
            prop_assert_eq!(&counts[0], &counts[2]);
            prop_assert_eq!(&counts[0], &counts[3]);
            // Euler characteristic is kept.
            let [v, e, f] = &counts[0];
            prop_assert_eq!(v - e + f, BigInt::from(mesh.euler_characteristic));
        }
    }

    #[test]
    fn powering_equals_stepping(mesh in closed_triangle_mesh(), level in 0u64..40) {
        for name in ["loop", "sqrt3", "sqrt3-boundary", "catmull-clark", "doo-sabin", "mid-edge"] {
            let s = builtin(name).unwrap();
            let x0 = s.initial_state(&mesh).unwrap();
            let stepped = s.states_up_to(&x0, level).unwrap();
            prop_assert_eq!(&s.state_at(&x0, level).unwrap(), &stepped[level as usize]);
        }
    }
}

/// A `w x h` grid of quads with some removed and some split into two triangles: a polygon
/// mesh whose edges have one or two faces (boundary included).
fn grid_mesh() -> impl Strategy<Value = (Vec<Vec<u32>>, bool)> {
    (1u32..7, 1u32..7, any::<bool>()).prop_flat_map(|(w, h, all_triangles)| {
        let cells = (w * h) as usize;
        (
            proptest::collection::vec(0u8..4, cells),
            Just((w, h, all_triangles)),
        )
            .prop_map(move |(kinds, (w, h, all_triangles))| {
                let id = |x: u32, y: u32| y * (w + 1) + x;
                let mut faces = Vec::new();
                for y in 0..h {
                    for x in 0..w {
                        let (a, b, c, d) = (id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1));
                        match kinds[(y * w + x) as usize] {
                            // A hole, unless it would leave the mesh empty.
                            0 if !(faces.is_empty() && (y * w + x) as usize + 1 == cells) => {}
                            1 | 2 if !all_triangles => faces.push(vec![a, b, c, d]),
                            _ => {
                                faces.push(vec![a, b, c]);
                                faces.push(vec![a, c, d]);
                            }
                        }
                    }
                }
                (faces, all_triangles)
            })
    })
}

proptest! {
    #[test]
    fn equivalent_schemes_agree_on_open_meshes((faces, all_triangles) in grid_mesh()) {
        let mesh = MeshCounts::from_polygons(&faces).unwrap();
        mesh.check_identities().unwrap();
        let families: Vec<Vec<&str>> = if all_triangles {
            vec![
                vec!["loop-boundary", "loop-general", "tri-split-2"],
                vec!["catmull-clark", "catmull-clark-general"],
                vec!["sqrt3-boundary"],
                vec!["tri-split-3"],
            ]
        } else {
            vec![vec!["catmull-clark", "catmull-clark-general"]]
        };
        for family in families {
            let runs: Vec<Vec<[BigInt; 3]>> = family
                .iter()
                .map(|name| {
                    let s = builtin(name).unwrap();
                    (0..=6u64)
                        .map(|level| {
                            let c = s.counts_at(&mesh, level).unwrap();
                            [c.vertices, c.edges, c.faces]
                        })
                        .collect()
                })
                .collect();
            for run in &runs {
                prop_assert_eq!(run, &runs[0]);
                for [v, e, f] in run {
                    prop_assert_eq!(v - e + f, BigInt::from(mesh.euler_characteristic));
                }
            }
        }
        // Typed counts V, E, F fill the same state as the full statistics, through the
        // identities of the scheme's class.
        if all_triangles {
            for name in ["loop-boundary", "sqrt3-boundary", "loop-general"] {
                let s = builtin(name).unwrap();
                let input: CountsInput = format!("V={},E={},F={}", mesh.vertices, mesh.edges, mesh.faces).parse().unwrap();
                prop_assert_eq!(s.state_from_input(&input).unwrap(), s.initial_state(&mesh).unwrap());
            }
        }
        let cc = builtin("catmull-clark").unwrap();
        let input: CountsInput = format!(
            "V={},E={},F={},BE={}", mesh.vertices, mesh.edges, mesh.faces, mesh.boundary_edges
        ).parse().unwrap();
        prop_assert_eq!(cc.state_from_input(&input).unwrap(), cc.initial_state(&mesh).unwrap());
    }

    #[test]
    fn typed_counts_of_closed_meshes(mesh in closed_triangle_mesh()) {
        for name in ["loop", "loop-boundary", "loop-general", "sqrt3", "sqrt3-boundary", "catmull-clark", "doo-sabin", "mid-edge"] {
            let s = builtin(name).unwrap();
            let input: CountsInput = format!("V={},E={},F={}", mesh.vertices, mesh.edges, mesh.faces).parse().unwrap();
            let typed = s.state_from_input(&input);
            if s.mesh_class().closed || s.mesh_class().faces == schemes::FaceKind::Triangles {
                prop_assert_eq!(typed.unwrap(), s.initial_state(&mesh).unwrap());
            } else {
                // catmull-clark on polygons: without BE the counts do not determine IE, BE, H.
                let missing_be = matches!(typed, Err(schemes::Error::MissingComponents { .. }));
                prop_assert!(missing_be);
            }
        }
    }
}
