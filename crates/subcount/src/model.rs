//! What a command counts, from the flags: a [`Counter`] over a recurrence (from `--matrix`)
//! or a scheme plan (from `--scheme`, `--scheme-file`), and its initial state (from `--init`,
//! `--counts`, `--mesh` or `--base`). The mesh is read once per command ([`Input`]).
//!
//! Every command reads its mesh through [`load_mesh`], the one place where the file's
//! OpenSubdiv tags meet the flags: [`resolve_options`] gives the subdivision options (a flag
//! wins over the tag, the tag over the default), and [`LoadedMesh::holes`] the faces that are
//! holes (the file's hole tags, and under `--boundary none` the faces at the boundary): every
//! command counts what is written, the statistics of the faces that are not holes, and
//! refuses holes under a scheme whose faces do not nest.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Owner of the subdivision options of a run (flag over tag over default), the notes about ignored
//! and overridden tags, the holes of a run (hole tags, boundary `none` for Loop and Catmull-Clark;
//! refused under schemes whose faces do not nest) and `--triangle-rule` with triangle schemes, the
//! tags' sharpness on the mesh subdivided: `crates/subcount/src/model.rs` (`load_mesh`,
//! `resolve_options`, `LoadedMesh::holes`, `refuse_triangle_rule`, `LoadedMesh::sharpness`): every
//! command reads its mesh through `load_mesh` and counts what is written.
//!
//! Owner of the UV layout a command counts (written faces with holes), the `UV` column of `table`,
//! `at`, `plot`, `fit`, the note when a scheme does not count UVs: `crates/subcount/src/model.rs`
//! (`Input::uv_counts`, `Input::uv_counter`); `stats`' layout line and `"uv"` object: `mesh.rs`
//! (`uv_layout_text`); `formula`'s `UV(s)`: `commands.rs` (`uv_formula`).

use std::cell::OnceCell;

use halfedge::holes::HoleSet;
use halfedge::io::ReadOptions;
use halfedge::subdivide::Sharpness;
use halfedge::tags::{BoundaryInterpolation, SubdivisionOptions, TagOptions, Tags};
use halfedge::{PolygonMesh, Rule};
use num_bigint::BigInt;
use recurrence::{IntMatrix, Recurrence};
use schemes::uv::{UvCounter, UvCounts};
use schemes::{Counter, CountsInput, MeshCounts, Plan, Scheme};

use crate::args::{MeshSource, Source};
use crate::failure::{input, scheme_failure, usage, Failure, Kind};

/// The default scheme and counts: the icosahedron under 4:1 (Loop) subdivision.
pub(crate) const DEFAULT_SCHEME: &str = "loop";
/// The icosahedron's counts.
pub(crate) const DEFAULT_COUNTS: &str = "V=12,E=30,F=20";

/// The flags that name what to count, with the statistics of their mesh read at most once.
pub(crate) struct Input<'a> {
    source: &'a Source,
    /// The mesh and the statistics of all its faces.
    loaded: OnceCell<Option<(LoadedMesh, MeshCounts)>>,
    /// What is counted: the statistics of the written faces.
    counts: OnceCell<Option<MeshCounts>>,
    /// The holes of the mesh under the plan counted (set with `counts`).
    holes: OnceCell<Option<HoleSet>>,
}

