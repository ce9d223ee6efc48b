//! OpenSubdiv's face-varying UVs, through the driver's `--fvar MODE` and `--fvar-counts`
//! (`tools/osd-driver/README.md`): the reference for differential tests of UV values and UV
//! counts.
//!
//! - [`opensubdiv_fvar`] starts the driver on an OBJ whose every face corner has a `vt`
//!   (`f v/vt`); [`Running::fvar_level`] collects its last level as an [`FvarLevel`]:
//!   positions and faces exactly as without `--fvar` (OpenSubdiv's numbering), the last
//!   level's face-varying values (`vt`, OpenSubdiv's value order) and the value of every face
//!   corner, and the faces OpenSubdiv tags as holes.
//! - [`opensubdiv_fvar_counts`] runs `--fvar-counts`: `GetNumFVarValues` at every level
//!   `0..=level` ([`FvarCounts`]).
//!
//! The driver's output is read by this module's own parser ([`parse_fvar_obj`]), not by
//! `halfedge::io`, so the reference does not go through the reader under test.
//!
//! What OpenSubdiv counts (measured, see the README): level 0 is every `vt` line of the file,
//! used by a corner or not; from level 1 on only values some face reaches; hole faces are
//! refined like the others, so the values only hole faces use are kept (see
//! [`FvarLevel::without_holes`] to drop them with the hole faces).
//!
//! ```ignore
//! use halfedge::tags::FaceVaryingInterpolation;
//! let running = opensubdiv_fvar(&[], Osd::Catmark, 2, &path, Some("edge-only"),
//!                               FaceVaryingInterpolation::CornersPlus1.into());
//! // ... refine with halfedge meanwhile ...
//! let theirs = running.fvar_level();
//! let to_ours = correspondence(&theirs.mesh, &ours_mesh, tolerance)?; // vertices, by position
//! for f in 0..theirs.mesh.n_faces() {
//!     for (&v, &value) in theirs.mesh.face(f).iter().zip(theirs.face_values(f)) {
//!         let uv = theirs.values()[value as usize]; // OpenSubdiv's UV at corner (f, v)
//!     }
//! }
//! ```

use std::path::Path;

use halfedge::glam::{DVec2, DVec3};
use halfedge::tags::FaceVaryingInterpolation;
use halfedge::uv::Uvs;
use halfedge::PolygonMesh;

use super::{opensubdiv_with, Osd, Running};

/// The driver's `--fvar` argument: which `Sdc::Options::FVarLinearInterpolation` it sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum FvarMode {
    /// The named mode (`--fvar none`, ..., `--fvar all`; `FaceVaryingInterpolation`'s names
    /// are the driver's), whatever the file's tags say.
    Linear(FaceVaryingInterpolation),
    /// `--fvar tag`: the file's `facevaryinginterpolateboundary` tag, else `corners-plus1`
    /// (`subcount subdivide`'s default). The driver reads the tag only with `--tags`: pass
    /// `"--tags"` in the flags, else the driver refuses the command line (and the run panics).
    Tag,
}

impl FvarMode {
    /// The six named modes, in `FVarLinearInterpolation`'s order.
    pub(crate) fn every_linear() -> impl Iterator<Item = FvarMode> {
        FaceVaryingInterpolation::ALL
            .iter()
            .map(|&m| FvarMode::Linear(m))
    }

    /// The driver's word for the mode.
    pub(crate) fn driver_name(self) -> &'static str {
        match self {
            FvarMode::Linear(mode) => mode.name(),
            FvarMode::Tag => "tag",
        }
    }
}

impl From<FaceVaryingInterpolation> for FvarMode {
    fn from(mode: FaceVaryingInterpolation) -> FvarMode {
        FvarMode::Linear(mode)
    }
}

/// Starts the driver with `--fvar MODE` on `path` (every face corner must have a `vt`, else
/// the driver fails and [`Running::fvar_level`] panics naming the line): `flags` (`--tags`,
/// `--crease-method M`, `--triangle-rule R`) go first, then `--fvar MODE`, then scheme, level,
/// file and the vertex boundary interpolation when given (`edge-only`, `edge-and-corner`,
/// `none`; else the file's tag with `--tags`, else `edge-only`). Collect the output with
/// [`Running::fvar_level`]; meanwhile the caller can refine its own side.
pub(crate) fn opensubdiv_fvar(
    flags: &[&str],
    scheme: Osd,
    level: u32,
    path: &Path,
    boundary: Option<&str>,
    mode: FvarMode,
) -> Running {
    let mut all: Vec<&str> = flags.to_vec();
    all.extend(["--fvar", mode.driver_name()]);
    opensubdiv_with(&all, scheme, level, path, boundary)
}

