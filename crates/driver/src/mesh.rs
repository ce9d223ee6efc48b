//! A mesh as a front end uses it: read (a file or a generated base mesh) within the memory
//! the system allows, with the file's OpenSubdiv tags, the subdivision options resolved (an
//! option given by the user wins over the file's tag, the tag over the default:
//! [`resolve_options`]) and the refusals every command shares: a face repeating a vertex,
//! holes under a scheme whose faces do not nest, boundary `none` where only Loop and
//! Catmull-Clark have it, Catmull-Clark's triangle rule asked of a triangle scheme.
//!
//! # Design notes (moved from the CLI's `model.rs`)
//!
//! Owner of the subdivision options of a run (flag over tag over default), the notes about
//! ignored and overridden tags, the holes of a run (hole tags, boundary `none` for Loop and
//! Catmull-Clark; refused under schemes whose faces do not nest) and `--triangle-rule` with
//! triangle schemes, the tags' sharpness on the mesh subdivided: [`load`], [`resolve_options`],
//! [`LoadedMesh::holes`], [`refuse_triangle_rule`], [`LoadedMesh::sharpness`]. Every command
//! reads its mesh through [`load`] and counts what is written.

use std::path::PathBuf;
use std::sync::Arc;

use halfedge::holes::HoleSet;
use halfedge::io::ReadOptions;
use halfedge::subdivide::Sharpness;
use halfedge::tags::{
    BoundaryInterpolation, CreaseMethod, SubdivisionOptions, TagOptions, Tags, TriangleRule,
};
use halfedge::{HalfEdgeMesh, PolygonMesh, Rule};
use schemes::MeshCounts;

use crate::error::{Error, Result};
use crate::Notes;

/// Where a mesh comes from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MeshSource {
    /// A mesh file (OBJ or OFF).
    File(PathBuf),
    /// A generated base mesh ([`halfedge::shapes::from_name`]): `icosahedron`, `torus:2`, ...
    Base(String),
}

impl MeshSource {
    /// How messages name the mesh: its path (control characters escaped), or `base mesh NAME`.
    pub fn label(&self) -> String {
        match self {
            MeshSource::File(path) => {
                halfedge::io::escape_controls(&path.display().to_string()).into_owned()
            }
            MeshSource::Base(name) => format!("base mesh {name}"),
        }
    }
}

/// The subdivision options the user gave, each overriding the file's tag (`None`: the tag, else
/// the default), and whether to read the file's tags at all.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct OptionFlags {
    /// Boundary interpolation (`--boundary`).
    pub boundary: Option<BoundaryInterpolation>,
    /// How semi-sharp creases decay (`--crease-method`).
    pub crease_method: Option<CreaseMethod>,
    /// Catmull-Clark's rule for triangles (`--triangle-rule`).
    pub triangle_rule: Option<TriangleRule>,
    /// Do not read the file's tags (`--ignore-tags`).
    pub ignore_tags: bool,
}

impl OptionFlags {
    /// The flags as given.
    pub fn new(
        boundary: Option<BoundaryInterpolation>,
        crease_method: Option<CreaseMethod>,
        triangle_rule: Option<TriangleRule>,
        ignore_tags: bool,
    ) -> OptionFlags {
        OptionFlags {
            boundary,
            crease_method,
            triangle_rule,
            ignore_tags,
        }
    }
}

/// A mesh as the commands use it: its face list, with the file's tags
/// ([`PolygonMesh::tags`]; none when the tags are ignored, for OFF files and base meshes), and
/// the subdivision options resolved from the flags, the tags and the defaults
/// ([`resolve_options`]).
#[derive(Debug)]
pub struct LoadedMesh {
    /// The face list and its tags (shared: a front end that keeps the mesh hands it over
    /// without a copy).
    pub poly: Arc<PolygonMesh>,
    /// The resolved options.
    pub options: SubdivisionOptions,
    /// The options the user gave.
    flags: OptionFlags,
    /// How messages name the mesh.
    label: String,
    /// At most two lines: the tags of the file not read, the flags that override the file's
    /// tags ([`LoadedMesh::notes`]).
    notes: Vec<String>,
}