impl<'a> Input<'a> {
    pub(crate) fn new(source: &'a Source) -> Input<'a> {
        Input {
            source,
            loaded: OnceCell::new(),
            counts: OnceCell::new(),
            holes: OnceCell::new(),
        }
    }

    /// The mesh named by `--mesh` or `--base`, if any, with the statistics of all its faces.
    fn loaded(&self) -> Result<Option<&(LoadedMesh, MeshCounts)>, Failure> {
        if let Some(loaded) = self.loaded.get() {
            return Ok(loaded.as_ref());
        }
        let loaded = match load_mesh(&self.source.mesh)? {
            Some(loaded) => {
                refuse_degenerate_faces(&loaded.poly, &self.source.mesh)?;
                let counts = halfedge::stats::face_list_counts(&loaded.poly);
                Some((loaded, counts))
            }
            None => None,
        };
        Ok(self.loaded.get_or_init(|| loaded).as_ref())
    }

    /// The statistics `plan` counts on the mesh named by `--mesh` or `--base`, if any: those
    /// of its written faces when it has holes ([`LoadedMesh::holes`]; refused, exit 2, under
    /// a stage whose faces do not nest), of all its faces otherwise. The plan is the same
    /// for every call of a command (its boundary variant has the same rules).
    fn mesh_counts(&self, plan: &Plan) -> Result<Option<&MeshCounts>, Failure> {
        if let Some(counts) = self.counts.get() {
            return Ok(counts.as_ref());
        }
        let counts = match self.loaded()? {
            Some((loaded, counts)) => {
                let stages: Vec<(&str, Option<Rule>)> = plan
                    .stages()
                    .iter()
                    .map(|s| (s.scheme().name(), s.scheme().subdivision_rule()))
                    .collect();
                let holes = loaded.holes(counts, &self.source.mesh, &plan.name(), &stages)?;
                loaded.print_notes();
                let written = match &holes {
                    Some(holes) => holes.written_counts(&loaded.poly),
                    None => counts.clone(),
                };
                let _ = self.holes.set(holes);
                Some(written)
            }
            None => None,
        };
        Ok(self.counts.get_or_init(|| counts).as_ref())
    }

    /// The statistics of the UV layout `plan` counts UV values from
    /// ([`halfedge::stats::uv_counts`]; with holes, of the written faces:
    /// [`HoleSet::written_uv_counts`]): `None` without `--mesh`/`--base` or when the mesh
    /// has no UV layout (no `vt`, or `vt` at only some corners).
    pub(crate) fn uv_counts(&self, plan: &Plan) -> Result<Option<UvCounts>, Failure> {
        if self.mesh_counts(plan)?.is_none() {
            return Ok(None);
        }
        let Some((loaded, _)) = self.loaded()? else {
            return Ok(None);
        };
        Ok(match self.holes.get() {
            Some(Some(holes)) => holes.written_uv_counts(&loaded.poly),
            _ => halfedge::stats::uv_counts(&loaded.poly),
        })
    }

    /// The UV values under `counter` of the mesh's layout ([`Input::uv_counts`]), for the
    /// `UV` column of `table`, `at` and `plot`: `Ok(None)` without a mesh, on a mesh without
    /// a UV layout, and when the counter does not count UV values
    /// ([`schemes::uv::NotCounted`]: a scheme without a rule, a composition of a dual
    /// rule with a rule of the other kind). The
    /// last, and a mesh with `vt` at only some corners, say so in one note on stderr
    /// (`note: a scheme without a subdivision rule does not count UV values: no UV column`, `note: FILE: 4
    /// of 24 face corners have texture coordinates: no UV layout: no UV column`), so that a
    /// missing column is explained; stdout is what it is without UVs.
    pub(crate) fn uv_counter(&self, counter: &Counter) -> Result<Option<UvCounter>, Failure> {
        if !self.has_mesh() {
            return Ok(None);
        }
        let Some(plan) = counter.plan() else {
            return Ok(None);
        };
        let Some(uv) = self.uv_counts(plan)? else {
            if let Some((loaded, _)) = self.loaded()? {
                if let Some(partial) = loaded.poly.partial_uvs() {
                    let label = mesh_label(&self.source.mesh);
                    eprintln!("note: {label}: {partial}: no UV column");
                }
            }
            return Ok(None);
        };
        match counter.uv_counter(&uv) {
            Ok(uv) => Ok(Some(uv)),
            Err(not) => {
                eprintln!("note: {not}: no UV column");
                Ok(None)
            }
        }
    }

    /// Whether a mesh is given (`--mesh`, `--base`).
    pub(crate) fn has_mesh(&self) -> bool {
        self.source.mesh.mesh.is_some() || self.source.mesh.base.is_some()
    }

    /// Whether an initial state is given (`--init`, `--counts`, `--mesh`, `--base`).
    pub(crate) fn has_state(&self) -> bool {
        let s = self.source;
        s.init.is_some() || s.counts.is_some() || s.mesh.mesh.is_some() || s.mesh.base.is_some()
    }

    /// Builds the counter named by the flags, or the default (`loop`), counted for the
    /// initial state the flags name (a 4:1 alias on a mesh with boundary counts as
    /// `loop-boundary`).
    pub(crate) fn counter(&self) -> Result<Counter, Failure> {
        let source = self.source;
        refuse_options_without_mesh(&source.mesh)?;
        if let Some(text) = source.matrix.as_deref() {
            if source.scheme.is_some() || source.scheme_file.is_some() {
                return Err(usage!(
                    "--matrix cannot be combined with --scheme or --scheme-file"
                ));
            }
            let matrix: IntMatrix = text.parse().map_err(|e| usage!("invalid --matrix: {e}"))?;
            let recurrence = match &source.names {
                Some(names) => Recurrence::with_names(matrix, names.iter().map(|n| n.trim()))
                    .map_err(|e| usage!("invalid --names: {e}"))?,
                None => Recurrence::new(matrix),
            };
            return Ok(Counter::Matrix(recurrence));
        }
        if source.names.is_some() {
            return Err(usage!(
                "--names needs --matrix (a scheme names its own state)"
            ));
        }
        let custom = match &source.scheme_file {
            Some(path) => Some(load_scheme_file(path)?),
            None => None,
        };
        let plan = match (&source.scheme, custom) {
            (Some(text), custom) => Plan::parse_with(text, |name| match &custom {
                Some(c) if c.name() == name => Ok(c.clone()),
                _ => schemes::builtin(name),
            })?,
            (None, Some(custom)) => Plan::single(custom),
            (None, None) => Plan::parse(DEFAULT_SCHEME)?,
        };
        let stages = plan
            .stages()
            .iter()
            .map(|stage| (stage.scheme().name(), stage.scheme().subdivision_rule()));
        refuse_triangle_rule(&source.mesh, &plan.name(), stages)?;
        Ok(Counter::Plan(self.for_initial_state(plan)?))
    }

    /// The plan that counts `plan` on the initial state the flags name: the 4:1 aliases
    /// (`midpoint`, `butterfly`, `icosphere`) count as `loop-boundary` on a mesh with
    /// boundary, `doo-sabin` and `mid-edge` as `doo-sabin-boundary` and `mid-edge-boundary`,
    /// exactly as `subdivide` and `verify` count them ([`Plan::for_mesh`],
    /// [`Plan::for_counts`]). `loop` itself is unchanged (it refuses a boundary). With no
    /// mesh or counts, or with more than one initial state (a usage error
    /// [`initial_state`](Self::initial_state) reports), or counts that do not parse
    /// (reported there too), the plan is unchanged.
    fn for_initial_state(&self, plan: Plan) -> Result<Plan, Failure> {
        if !plan.has_boundary_variant() {
            return Ok(plan);
        }
        let source = self.source;
        let mesh_given = source.mesh.mesh.is_some() || source.mesh.base.is_some();
        match (&source.init, &source.counts, mesh_given) {
            (None, Some(text), false) => Ok(match CountsInput::parse(text) {
                Ok(input) => plan.for_counts(&input),
                Err(_) => plan,
            }),
            (None, None, true) => Ok(match self.mesh_counts(&plan)? {
                Some(counts) => plan.for_mesh(counts),
                None => plan,
            }),
            _ => Ok(plan),
        }
    }

    /// Whether neither a matrix nor a scheme was named (the built-in default).
    fn is_default(&self) -> bool {
        let s = self.source;
        s.matrix.is_none() && s.scheme.is_none() && s.scheme_file.is_none()
    }

    /// The initial state named by the flags (for the default, the icosahedron).
    pub(crate) fn initial_state(&self, counter: &Counter) -> Result<Vec<BigInt>, Failure> {
        let source = self.source;
        let given = [
            source.init.is_some(),
            source.counts.is_some(),
            source.mesh.mesh.is_some() || source.mesh.base.is_some(),
        ]
        .iter()
        .filter(|&&b| b)
        .count();
        if given > 1 {
            return Err(usage!(
                "give the initial state once: --init, --counts, or --mesh/--base"
            ));
        }
        if let Some(text) = &source.init {
            let values = schemes::parse_init(text).map_err(|e| match e {
                schemes::Error::InitSyntax { item, .. } => {
                    usage!("invalid --init: `{item}` is not an integer")
                }
                e => scheme_failure(e),
            })?;
            if values.len() != counter.dim() {
                return Err(usage!(
                    "--init has {} values but the state has {} components ({})",
                    values.len(),
                    counter.dim(),
                    counter.state_names().join(", ")
                ));
            }
            if let Some(plan) = counter.plan() {
                plan.first().check_state(&values)?;
            }
            return Ok(values);
        }
        let Some(plan) = counter.plan() else {
            return Err(usage!("--matrix needs --init with one value per component"));
        };
        if let Some(counts) = self.mesh_counts(plan)? {
            return plan
                .initial_state(counts)
                .map_err(|e| not_applicable(&source.mesh, e));
        }
        let text = match (&source.counts, self.is_default()) {
            (Some(text), _) => text.as_str(),
            (None, true) => DEFAULT_COUNTS,
            (None, false) => {
                return Err(usage!(
                    "{} needs an initial state: --counts (e.g. {DEFAULT_COUNTS}), --init, --mesh or --base",
                    plan.name()
                ))
            }
        };
        Ok(plan.state_from_input(&CountsInput::parse(text)?)?)
    }
}

/// A mesh as the commands use it: its face list, with the file's tags
/// ([`PolygonMesh::tags`]; none with `--ignore-tags`, for OFF files and base meshes), and
/// the subdivision options resolved from the flags, the tags and the defaults
/// ([`resolve_options`]). `subdivide` and `verify` hand both to the geometry
/// ([`LoadedMesh::sharpness`], [`LoadedMesh::options`]).
pub(crate) struct LoadedMesh {
    /// The face list and its tags.
    pub(crate) poly: PolygonMesh,
    /// The resolved options.
    pub(crate) options: SubdivisionOptions,
    /// At most two lines for stderr: the tags of the file not read, the flags that override
    /// the file's tags ([`LoadedMesh::print_notes`]).
    notes: Vec<String>,
}

impl LoadedMesh {
    /// The creases, corners, holes and options of the file (empty with `--ignore-tags`).
    pub(crate) fn tags(&self) -> &Tags {
        self.poly.tags()
    }