impl Running {
    /// The last level written by a run of [`opensubdiv_fvar`], once the driver has finished;
    /// panics when the driver fails or its output does not parse.
    pub(crate) fn fvar_level(self) -> FvarLevel {
        let (stdout, what) = self.stdout();
        let text = String::from_utf8(stdout)
            .unwrap_or_else(|e| panic!("{what} wrote something that is not UTF-8: {e}"));
        parse_fvar_obj(&text).unwrap_or_else(|e| panic!("{what}: {e}"))
    }
}

/// OpenSubdiv's last level with its face-varying UV channel, as the driver writes it with
/// `--fvar`.
#[derive(Clone, Debug)]
pub(crate) struct FvarLevel {
    /// Positions and faces, in OpenSubdiv's vertex and face numbering, with
    /// [`PolygonMesh::uvs`] set: its `coords` are the level's face-varying values (one per
    /// `vt` line, OpenSubdiv's value order, `GetNumFVarValues` of them) and its `corners` the
    /// value of every face corner (`GetFaceFVarValues`), in the order of
    /// [`PolygonMesh::face_indices`]. Hole faces are included (see [`FvarLevel::holes`]).
    pub(crate) mesh: PolygonMesh,
    /// The faces OpenSubdiv tags as holes (the driver's `# hole F` comments), ascending.
    pub(crate) holes: Vec<usize>,
    /// With the driver's `--limit`: the limit of every value (`LimitFaceVarying`, its
    /// `# limituv u v` comments), in the values' order.
    pub(crate) limit: Vec<DVec2>,
}

impl FvarLevel {
    /// The level's face-varying channel: values and the value of each corner.
    pub(crate) fn uvs(&self) -> &Uvs {
        self.mesh
            .uvs()
            .expect("parse_fvar_obj sets the UVs of every FvarLevel")
    }

    /// The level's face-varying values, indexed by [`FvarLevel::corner_values`].
    pub(crate) fn values(&self) -> &[DVec2] {
        self.uvs().coords()
    }

    /// The value index of every face corner, in the order of the mesh's `face_indices`.
    pub(crate) fn corner_values(&self) -> &[u32] {
        self.uvs().corners()
    }

    /// The value indices of face `f`'s corners, in the order of `mesh.face(f)`.
    pub(crate) fn face_values(&self, f: usize) -> &[u32] {
        let offsets = self.mesh.face_offsets();
        &self.corner_values()[offsets[f]..offsets[f + 1]]
    }

    /// The level without its hole faces: the faces not listed in [`FvarLevel::holes`], the
    /// vertices and the values they use, both renumbered in their order here (so a vertex or
    /// value only hole faces use is gone); `holes` is then empty.
    pub(crate) fn without_holes(&self) -> FvarLevel {
        let is_hole = {
            let mut is_hole = vec![false; self.mesh.n_faces()];
            for &f in &self.holes {
                is_hole[f] = true;
            }
            is_hole
        };
        let kept: Vec<usize> = (0..self.mesh.n_faces()).filter(|&f| !is_hole[f]).collect();
        // new_index[i]: i's index among the used ones, u32::MAX when unused.
        let renumber = |count: usize, used: &mut dyn Iterator<Item = u32>| {
            let mut is_used = vec![false; count];
            for i in used {
                is_used[i as usize] = true;
            }
            let mut next = 0;
            is_used
                .iter()
                .map(|&u| {
                    if u {
                        next += 1;
                        next - 1
                    } else {
                        u32::MAX
                    }
                })
                .collect::<Vec<u32>>()
        };
        let vertex_index = renumber(
            self.mesh.n_vertices(),
            &mut kept.iter().flat_map(|&f| self.mesh.face(f).iter().copied()),
        );
        let value_index = renumber(
            self.values().len(),
            &mut kept
                .iter()
                .flat_map(|&f| self.face_values(f).iter().copied()),
        );
        let positions: Vec<DVec3> = self
            .mesh
            .positions
            .iter()
            .zip(&vertex_index)
            .filter(|(_, &i)| i != u32::MAX)
            .map(|(&p, _)| p)
            .collect();
        let values: Vec<DVec2> = self
            .values()
            .iter()
            .zip(&value_index)
            .filter(|(_, &i)| i != u32::MAX)
            .map(|(&uv, _)| uv)
            .collect();
        let mut mesh = PolygonMesh::from_faces(
            positions,
            kept.iter().map(|&f| {
                self.mesh
                    .face(f)
                    .iter()
                    .map(|&v| vertex_index[v as usize])
                    .collect::<Vec<u32>>()
            }),
        );
        let corners: Vec<u32> = kept
            .iter()
            .flat_map(|&f| self.face_values(f).iter().map(|&i| value_index[i as usize]))
            .collect();
        let uvs = Uvs::new(values, corners).expect("renumbered values stay in range");
        mesh.set_uvs(Some(uvs)).expect("one value per kept corner");
        FvarLevel {
            mesh,
            holes: Vec::new(),
            limit: Vec::new(),
        }
    }

