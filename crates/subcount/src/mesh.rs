//! `stats`, `verify` and `subdivide`: real meshes and real subdivision.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Owner of UVs through `subdivide` and `verify`: the layout refined or why not (`--no-uv`,
//! partial `vt`, a rule without UVs: one note each; the raw face-list path writes UVs refined by
//! `subdivide_polygons`), `--uv-interpolation` over the tag, the summary's `UV = N`, the memory
//! guard's UV share (`mesh.rs`'s `uv_bytes`, when UVs will be refined), `--timings`' `uv_s`
//! (`refined::SurfaceClock`: the surface's last level reported splits its work from the UVs'),
//! `verify`'s `UV` component (`UvCheck`: predicted by `schemes::uv::UvCounter`, measured as the
//! distinct values the corners of a `Refinement` with UVs use at each level, or on the face-list
//! path those of `subdivide_polygons`' written UVs, predicted from `UV0 = V`):
//! `crates/subcount/src/mesh.rs` (`subdivide`, `uv_interpolation`, `UvCheck`) and `refined.rs`
//! (UVs of the refine-once path into caller-owned buffers); the refinement itself:
//! `halfedge::refine::face_varying`.

use std::io::Write;
use std::time::{Duration, Instant};

use halfedge::io::ObjWriteOptions;
use halfedge::subdivide::{self as sub, LevelDone, SubdivideOptions};
use halfedge::tags::FaceVaryingInterpolation;
use halfedge::uv::UvLayout;
use halfedge::{HalfEdgeMesh, PolygonMesh, Rule};
use num_bigint::BigInt;
use num_traits::ToPrimitive;
use schemes::uv::UvCounter;
use schemes::{Budget, MeshCounts, Plan, Scheme};

use crate::args::{
    MeshSource, Precision, ReportFormat, SchemeChoice, StatsArgs, SubdivideArgs, VerifyArgs,
};
use crate::refined;
use serde_json::{json, Value};

use crate::failure::{scheme_failure, usage, write_failure, Failure, Kind};
use crate::levels::parse_levels_count;
use crate::model::{
    face_place, load_mesh, load_scheme_file, mesh_label, not_applicable, refuse_degenerate_faces,
    refuse_triangle_rule, validate, LoadedMesh,
};
use crate::output::json_text;

/// The most levels `verify` picks by itself from `--max-faces`.
const MAX_VERIFY_LEVELS: u64 = 64;

pub(crate) fn required_mesh(mesh: &MeshSource) -> Result<LoadedMesh, Failure> {
    load_mesh(mesh)?.ok_or_else(|| usage!("give a mesh: --mesh FILE or --base NAME"))
}

/// Maps a `halfedge` error to an exit code.
pub(crate) fn halfedge_failure(e: halfedge::Error) -> Failure {
    use halfedge::Error as E;
    let kind = match &e {
        E::Scheme(inner) => return scheme_failure(inner.clone()),
        E::NoSubdivision { .. } | E::NotComposable { .. } => Kind::Usage,
        E::CreasesNotSupported { .. } => {
            return Failure::new(
                Kind::Input,
                anyhow::anyhow!(
                    "{e}: use a Loop or Catmull-Clark scheme, --ignore-tags (for the file's tags), or drop the option flags"
                ),
            )
        }
        _ if e.is_resource_limit() => Kind::Guard,
        E::PredictionMismatch { .. } | E::InvalidOutput { .. } | E::BrokenInvariant { .. } => {
            Kind::Mismatch
        }
        _ => Kind::Input,
    };
    Failure::new(kind, e)
}

/// As [`halfedge_failure`], and an error about a face of the input (a face-list subdivider's
/// refusal) names the mesh file and the face's line.
fn located_failure(e: halfedge::Error, poly: &PolygonMesh, mesh: &MeshSource) -> Failure {
    if let Some(f) = e.face() {
        let (label, place) = (mesh_label(mesh), face_place(poly, f as usize));
        return Failure::new(Kind::Input, anyhow::anyhow!("{label}: {place}{e}"));
    }
    halfedge_failure(e)
}