    /// Whether the subdivision may follow crease rules: the file's tags make an edge or a
    /// vertex sharp, or the resolved options are not the defaults (the library decides whether
    /// they change anything on the mesh; the memory guard counts their tables when they may).
    pub(crate) fn has_crease_rules(&self, rule: Rule) -> bool {
        follows_creases(rule) && self.has_crease_input()
    }

    /// Whether the file's tags make an edge or a vertex sharp, or the resolved boundary, crease
    /// method or triangle rule are not the defaults.
    fn has_crease_input(&self) -> bool {
        // The face-varying mode is read by no vertex rule.
        let (o, d) = (&self.options, SubdivisionOptions::default());
        let tags = self.tags();
        !tags.sharp_edges().is_empty()
            || !tags.sharp_vertices().is_empty()
            || o.boundary != d.boundary
            || o.crease_method != d.crease_method
            || o.triangle_rule != d.triangle_rule
    }

    /// The sharpness ([`LoadedMesh::sharpness`]) and options a subdivision by `rule` of
    /// `mesh` follows. Only Loop and Catmull-Clark have crease rules (OpenSubdiv's): under any
    /// other rule both are left out, with one line on stderr when the file or the flags gave
    /// some, so a tagged file still subdivides by every scheme.
    pub(crate) fn crease_inputs(
        &self,
        rule: Rule,
        mesh: &halfedge::HalfEdgeMesh,
        source: &MeshSource,
    ) -> Result<(Option<Sharpness>, SubdivisionOptions), Failure> {
        if follows_creases(rule) {
            return Ok((self.sharpness(mesh, source)?, self.options));
        }
        if self.has_crease_input() {
            eprintln!(
                "note: {}: creases, corners and the --boundary/--crease-method/--triangle-rule options are not applied by {rule}: only loop and catmull-clark have crease rules (OpenSubdiv's)",
                mesh_label(source)
            );
        }
        Ok((None, SubdivisionOptions::default()))
    }

