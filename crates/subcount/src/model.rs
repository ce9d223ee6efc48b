//! What a command counts, from the flags: a [`Counter`] over a recurrence (from `--matrix`)
//! or a scheme plan (from `--scheme`, `--scheme-file`), and its initial state (from `--init`,
//! `--counts`, `--mesh` or `--base`). The mesh is read once per command ([`Input`]).
//!
//! Every command reads its mesh through [`load_mesh`] ([`driver::load`], the one place where
//! the file's OpenSubdiv tags meet the flags: [`driver::resolve_options`]), and
//! [`LoadedMesh::holes`] gives the faces that are holes: every command counts what is
//! written, the statistics of the faces that are not holes.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Owner of the UV layout a command counts (written faces with holes), the `UV` column of `table`,
//! `at`, `plot`, `fit`, the note when a scheme does not count UVs: `crates/subcount/src/model.rs`
//! (`Input::uv_counts`, `Input::uv_counter`); `stats`' layout line and `"uv"` object: `mesh.rs`
//! (`uv_layout_text`); `formula`'s `UV(s)`: `commands.rs` (`uv_formula`).

use std::cell::OnceCell;

pub(crate) use driver::LoadedMesh;
use halfedge::holes::HoleSet;
use num_bigint::BigInt;
use recurrence::{IntMatrix, Recurrence};
use schemes::uv::{UvCounter, UvCounts};
use schemes::{Counter, CountsInput, MeshCounts, Plan};

use crate::args::{MeshSource, Source};
use crate::failure::{input, print_note, scheme_failure, usage, Failure, Kind};

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
                loaded.refuse_degenerate_faces()?;
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
                let holes = loaded.plan_holes(counts, plan)?;
                print_notes(loaded);
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
                    print_note(format!("note: {label}: {partial}: no UV column"));
                }
            }
            return Ok(None);
        };
        match counter.uv_counter(&uv) {
            Ok(uv) => Ok(Some(uv)),
            Err(not) => {
                print_note(format!("note: {not}: no UV column"));
                Ok(None)
            }
        }
    }

    /// Whether a mesh is given (`--mesh`, `--base`).
    pub(crate) fn has_mesh(&self) -> bool {
        self.source.mesh.is_given()
    }

    /// Whether an initial state is given (`--init`, `--counts`, `--mesh`, `--base`).
    pub(crate) fn has_state(&self) -> bool {
        let s = self.source;
        s.init.is_some() || s.counts.is_some() || s.mesh.is_given()
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
            Some(path) => Some(driver::load_scheme_file(path)?),
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
        driver::refuse_triangle_rule(source.mesh.triangle_rule, &plan.name(), stages)?;
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
        let mesh_given = source.mesh.is_given();
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
            source.mesh.is_given(),
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

/// Reads the mesh named by `--mesh` or `--base`, if any ([`driver::load`]: its tags unless
/// `--ignore-tags`, the subdivision options resolved). The two flags together are a usage
/// error, and so are the option flags without either.
pub(crate) fn load_mesh(mesh: &MeshSource) -> Result<Option<LoadedMesh>, Failure> {
    let flags = driver::OptionFlags::new(
        mesh.boundary,
        mesh.crease_method,
        mesh.triangle_rule,
        mesh.ignore_tags,
    );
    let source = match (&mesh.mesh, &mesh.base, &mesh.memory) {
        (Some(_), Some(_), _) | (_, Some(_), Some(_)) => {
            return Err(usage!("--mesh and --base cannot be used together"))
        }
        (_, _, Some(memory)) => {
            let (poly, label) = memory;
            return Ok(Some(driver::load_polygon_mesh(
                poly.clone(),
                label,
                &flags,
            )?));
        }
        (Some(path), None, None) => driver::MeshSource::File(path.clone()),
        (None, Some(name), None) => driver::MeshSource::Base(name.clone()),
        (None, None, None) => {
            refuse_options_without_mesh(mesh)?;
            return Ok(None);
        }
    };
    match driver::load(&source, &flags) {
        Ok(loaded) => Ok(Some(loaded)),
        // An unknown or malformed base mesh name is the command line's fault.
        Err(driver::Error::Geometry(e)) if mesh.base.is_some() && !e.is_resource_limit() => {
            Err(Failure::new(Kind::Usage, e))
        }
        Err(e) => Err(e.into()),
    }
}

/// Prints the mesh's notes on stderr ([`LoadedMesh::notes`]).
pub(crate) fn print_notes(loaded: &LoadedMesh) {
    for note in loaded.notes() {
        print_note(note.to_string());
    }
}

/// The subdivision option flags describe how a mesh is subdivided: without `--mesh` or
/// `--base` they are a usage error (exit 2), not silently ignored.
pub(crate) fn refuse_options_without_mesh(mesh: &MeshSource) -> Result<(), Failure> {
    match mesh.option_flag() {
        Some(flag) if !mesh.is_given() => Err(usage!(
            "{flag} describes how a mesh is subdivided: give --mesh FILE or --base NAME"
        )),
        _ => Ok(()),
    }
}

/// How errors name the mesh: its path, or `base mesh NAME`.
pub(crate) fn mesh_label(mesh: &MeshSource) -> String {
    if let Some(memory) = &mesh.memory {
        return memory.1.clone();
    }
    match (&mesh.mesh, &mesh.base) {
        (Some(path), _) => halfedge::io::escape_controls(&path.display().to_string()).into_owned(),
        (None, Some(name)) => format!("base mesh {name}"),
        (None, None) => "the mesh".to_string(),
    }
}

/// A scheme that does not apply to the mesh: exit 3, naming the mesh.
pub(crate) fn not_applicable(mesh: &MeshSource, e: schemes::Error) -> Failure {
    input!("{}: {e}", mesh_label(mesh))
}