pub(crate) fn stats(args: StatsArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let loaded = required_mesh(&args.mesh)?;
    loaded.print_notes();
    let poly = &loaded.poly;
    // Present only when the file has tags: an untagged mesh's output is what it always was.
    let tags = poly.has_tags().then(|| tag_summary(loaded.tags(), poly));
    let counts = halfedge::stats::face_list_counts(poly);
    let problems = halfedge::stats::face_list_problems(poly);
    let validation = validate(poly, &args.mesh).err();
    // A face that repeats a vertex is refused on every path, so no scheme applies.
    let applicable = if problems.faces_with_repeated_vertex > 0 {
        Vec::new()
    } else {
        // Holes need faces that nest, boundary `none` (on a mesh with boundary) is a mode of
        // Loop and Catmull-Clark: the schemes that would refuse them are not listed.
        let holes = !loaded.tags().hole_faces().is_empty();
        let none = loaded.options.boundary == halfedge::tags::BoundaryInterpolation::None
            && counts.boundary_edges > 0;
        sub::applicable_schemes(&counts, validation.is_none())
            .iter()
            .filter(|s| {
                let rule = s.subdivision_rule();
                (!holes || rule.is_some_and(schemes::holes::nests_faces))
                    && (!none || matches!(rule, Some(Rule::Loop | Rule::CatmullClark)))
            })
            .map(|s| s.name().to_owned())
            .collect()
    };
    let genus = if validation.is_none() {
        halfedge::stats::genus(&counts)
    } else {
        None
    };
    // Present only when the file has texture coordinates (a layout, or `vt` at only some
    // corners: one line, `"uv": null`): a mesh without `vt` prints what it always printed.
    let uv = halfedge::stats::uv_counts(poly);
    let c = &counts;
    let text = match args.format {
        ReportFormat::Json => {
            let degrees: serde_json::Map<String, Value> = c
                .faces_by_degree
                .iter()
                .map(|(d, n)| (d.to_string(), Value::from(*n)))
                .collect();
            let mut object = json!({
                "V": c.vertices,
                "E": c.edges,
                "IE": c.interior_edges,
                "BE": c.boundary_edges,
                "NME": c.nonmanifold_edges,
                "F": c.faces,
                "H": c.corners,
                "faces_by_degree": degrees,
                "boundary_loops": c.boundary_loops,
                "components": c.components,
                "euler_characteristic": c.euler_characteristic,
                "genus": genus,
                "unreferenced_vertices": c.unreferenced_vertices,
                "manifold": validation.is_none(),
                "problems": {
                    "faces_with_repeated_vertex": problems.faces_with_repeated_vertex,
                    "duplicate_faces": problems.duplicate_faces,
                    "nonmanifold_edges": problems.nonmanifold_edges,
                    "nonmanifold_vertices": problems.nonmanifold_vertices,
                    "inconsistently_oriented_edges": problems.inconsistently_oriented_edges,
                },
            });
            if let (Some(tags), Value::Object(map)) = (&tags, &mut object) {
                map.insert("tags".to_owned(), tags.to_json());
            }
            if let Value::Object(map) = &mut object {
                match (&uv, poly.partial_uvs()) {
                    (Some(uv), _) => {
                        map.insert("uv".to_owned(), json!(uv));
                    }
                    (None, Some(_)) => {
                        map.insert("uv".to_owned(), Value::Null);
                    }
                    (None, None) => {}
                }
            }
            if let Value::Object(map) = &mut object {
                map.insert("applicable_schemes".to_owned(), json!(applicable));
            }
            json_text(&object)
        }
        ReportFormat::Text => {
            let degrees: Vec<String> = c
                .faces_by_degree
                .iter()
                .map(|(d, n)| format!("{n} of degree {d}"))
                .collect();
            let mut t = format!(
                "V = {} (vertices used by faces; {} unreferenced)\nE = {} (IE = {} interior, BE = {} boundary, NME = {} non-manifold)\nF = {} ({})\nH = {} (sum of face degrees)\nboundary loops = {}\ncomponents = {}\nEuler characteristic = {}\n",
                c.vertices,
                c.unreferenced_vertices,
                c.edges,
                c.interior_edges,
                c.boundary_edges,
                c.nonmanifold_edges,
                c.faces,
                degrees.join(", "),
                c.corners,
                c.boundary_loops,
                c.components,
                c.euler_characteristic,
            );
            if let Some(g) = genus {
                t.push_str(&format!("genus = {g}\n"));
            }
            match &validation {
                None => t.push_str("manifold, consistently oriented\n"),
                Some(e) => t.push_str(&format!("not a valid half-edge mesh: {:#}\n", e.error)),
            }
            if let Some(tags) = &tags {
                t.push_str(&format!("{}\n", tags.to_text()));
            }
            match (&uv, poly.partial_uvs()) {
                (Some(uv), _) => t.push_str(&format!("{}\n", uv_layout_text(uv))),
                (None, Some(partial)) => t.push_str(&format!("{partial}\n")),
                (None, None) => {}
            }
            t.push_str(&format!("applicable schemes: {}", applicable.join(", ")));
            t
        }
    };
    writeln!(out, "{text}").map_err(write_failure)?;
    Ok(0)
}

/// The UV layout line of `stats`: `UV layout: V = 267, E = 438, BE = 144, seam edges = 72,
/// boundary loops = 13, charts = 13, unreferenced = 0`.
fn uv_layout_text(uv: &schemes::uv::UvCounts) -> String {
    format!(
        "UV layout: V = {}, E = {}, BE = {}, seam edges = {}, boundary loops = {}, charts = {}, unreferenced = {}",
        uv.values,
        uv.edges,
        uv.boundary_edges,
        uv.seam_edges,
        uv.boundary_loops,
        uv.charts,
        uv.unreferenced
    )
}

/// What a file's tags hold, for `stats`: distinct sharp edges and vertices (sharpness > 0),
/// distinct hole faces, the options the tags set, and the tags not read.
struct TagSummary {
    crease_edges: usize,
    corners: usize,
    holes: usize,
    /// `(key, value)`: `boundary`, `face_varying`, `crease_method`, `triangle_rule`, each only
    /// when a tag sets it, valued by its command-line name.
    options: Vec<(&'static str, &'static str)>,
    /// Tag names not read, with their number of lines.
    ignored: Vec<(String, u64)>,
}

fn tag_summary(tags: &halfedge::tags::Tags, poly: &PolygonMesh) -> TagSummary {
    let o = &tags.options;
    let options = [
        ("boundary", o.boundary.map(|v| v.name())),
        ("face_varying", o.face_varying.map(|v| v.name())),
        ("crease_method", o.crease_method.map(|v| v.name())),
        ("triangle_rule", o.triangle_rule.map(|v| v.name())),
    ]
    .into_iter()
    .filter_map(|(k, v)| v.map(|v| (k, v)))
    .collect();
    TagSummary {
        crease_edges: tags.sharp_edges().len(),
        corners: tags.sharp_vertices().len(),
        holes: tags.hole_faces().len(),
        options,
        ignored: poly
            .ignored_tags()
            .iter()
            .map(|t| (t.name.clone(), t.count))
            .collect(),
    }
}

