//! Base meshes generated in code, also by name for the command line's `--base NAME`.
//!
//! Every shape is a consistently oriented manifold face list (counterclockwise faces seen
//! from outside; planar shapes face `+z`) that [`crate::HalfEdgeMesh`] accepts:
//!
//! | name | faces | V | E | F | boundary loops | genus |
//! |---|---|---|---|---|---|---|
//! | `tetrahedron` | triangles | 4 | 6 | 4 | 0 | 0 |
//! | `octahedron` | triangles | 6 | 12 | 8 | 0 | 0 |
//! | `icosahedron` | triangles | 12 | 30 | 20 | 0 | 0 |
//! | `cube` | quads | 8 | 12 | 6 | 0 | 0 |
//! | `torus:G` | triangles | 26G + 22 | 84G + 60 | 56G + 40 | 0 | G |
//! | `icosahedron-holes:K` | triangles | 12 | 30 | 20 - K | K | 0 |
//! | `grid:WxH` | triangles | (W+1)(H+1) | 3WH + W + H | 2WH | 1 | 0 |
//! | `quad-grid:WxH` | quads | (W+1)(H+1) | 2WH + W + H | WH | 1 | 0 |
//! | `mixed` | 4 triangles, 3 quads, a pentagon, a hexagon | 13 | 21 | 9 | 1 | 0 |
//!
//! The platonic solids have their vertices on the unit sphere; the cube is `[-1, 1]^3`.
//!
//! # Example
//!
//! ```
//! use halfedge::{shapes, HalfEdgeMesh};
//!
//! let mesh = HalfEdgeMesh::try_from(&shapes::from_name("torus:2")?)?;
//! assert_eq!(mesh.genus(), 2);
//! assert!(shapes::from_name("torus:0").is_err());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use glam::DVec3;

use crate::error::{Error, Result};
use crate::polygon::PolygonMesh;

/// Largest number of grid cells (or torus handles) a generated mesh may have.
pub const MAX_CELLS: u64 = 1 << 24;

/// The largest `K` for `icosahedron-holes:K`: the icosahedron has at most 4 faces no two of
/// which share a vertex (removing faces that share a vertex would pinch it).
pub const MAX_ICOSAHEDRON_HOLES: u32 = 4;

/// The base mesh called `name`: `tetrahedron`, `octahedron`, `icosahedron`, `cube`,
/// `torus:G`, `icosahedron-holes:K`, `grid:WxH`, `quad-grid:WxH` or `mixed`.
///
/// # Errors
///
/// [`Error::UnknownShape`] for another name, [`Error::InvalidShapeParameter`] for a missing,
/// malformed or out-of-range parameter, [`Error::ShapeTooLarge`] for a mesh that would need
/// more than half of `available` bytes (with [`from_name_within`]; checked before
/// allocating).
///
/// # Example
///
/// ```
/// let grid = halfedge::shapes::from_name("quad-grid:3x2")?;
/// assert_eq!((grid.n_vertices(), grid.n_faces()), (12, 6));
/// let err = halfedge::shapes::from_name("grid:3").unwrap_err();
/// assert_eq!(err.to_string(), "base mesh `grid:3`: expected grid:WxH with W, H >= 1 (for example grid:4x3)");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn from_name(name: &str) -> Result<PolygonMesh> {
    from_name_within(name, None)
}