/// Reads the mesh of `source` (with its tags unless `flags` ignores them), within the memory
/// this process may allocate ([`crate::system::available_bytes`]), refuses it when analysing it
/// would not fit half of that, and resolves the subdivision options. Its notes
/// ([`LoadedMesh::notes`]) are the tags the file has that are not read (each name with its
/// count), and the flags that override the file's tags (naming both values).
///
/// # Errors
///
/// The reader's errors ([`Error::Geometry`]: a bad file is input, an unknown base mesh a
/// usage error, a resource limit a guard's), [`Error::AnalysisTooLarge`].
pub fn load(source: &MeshSource, flags: &OptionFlags) -> Result<LoadedMesh> {
    let available = crate::system::available_bytes();
    let poly = match source {
        MeshSource::File(path) => {
            let options = if flags.ignore_tags {
                ReadOptions::without_tags()
            } else {
                ReadOptions::default()
            };
            halfedge::io::read_mesh_with(path, &options.with_available_bytes(available))?
        }
        MeshSource::Base(name) => halfedge::shapes::from_name_within(name, available)?,
    };
    loaded(Arc::new(poly), source.label(), flags)
}

/// A mesh already in memory (a front end's arrays, a mesh read earlier) as [`load`] gives a
/// file's: `label` names it in messages, the file's tags it carries are dropped when `flags`
/// ignores them, and the same refusal and resolution of options follow.
///
/// ```
/// use driver::{load_polygon_mesh, OptionFlags};
/// let cube = halfedge::shapes::cube();
/// let loaded = load_polygon_mesh(cube, "<mesh>", &OptionFlags::default())?;
/// assert_eq!((loaded.label(), loaded.poly.n_faces()), ("<mesh>", 6));
/// assert!(loaded.notes().is_empty());
/// # Ok::<(), driver::Error>(())
/// ```
///
/// # Errors
///
/// [`Error::AnalysisTooLarge`].
pub fn load_polygon_mesh(
    poly: impl Into<Arc<PolygonMesh>>,
    label: &str,
    flags: &OptionFlags,
) -> Result<LoadedMesh> {
    let mut poly = poly.into();
    if flags.ignore_tags && !poly.tags().is_empty() {
        // Empty tags name no vertex, face or edge: they always fit. (A shared mesh is copied
        // first: its owner keeps its tags.)
        let cleared = Arc::make_mut(&mut poly).set_tags(Tags::default());
        debug_assert!(cleared.is_ok());
    }
    loaded(poly, label.to_owned(), flags)
}