impl TagSummary {
    fn to_json(&self) -> Value {
        let options: serde_json::Map<String, Value> = self
            .options
            .iter()
            .map(|&(k, v)| (k.to_owned(), Value::from(v)))
            .collect();
        let mut object = json!({
            "crease_edges": self.crease_edges,
            "corners": self.corners,
            "holes": self.holes,
            "options": options,
        });
        if let (false, Value::Object(map)) = (self.ignored.is_empty(), &mut object) {
            let ignored: serde_json::Map<String, Value> = self
                .ignored
                .iter()
                .map(|(k, n)| (k.clone(), Value::from(*n)))
                .collect();
            map.insert("ignored".to_owned(), ignored.into());
        }
        object
    }

    fn to_text(&self) -> String {
        let mut t = format!(
            "tags: {} crease edges, {} corners, {} holes",
            self.crease_edges, self.corners, self.holes
        );
        if !self.options.is_empty() {
            let options: Vec<String> = self
                .options
                .iter()
                .map(|(k, v)| format!("{k} = {v}"))
                .collect();
            t.push_str(&format!("; options: {}", options.join(", ")));
        }
        if !self.ignored.is_empty() {
            let ignored: Vec<String> = self
                .ignored
                .iter()
                .map(|(k, n)| format!("{k} ({n})"))
                .collect();
            t.push_str(&format!("; ignored: {}", ignored.join(", ")));
        }
        t
    }
}

/// What `verify` and `subdivide` run: the scheme as it counts what is written, its rule, and
/// the holes.
struct Chosen {
    /// The scheme of `--scheme` or `--scheme-file` for the written faces.
    scheme: Scheme,
    /// The rule that really subdivides it.
    rule: Rule,
    /// The faces that are holes ([`LoadedMesh::holes`]), if any.
    holes: Option<halfedge::holes::HoleSet>,
}

/// The scheme of `--scheme` (built-in) or `--scheme-file` as it counts what is written of
/// this mesh (`loop` and its aliases count as `loop-boundary` on a mesh with boundary:
/// [`Scheme::for_mesh`]; with holes, the statistics of the written faces, so a closed mesh
/// with holes counts with the boundary-aware state), the rule that really subdivides it
/// ([`sub::checked_rule`]) and the holes. `counts` are the statistics of all faces.
fn chosen_scheme(
    choice: &SchemeChoice,
    loaded: &LoadedMesh,
    counts: &MeshCounts,
    mesh: &MeshSource,
) -> Result<Chosen, Failure> {
    let scheme = match (&choice.scheme_file, &choice.scheme) {
        (Some(path), name) => {
            let custom = load_scheme_file(path)?;
            if let Some(name) = name.as_deref().filter(|n| *n != custom.name()) {
                return Err(usage!(
                    "--scheme {name} is not the scheme of {} (`{}`)",
                    path.display(),
                    custom.name()
                ));
            }
            custom
        }
        (None, Some(name)) => schemes::builtin(name).map_err(scheme_failure)?,
        (None, None) => return Err(usage!("give --scheme NAME or --scheme-file FILE")),
    };
    let holes = loaded.holes(
        counts,
        mesh,
        scheme.name(),
        &[(scheme.name(), scheme.subdivision_rule())],
    )?;
    let written = holes.as_ref().map(|h| h.written_counts(&loaded.poly));
    let counts = written.as_ref().unwrap_or(counts);
    let scheme = scheme.for_mesh(counts);
    refuse_triangle_rule(
        mesh,
        scheme.name(),
        [(scheme.name(), scheme.subdivision_rule())],
    )?;
    scheme
        .initial_state(counts)
        .map_err(|e| not_applicable(mesh, e))?;
    let rule = sub::checked_rule(&scheme, counts).map_err(halfedge_failure)?;
    Ok(Chosen {
        scheme,
        rule,
        holes,
    })
}

/// Whether to run on the raw face list: a built-in scheme that allows non-manifold input
/// (`loop-general`, `catmull-clark-general`, `tri-split-N`), or a custom one on a mesh with
/// non-manifold edges, when its rule refines each face on its own.
fn on_face_list(scheme: &Scheme, rule: Rule, counts: &MeshCounts, custom: bool) -> bool {
    let general = if custom {
        counts.nonmanifold_edges > 0
    } else {
        !scheme.mesh_class().needs_manifold()
    };
    general && rule.refines_faces()
}

/// The last level of a real subdivision: at most 64, refused (exit 4) before any count is
/// computed, since every rule at least doubles the faces per level and level 65 could not be
/// indexed by 32-bit integers (and its exact counts would take long to compute).
pub(crate) fn real_levels(text: &str) -> Result<u32, Failure> {
    let levels = parse_levels_count(text)?;
    if levels > 64 {
        return Err(Failure::new(
            Kind::Guard,
            anyhow::anyhow!(
                "--levels {levels}: real subdivision stops at level 64 (every rule at least doubles the faces per level, so no later level fits 32-bit indices)"
            ),
        ));
    }
    Ok(levels)
}

/// The memory guard: `need` (a [`halfedge::memory`] prediction, with the UV channel's
/// [`uv_bytes`] when UVs are refined) against half the available memory, unless lifted.
fn guard_memory(
    need: halfedge::Result<BigInt>,
    scheme: &str,
    levels: u32,
    allow_large: bool,
) -> Result<BigInt, Failure> {
    let limit = if allow_large {
        u128::MAX
    } else {
        halfedge::memory::peak_limit()
    };
    need.and_then(|need| halfedge::memory::within_limit(need, scheme, levels, limit))
        .map_err(guard_failure)
}

