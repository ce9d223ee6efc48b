//! `Refinement::base_faces`: the base face of every face of a level, checked against what
//! each split's faces are, from the public API only.
//!
//! - Linear rules (`midpoint`, `tri-split-N`): every output face lies in the plane of its
//!   base triangle, inside it (barycentric coordinates of its centroid in [0, 1]).
//! - Catmull-Clark: each base face owns `degree · 4^(s - 1)` consecutive faces.
//! - √3, Doo-Sabin, mid-edge at level 1: the base faces around each output face's origin
//!   (its own face, the two faces of an edge, the faces around a vertex), the least one;
//!   at level 2, the least over the level-1 faces it comes from, chained.
//! - Holes: the written faces only, none from a hole.

use halfedge::holes::HoleSet;
use halfedge::subdivide::{subdivide, SubdivideOptions};
use halfedge::{shapes, HalfEdgeMesh, PolygonMesh, Refinement, Rule};

fn mesh(p: &PolygonMesh) -> HalfEdgeMesh {
    HalfEdgeMesh::try_from_polygon_mesh(p).expect("a manifold mesh")
}

fn refine(m: &HalfEdgeMesh, rule: Rule, levels: u32) -> Refinement {
    Refinement::new(m, rule, levels, &SubdivideOptions::default()).expect("refined")
}

/// The faces of the last level of `r`, as vertex lists.
fn faces(r: &Refinement) -> Vec<Vec<u32>> {
    let levels = r.levels();
    let nf = r.n_faces(levels);
    let mut offsets = vec![0u32; nf + 1];
    let mut indices = vec![0u32; r.n_corners(levels)];
    r.write_polygons(&mut offsets, &mut indices)
        .expect("polygons");
    offsets
        .windows(2)
        .map(|w| indices[w[0] as usize..w[1] as usize].to_vec())
        .collect()
}

#[test]
fn linear_splits_put_each_face_inside_its_base_triangle() {
    for base in [shapes::icosahedron(), shapes::grid(3, 2).expect("grid")] {
        let m = mesh(&base);
        for rule in [Rule::Midpoint, Rule::TriSplit(3)] {
            for levels in 0..=2 {
                let r = refine(&m, rule, levels);
                let bases = r.base_faces(levels).expect("base faces");
                assert_eq!(bases.len(), r.n_faces(levels));
                let mut positions = vec![[0.0f64; 3]; r.n_vertices(levels)];
                let control: Vec<[f64; 3]> = m.positions().iter().map(|p| p.to_array()).collect();
                r.evaluate(&control, &mut positions).expect("evaluated");
                for (face, &b) in faces(&r).iter().zip(&bases) {
                    let tri: Vec<glam::DVec3> = base
                        .face(b as usize)
                        .iter()
                        .map(|&v| m.positions()[v as usize])
                        .collect();
                    let centroid = face
                        .iter()
                        .map(|&v| glam::DVec3::from_array(positions[v as usize]))
                        .sum::<glam::DVec3>()
                        / face.len() as f64;
                    let (u, v, w) = barycentric(centroid, &tri);
                    let inside = [u, v, w]
                        .iter()
                        .all(|&x| (-1e-12..=1.0 + 1e-12).contains(&x));
                    let plane = (centroid - (u * tri[0] + v * tri[1] + w * tri[2])).length();
                    assert!(
                        inside && plane < 1e-12,
                        "{rule} L{levels}: face in base {b}"
                    );
                }
            }
        }
    }
}

/// Barycentric coordinates of the projection of `p` on the triangle `t`.
fn barycentric(p: glam::DVec3, t: &[glam::DVec3]) -> (f64, f64, f64) {
    let (e1, e2, d) = (t[1] - t[0], t[2] - t[0], p - t[0]);
    let (a, b, c) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (x, y) = (d.dot(e1), d.dot(e2));
    let det = a * c - b * b;
    let v = (c * x - b * y) / det;
    let w = (a * y - b * x) / det;
    (1.0 - v - w, v, w)
}

#[test]
fn catmull_clark_faces_come_in_blocks_per_base_face() {
    for base in [shapes::cube(), shapes::icosahedron(), shapes::mixed()] {
        let m = mesh(&base);
        for levels in 0..=3u32 {
            let r = refine(&m, Rule::CatmullClark, levels);
            let bases = r.base_faces(levels).expect("base faces");
            let mut expected = Vec::new();
            for f in 0..base.n_faces() {
                let per = match levels {
                    0 => 1,
                    s => base.face(f).len() * 4usize.pow(s - 1),
                };
                expected.extend(std::iter::repeat(f as u32).take(per));
            }
            assert_eq!(bases, expected, "level {levels}");
        }
    }
}

/// The faces of level 1 of a non-nesting `rule` on `m` and where each comes from, in the
/// numbering of the rule's docs: the least of the base faces at its origin.
fn expected_level_one(m: &HalfEdgeMesh, rule: Rule) -> Vec<u32> {
    let own: Vec<u32> = (0..m.n_faces() as u32).collect();
    least_over_parents(m, rule, &own)
}