/// [`from_name`] for a process that may still allocate `available` bytes (as its caller
/// measured them, e.g. `driver::system::available_bytes`): a mesh whose face list would need
/// more than half of them is [`Error::ShapeTooLarge`], refused before anything is allocated.
/// `None`: no limit but [`MAX_CELLS`].
///
/// # Errors
///
/// As [`from_name`].
///
/// ```
/// let err = halfedge::shapes::from_name_within("grid:1000x1000", Some(1 << 20)).unwrap_err();
/// assert!(err.to_string().contains("half the memory available"), "{err}");
/// ```
pub fn from_name_within(name: &str, available: Option<u64>) -> Result<PolygonMesh> {
    let (base, parameter) = match name.split_once(':') {
        Some((b, p)) => (b, Some(p)),
        None => (name, None),
    };
    let invalid = |what: String| Error::InvalidShapeParameter {
        name: name.to_string(),
        what,
    };
    let no_parameter = |mesh: PolygonMesh| match parameter {
        None => Ok(mesh),
        Some(_) => Err(invalid(format!("{base} takes no parameter"))),
    };
    let count = |what: &str| -> Result<u32> {
        parameter
            .and_then(|p| p.trim().parse::<u32>().ok())
            .ok_or_else(|| invalid(format!("expected {base}:{what}")))
    };
    let size = || -> Result<(u32, u32)> {
        let expected = || {
            invalid(format!(
                "expected {base}:WxH with W, H >= 1 (for example {base}:4x3)"
            ))
        };
        let (w, h) = parameter
            .and_then(|p| p.split_once(['x', 'X']))
            .ok_or_else(expected)?;
        let w = w.trim().parse::<u32>().map_err(|_| expected())?;
        let h = h.trim().parse::<u32>().map_err(|_| expected())?;
        Ok((w, h))
    };
    let rename = |e: Error| match e {
        Error::InvalidShapeParameter { what, .. } => invalid(what),
        other => other,
    };
    match base {
        "tetrahedron" => no_parameter(tetrahedron()),
        "octahedron" => no_parameter(octahedron()),
        "icosahedron" => no_parameter(icosahedron()),
        "cube" => no_parameter(cube()),
        "mixed" => no_parameter(mixed()),
        "torus" => torus_within(count("G with the genus G >= 1")?, available).map_err(rename),
        "icosahedron-holes" => {
            icosahedron_holes(count("K with K holes, 1 <= K <= 4")?).map_err(rename)
        }
        "grid" => {
            let (w, h) = size()?;
            grid_within(w, h, available).map_err(rename)
        }
        "quad-grid" => {
            let (w, h) = size()?;
            quad_grid_within(w, h, available).map_err(rename)
        }
        _ => Err(Error::UnknownShape {
            name: name.to_string(),
        }),
    }
}

/// Turns every face outward (for convex shapes around the origin): a face whose normal
/// points towards the origin is reversed.
fn orient_outward(positions: Vec<DVec3>, faces: &[&[u32]]) -> PolygonMesh {
    let mut mesh = PolygonMesh::with_positions(positions);
    for face in faces {
        let p: Vec<DVec3> = face.iter().map(|&v| mesh.positions[v as usize]).collect();
        let centroid = p.iter().copied().sum::<DVec3>() / p.len() as f64;
        let normal = (p[1] - p[0]).cross(p[2] - p[0]);
        if normal.dot(centroid) >= 0.0 {
            mesh.push_face(face);
        } else {
            mesh.push_face_from_iter(face.iter().rev().copied());
        }
    }
    mesh
}

/// The regular tetrahedron with its vertices on the unit sphere.
pub fn tetrahedron() -> PolygonMesh {
    let s = 1.0 / 3f64.sqrt();
    let positions = vec![
        DVec3::new(s, s, s),
        DVec3::new(s, -s, -s),
        DVec3::new(-s, s, -s),
        DVec3::new(-s, -s, s),
    ];
    orient_outward(positions, &[&[0, 1, 2], &[0, 3, 1], &[0, 2, 3], &[1, 3, 2]])
}

/// The regular octahedron with vertices `±x`, `±y`, `±z`.
pub fn octahedron() -> PolygonMesh {
    let positions = vec![
        DVec3::X,
        DVec3::NEG_X,
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::Z,
        DVec3::NEG_Z,
    ];
    let mut faces: Vec<[u32; 3]> = Vec::new();
    for x in [0, 1] {
        for y in [2, 3] {
            for z in [4, 5] {
                faces.push([x, y, z]);
            }
        }
    }
    let faces: Vec<&[u32]> = faces.iter().map(|f| f.as_slice()).collect();
    orient_outward(positions, &faces)
}