/// The memory guard's refusal (exit 4, saying how to lift it); other errors as
/// [`halfedge_failure`].
pub(crate) fn guard_failure(e: halfedge::Error) -> Failure {
    match e {
        halfedge::Error::OverMemoryLimit { .. } => Failure::new(
            Kind::Guard,
            anyhow::anyhow!("{e}; use fewer levels, or --allow-large to try anyway"),
        ),
        e => halfedge_failure(e),
    }
}

/// What refining the UV layout of `poly` adds to the memory guard's need
/// ([`halfedge::memory::predicted_uv_bytes`] of its layout's statistics); 0 for a rule without
/// a face-varying rule (it writes without UVs) or a mesh without a layout.
pub(crate) fn uv_bytes(
    poly: &PolygonMesh,
    rule: Rule,
    levels: u32,
    scalar_bytes: usize,
    holes: bool,
) -> halfedge::Result<BigInt> {
    let Some(layout) = halfedge::stats::uv_layout_counts(poly) else {
        return Ok(BigInt::from(0));
    };
    match halfedge::memory::predicted_uv_bytes(rule, &layout, levels, scalar_bytes, holes) {
        Err(halfedge::Error::UvsNotSupported { .. }) => Ok(BigInt::from(0)),
        bytes => bytes,
    }
}

/// The `UV` component of `verify`: the UV values a scheme predicts for the mesh's layout
/// ([`UvCounter`]), against those of the real face-varying subdivision.
struct UvCheck {
    /// The layout refined.
    layout: UvLayout,
    /// The prediction.
    counter: UvCounter,
    /// Level 0 as [`schemes::uv`] defines it: the `vt` entries the written corners use.
    used_vt: u64,
}

impl UvCheck {
    /// `None` for a mesh without a UV layout (no `vt`, or `vt` at only some corners: what is
    /// verified is then what it always was), and for a scheme that does not count UV values
    /// (one note on stderr, as `table` gives).
    fn new(
        loaded: &LoadedMesh,
        scheme: &Scheme,
        holes: Option<&halfedge::holes::HoleSet>,
    ) -> Result<Option<UvCheck>, Failure> {
        let poly = &loaded.poly;
        let (Some(layout), Some(uvs)) = (poly.uv_layout(), poly.uvs()) else {
            return Ok(None);
        };
        let counts = match holes {
            Some(holes) => holes.written_uv_counts(poly),
            None => halfedge::stats::uv_counts(poly),
        };
        let Some(counts) = counts else {
            return Ok(None);
        };
        let counter = match UvCounter::new(&Plan::single(scheme.clone()), counts) {
            Ok(counter) => counter,
            Err(not) => {
                eprintln!("note: {not}: no UV rows");
                return Ok(None);
            }
        };
        // Level 0, measured: the distinct `vt` of the written faces' corners.
        let offsets = poly.face_offsets();
        let mut used = vec![false; uvs.coords().len()];
        for f in (0..poly.n_faces()).filter(|&f| holes.map_or(true, |h| !h.contains(f as u32))) {
            for &t in &uvs.corners()[offsets[f]..offsets[f + 1]] {
                used[t as usize] = true;
            }
        }
        let used_vt = used.iter().filter(|&&u| u).count() as u64;
        Ok(Some(UvCheck {
            layout,
            counter,
            used_vt,
        }))
    }

    /// Refines the layout on `mesh` by `rule` to each level `1..=levels` (a
    /// [`halfedge::Refinement`] with UVs per level, under `opts`: holes, creases, options) and
    /// counts the distinct UV values its faces' corners use
    /// ([`halfedge::Refinement::write_uv_indices`]): the measured values of levels `1..`.
    fn measure(
        &self,
        mesh: &HalfEdgeMesh,
        rule: Rule,
        levels: u32,
        opts: &SubdivideOptions<'_>,
    ) -> Result<Vec<u64>, Failure> {
        let opts = opts.with_uvs(&self.layout);
        let mut measured = Vec::with_capacity(levels as usize);
        for level in 1..=levels {
            let r =
                halfedge::Refinement::new(mesh, rule, level, &opts).map_err(halfedge_failure)?;
            let mut corners = vec![0u32; r.n_corners(level)];
            r.write_uv_indices(&mut corners).map_err(halfedge_failure)?;
            let n = corners.iter().max().map_or(0, |&m| m as usize + 1);
            let mut used = vec![false; n];
            for &k in &corners {
                used[k as usize] = true;
            }
            measured.push(used.iter().filter(|&&u| u).count() as u64);
        }
        Ok(measured)
    }

    /// As [`UvCheck::measure`] on a raw face list: the distinct UV values the corners of
    /// each level `1..=levels` of [`sub::subdivide_polygons`] (with the layout) use.
    fn measure_polygons(
        &self,
        poly: &PolygonMesh,
        rule: Rule,
        levels: u32,
        opts: &SubdivideOptions<'_>,
        path: &MeshSource,
    ) -> Result<Vec<u64>, Failure> {
        let opts = opts.with_uvs(&self.layout);
        let mut measured = Vec::with_capacity(levels as usize);
        for level in 1..=levels {
            let out = sub::subdivide_polygons(poly, rule, level, &opts)
                .map_err(|e| located_failure(e, poly, path))?;
            let uvs = out
                .uvs()
                .ok_or_else(|| halfedge_failure(halfedge::Error::NoUvs))?;
            measured.push((uvs.coords().len() - uvs.unreferenced()) as u64);
        }
        Ok(measured)
    }

