//! The limit surface against OpenSubdiv 3.5's `PrimvarRefiner::Limit` (the driver's
//! `--limit`): limit positions and both tangents at every vertex of the last level, on every
//! shared mesh (tagged ones with their tags) and on generated grids with corners, semi-sharp
//! and infinitely sharp creases, darts and holes, every boundary mode and crease method,
//! levels 0-3. Positions must agree to 1e-12 of the base's bounding-box diagonal, tangents to
//! 1e-10 of their length (direction and length: OpenSubdiv's scaling and leading edges), the
//! normals `T1 × T2` to 1e-10 rad. Vertices are matched through the refined positions, as in
//! the other comparisons. Catmull-Clark at level 0 on a mesh with a face other than a quad is
//! refused (`Error::LimitNeedsQuads`), where OpenSubdiv weighs a corner of no meaning.

use super::*;
use halfedge::holes::HoleSet;
use halfedge::Error;

/// A level is compared when its output has at most this many faces.
const MAX_LIMIT_FACES: u64 = 600_000;

/// Tangents must agree to this fraction of their length.
const TANGENT_TOLERANCE: f64 = 1e-10;

/// Normals must agree to this angle (radians).
const NORMAL_TOLERANCE: f64 = 1e-10;

/// One vertex's limit: position, first and second tangent.
type Limit = [DVec3; 3];

/// The worst disagreements of one comparison.
#[derive(Default, Clone, Copy)]
struct Worst {
    position: f64,
    tangent: f64,
    normal: f64,
}

impl Worst {
    fn max(self, other: Worst) -> Worst {
        Worst {
            position: self.position.max(other.position),
            tangent: self.tangent.max(other.tangent),
            normal: self.normal.max(other.normal),
        }
    }
}

/// The driver's last level with `--limit`: the refined level (its vertices in no face taken
/// out, as `halfedge` drops them, and with `holes` the faces it tags as holes and the vertices
/// only they use) and each vertex's limit.
fn theirs(
    flags: &[&str],
    scheme: Osd,
    level: u32,
    path: &Path,
    boundary: &str,
    holes: bool,
) -> (PolygonMesh, Vec<Limit>) {
    let mut all = vec!["--limit"];
    all.extend_from_slice(flags);
    let (stdout, what) = opensubdiv_with(&all, scheme, level, path, Some(boundary)).stdout();
    let text = String::from_utf8_lossy(&stdout);
    let limits: Vec<Limit> = text
        .lines()
        .filter_map(|l| l.strip_prefix("# limit "))
        .map(|l| {
            let x: Vec<f64> = l
                .split_whitespace()
                .map(|w| w.parse().expect("a number"))
                .collect();
            assert_eq!(x.len(), 9, "{what}: a limit line has 9 numbers");
            [0, 3, 6].map(|k| DVec3::new(x[k], x[k + 1], x[k + 2]))
        })
        .collect();
    let all = io::read_obj_from(stdout.as_slice(), "osd_driver output")
        .unwrap_or_else(|e| panic!("{what} wrote an unreadable OBJ: {e}"));
    assert_eq!(
        limits.len(),
        all.n_vertices(),
        "{what}: one limit line per vertex"
    );
    let hole_faces: std::collections::HashSet<usize> = text
        .lines()
        .filter_map(|l| l.strip_prefix("# hole "))
        .map(|f| f.trim().parse().expect("a face index"))
        .collect();
    assert!(!holes || !hole_faces.is_empty(), "{what}: no hole listed");
    let mesh = PolygonMesh::from_faces(
        all.positions.clone(),
        (0..all.n_faces())
            .filter(|f| !holes || !hole_faces.contains(f))
            .map(|f| all.face(f).to_vec()),
    );
    let mut used = vec![false; mesh.n_vertices()];
    for &v in mesh.face_indices() {
        used[v as usize] = true;
    }
    let kept: Vec<Limit> = limits
        .into_iter()
        .zip(&used)
        .filter(|(_, &u)| u)
        .map(|(l, _)| l)
        .collect();
    (without_bare_vertices(&mesh), kept)
}