/// The part of [`load`] after the read: the memory refusal, the notes, the options.
fn loaded(poly: Arc<PolygonMesh>, label: String, flags: &OptionFlags) -> Result<LoadedMesh> {
    // Every command analyses the face list it read (counts, problems, a half-edge mesh):
    // refused here, before that analysis allocates, when it would not fit.
    let need = poly.heap_bytes() as u128 + halfedge::memory::face_list_analysis_bytes(&poly);
    let limit = crate::system::peak_limit();
    if need > limit {
        return Err(Error::AnalysisTooLarge {
            mesh: label,
            faces: poly.n_faces(),
            corners: poly.n_corners(),
            need: halfedge::memory::human_bytes(need as f64),
            limit: halfedge::memory::human_bytes(limit as f64),
        });
    }
    let mut notes = Vec::new();
    // Tags not read at all (`--ignore-tags`) are not reported as ignored either.
    if !flags.ignore_tags && !poly.ignored_tags().is_empty() {
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
    let (options, overrides) = resolve_options(flags, &poly.tags().options);
    if !overrides.is_empty() {
        notes.push(format!("note: {label}: {}", overrides.join("; ")));
    }
    Ok(LoadedMesh {
        poly,
        options,
        flags: *flags,
        label,
        notes,
    })
}

/// The one resolution of the subdivision options: a flag wins over the file's tag, the tag
/// wins over the default (edge, uniform, catmark; face-varying corners-plus1). Also returns,
/// for each flag that overrides a tag with another value, a note naming both (`--boundary edge
/// overrides the tag interpolateboundary 1 (edge-and-corner)`).
///
/// ```
/// use driver::{resolve_options, OptionFlags};
/// use halfedge::tags::{BoundaryInterpolation, TagOptions};
/// let mut tags = TagOptions::default();
/// tags.boundary = Some(BoundaryInterpolation::EdgeAndCorner);
/// let flags = OptionFlags::new(Some(BoundaryInterpolation::Edge), None, None, false);
/// let (options, notes) = resolve_options(&flags, &tags);
/// assert_eq!(options.boundary, BoundaryInterpolation::Edge);
/// assert_eq!(notes, ["--boundary edge overrides the tag interpolateboundary 1 (edge-and-corner)"]);
/// ```
pub fn resolve_options(
    flags: &OptionFlags,
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

/// `--triangle-rule` (`rule`) is Catmull-Clark's rule for triangles (OpenSubdiv's
/// `TriangleSubdivision`): refused for a scheme, or a composition without a Catmull-Clark
/// stage, whose rule works on triangles (the Loop family, 1:N², √3), which has no such choice.
/// `stages` are each stage's name and rule; `scheme` names them all.
///
/// # Errors
///
/// [`Error::TriangleRule`] (a usage error).
pub fn refuse_triangle_rule<'a>(
    rule: Option<TriangleRule>,
    scheme: &str,
    stages: impl IntoIterator<Item = (&'a str, Option<Rule>)>,
) -> Result<()> {
    let Some(rule) = rule else {
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
        return Err(Error::TriangleRule { rule, which });
    }
    Ok(())
}

/// Whether `rule` has crease rules (Loop and Catmull-Clark, as in OpenSubdiv).
fn follows_creases(rule: Rule) -> bool {
    matches!(rule, Rule::Loop | Rule::CatmullClark)
}

impl LoadedMesh {
    /// The creases, corners, holes and options of the file (empty when the tags are ignored).
    pub fn tags(&self) -> &Tags {
        self.poly.tags()
    }

    /// How messages name the mesh ([`MeshSource::label`]).
    pub fn label(&self) -> &str {
        &self.label
    }

    /// The options the user gave.
    pub fn flags(&self) -> &OptionFlags {
        &self.flags
    }

    /// At most two lines for the user: the tags of the file not read (`warning: ...`), the
    /// flags that override the file's tags (`note: ...`). The driver hands them to a
    /// [`Notes`] once the mesh passed a command's checks, so that a refusal stays one line.
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// Hands [`LoadedMesh::notes`] to `notes`.
    pub fn emit_notes(&self, notes: Notes<'_>) {
        for note in &self.notes {
            notes(note.clone());
        }
    }

    /// The notes on what an output leaves out: vertex colors on only some vertices (no color
    /// channel), and with an output (`output`) the lines of the file no output carries and,
    /// for a PLY output, the materials and groups (PLY has no place for them).
    pub fn carry_notes(&self, output: Option<&std::path::Path>, notes: Notes<'_>) {
        let (poly, label) = (&self.poly, self.label());
        if let Some(partial) = poly.partial_colors() {
            notes(format!("note: {label}: {partial}"));
        }
        let Some(path) = output else {
            return;
        };
        if !poly.uncarried().is_empty() {
            let kinds: Vec<String> = poly.uncarried().iter().map(ToString::to_string).collect();
            notes(format!(
                "note: {label}: not carried into the output: {}",
                kinds.join(", ")
            ));
        }
        let ply = crate::output::MeshFormat::of(path) == crate::output::MeshFormat::Ply;
        if ply && poly.groups().is_some() {
            notes(format!(
                "note: {label}: materials and groups are not written to PLY: name the output .obj to keep them"
            ));
        }
    }

    /// The place of face `f` in a message: `line 12: `, or nothing when the mesh has no lines.
    pub fn face_place(&self, f: usize) -> String {
        self.poly
            .face_line(f)
            .map(|l| format!("line {l}: "))
            .unwrap_or_default()
    }

    /// The validated half-edge mesh.
    ///
    /// # Errors
    ///
    /// [`Error::InMesh`] naming the mesh and the line of the offending face.
    pub fn validate(&self) -> Result<HalfEdgeMesh> {
        HalfEdgeMesh::try_from_polygon_mesh(&self.poly).map_err(|e| Error::InMesh {
            mesh: self.label.clone(),
            place: e
                .face()
                .map_or_else(String::new, |f| self.face_place(f as usize)),
            error: Box::new(e),
        })
    }

    /// Refuses a face that uses a vertex twice (such a face makes the counts meaningless),
    /// naming the mesh, the line and the face: before any counting of the face list, and
    /// before the half-edge build's own error when that build refuses the mesh.
    ///
    /// # Errors
    ///
    /// [`Error::RepeatedVertex`].
    pub fn refuse_degenerate_faces(&self) -> Result<()> {
        let poly = &self.poly;
        if let Some((f, v)) = schemes::first_repeated_vertex(poly.faces()) {
            let vertices: Vec<String> = poly.face(f).iter().map(ToString::to_string).collect();
            return Err(Error::RepeatedVertex {
                mesh: self.label.clone(),
                place: self.face_place(f),
                face: f,
                vertices: vertices.join(", "),
                vertex: v,
            });
        }
        Ok(())
    }

    /// A scheme's refusal of this mesh ([`Error::NotApplicable`], naming it).
    pub fn not_applicable(&self, error: schemes::Error) -> Error {
        Error::NotApplicable {
            mesh: self.label.clone(),
            error: Box::new(error),
        }
    }

    /// Whether the subdivision may follow crease rules: `rule` has them and the file's tags
    /// make an edge or a vertex sharp, or the resolved options are not the defaults (the
    /// library decides whether they change anything on the mesh; the memory guard counts their
    /// tables when they may).
    pub fn has_crease_rules(&self, rule: Rule) -> bool {
        follows_creases(rule) && self.has_crease_input()
    }

    /// Whether the file's tags make an edge or a vertex sharp, or the resolved boundary,
    /// crease method or triangle rule are not the defaults.
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
    /// other rule both are left out, with one note when the file or the flags gave some, so a
    /// tagged file still subdivides by every scheme.
    ///
    /// # Errors
    ///
    /// As [`LoadedMesh::sharpness`].
    pub fn crease_inputs(
        &self,
        rule: Rule,
        mesh: &HalfEdgeMesh,
        notes: Notes<'_>,
    ) -> Result<(Option<Sharpness>, SubdivisionOptions)> {
        if follows_creases(rule) {
            return Ok((self.sharpness(mesh)?, self.options));
        }
        if self.has_crease_input() {
            notes(format!(
                "note: {}: creases, corners and the --boundary/--crease-method/--triangle-rule options are not applied by {rule}: only loop and catmull-clark have crease rules (OpenSubdiv's)",
                self.label
            ));
        }
        Ok((None, SubdivisionOptions::default()))
    }

    /// The creases and corners of the file's tags on `mesh`, the half-edge mesh built from
    /// [`LoadedMesh::poly`] ([`Sharpness::from_tags_of`]: its vertices renumbered when some
    /// vertex of the file is in no face); `None` when no edge or vertex is sharp (and when the
    /// tags are ignored).
    ///
    /// # Errors
    ///
    /// A crease the half-edge mesh cannot resolve: [`Error::InMesh`].
    pub fn sharpness(&self, mesh: &HalfEdgeMesh) -> Result<Option<Sharpness>> {
        let tags = self.tags();
        if tags.creases().is_empty() && tags.corners().is_empty() {
            return Ok(None);
        }
        let sharpness =
            Sharpness::from_tags_of(&self.poly, mesh, tags).map_err(|e| self.in_mesh(e))?;
        Ok((!sharpness.is_smooth()).then_some(sharpness))
    }

    /// The geometry's error about this mesh, naming it.
    fn in_mesh(&self, error: halfedge::Error) -> Error {
        Error::InMesh {
            mesh: self.label.clone(),
            place: String::new(),
            error: Box::new(error),
        }
    }

    /// The schemes that subdivide this mesh, whose faces have the statistics `counts`
    /// (`manifold`: it builds a half-edge mesh): [`halfedge::subdivide::applicable_schemes`]
    /// without those that would refuse the file's holes (their faces do not nest) or boundary
    /// `none` on a mesh with boundary (a mode of Loop and Catmull-Clark only).
    pub fn applicable_schemes(&self, counts: &MeshCounts, manifold: bool) -> Vec<schemes::Scheme> {
        let holes = !self.tags().hole_faces().is_empty();
        let none =
            self.options.boundary == BoundaryInterpolation::None && counts.boundary_edges > 0;
        halfedge::subdivide::applicable_schemes(counts, manifold)
            .into_iter()
            .filter(|s| {
                let rule = s.subdivision_rule();
                (!holes || rule.is_some_and(schemes::holes::nests_faces))
                    && (!none || matches!(rule, Some(Rule::Loop | Rule::CatmullClark)))
            })
            .collect()
    }

    /// The faces that are holes under `plan` ([`LoadedMesh::holes`] of its stages).
    ///
    /// # Errors
    ///
    /// As [`LoadedMesh::holes`].
    pub fn plan_holes(&self, counts: &MeshCounts, plan: &schemes::Plan) -> Result<Option<HoleSet>> {
        let stages: Vec<(&str, Option<Rule>)> = plan
            .stages()
            .iter()
            .map(|s| (s.scheme().name(), s.scheme().subdivision_rule()))
            .collect();
        self.holes(counts, &plan.name(), &stages)
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
    /// Usage errors: boundary `none` on a mesh with boundary under a stage other than Loop or
    /// Catmull-Clark ([`Error::BoundaryNone`]); holes under a stage whose faces do not nest
    /// (√3, Doo-Sabin, mid-edge: a hole has no descendants) or that names no rule
    /// ([`Error::HolesNotNested`]).
    pub fn holes(
        &self,
        counts: &MeshCounts,
        scheme: &str,
        stages: &[(&str, Option<Rule>)],
    ) -> Result<Option<HoleSet>> {
        let which = |name: &str| {
            if name == scheme {
                name.to_owned()
            } else {
                format!("{scheme} (its stage {name})")
            }
        };
        let tagged = self.tags().hole_faces().len();
        if self.options.boundary == BoundaryInterpolation::None && counts.boundary_edges > 0 {
            let (option, fix) = if self.flags.boundary.is_some() {
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
                return Err(Error::BoundaryNone {
                    mesh: self.label.clone(),
                    option,
                    stage: which(name),
                    boundary_edges: counts.boundary_edges,
                    fix,
                });
            }
        }
        let faces = halfedge::holes::holes_of(&self.poly, self.tags(), self.options.boundary);
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
            return Err(Error::HolesNotNested {
                mesh: self.label.clone(),
                tagged,
                stage: which(name),
                why,
            });
        }
        HoleSet::new(self.poly.n_faces(), faces)
            .map(Some)
            .map_err(|e| self.in_mesh(e))
    }
}