    /// The creases and corners of the file's tags on `mesh`, the half-edge mesh built from
    /// [`LoadedMesh::poly`] ([`Sharpness::from_tags_of`]: its vertices renumbered when some
    /// vertex of the file is in no face); `None` when no edge or vertex is sharp (and with
    /// `--ignore-tags`, whose tags are empty). A crease the half-edge mesh cannot resolve is
    /// exit 3, naming the file.
    pub(crate) fn sharpness(
        &self,
        mesh: &halfedge::HalfEdgeMesh,
        source: &MeshSource,
    ) -> Result<Option<Sharpness>, Failure> {
        let tags = self.tags();
        if tags.creases().is_empty() && tags.corners().is_empty() {
            return Ok(None);
        }
        let sharpness = Sharpness::from_tags_of(&self.poly, mesh, tags)
            .map_err(|e| input!("{}: {e}", mesh_label(source)))?;
        Ok((!sharpness.is_smooth()).then_some(sharpness))
    }

    /// The faces that are holes when `stages` (each stage's name and rule; `scheme` names
    /// them all) run on this mesh, whose faces have the statistics `counts`: the file's hole
    /// tags, and the faces at the boundary under boundary interpolation `none` (OpenSubdiv's
    /// `VTX_BOUNDARY_NONE`, Loop and Catmull-Clark: [`halfedge::holes::boundary_faces_with`],
    /// which keeps the faces at vertices whose boundary edges the file makes infinitely
    /// sharp). `None` when there are none.
    ///
    /// # Errors
    ///
    /// Usage errors (exit 2): boundary `none` on a mesh with boundary under a stage other
    /// than Loop or Catmull-Clark (which have no such mode); holes under a stage whose faces
    /// do not nest (√3, Doo-Sabin, mid-edge: a hole has no descendants) or that names no
    /// rule.
    pub(crate) fn holes(
        &self,
        counts: &MeshCounts,
        mesh: &MeshSource,
        scheme: &str,
        stages: &[(&str, Option<Rule>)],
    ) -> Result<Option<HoleSet>, Failure> {
        let label = mesh_label(mesh);
        let which = |name: &str| {
            if name == scheme {
                name.to_owned()
            } else {
                format!("{scheme} (its stage {name})")
            }
        };
        let mut faces = self.tags().hole_faces();
        let tagged = faces.len();
        if self.options.boundary == BoundaryInterpolation::None && counts.boundary_edges > 0 {
            let (source, fix) = if mesh.boundary.is_some() {
                (
                    "--boundary none".to_string(),
                    "use --boundary edge or edge-and-corner",
                )
            } else {
                (
                    "the file's tag interpolateboundary 0 (none)".to_string(),
                    "use --boundary edge or edge-and-corner, or --ignore-tags",
                )
            };
            let other = stages
                .iter()
                .find(|(_, r)| !matches!(r, Some(Rule::Loop | Rule::CatmullClark)));
            if let Some((name, _)) = other {
                return Err(usage!(
                    "{label}: {source} is OpenSubdiv's VTX_BOUNDARY_NONE (the faces at the boundary become holes), a mode of loop and catmull-clark; {} has no such mode on a mesh with boundary ({} boundary edges): {fix}",
                    which(name),
                    counts.boundary_edges
                ));
            }
            faces.extend(halfedge::holes::boundary_faces_with(
                &self.poly,
                self.tags(),
            ));
        }
        if faces.is_empty() {
            return Ok(None);
        }
        let nests = |r: &Option<Rule>| r.is_some_and(schemes::holes::nests_faces);
        if let Some((name, rule)) = stages.iter().find(|(_, r)| !nests(r)) {
            let why = match rule {
                Some(_) => "its faces do not nest, so a hole has no descendants",
                None => {
                    "it names no subdivision rule (`topology`), so a hole's descendants are unknown"
                }
            };
            return Err(usage!(
                "{label}: the file's hole tags make {tagged} face{} holes, but {}: {why}; holes are counted and written by the 4:1 family (loop, midpoint, butterfly, icosphere), tri-split-N and catmull-clark: use one of them, or --ignore-tags to count the mesh without its tags",
                if tagged == 1 { "" } else { "s" },
                which(name)
            ));
        }
        HoleSet::new(self.poly.n_faces(), faces)
            .map(Some)
            .map_err(|e| input!("{label}: {e}"))
    }