    /// Appends `("UV", predicted)` and `("UV", measured)` to every report, `measured` being
    /// the values of levels `1..` ([`UvCheck::measure`]).
    fn extend(&self, reports: &mut [sub::LevelReport], measured: &[u64]) -> Result<(), Failure> {
        for r in reports.iter_mut() {
            let m = match r.level {
                0 => self.used_vt,
                s => match measured.get(s as usize - 1) {
                    Some(&m) => m,
                    None => continue,
                },
            };
            let p = self
                .counter
                .values_at(u64::from(r.level))
                .map_err(scheme_failure)?;
            r.predicted.push(("UV".to_owned(), p));
            r.measured.push(("UV".to_owned(), BigInt::from(m)));
        }
        Ok(())
    }
}

/// The last level `verify` checks: `--levels`, or the highest level whose predicted face
/// count under `plan` from `x0` stays within `--max-faces` (at most 64).
pub(crate) fn verify_levels(args: &VerifyArgs, plan: &Plan, x0: &[BigInt]) -> Result<u32, Failure> {
    match &args.levels {
        Some(t) => real_levels(t),
        None => {
            let budget = Budget {
                max_faces: Some(BigInt::from(args.max_faces)),
                ..Budget::default()
            };
            let fit = schemes::fit(plan, x0, &budget)?;
            Ok(fit.highest_level(MAX_VERIFY_LEVELS).unwrap_or(0) as u32)
        }
    }
}

pub(crate) fn verify(args: VerifyArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let loaded = required_mesh(&args.mesh)?;
    let poly = &loaded.poly;
    refuse_degenerate_faces(poly, &args.mesh)?;
    let counts = halfedge::stats::face_list_counts(poly);
    let chosen = chosen_scheme(&args.scheme, &loaded, &counts, &args.mesh)?;
    let (scheme, rule) = (&chosen.scheme, chosen.rule);
    loaded.print_notes();
    // The rule's own scheme sizes the real subdivision of the whole mesh (a custom matrix may
    // be wrong); the scheme predicts what is written.
    let sizing = rule.scheme_for(&counts).map_err(scheme_failure)?;
    let x0 = sizing
        .initial_state(&counts)
        .map_err(|e| not_applicable(&args.mesh, e))?;
    let levels = verify_levels(&args, &Plan::single(sizing.clone()), &x0)?;
    let custom = args.scheme.scheme_file.is_some();
    let face_list = on_face_list(scheme, rule, &counts, custom);
    let need = if loaded.has_crease_rules(rule) && !face_list {
        halfedge::memory::predicted_peak_bytes_with_creases(rule, &counts, levels, None)
    } else {
        halfedge::memory::predicted_peak_bytes(&sizing, &counts, levels, None).map_err(Into::into)
    };
    let uv_check = UvCheck::new(&loaded, scheme, chosen.holes.as_ref())?;
    // The UV component refines the layout with the surface (a refinement with UVs per level,
    // the largest the last).
    let need = match &uv_check {
        Some(_) => need
            .and_then(|need| Ok(need + uv_bytes(poly, rule, levels, 8, chosen.holes.is_some())?)),
        None => need,
    };
    let need = need.map(|need| need + halfedge::memory::read_extra_bytes(poly));
    guard_memory(need, sizing.name(), levels, args.allow_large)?;
    let mut opts = SubdivideOptions::default().with_threads(args.threads);
    if let Some(holes) = &chosen.holes {
        opts = opts.with_holes(holes);
    }
    // The UV values measured at levels 1.., when there is a UV component.
    let mut uv_measured = None;
    let mut reports = if face_list {
        // The face-list subdividers place points linearly: no crease rules to follow.
        let reports = sub::verify_polygons(poly, scheme, levels, &opts)
            .map_err(|e| located_failure(e, poly, &args.mesh))?;
        if let Some(check) = &uv_check {
            // The face-list subdividers refine the layout linearly with the faces: the
            // values their written UVs use.
            uv_measured = Some(check.measure_polygons(poly, rule, levels, &opts, &args.mesh)?);
        }
        reports
    } else {
        let mesh = validate(poly, &args.mesh)?;
        let (sharpness, options) = loaded.crease_inputs(rule, &mesh, &args.mesh)?;
        let mut opts = opts.with_subdivision(options);
        if let Some(sharpness) = &sharpness {
            opts = opts.with_sharpness(sharpness);
        }
        let reports = sub::verify(&mesh, scheme, levels, &opts)
            .map_err(|e| located_failure(e, poly, &args.mesh))?;
        if let Some(check) = &uv_check {
            uv_measured = Some(check.measure(&mesh, rule, levels, &opts)?);
        }
        reports
    };
    if let (Some(check), Some(measured)) = (&uv_check, &uv_measured) {
        check.extend(&mut reports, measured)?;
    }
    write_reports(
        &reports,
        scheme.name(),
        &args.mesh,
        levels,
        args.format,
        out,
    )
}