/// The regular icosahedron with its vertices on the unit sphere.
pub fn icosahedron() -> PolygonMesh {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let raw = [
        (-1.0, phi, 0.0),
        (1.0, phi, 0.0),
        (-1.0, -phi, 0.0),
        (1.0, -phi, 0.0),
        (0.0, -1.0, phi),
        (0.0, 1.0, phi),
        (0.0, -1.0, -phi),
        (0.0, 1.0, -phi),
        (phi, 0.0, -1.0),
        (phi, 0.0, 1.0),
        (-phi, 0.0, -1.0),
        (-phi, 0.0, 1.0),
    ];
    let positions = raw
        .iter()
        .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
        .collect();
    orient_outward(
        positions,
        &ICOSAHEDRON_FACES
            .iter()
            .map(|f| f.as_slice())
            .collect::<Vec<_>>(),
    )
}

const ICOSAHEDRON_FACES: [[u32; 3]; 20] = [
    [0, 11, 5],
    [0, 5, 1],
    [0, 1, 7],
    [0, 7, 10],
    [0, 10, 11],
    [1, 5, 9],
    [5, 11, 4],
    [11, 10, 2],
    [10, 7, 6],
    [7, 1, 8],
    [3, 9, 4],
    [3, 4, 2],
    [3, 2, 6],
    [3, 6, 8],
    [3, 8, 9],
    [4, 9, 5],
    [2, 4, 11],
    [6, 2, 10],
    [8, 6, 7],
    [9, 8, 1],
];

/// The cube `[-1, 1]^3` as 6 quads.
pub fn cube() -> PolygonMesh {
    let positions = (0..8u32)
        .map(|i| {
            let c = |bit: u32| if i & bit != 0 { 1.0 } else { -1.0 };
            DVec3::new(c(1), c(2), c(4))
        })
        .collect();
    orient_outward(
        positions,
        &[
            &[0, 2, 3, 1],
            &[4, 5, 7, 6],
            &[0, 1, 5, 4],
            &[2, 6, 7, 3],
            &[0, 4, 6, 2],
            &[1, 3, 7, 5],
        ],
    )
}

/// The icosahedron with `holes` faces removed, no two of them sharing a vertex (so the
/// surface stays manifold): `holes` boundary loops, genus 0.
///
/// # Errors
///
/// [`Error::InvalidShapeParameter`] unless `1 <= holes <= 4` ([`MAX_ICOSAHEDRON_HOLES`]).
pub fn icosahedron_holes(holes: u32) -> Result<PolygonMesh> {
    if holes == 0 || holes > MAX_ICOSAHEDRON_HOLES {
        return Err(Error::InvalidShapeParameter {
            name: format!("icosahedron-holes:{holes}"),
            what: format!(
                "the icosahedron can have 1 to {MAX_ICOSAHEDRON_HOLES} holes without two sharing a vertex, not {holes}"
            ),
        });
    }
    let full = icosahedron();
    // Depth-first search for `holes` vertex-disjoint faces, in face order (deterministic).
    fn search(
        faces: &[&[u32]],
        from: usize,
        used: u32,
        left: u32,
        chosen: &mut Vec<usize>,
    ) -> bool {
        if left == 0 {
            return true;
        }
        for f in from..faces.len() {
            let mask = faces[f].iter().fold(0u32, |m, &v| m | 1 << v);
            if mask & used == 0 {
                chosen.push(f);
                if search(faces, f + 1, used | mask, left - 1, chosen) {
                    return true;
                }
                chosen.pop();
            }
        }
        false
    }
    let faces: Vec<&[u32]> = full.faces().collect();
    let mut removed = Vec::new();
    if !search(&faces, 0, 0, holes, &mut removed) {
        return Err(Error::InvalidShapeParameter {
            name: format!("icosahedron-holes:{holes}"),
            what: format!("no {holes} faces of the icosahedron are vertex-disjoint"),
        });
    }
    let mut mesh = PolygonMesh::with_positions(full.positions.clone());
    for (f, face) in faces.iter().enumerate() {
        if !removed.contains(&f) {
            mesh.push_face(face);
        }
    }
    Ok(mesh)
}

fn check_cells(name: String, w: u64, h: u64) -> Result<()> {
    if w == 0 || h == 0 {
        return Err(Error::InvalidShapeParameter {
            name,
            what: "W and H must be at least 1".to_string(),
        });
    }
    if w * h > MAX_CELLS {
        return Err(Error::InvalidShapeParameter {
            name,
            what: format!("{w}x{h} cells is more than the {MAX_CELLS} allowed"),
        });
    }
    Ok(())
}