    /// The level with the limit of its values in place of the values (the driver ran with
    /// `--limit`); panics without them.
    // Used by `tests/opensubdiv_uv.rs` only.
    #[allow(dead_code)]
    pub(crate) fn with_limit_values(mut self) -> FvarLevel {
        let corners = self.corner_values().to_vec();
        assert_eq!(self.limit.len(), self.values().len(), "one limit per value");
        let limit = std::mem::take(&mut self.limit);
        let uvs = Uvs::new(limit, corners).expect("the same values");
        self.mesh.set_uvs(Some(uvs)).expect("one value per corner");
        self
    }
}

/// Parses the driver's `--fvar` output: `v x y z` lines, `vt u v` lines, faces `f v/vt ...`
/// (1-based) and `# hole F` comments (0-based faces); anything else is an error, naming the
/// line. Every index must be in range, every corner must have its value index.
pub(crate) fn parse_fvar_obj(text: &str) -> Result<FvarLevel, String> {
    let mut positions: Vec<DVec3> = Vec::new();
    let mut values: Vec<DVec2> = Vec::new();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    let mut corners: Vec<u32> = Vec::new();
    let mut holes: Vec<usize> = Vec::new();
    let mut limit: Vec<DVec2> = Vec::new();
    let numbers = |words: std::str::SplitWhitespace<'_>, at: &str| -> Result<Vec<f64>, String> {
        words
            .map(|w| w.parse::<f64>().map_err(|e| format!("{at}: '{w}': {e}")))
            .collect()
    };
    let index = |text: &str, count: usize, what: &str, at: &str| -> Result<u32, String> {
        let i: usize = text
            .parse()
            .map_err(|e| format!("{at}: {what} index '{text}': {e}"))?;
        if i == 0 || i > count {
            return Err(format!("{at}: {what} index {i} out of 1..={count}"));
        }
        u32::try_from(i - 1).map_err(|e| format!("{at}: {what} index {i}: {e}"))
    };
    for (n, line) in text.lines().enumerate() {
        let at = format!("line {}", n + 1);
        if let Some(face) = line.strip_prefix("# hole ") {
            let f: usize = face
                .trim()
                .parse()
                .map_err(|e| format!("{at}: hole face '{face}': {e}"))?;
            holes.push(f);
            continue;
        }
        if let Some(uv) = line.strip_prefix("# limituv ") {
            match numbers(uv.split_whitespace(), &at)?.as_slice() {
                &[u, v] => limit.push(DVec2::new(u, v)),
                other => return Err(format!("{at}: a limit UV has {} numbers", other.len())),
            }
            continue;
        }
        if line.starts_with("# limit ") {
            continue;
        }
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => match numbers(words, &at)?.as_slice() {
                &[x, y, z] => positions.push(DVec3::new(x, y, z)),
                other => return Err(format!("{at}: a vertex has {} numbers", other.len())),
            },
            Some("vt") => match numbers(words, &at)?.as_slice() {
                &[u, v] => values.push(DVec2::new(u, v)),
                other => return Err(format!("{at}: a vt has {} numbers", other.len())),
            },
            Some("f") => {
                let mut face = Vec::new();
                for corner in words {
                    let (v, vt) = corner
                        .split_once('/')
                        .ok_or_else(|| format!("{at}: corner '{corner}' has no value index"))?;
                    face.push(index(v, positions.len(), "vertex", &at)?);
                    corners.push(index(vt, values.len(), "value", &at)?);
                }
                if face.len() < 3 {
                    return Err(format!("{at}: a face of {} corners", face.len()));
                }
                faces.push(face);
            }
            _ => return Err(format!("{at}: unexpected line '{line}'")),
        }
    }
    if let Some(&f) = holes.iter().find(|&&f| f >= faces.len()) {
        return Err(format!("hole face {f} of {} faces", faces.len()));
    }
    if holes.windows(2).any(|w| w[0] >= w[1]) {
        return Err("hole faces are not ascending".to_owned());
    }
    let mut mesh = PolygonMesh::from_faces(positions, faces);
    let uvs = Uvs::new(values, corners).map_err(|e| e.to_string())?;
    mesh.set_uvs(Some(uvs)).map_err(|e| e.to_string())?;
    Ok(FvarLevel { mesh, holes, limit })
}