/// Writes `verify`'s reports (text or JSON) and returns its exit code: 0 when every level
/// matches, [`Kind::Mismatch`] otherwise.
pub(crate) fn write_reports(
    reports: &[sub::LevelReport],
    name: &str,
    mesh: &MeshSource,
    levels: u32,
    format: ReportFormat,
    out: &mut impl Write,
) -> Result<u8, Failure> {
    let all_match = reports.iter().all(|r| r.is_match());
    let text = match format {
        ReportFormat::Json => {
            // Counts of a mesh in memory fit in u64; a larger one would be written as a string.
            let object = |pairs: &[(String, BigInt)]| -> Value {
                pairs
                    .iter()
                    .map(|(k, v)| {
                        let v = v.to_u64().map_or_else(|| v.to_string().into(), Value::from);
                        (k.clone(), v)
                    })
                    .collect::<serde_json::Map<_, _>>()
                    .into()
            };
            let rows: Vec<String> = reports
                .iter()
                .map(|r| {
                    json_text(&json!({
                        "level": r.level,
                        "match": r.is_match(),
                        "predicted": object(&r.predicted),
                        "measured": object(&r.measured),
                    }))
                })
                .collect();
            format!("[\n{}\n]", rows.join(",\n"))
        }
        ReportFormat::Text => {
            let mut t = format!(
                "{} on {} levels 0..={levels}\n",
                name,
                mesh.mesh.as_ref().map_or_else(
                    || mesh.base.clone().unwrap_or_default(),
                    |p| p.display().to_string()
                )
            );
            t.push_str("level  component  predicted  measured\n");
            for r in reports {
                for ((name, p), (_, m)) in r.predicted.iter().zip(&r.measured) {
                    let flag = if p == m { "" } else { "  MISMATCH" };
                    t.push_str(&format!(
                        "{:>5}  {name:>9}  {p:>9}  {m:>8}{flag}\n",
                        r.level
                    ));
                }
            }
            t.push_str(if all_match {
                "all counts match the prediction"
            } else {
                "MISMATCH: the prediction is wrong"
            });
            t
        }
    };
    writeln!(out, "{text}").map_err(write_failure)?;
    if all_match {
        Ok(0)
    } else {
        Err(Failure::new(
            Kind::Mismatch,
            anyhow::anyhow!("{}: real subdivision disagrees with the prediction", name),
        ))
    }
}

