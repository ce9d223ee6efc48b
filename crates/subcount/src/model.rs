//! What a command counts, from the flags: a [`Counter`] over a recurrence (from `--matrix`)
//! or a scheme plan (from `--scheme`, `--scheme-file`), and its initial state (from `--init`,
//! `--counts`, `--mesh` or `--base`). The mesh is read once per command ([`Input`]).

use std::cell::OnceCell;

use num_bigint::BigInt;
use recurrence::{IntMatrix, Recurrence};
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
    counts: OnceCell<Option<MeshCounts>>,
}

impl<'a> Input<'a> {
    pub(crate) fn new(source: &'a Source) -> Input<'a> {
        Input {
            source,
            counts: OnceCell::new(),
        }
    }

    /// The statistics of the mesh named by `--mesh` or `--base`, if any.
    fn mesh_counts(&self) -> Result<Option<&MeshCounts>, Failure> {
        if let Some(counts) = self.counts.get() {
            return Ok(counts.as_ref());
        }
        let counts = match load_mesh(&self.source.mesh)? {
            Some(poly) => {
                refuse_degenerate_faces(&poly, &self.source.mesh)?;
                Some(halfedge::stats::face_list_counts(&poly))
            }
            None => None,
        };
        Ok(self.counts.get_or_init(|| counts).as_ref())
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
            (None, None, true) => Ok(match self.mesh_counts()? {
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
        if let Some(counts) = self.mesh_counts()? {
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

/// Reads the mesh named by `--mesh` or `--base`, if any.
pub(crate) fn load_mesh(mesh: &MeshSource) -> Result<Option<halfedge::PolygonMesh>, Failure> {
    match (&mesh.mesh, &mesh.base) {
        (Some(_), Some(_)) => Err(usage!("--mesh and --base cannot be used together")),
        (Some(path), None) => halfedge::io::read_mesh(path)
            .map(Some)
            .map_err(|e| mesh_failure(e, Kind::Input)),
        (None, Some(name)) => halfedge::shapes::from_name(name)
            .map(Some)
            .map_err(|e| mesh_failure(e, Kind::Usage)),
        (None, None) => Ok(None),
    }
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
        (Some(path), _) => path.display().to_string(),
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