/// What `--fvar-counts` prints.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct FvarCounts {
    /// The mode the driver used (for [`FvarMode::Tag`], what the file's tag chose).
    pub(crate) mode: FaceVaryingInterpolation,
    /// `GetNumFVarValues(0)` at levels `0..=level`: level 0 counts every `vt` line of the
    /// file, used or not.
    pub(crate) values: Vec<u64>,
}

/// Runs the driver with `--fvar MODE --fvar-counts` (arguments as for [`opensubdiv_fvar`])
/// and returns its counts; panics when the driver fails or prints something else than its
/// JSON line (`{"scheme": ..., "level": L, "fvar": MODE, "fvar_values": [...]}`).
pub(crate) fn opensubdiv_fvar_counts(
    flags: &[&str],
    scheme: Osd,
    level: u32,
    path: &Path,
    boundary: Option<&str>,
    mode: FvarMode,
) -> FvarCounts {
    let mut all: Vec<&str> = flags.to_vec();
    all.push("--fvar-counts");
    let (stdout, what) = opensubdiv_fvar(&all, scheme, level, path, boundary, mode).stdout();
    let json: serde_json::Value = serde_json::from_slice(&stdout)
        .unwrap_or_else(|e| panic!("{what} --fvar-counts printed no JSON: {e}"));
    let mode = json["fvar"]
        .as_str()
        .and_then(|m| m.parse::<FaceVaryingInterpolation>().ok())
        .unwrap_or_else(|| panic!("{what} --fvar-counts: no known \"fvar\" mode in {json}"));
    let values: Vec<u64> = json["fvar_values"]
        .as_array()
        .and_then(|a| a.iter().map(serde_json::Value::as_u64).collect())
        .unwrap_or_else(|| panic!("{what} --fvar-counts: no \"fvar_values\" list in {json}"));
    assert_eq!(
        values.len(),
        level as usize + 1,
        "{what} --fvar-counts: one count per level 0..={level} expected in {json}"
    );
    FvarCounts { mode, values }
}

/// The largest difference between OpenSubdiv's corner UVs and ours, relative to the diagonal of
/// OpenSubdiv's UV bounding box, and where it is. Faces are matched by their vertex cycle
/// (`to_ours` maps `their_mesh`'s vertices to `ours`', as `correspondence` gives it), corners
/// along the cycle; `our_uv(g, k)` is our UV at corner `k` of our face `g`.
///
/// # Errors
///
/// An OpenSubdiv face that is none of ours.
// Used by `tests/opensubdiv_uv.rs` and the CLI's `uv_subdivide.rs`, not by `tests/opensubdiv.rs`.
#[allow(dead_code)]
pub(crate) fn corner_uv_error(
    theirs: &FvarLevel,
    their_mesh: &PolygonMesh,
    ours: &PolygonMesh,
    to_ours: &[u32],
    our_uv: impl Fn(usize, usize) -> DVec2,
) -> Result<(f64, String), String> {
    // A face by its vertex cycle from its smallest vertex, and where that starts.
    let key = |face: &[u32]| {
        let start = (0..face.len()).min_by_key(|&i| face[i]).unwrap_or(0);
        let cycle: Vec<u32> = (0..face.len())
            .map(|j| face[(start + j) % face.len()])
            .collect();
        (cycle, start)
    };
    let faces: std::collections::HashMap<Vec<u32>, (usize, usize)> = (0..ours.n_faces())
        .map(|f| {
            let (cycle, start) = key(ours.face(f));
            (cycle, (f, start))
        })
        .collect();
    let (lo, hi) = theirs.values().iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let scale = (hi - lo).length().max(f64::MIN_POSITIVE);
    let (mut worst, mut at) = (0.0f64, String::from("no corners"));
    for f in 0..their_mesh.n_faces() {
        let mapped: Vec<u32> = their_mesh
            .face(f)
            .iter()
            .map(|&v| to_ours[v as usize])
            .collect();
        let (cycle, start) = key(&mapped);
        let &(g, our_start) = faces
            .get(&cycle)
            .ok_or_else(|| format!("OpenSubdiv's face {f} is not one of ours"))?;
        let n = mapped.len();
        let values = theirs.face_values(f);
        for j in 0..n {
            let theirs_uv = theirs.values()[values[(start + j) % n] as usize];
            let ours_uv = our_uv(g, (our_start + j) % n);
            let e = theirs_uv.distance(ours_uv) / scale;
            if e > worst || at == "no corners" {
                worst = worst.max(e);
                at = format!(
                    "face {f} corner {j}: OpenSubdiv {theirs_uv}, ours {ours_uv} ({e:e} of the UV box)"
                );
            }
        }
    }
    Ok((worst, at))
}