pub(crate) fn subdivide(args: SubdivideArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let levels = real_levels(&args.levels)?;
    // OBJ text in a file named for another mesh format would mislead whatever opens it.
    if let Some(path) = &args.output {
        if let Some(format) = halfedge::io::unwritten_mesh_format(path) {
            return Err(usage!(
                "-o {}: subdivide does not write {} files; it writes OBJ (name the output .obj, or anything that is not another mesh format's extension)",
                path.display(),
                format.to_ascii_uppercase()
            ));
        }
    }
    let start = Instant::now();
    // `loaded.tags()` (creases and corners; holes, left out of what is written) and
    // `loaded.options` (resolved boundary, crease method, triangle rule) are what the geometry
    // follows.
    let loaded = required_mesh(&args.mesh)?;
    let poly = &loaded.poly;
    refuse_degenerate_faces(poly, &args.mesh)?;
    let counts = halfedge::stats::face_list_counts(poly);
    let Chosen {
        scheme: chosen,
        rule,
        holes,
    } = chosen_scheme(&args.scheme, &loaded, &counts, &args.mesh)?;
    loaded.print_notes();
    let label = mesh_label(&args.mesh);
    let mut face_list = on_face_list(&chosen, rule, &counts, args.scheme.scheme_file.is_some());
    // The UV layout to refine: none with --no-uv; vt at only some corners is written
    // without UVs, saying why.
    let layout = if args.no_uv {
        None
    } else {
        if let Some(partial) = poly.partial_uvs() {
            eprintln!("note: {label}: {partial}: writing without UVs");
        }
        poly.uv_layout()
    };
    if layout.is_some()
        && face_list
        && matches!(rule, Rule::TriSplit(_))
        && halfedge::HalfEdgeMesh::try_from(poly).is_ok()
    {
        // The 1:N² splits (placed on the flat triangles either way) run on the half-edge
        // mesh when the face list is one; the -general schemes and non-manifold input keep
        // the raw face list, whose subdividers refine the UV layout linearly with it.
        face_list = false;
    }
    let refine_once = args.frames > 0 || args.precision == Precision::F32;
    if refine_once && (face_list || args.no_preallocate) {
        return Err(usage!(
            "--precision f32 and --frames refine a manifold mesh once: {}",
            if face_list {
                "this scheme runs on the raw face list (loop-general, catmull-clark-general, \
                 tri-split-N or a non-manifold mesh); use loop, catmull-clark or --precision f64"
            } else {
                "not with --no-preallocate"
            }
        ));
    }
    // The rule's own scheme sizes the output (a custom matrix may be wrong); one that does
    // not apply (a scheme file's `topology = "loop"` on quads) names the mesh, as `verify`.
    let scheme = rule.scheme_for(&counts).map_err(scheme_failure)?;
    scheme
        .initial_state(&counts)
        .map_err(|e| not_applicable(&args.mesh, e))?;
    // Manifold input, preallocated: the 4:1 family and Catmull-Clark write the last level
    // straight into a face list (half the peak memory of a half-edge last level).
    let last_faces = (!face_list && !args.no_preallocate)
        .then(|| sub::direct_face_degree(rule))
        .flatten();
    // With holes a manifold mesh's last level is written as a face list (the written faces
    // need not be a manifold), compacted in place.
    let holes_as_faces = holes.is_some() && !face_list && !refine_once;
    let need = if refine_once {
        let bytes = match args.precision {
            Precision::F32 => 4,
            Precision::F64 => 8,
        };
        halfedge::memory::predicted_refinement_peak_bytes(
            rule,
            &counts,
            levels,
            bytes,
            args.frames > 0,
            loaded.has_crease_rules(rule),
        )
        .and_then(|peak| match holes {
            Some(_) => halfedge::memory::refinement_hole_bytes(&scheme, &counts, levels, bytes)
                .map(|holes| peak + holes)
                .map_err(Into::into),
            None => Ok(peak),
        })
    } else {
        let levels_bytes = if loaded.has_crease_rules(rule) && !face_list {
            halfedge::memory::predicted_peak_bytes_with_creases(rule, &counts, levels, last_faces)
        } else {
            halfedge::memory::predicted_peak_bytes(&scheme, &counts, levels, last_faces)
                .map_err(Into::into)
        };
        // A last level built as a half-edge mesh is copied into the face list written.
        let levels_bytes = match last_faces {
            None if !face_list => levels_bytes.and_then(|bytes| {
                Ok(bytes + halfedge::memory::face_list_copy_bytes(&scheme, &counts, levels)?)
            }),
            _ => levels_bytes,
        };
        levels_bytes.and_then(|bytes| match holes {
            Some(_) => halfedge::memory::hole_filter_bytes(&scheme, &counts, levels, last_faces)
                .map(|filter| bytes + filter)
                .map_err(Into::into),
            None => Ok(bytes),
        })
    };
    // With UVs the face-varying channel adds its refinement and buffers (the one-shot path
    // refines them in f64); a rule without a face-varying rule writes without them.
    let need = match &layout {
        Some(_) => need.and_then(|need| {
            let scalar = match args.precision {
                Precision::F32 if refine_once => 4,
                _ => 8,
            };
            Ok(need + uv_bytes(poly, rule, levels, scalar, holes.is_some())?)
        }),
        None => need,
    };
    // The face list as read holds its file lines and UVs beyond what its counts predict.
    let need = need.map(|need| need + halfedge::memory::read_extra_bytes(poly));
    let predicted = guard_memory(need, scheme.name(), levels, args.allow_large)?;
    if let Some(path) = &args.output {
        halfedge::io::check_output(path).map_err(|e| Failure::new(Kind::Input, e))?;
    }
    let mesh = if face_list {
        None
    } else {
        Some(validate(poly, &args.mesh)?)
    };
    let load_s = start.elapsed().as_secs_f64();

    let final_faces = scheme
        .counts_at(&counts, u64::from(levels))
        .map_err(scheme_failure)?
        .faces
        .to_u64()
        .unwrap_or(u64::MAX);
    let bar = (final_faces >= 1_000_000).then(|| {
        let bar = indicatif::ProgressBar::new(u64::from(levels));
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{msg} [{bar:30}] level {pos}/{len} ({elapsed})",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar.set_message(format!("subdividing with {}", chosen.name()));
        bar
    });
    // The surface's levels move the bar; a face-varying channel reports its own after them.
    let clock = refined::SurfaceClock::new(levels);
    let progress = |done: &LevelDone| {
        if let (true, Some(bar)) = (clock.report(done), &bar) {
            bar.set_position(u64::from(done.level));
        }
    };
    // The file's creases and corners and the resolved options (the face-list subdividers
    // place points linearly and read neither).
    let (sharpness, mut options) = match &mesh {
        Some(mesh) => loaded.crease_inputs(rule, mesh, &args.mesh)?,
        None => (None, Default::default()),
    };
    if layout.is_some() {
        options =
            options.with_face_varying(uv_interpolation(&args, &loaded, rule, &label, face_list));
    }
    let mut opts = SubdivideOptions::default()
        .with_threads(args.threads)
        .with_preallocate(!args.no_preallocate)
        .with_progress(&progress)
        .with_subdivision(options);
    if let Some(sharpness) = &sharpness {
        opts = opts.with_sharpness(sharpness);
    }
    if let Some(holes) = &holes {
        opts = opts.with_holes(holes);
    }
    // Level 0 writes the file's UVs as read: the `vt` entries its written corners use, which
    // is what `table` counts at level 0 (the layout's values split a `vt` used at several
    // vertices).
    let as_read = match (&layout, poly.uvs()) {
        (Some(_), Some(uvs)) if levels == 0 => {
            Some(uvs.of_written_faces(poly.face_offsets(), |f| {
                holes.as_ref().map_or(true, |h| !h.contains(f as u32))
            }))
        }
        _ => None,
    };
    let t1 = Instant::now();
    let run = |opts: &SubdivideOptions<'_>| match &mesh {
        Some(mesh) if refine_once => refined::run(
            mesh,
            rule,
            levels,
            args.precision,
            args.frames,
            opts,
            &clock,
            as_read.as_ref(),
        )
        .map(Output::Refined),
        // With UVs the last level is a face list carrying them.
        Some(mesh) if opts.uvs.is_some() || last_faces.is_some() || holes_as_faces => {
            sub::subdivide_to_face_list(mesh, rule, levels, opts).map(Output::Faces)
        }
        Some(mesh) => sub::subdivide(mesh, rule, levels, opts).map(Output::Mesh),
        None => sub::subdivide_polygons(poly, rule, levels, opts).map(Output::Polygons),
    };
    let mut result = match &layout {
        Some(layout) => match run(&opts.with_uvs(layout)) {
            // Refused before anything is built: the rule has no face-varying rule.
            Err(e @ halfedge::Error::UvsNotSupported { .. }) => {
                eprintln!("note: {label}: {e}: writing without UVs");
                run(&opts)
            }
            result => result,
        },
        None => run(&opts),
    }
    .map_err(|e| located_failure(e, poly, &args.mesh))?;
    if let Some(as_read) = &as_read {
        let written = match &mut result {
            Output::Faces(level) => Some(&mut level.mesh),
            Output::Polygons(p) => Some(p),
            Output::Refined(_) | Output::Mesh(_) => None,
        };
        if let Some(m) = written.filter(|m| m.uvs().is_some()) {
            m.set_uvs(Some(as_read.clone())).map_err(|e| {
                halfedge_failure(halfedge::Error::UvLayoutMismatch {
                    reason: e.to_string(),
                })
            })?;
        }
    }
    let end = Instant::now();
    let subdivide_s = match &result {
        Output::Refined(r) => {
            // The UVs' topology is part of refine_topology; their evaluation is not.
            let uv_evaluation = r.uvs.map_or(Duration::ZERO, |u| u.2);
            (r.refine_topology + r.first_evaluation + uv_evaluation).as_secs_f64()
        }
        _ => (end - t1).as_secs_f64(),
    };
    // The UV values written and the time spent on them (the one-shot path refines them
    // after the surface's last level).
    let uvs = match &result {
        Output::Refined(r) => r
            .uvs
            .map(|(n, topology, evaluation)| (n, (topology + evaluation).as_secs_f64())),
        Output::Faces(level) => level
            .mesh
            .uvs()
            .map(|u| (u.coords().len(), clock.since_surface(t1, end).as_secs_f64())),
        // A level-0 copy keeps the file's UVs (the layout's values), as the other levels do.
        Output::Polygons(p) => p
            .uvs()
            .map(|u| (u.coords().len(), clock.since_surface(t1, end).as_secs_f64())),
        _ => None,
    };
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    drop(mesh);

    let t2 = Instant::now();
    if let Some(path) = &args.output {
        // UVs only when refined (a level-0 copy of the face list keeps the file's), normals
        // of the output with --normals.
        let options = ObjWriteOptions::default()
            .with_uvs(uvs.is_some())
            .with_normals(args.normals);
        match &result {
            Output::Mesh(m) => halfedge::io::write_obj_file_with(m, path, &options),
            Output::Polygons(p) => halfedge::io::write_polygon_obj_file_with(p, path, &options),
            Output::Faces(level) => {
                halfedge::io::write_polygon_obj_file_with(&level.mesh, path, &options)
            }
            Output::Refined(r) => r.write(path, &options),
        }
        .map_err(|e| Failure::new(Kind::Input, e))?;
    }
    let write_s = t2.elapsed().as_secs_f64();
    let (v, e, f) = match &result {
        Output::Mesh(m) => (m.n_vertices(), m.n_edges(), m.n_faces()),
        Output::Faces(level) => (level.mesh.n_vertices(), level.edges, level.mesh.n_faces()),
        Output::Refined(r) => (r.vef[0], r.vef[1], r.vef[2]),
        Output::Polygons(p) => {
            let c = halfedge::stats::face_list_counts(p);
            (c.vertices as usize, c.edges as usize, c.faces as usize)
        }
    };
    let uv = uvs.map_or_else(String::new, |(n, _)| format!(", UV = {n}"));
    let message = match &args.output {
        Some(path) => format!(
            "level {levels}: V = {v}, E = {e}, F = {f}{uv}; wrote {}",
            path.display()
        ),
        None => format!("level {levels}: V = {v}, E = {e}, F = {f}{uv} (no -o: nothing written)"),
    };
    // With `-o -` the mesh is standard output: the summary goes to stderr.
    if args.output.as_deref() == Some(std::path::Path::new("-")) {
        eprintln!("{}", message.replace("wrote -", "wrote standard output"));
    } else {
        writeln!(out, "{message}").map_err(write_failure)?;
    }
    if args.timings {
        let peak = halfedge::memory::peak_resident_bytes()
            .map_or_else(|| "null".to_string(), |b| b.to_string());
        let frames = match &result {
            Output::Refined(r) if args.frames > 0 => format!(
                ", \"refine_topology_s\": {:.6}, \"evaluate_s\": {:.6}",
                r.refine_topology.as_secs_f64(),
                r.evaluate_median.unwrap_or_default().as_secs_f64()
            ),
            _ => String::new(),
        };
        let uv_s = uvs.map_or_else(String::new, |(_, s)| format!(", \"uv_s\": {s:.6}"));
        eprintln!(
            "timings: {{\"load_s\": {load_s:.6}, \"subdivide_s\": {subdivide_s:.6}, \"write_s\": {write_s:.6}, \"peak_bytes\": {peak}, \"predicted_peak_bytes\": {predicted}{frames}{uv_s}}}"
        );
    }
    Ok(0)
}