/// `halfedge`'s last level and its limit, with `tags`' sharpness and `options`.
fn ours(
    base: &Base,
    scheme: Osd,
    level: u32,
    tags: &Tags,
    options: SubdivisionOptions,
) -> Result<(PolygonMesh, Vec<Limit>), Error> {
    let rule = match scheme {
        Osd::Loop => Rule::Loop,
        Osd::Catmark => Rule::CatmullClark,
    };
    let sharpness = Sharpness::from_tags_of(&base.polygons, &base.mesh, tags)?;
    let holes = HoleSet::new(base.mesh.n_faces(), tags.holes().iter().copied())?;
    let mut opts = SubdivideOptions::default()
        .with_sharpness(&sharpness)
        .with_subdivision(options)
        .with_limit(true);
    if uses_holes(tags, options) {
        opts = opts.with_holes(&holes);
    }
    let r = Refinement::new(&base.mesh, rule, level, &opts)?;
    let points: Vec<[f64; 3]> = base.mesh.positions().iter().map(|p| p.to_array()).collect();
    let n = r.n_vertices(level);
    let mut refined = vec![[0.0; 3]; n];
    r.evaluate(&points, &mut refined)?;
    let (mut p, mut t1, mut t2) = (vec![[0.0; 3]; n], vec![[0.0; 3]; n], vec![[0.0; 3]; n]);
    r.evaluate_limit(&points, &mut p, Some((&mut t1, &mut t2)))?;
    let mut offsets = vec![0u32; r.n_faces(level) + 1];
    let mut indices = vec![0u32; r.n_corners(level)];
    r.write_polygons(&mut offsets, &mut indices)?;
    let faces: Vec<Vec<u32>> = offsets
        .windows(2)
        .map(|w| indices[w[0] as usize..w[1] as usize].to_vec())
        .collect();
    let mesh = PolygonMesh::from_faces(refined.into_iter().map(DVec3::from_array).collect(), faces);
    let limits: Vec<Limit> = (0..n)
        .map(|i| [p[i], t1[i], t2[i]].map(DVec3::from_array))
        .collect();
    if level <= 2 {
        // The limit stencils give the same surface, to rounding.
        let stencils = r.limit_stencils()?;
        let diagonal = bounding_box_diagonal(&base.polygons.positions);
        for (m, table) in [&stencils.position, &stencils.tangent1, &stencils.tangent2]
            .into_iter()
            .enumerate()
        {
            let mut out = vec![[0.0; 3]; n];
            table.apply(&points, &mut out)?;
            for (i, x) in out.iter().enumerate() {
                let d = DVec3::from_array(*x).distance(limits[i][m]);
                assert!(
                    d <= 1e-12 * diagonal,
                    "{} level {level}: limit stencil {m} of vertex {i} is {d:e} away",
                    base.file
                );
            }
        }
    }
    Ok((mesh, limits))
}

/// Whether a comparison leaves the tags' holes out on both sides: under every boundary mode
/// but `none`, where OpenSubdiv also tags every face at a boundary vertex as a hole (the
/// other comparisons keep the whole level: holes move no vertex).
fn uses_holes(tags: &Tags, options: SubdivisionOptions) -> bool {
    !tags.holes().is_empty() && options.boundary != BoundaryInterpolation::None
}

/// The angle between two vectors.
fn angle(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(a.dot(b))
}

/// One comparison; `Ok(None)` when `halfedge` refuses it as it should (Catmull-Clark's masks
/// at level 0 next to a face other than a quad).
fn compare_limit(
    base: &Base,
    scheme: Osd,
    level: u32,
    tags: &Tags,
    options: SubdivisionOptions,
) -> Result<Option<Worst>, String> {
    let method = options.crease_method.name();
    let triangles = options.triangle_rule.name();
    let boundary = match options.boundary {
        BoundaryInterpolation::Edge => "edge-only",
        BoundaryInterpolation::EdgeAndCorner => "edge-and-corner",
        BoundaryInterpolation::None => "none",
    };
    let at = format!(
        "{} {} level {level}, boundary {boundary}, {method}, {triangles}",
        base.file,
        scheme.driver_name()
    );
    let non_quad = base.polygons.faces().position(|f| f.len() != 4);
    let (ours_mesh, ours_limit) = match ours(base, scheme, level, tags, options) {
        Err(Error::LimitNeedsQuads { face, .. })
            if matches!(scheme, Osd::Catmark) && level == 0 && non_quad.is_some() =>
        {
            let _ = face;
            return Ok(None);
        }
        Err(e) => return Err(format!("{at}: {e}")),
        Ok(found) => found,
    };
    if matches!(scheme, Osd::Catmark) && level == 0 && non_quad.is_some() {
        return Err(format!(
            "{at}: a face that is not a quad, yet the limit was computed"
        ));
    }
    let flags = [
        "--tags",
        "--crease-method",
        method,
        "--triangle-rule",
        triangles,
    ];
    let holes = uses_holes(tags, options);
    let (theirs_mesh, theirs_limit) = theirs(&flags, scheme, level, &base.path, boundary, holes);
    let diagonal = bounding_box_diagonal(&base.polygons.positions);
    let to_ours = osd_support::correspondence(&theirs_mesh, &ours_mesh, 1e-12 * diagonal)
        .map_err(|e| format!("{at}: {e}"))?;
    let mut worst = Worst::default();
    for (v, (limit, &i)) in theirs_limit.iter().zip(&to_ours).enumerate() {
        let mine = ours_limit[i as usize];
        let position = mine[0].distance(limit[0]) / diagonal;
        let floor = 1e-9 * diagonal;
        let tangent = (1..3)
            .map(|k| mine[k].distance(limit[k]) / limit[k].length().max(floor))
            .fold(0.0, f64::max);
        let (n_theirs, n_ours) = (limit[1].cross(limit[2]), mine[1].cross(mine[2]));
        let degenerate = n_theirs.length() <= 1e-12 * limit[1].length() * limit[2].length();
        let normal = if degenerate {
            0.0
        } else {
            angle(n_theirs, n_ours)
        };
        if position > 1e-12 || tangent > TANGENT_TOLERANCE || normal > NORMAL_TOLERANCE {
            return Err(format!(
                "{at}: OpenSubdiv vertex {v} (halfedge {i}): position {} vs {} ({position:.2e} \
                 of the diagonal), tangents {} {} vs {} {} (relative {tangent:.2e}), normal \
                 {normal:.2e} rad",
                mine[0], limit[0], mine[1], mine[2], limit[1], limit[2]
            ));
        }
        worst = worst.max(Worst {
            position,
            tangent,
            normal,
        });
    }
    Ok(Some(worst))
}