/// Refuses a generated mesh of `vertices`, `faces` and `corners` whose face list would need
/// more than half of `available` bytes (the rule the CLI applies to subdivision), before
/// anything is allocated.
fn guard_memory(
    name: String,
    (vertices, faces, corners): (u64, u64, u64),
    available: Option<u64>,
) -> Result<()> {
    let bytes = PolygonMesh::bytes_for(vertices, faces, corners);
    let limit = available.map_or(u64::MAX, |b| b / 2);
    if bytes > u128::from(limit) {
        return Err(Error::ShapeTooLarge { name, bytes, limit });
    }
    Ok(())
}

/// The grid `kind:WxH` of `w` x `h` unit cells in the plane `z = 0`, checked
/// ([`check_cells`], [`guard_memory`] for `faces_per_cell` faces of `corners` corners each per
/// cell): vertices `(i, j)` for `0 <= i <= w`, `0 <= j <= h` row by row, then the faces of each
/// cell, row by row, from `cell(mesh, [a, b, c, d])` (its corners counterclockwise from
/// `(i, j)`).
fn grid_of(
    kind: &str,
    (w, h): (u32, u32),
    (faces_per_cell, corners): (u64, u64),
    available: Option<u64>,
    cell: impl Fn(&mut PolygonMesh, [u32; 4]),
) -> Result<PolygonMesh> {
    let (w64, h64) = (u64::from(w), u64::from(h));
    check_cells(format!("{kind}:{w}x{h}"), w64, h64)?;
    let faces = faces_per_cell * w64 * h64;
    let vertices = (w64 + 1) * (h64 + 1);
    guard_memory(
        format!("{kind}:{w}x{h}"),
        (vertices, faces, corners * faces),
        available,
    )?;
    let mut positions = Vec::with_capacity(vertices as usize);
    for j in 0..=h {
        for i in 0..=w {
            positions.push(DVec3::new(f64::from(i), f64::from(j), 0.0));
        }
    }
    let mut mesh = PolygonMesh::with_positions(positions);
    mesh.reserve_faces(faces as usize, (corners * faces) as usize);
    let id = |i: u32, j: u32| j * (w + 1) + i;
    for j in 0..h {
        for i in 0..w {
            cell(
                &mut mesh,
                [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
            );
        }
    }
    Ok(mesh)
}

/// A `w` x `h` grid of squares in the plane `z = 0`, each split into two triangles, facing
/// `+z`: a disk with one boundary loop.
///
/// # Errors
///
/// [`Error::InvalidShapeParameter`] when `w` or `h` is 0 or `w * h > MAX_CELLS`.
pub fn grid(w: u32, h: u32) -> Result<PolygonMesh> {
    grid_within(w, h, None)
}

/// [`grid`], refused ([`Error::ShapeTooLarge`]) beyond half of `available` bytes.
fn grid_within(w: u32, h: u32, available: Option<u64>) -> Result<PolygonMesh> {
    grid_of("grid", (w, h), (2, 3), available, |mesh, [a, b, c, d]| {
        mesh.push_face(&[a, b, c]);
        mesh.push_face(&[a, c, d]);
    })
}

/// A `w` x `h` grid of unit squares (quads) in the plane `z = 0`, facing `+z`.
///
/// # Errors
///
/// As [`grid`].
pub fn quad_grid(w: u32, h: u32) -> Result<PolygonMesh> {
    quad_grid_within(w, h, None)
}

/// [`quad_grid`], refused ([`Error::ShapeTooLarge`]) beyond half of `available` bytes.
fn quad_grid_within(w: u32, h: u32, available: Option<u64>) -> Result<PolygonMesh> {
    grid_of("quad-grid", (w, h), (1, 4), available, |mesh, cell| {
        mesh.push_face(&cell)
    })
}

/// A closed triangle surface of genus `genus` (`>= 1`): a flat slab with `genus` square holes
/// in a row. The domain is a `(3G + 2)` x 5 grid of unit squares with the cells
/// `(3t + 2, 2)`, `t < G`, removed; it is doubled into a top sheet (inner vertices at
/// `z = +0.5`) and a bottom sheet (`z = -0.5`) glued along the outer and hole boundaries at
/// `z = 0`. Each square is split along a diagonal through an inner vertex, so no face and no
/// edge of the top sheet reappears in the bottom one.
///
/// # Errors
///
/// [`Error::InvalidShapeParameter`] when `genus` is 0 or more than [`MAX_CELLS`] / 16.
pub fn torus(genus: u32) -> Result<PolygonMesh> {
    torus_within(genus, None)
}

/// [`torus`], refused ([`Error::ShapeTooLarge`]) beyond half of `available` bytes.
fn torus_within(genus: u32, available: Option<u64>) -> Result<PolygonMesh> {
    if genus == 0 || u64::from(genus) > MAX_CELLS / 16 {
        return Err(Error::InvalidShapeParameter {
            name: format!("torus:{genus}"),
            what: format!(
                "the genus must be between 1 and {}, not {genus}",
                MAX_CELLS / 16
            ),
        });
    }
    let nx = 3 * genus + 2;
    let ny = 5u32;
    {
        // At most two vertices per grid point; four triangles per kept square.
        let points = u64::from(nx + 1) * u64::from(ny + 1);
        let faces = 4 * (u64::from(nx) * u64::from(ny) - u64::from(genus));
        guard_memory(
            format!("torus:{genus}"),
            (2 * points, faces, 3 * faces),
            available,
        )?;
    }
    let is_hole = |i: u32, j: u32| j == 2 && i >= 2 && i < 3 * genus + 2 && (i - 2) % 3 == 0;
    let hole_corner =
        |i: u32, j: u32| (j == 2 || j == 3) && i >= 2 && i <= 3 * genus && (i - 2) % 3 != 2;
    let on_boundary = |i: u32, j: u32| i == 0 || j == 0 || i == nx || j == ny || hole_corner(i, j);
    let mut positions = Vec::new();
    let n_grid = ((nx + 1) * (ny + 1)) as usize;
    let mut top = vec![0u32; n_grid];
    let mut bottom = vec![0u32; n_grid];
    let mut interior = vec![false; n_grid];
    for j in 0..=ny {
        for i in 0..=nx {
            let k = (j * (nx + 1) + i) as usize;
            let (x, y) = (f64::from(i), f64::from(j));
            top[k] = positions.len() as u32;
            if on_boundary(i, j) {
                bottom[k] = top[k];
                positions.push(DVec3::new(x, y, 0.0));
            } else {
                interior[k] = true;
                positions.push(DVec3::new(x, y, 0.5));
                bottom[k] = positions.len() as u32;
                positions.push(DVec3::new(x, y, -0.5));
            }
        }
    }
    let mut mesh = PolygonMesh::with_positions(positions);
    let k = |i: u32, j: u32| (j * (nx + 1) + i) as usize;
    for j in 0..ny {
        for i in 0..nx {
            if is_hole(i, j) {
                continue;
            }
            let (a, b, c, d) = (k(i, j), k(i + 1, j), k(i + 1, j + 1), k(i, j + 1));
            // Split along a diagonal with an inner end (every kept square has one).
            let triangles = if interior[a] || interior[c] {
                [[a, b, c], [a, c, d]]
            } else {
                [[a, b, d], [b, c, d]]
            };
            for [p, q, r] in triangles {
                mesh.push_face(&[top[p], top[q], top[r]]);
                mesh.push_face(&[bottom[p], bottom[r], bottom[q]]);
            }
        }
    }
    Ok(mesh)
}

/// A planar disk (facing `+z`) mixing polygon degrees: a regular hexagon, surrounded by three
/// quads, four triangles and a pentagon.
pub fn mixed() -> PolygonMesh {
    let ring = |r: f64, i: u32| {
        let a = std::f64::consts::TAU * f64::from(i) / 6.0;
        DVec3::new(r * a.cos(), r * a.sin(), 0.0)
    };
    // 0..6: inner hexagon, 6..12: outer ring, 12: outer point between 11 and 6.
    let mut positions: Vec<DVec3> = (0..6).map(|i| ring(1.0, i)).collect();
    positions.extend((0..6).map(|i| ring(2.0, i)));
    positions.push((ring(2.0, 5) + ring(2.0, 0)) * 0.5 * 1.2);
    let h = |i: u32| i % 6;
    let o = |i: u32| 6 + i % 6;
    let mut mesh = PolygonMesh::with_positions(positions);
    mesh.push_face(&[0, 1, 2, 3, 4, 5]);
    for i in 0..3 {
        mesh.push_face(&[h(i), o(i), o(i + 1), h(i + 1)]);
    }
    for i in 3..5 {
        mesh.push_face(&[h(i), o(i), o(i + 1)]);
        mesh.push_face(&[h(i), o(i + 1), h(i + 1)]);
    }
    mesh.push_face(&[h(5), o(5), 12, o(0), h(0)]);
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{stats, HalfEdgeMesh};

    /// (name, V, E, F, boundary edges, boundary loops, genus, faces by degree)
    #[allow(clippy::type_complexity)]
    const CASES: &[(&str, u64, u64, u64, u64, u64, u64, &[(u32, u64)])] = &[
        ("tetrahedron", 4, 6, 4, 0, 0, 0, &[(3, 4)]),
        ("octahedron", 6, 12, 8, 0, 0, 0, &[(3, 8)]),
        ("icosahedron", 12, 30, 20, 0, 0, 0, &[(3, 20)]),
        ("cube", 8, 12, 6, 0, 0, 0, &[(4, 6)]),
        ("torus:1", 48, 144, 96, 0, 0, 1, &[(3, 96)]),
        ("torus:2", 74, 228, 152, 0, 0, 2, &[(3, 152)]),
        ("torus:5", 152, 480, 320, 0, 0, 5, &[(3, 320)]),
        ("icosahedron-holes:1", 12, 30, 19, 3, 1, 0, &[(3, 19)]),
        ("icosahedron-holes:2", 12, 30, 18, 6, 2, 0, &[(3, 18)]),
        ("icosahedron-holes:4", 12, 30, 16, 12, 4, 0, &[(3, 16)]),
        ("grid:1x1", 4, 5, 2, 4, 1, 0, &[(3, 2)]),
        ("grid:4x3", 20, 43, 24, 14, 1, 0, &[(3, 24)]),
        ("quad-grid:4x3", 20, 31, 12, 14, 1, 0, &[(4, 12)]),
        ("quad-grid:1x7", 16, 22, 7, 16, 1, 0, &[(4, 7)]),
        (
            "mixed",
            13,
            21,
            9,
            7,
            1,
            0,
            &[(3, 4), (4, 3), (5, 1), (6, 1)],
        ),
    ];

    #[test]
    fn every_shape_has_its_counts_and_is_valid() {
        for &(name, v, e, f, be, loops, genus, degrees) in CASES {
            let polygons = from_name(name).unwrap_or_else(|err| panic!("{name}: {err}"));
            let mesh =
                HalfEdgeMesh::try_from(&polygons).unwrap_or_else(|err| panic!("{name}: {err}"));
            mesh.check_invariants()
                .unwrap_or_else(|err| panic!("{name}: {err}"));
            let c = mesh.counts();
            assert_eq!(
                (
                    c.vertices,
                    c.edges,
                    c.faces,
                    c.boundary_edges,
                    c.boundary_loops
                ),
                (v, e, f, be, loops),
                "{name}"
            );
            assert_eq!(
                c.euler_characteristic,
                v as i64 - e as i64 + f as i64,
                "{name}"
            );
            assert_eq!(c.components, 1, "{name}");
            assert_eq!(mesh.genus(), genus, "{name}");
            assert_eq!(stats::genus(&c), Some(genus), "{name}");
            assert_eq!(
                c.faces_by_degree.into_iter().collect::<Vec<_>>(),
                degrees,
                "{name}"
            );
            assert_eq!(stats::face_list_counts(&polygons), mesh.counts(), "{name}");
            assert_eq!(c.unreferenced_vertices, 0, "{name}");
        }
    }

    #[test]
    fn torus_counts_follow_the_documented_formulas() {
        for g in [1u64, 3, 7, 20] {
            let mesh = HalfEdgeMesh::try_from(&torus(g as u32).expect("torus")).expect("valid");
            let c = mesh.counts();
            assert_eq!(
                (c.vertices, c.edges, c.faces),
                (26 * g + 22, 84 * g + 60, 56 * g + 40)
            );
            assert_eq!(c.euler_characteristic, 2 - 2 * g as i64);
            assert!(mesh.is_closed() && mesh.is_triangle_mesh());
        }
    }

    /// Signed volume by the divergence theorem: positive when every face points outward.
    fn signed_volume(mesh: &PolygonMesh) -> f64 {
        let mut volume = 0.0;
        for face in mesh.faces() {
            let p0 = mesh.positions[face[0] as usize];
            for w in face[1..].windows(2) {
                let (p1, p2) = (mesh.positions[w[0] as usize], mesh.positions[w[1] as usize]);
                volume += p0.dot(p1.cross(p2)) / 6.0;
            }
        }
        volume
    }

    #[test]
    fn closed_shapes_point_outward_and_solids_sit_on_the_unit_sphere() {
        let regular_tetrahedron = 8.0 / (9.0 * 3f64.sqrt());
        for (mesh, volume) in [
            (tetrahedron(), regular_tetrahedron),
            (octahedron(), 4.0 / 3.0),
            (cube(), 8.0),
        ] {
            assert!(
                (signed_volume(&mesh) - volume).abs() < 1e-12,
                "{}",
                signed_volume(&mesh)
            );
        }
        assert!(signed_volume(&icosahedron()) > 2.5);
        for g in 1..4 {
            // The slab: top at +0.5, bottom at -0.5, thinner towards the boundaries.
            assert!(signed_volume(&torus(g).expect("torus")) > 0.0);
        }
        for mesh in [tetrahedron(), octahedron(), icosahedron()] {
            for p in &mesh.positions {
                assert!((p.length() - 1.0).abs() < 1e-15, "{p}");
            }
        }
        for p in &cube().positions {
            assert_eq!(p.abs(), DVec3::ONE);
        }
    }

    #[test]
    fn planar_shapes_face_up() {
        for mesh in [
            grid(3, 2).expect("grid"),
            quad_grid(2, 2).expect("grid"),
            mixed(),
        ] {
            for face in mesh.faces() {
                let p: Vec<DVec3> = face.iter().map(|&v| mesh.positions[v as usize]).collect();
                // Shoelace area of the polygon (positive = counterclockwise seen from +z).
                let area: f64 = (0..p.len())
                    .map(|i| {
                        let (a, b) = (p[i], p[(i + 1) % p.len()]);
                        a.x * b.y - b.x * a.y
                    })
                    .sum();
                assert!(area > 0.0, "{face:?}");
            }
        }
    }

    #[test]
    fn bad_names_and_parameters_are_refused() {
        let cases = [
            ("sphere", "unknown base mesh `sphere` (known: tetrahedron, octahedron, icosahedron, cube, torus:G, icosahedron-holes:K, grid:WxH, quad-grid:WxH, mixed)"),
            ("cube:2", "base mesh `cube:2`: cube takes no parameter"),
            ("torus", "base mesh `torus`: expected torus:G with the genus G >= 1"),
            ("torus:x", "base mesh `torus:x`: expected torus:G with the genus G >= 1"),
            ("torus:0", "base mesh `torus:0`: the genus must be between 1 and 1048576, not 0"),
            ("torus:-1", "base mesh `torus:-1`: expected torus:G with the genus G >= 1"),
            ("icosahedron-holes:0", "base mesh `icosahedron-holes:0`: the icosahedron can have 1 to 4 holes without two sharing a vertex, not 0"),
            ("icosahedron-holes:5", "base mesh `icosahedron-holes:5`: the icosahedron can have 1 to 4 holes without two sharing a vertex, not 5"),
            ("grid:3", "base mesh `grid:3`: expected grid:WxH with W, H >= 1 (for example grid:4x3)"),
            ("grid:0x3", "base mesh `grid:0x3`: W and H must be at least 1"),
            ("quad-grid:5000x5000", "base mesh `quad-grid:5000x5000`: 5000x5000 cells is more than the 16777216 allowed"),
            ("quad-grid:axb", "base mesh `quad-grid:axb`: expected quad-grid:WxH with W, H >= 1 (for example quad-grid:4x3)"),
        ];
        for (name, message) in cases {
            assert_eq!(from_name(name).unwrap_err().to_string(), message, "{name}");
        }
    }
}