/// The face-varying interpolation of a run with UVs: `--uv-interpolation` over the file's
/// `facevaryinginterpolateboundary` tag over `corners-plus1` ([`resolve_options`] resolved
/// the tag; [`LoadedMesh::crease_inputs`] hands it on under Loop and Catmull-Clark). One
/// note when the flag overrides the tag with another value, one when the rule has no such
/// mode (the other rules refine UVs linearly, or not at all).
///
/// [`resolve_options`]: crate::model::resolve_options
fn uv_interpolation(
    args: &SubdivideArgs,
    loaded: &LoadedMesh,
    rule: Rule,
    label: &str,
    face_list: bool,
) -> FaceVaryingInterpolation {
    let resolved = loaded.options.face_varying;
    let Some(flag) = args.uv_interpolation else {
        return resolved;
    };
    if let Some(tag) = loaded.tags().options.face_varying.filter(|&t| t != flag) {
        eprintln!(
            "note: {label}: --uv-interpolation {flag} overrides the tag facevaryinginterpolateboundary {} ({tag})",
            tag.tag_value()
        );
    }
    if !matches!(rule, Rule::Loop | Rule::CatmullClark) {
        eprintln!(
            "note: {label}: --uv-interpolation is a mode of loop and catmull-clark, not applied by {rule}"
        );
    } else if face_list {
        eprintln!(
            "note: {label}: --uv-interpolation is not applied on the raw face list, which refines UVs linearly"
        );
    }
    flag
}

enum Output {
    /// The whole last level as a half-edge mesh.
    Mesh(HalfEdgeMesh),
    /// The last level written straight into a face list.
    Faces(sub::FaceListLevel),
    /// The face-list subdividers' result (non-manifold input).
    Polygons(PolygonMesh),
    /// Refined once, evaluated into buffers (`--precision f32`, `--frames`).
    Refined(crate::refined::Refined),
}