#[test]
fn non_nesting_rules_take_the_least_base_face_they_come_from() {
    let cases = [
        (shapes::cube(), Rule::DooSabin),
        (shapes::cube(), Rule::MidEdge),
        (shapes::icosahedron(), Rule::Sqrt3),
        (shapes::grid(3, 2).expect("grid"), Rule::DooSabin),
        (shapes::grid(3, 2).expect("grid"), Rule::MidEdge),
        (shapes::grid(3, 2).expect("grid"), Rule::Sqrt3),
        (shapes::mixed(), Rule::DooSabin),
        (shapes::mixed(), Rule::MidEdge),
    ];
    for (base, rule) in cases {
        let m = mesh(&base);
        let one = expected_level_one(&m, rule);
        let r = refine(&m, rule, 2);
        assert_eq!(
            r.base_faces(0).expect("level 0"),
            (0..m.n_faces() as u32).collect::<Vec<_>>()
        );
        assert_eq!(r.base_faces(1).expect("level 1"), one, "{rule} level 1");
        // Level 2: the least over the level-1 faces each comes from.
        let level1 = subdivide(&m, rule, 1, &SubdivideOptions::default()).expect("level 1");
        let least = least_over_parents(&level1, rule, &one);
        assert_eq!(r.base_faces(2).expect("level 2"), least, "{rule} level 2");
    }
}

/// The least of `values` (per face of `m`) over the faces each face of the level after `m`
/// under `rule` comes from: its own face, an edge's faces, the faces around a vertex (the
/// dual rules), the two faces of a flipped edge (√3).
fn least_over_parents(m: &HalfEdgeMesh, rule: Rule, values: &[u32]) -> Vec<u32> {
    let value = |f: halfedge::FaceId| values[f.0 as usize];
    let of_edge = |e: usize| {
        let h = 2 * e as u32;
        [h, h ^ 1]
            .iter()
            .filter_map(|&h| m.face(halfedge::HalfedgeId(h)).map(value))
            .min()
            .expect("an edge has a face")
    };
    let around = |v: u32| {
        m.halfedges()
            .filter(|&h| m.to_vertex(h).0 == v)
            .filter_map(|h| m.face(h).map(value))
            .min()
            .expect("a vertex has a face")
    };
    let nf = m.n_faces() as u32;
    let own = (0..nf).map(|f| values[f as usize]);
    match rule {
        Rule::DooSabin => own
            .chain((0..m.n_edges()).map(of_edge))
            .chain((0..m.n_vertices() as u32).map(around))
            .collect(),
        Rule::MidEdge => own.chain((0..m.n_vertices() as u32).map(around)).collect(),
        Rule::Sqrt3 => (0..nf)
            .flat_map(|f| {
                let h0 = m.face_halfedge(halfedge::FaceId(f));
                [h0, m.next(h0), m.prev(h0)].map(|h| {
                    let twin = halfedge::HalfedgeId(h.0 ^ 1);
                    let mine = values[f as usize];
                    m.face(twin).map_or(mine, |g| value(g).min(mine))
                })
            })
            .collect(),
        _ => unreachable!("a non-nesting rule"),
    }
}

#[test]
fn holes_leave_their_faces_out() {
    let base = shapes::icosahedron();
    let m = mesh(&base);
    let holes = HoleSet::new(base.n_faces(), [3, 7]).expect("holes");
    for rule in [Rule::Loop, Rule::CatmullClark] {
        for levels in 0..=2 {
            let opts = SubdivideOptions::default().with_holes(&holes);
            let r = Refinement::new(&m, rule, levels, &opts).expect("refined");
            let bases = r.base_faces(levels).expect("base faces");
            assert_eq!(bases.len(), r.n_faces(levels), "{rule} L{levels}");
            assert!(bases.iter().all(|&b| b != 3 && b != 7));
            let per = match (rule, levels) {
                (_, 0) => 1,
                (Rule::Loop, s) => 4usize.pow(s),
                (_, s) => 3 * 4usize.pow(s - 1),
            };
            assert_eq!(bases.len(), (base.n_faces() - 2) * per);
        }
    }
    let r = refine(&m, Rule::Loop, 1);
    assert!(r.base_faces(2).is_err());
}

/// The one-shot face list's base faces ([`SubdivideOptions::base_faces`]) are the
/// refinement's, for every rule, with and without holes, at levels 0 to 2; without the option
/// the level has none.
#[test]
fn the_one_shot_face_list_gives_the_refinements_base_faces() {
    use halfedge::subdivide::subdivide_to_face_list;
    let tri = shapes::icosahedron();
    let quad = shapes::mixed();
    let cases: Vec<(&PolygonMesh, Rule)> = vec![
        (&tri, Rule::Loop),
        (&tri, Rule::Butterfly),
        (&tri, Rule::TriSplit(3)),
        (&tri, Rule::Sqrt3),
        (&quad, Rule::CatmullClark),
        (&quad, Rule::DooSabin),
        (&quad, Rule::MidEdge),
    ];
    for (base, rule) in cases {
        let m = mesh(base);
        let holes = HoleSet::new(m.n_faces(), [1, 3]).expect("faces of the mesh");
        let nests = !matches!(rule, Rule::Sqrt3 | Rule::DooSabin | Rule::MidEdge);
        for with_holes in [false, true].into_iter().filter(|&h| nests || !h) {
            for levels in 0..=2 {
                let mut opts = SubdivideOptions::default();
                if with_holes {
                    opts = opts.with_holes(&holes);
                }
                let level = subdivide_to_face_list(&m, rule, levels, &opts).expect("one-shot");
                assert_eq!(level.base_faces, None);
                let with = opts.with_base_faces(true);
                let level = subdivide_to_face_list(&m, rule, levels, &with).expect("one-shot");
                let r = Refinement::new(&m, rule, levels, &opts).expect("refined");
                let expected = r.base_faces(levels).expect("base faces");
                let what = format!("{rule} level {levels} holes {with_holes}");
                assert_eq!(level.base_faces.as_ref(), Some(&expected), "{what}");
                assert_eq!(expected.len(), level.mesh.n_faces(), "{what}");
                if with_holes {
                    assert!(expected.iter().all(|f| !holes.contains(*f)), "{what}");
                }
            }
        }
    }
}