    /// Prints the notes on stderr. Commands call it once the mesh passed their checks, so
    /// that a refusal stays one line on stderr.
    pub(crate) fn print_notes(&self) {
        for note in &self.notes {
            eprintln!("{note}");
        }
    }
}

/// Whether `rule` has crease rules (Loop and Catmull-Clark, as in OpenSubdiv).
fn follows_creases(rule: Rule) -> bool {
    matches!(rule, Rule::Loop | Rule::CatmullClark)
}

/// Reads the mesh named by `--mesh` or `--base`, if any, with its tags (unless
/// `--ignore-tags`), and resolves the subdivision options. Its notes
/// ([`LoadedMesh::print_notes`]) are the tags the file has that are not read (each name with
/// its count), and the flags that override the file's tags (naming both values).
pub(crate) fn load_mesh(mesh: &MeshSource) -> Result<Option<LoadedMesh>, Failure> {
    let poly = match (&mesh.mesh, &mesh.base) {
        (Some(_), Some(_)) => return Err(usage!("--mesh and --base cannot be used together")),
        (Some(path), None) => {
            let options = if mesh.ignore_tags {
                ReadOptions::without_tags()
            } else {
                ReadOptions::default()
            };
            halfedge::io::read_mesh_with(path, &options)
                .map_err(|e| mesh_failure(e, Kind::Input))?
        }
        (None, Some(name)) => {
            halfedge::shapes::from_name(name).map_err(|e| mesh_failure(e, Kind::Usage))?
        }
        (None, None) => {
            refuse_options_without_mesh(mesh)?;
            return Ok(None);
        }
    };
    let label = mesh_label(mesh);
    // Every command analyses the face list it read (counts, problems, a half-edge mesh):
    // refused here, before that analysis allocates, when it would not fit.
    let need = poly.heap_bytes() as u128 + halfedge::memory::face_list_analysis_bytes(&poly);
    let limit = halfedge::memory::peak_limit();
    if need > limit {
        return Err(Failure::new(
            Kind::Guard,
            anyhow::anyhow!(
                "{label}: analysing the mesh ({} faces, {} corners) needs about {}, more than half of the memory available to this process ({} is half)",
                poly.n_faces(),
                poly.n_corners(),
                halfedge::memory::human_bytes(need as f64),
                halfedge::memory::human_bytes(limit as f64)
            ),
        ));
    }
    let mut notes = Vec::new();
    if !poly.ignored_tags().is_empty() {
        let total: u64 = poly.ignored_tags().iter().map(|t| t.count).sum();
        let names: Vec<String> = poly
            .ignored_tags()
            .iter()
            .map(|t| format!("{} ({})", t.name, t.count))
            .collect();
        notes.push(format!(
            "warning: {label}: ignored {total} tag line{} this program does not read: {}",
            if total == 1 { "" } else { "s" },
            names.join(", ")
        ));
    }
    let (options, overrides) = resolve_options(mesh, &poly.tags().options);
    if !overrides.is_empty() {
        notes.push(format!("note: {label}: {}", overrides.join("; ")));
    }
    Ok(Some(LoadedMesh {
        poly,
        options,
        notes,
    }))
}

/// The one resolution of the subdivision options: a flag given on the command line wins over
/// the file's tag, the tag wins over the default (edge, uniform, catmark; face-varying
/// corners-plus1). Also returns, for each flag that overrides a tag with another value, a
/// note naming both (`--boundary edge overrides the tag interpolateboundary 1
/// (edge-and-corner)`).
pub(crate) fn resolve_options(
    flags: &MeshSource,
    tags: &TagOptions,
) -> (SubdivisionOptions, Vec<String>) {
    let mut overrides = Vec::new();
    let mut from_flags = TagOptions::default();
    from_flags.boundary = flags.boundary;
    from_flags.crease_method = flags.crease_method;
    from_flags.triangle_rule = flags.triangle_rule;
    if let (Some(flag), Some(tag)) = (flags.boundary, tags.boundary) {
        if flag != tag {
            overrides.push(format!(
                "--boundary {flag} overrides the tag interpolateboundary {} ({tag})",
                tag.tag_value()
            ));
        }
    }
    if let (Some(flag), Some(tag)) = (flags.crease_method, tags.crease_method) {
        if flag != tag {
            overrides.push(format!(
                "--crease-method {flag} overrides the tag creasemethod {} ({tag})",
                tag.tag_name()
            ));
        }
    }
    if let (Some(flag), Some(tag)) = (flags.triangle_rule, tags.triangle_rule) {
        if flag != tag {
            overrides.push(format!(
                "--triangle-rule {flag} overrides the tag smoothtriangles {}",
                tag.tag_name()
            ));
        }
    }
    let options = from_flags.over(tags.over(SubdivisionOptions::default()));
    (options, overrides)
}

/// The subdivision option flags describe how a mesh is subdivided: without `--mesh` or
/// `--base` they are a usage error (exit 2), not silently ignored.
pub(crate) fn refuse_options_without_mesh(mesh: &MeshSource) -> Result<(), Failure> {
    match mesh.option_flag() {
        Some(flag) if mesh.mesh.is_none() && mesh.base.is_none() => Err(usage!(
            "{flag} describes how a mesh is subdivided: give --mesh FILE or --base NAME"
        )),
        _ => Ok(()),
    }
}

/// `--triangle-rule` is Catmull-Clark's rule for triangles (OpenSubdiv's
/// `TriangleSubdivision`): refused (exit 2) for a scheme, or a composition without a
/// Catmull-Clark stage, whose rule works on triangles (the Loop family, 1:N², √3), which has
/// no such choice. `stages` are each stage's name and rule.
pub(crate) fn refuse_triangle_rule<'a>(
    mesh: &MeshSource,
    scheme: &str,
    stages: impl IntoIterator<Item = (&'a str, Option<Rule>)>,
) -> Result<(), Failure> {
    let Some(rule) = mesh.triangle_rule else {
        return Ok(());
    };
    let stages: Vec<(&str, Option<Rule>)> = stages.into_iter().collect();
    if stages.iter().any(|(_, r)| *r == Some(Rule::CatmullClark)) {
        return Ok(());
    }
    if let Some((name, _)) = stages
        .iter()
        .find(|(_, r)| r.is_some_and(Rule::needs_triangles))
    {
        let which = if *name == scheme {
            format!("{name} is a triangle scheme")
        } else {
            format!("{scheme} has the triangle scheme {name} and no catmull-clark stage")
        };
        return Err(usage!(
            "--triangle-rule {rule} is Catmull-Clark's rule for triangles (OpenSubdiv's TriangleSubdivision), but {which}: triangle schemes (the Loop family, tri-split-N, sqrt3) have no such choice; drop the flag or use --scheme catmull-clark"
        ));
    }
    Ok(())
}

/// A mesh that could not be loaded: a resource limit is exit 4, anything else `otherwise`.
fn mesh_failure(e: halfedge::Error, otherwise: Kind) -> Failure {
    let kind = if e.is_resource_limit() {
        Kind::Guard
    } else {
        otherwise
    };
    Failure::new(kind, e)
}

/// How errors name the mesh: its path, or `base mesh NAME`.
pub(crate) fn mesh_label(mesh: &MeshSource) -> String {
    match (&mesh.mesh, &mesh.base) {
        (Some(path), _) => halfedge::io::escape_controls(&path.display().to_string()).into_owned(),
        (None, Some(name)) => format!("base mesh {name}"),
        (None, None) => "the mesh".to_string(),
    }
}

/// The place of face `f` in an error: `line 12: `, or nothing when the mesh has no lines.
pub(crate) fn face_place(poly: &halfedge::PolygonMesh, f: usize) -> String {
    poly.face_line(f)
        .map(|l| format!("line {l}: "))
        .unwrap_or_default()
}

/// Builds the validated half-edge mesh, naming the file and the line of the offending face.
pub(crate) fn validate(
    poly: &halfedge::PolygonMesh,
    mesh: &MeshSource,
) -> Result<halfedge::HalfEdgeMesh, Failure> {
    halfedge::HalfEdgeMesh::try_from(poly).map_err(|e| {
        let place = e
            .face()
            .map_or_else(String::new, |f| face_place(poly, f as usize));
        input!("{}: {place}{e}", mesh_label(mesh))
    })
}

/// Refuses a face that uses a vertex twice (on every path, before any counting: such a face
/// makes the counts meaningless), naming the file, the line and the face.
pub(crate) fn refuse_degenerate_faces(
    poly: &halfedge::PolygonMesh,
    mesh: &MeshSource,
) -> Result<(), Failure> {
    if let Some((f, v)) = schemes::first_repeated_vertex(poly.faces()) {
        let vertices: Vec<String> = poly.face(f).iter().map(ToString::to_string).collect();
        return Err(input!(
            "{}: {}face {f} (vertices {}) repeats vertex {v}",
            mesh_label(mesh),
            face_place(poly, f),
            vertices.join(", ")
        ));
    }
    Ok(())
}

/// A scheme that does not apply to the mesh: exit 3, naming the mesh.
pub(crate) fn not_applicable(mesh: &MeshSource, e: schemes::Error) -> Failure {
    input!("{}: {e}", mesh_label(mesh))
}

/// The largest scheme file read, in bytes (a 32-component matrix of 20-digit entries is
/// about 25 KB).
pub(crate) const SCHEME_FILE_MAX_BYTES: u64 = 1 << 20;

/// Reads and validates a custom scheme file.
pub(crate) fn load_scheme_file(path: &std::path::Path) -> Result<Scheme, Failure> {
    let text = halfedge::io::read_text_capped(path, SCHEME_FILE_MAX_BYTES)
        .map_err(|e| input!("cannot read {}: {e}", path.display()))?;
    Scheme::from_toml(&text).map_err(|e| input!("{}: {e}", path.display()))
}
