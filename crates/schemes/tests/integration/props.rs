//! Property tests: random closed triangle meshes give the same counts under every Loop state.

use num_bigint::BigInt;
use proptest::prelude::*;
use schemes::{builtin, MeshCounts};

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