/// Runs `cases` at `levels` (those within [`MAX_LIMIT_FACES`]), prints the worst agreement
/// and fails with every disagreement; returns the number of comparisons and of refusals.
fn check_limits(
    cases: &[(&Base, Osd, &Tags, SubdivisionOptions)],
    levels: &[u32],
) -> (usize, usize) {
    driver();
    let (mut failures, mut worst) = (Vec::new(), Worst::default());
    let (mut compared, mut refused) = (0, 0);
    for &(base, scheme, tags, options) in cases {
        let (faces, corners) = (base.polygons.n_faces(), base.polygons.n_corners());
        for &level in levels {
            if scheme.faces_at(faces, corners, level) > MAX_LIMIT_FACES {
                continue;
            }
            match compare_limit(base, scheme, level, tags, options) {
                Ok(Some(w)) => {
                    worst = worst.max(w);
                    compared += 1;
                }
                Ok(None) => refused += 1,
                Err(message) => failures.push(message),
            }
        }
    }
    eprintln!(
        "{compared} limit comparisons ({refused} refused at level 0): worst position {:.2e} of \
         the diagonal, tangent {:.2e} relative, normal {:.2e} rad",
        worst.position, worst.tangent, worst.normal
    );
    assert!(
        failures.is_empty(),
        "the limit disagrees with OpenSubdiv:\n{}",
        failures.join("\n")
    );
    (compared, refused)
}

/// Every shared mesh `halfedge` reads (Loop on the triangle meshes, Catmull-Clark on all),
/// tagged ones with their tags and options, levels 0-3.
#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn the_limit_matches_opensubdiv_on_every_shared_mesh() {
    let bases: Vec<(Base, Tags)> = shared_meshes()
        .iter()
        .map(|file| {
            let base = Base::load(file).unwrap_or_else(|e| panic!("{e}"));
            let tags = read_tags(&base.path);
            (base, tags)
        })
        .collect();
    let mut cases = Vec::new();
    for (base, tags) in &bases {
        let options = tag_options(tags);
        if base.is_triangle_mesh() {
            cases.push((base, Osd::Loop, tags, options));
        }
        cases.push((base, Osd::Catmark, tags, options));
    }
    let (compared, _) = check_limits(&cases, &[0, 1, 2, 3]);
    assert!(compared >= bases.len() * 2, "only {compared} comparisons");
}

/// Generated grids with every kind of sharpness, each boundary mode and crease method, and a
/// grid with holes, Catmull-Clark and Loop, levels 0-3.
#[test]
#[ignore = "needs the OpenSubdiv driver"]
fn the_limit_matches_opensubdiv_on_generated_grids() {
    let grids = generated_grids("limit-");
    let cases = grid_cases(&grids);
    let (compared, refused) = check_limits(&cases, &[0, 1, 2, 3]);
    // The triangle grid under Catmull-Clark at level 0, in every mode.
    assert_eq!(refused, all_modes().len());
    assert_eq!(compared + refused, cases.len() * 4);
}
