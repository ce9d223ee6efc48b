//! `subcount._subcount`: the Python bindings of subcount's library crates (the `subcount`
//! package re-exports them). Every mesh and run goes through `driver`, as the command line's
//! do: `read_mesh` is `driver::load`, `subdivide` is `driver::subdivide::prepare` and `run`
//! (so positions equal `subcount subdivide -o` to the bit), `write_mesh` writes through
//! `driver::output`. Nothing here re-implements a rule, a guard or a refusal; this crate turns
//! arrays and keywords into the driver's types and its errors into exceptions
//! ([`errors`]).

mod arrays;
mod errors;
mod mesh;
mod options;
mod refinement;
mod tags;

use std::path::PathBuf;
use std::time::Instant;

use driver::{MeshSource, OptionFlags};
use halfedge::io::ObjWriteOptions;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyInt};

use crate::errors::{attempt, entry, warn_notes, Failure, Result};
use crate::mesh::{Mesh, MeshArg, ARRAYS_LABEL};
use crate::options::RunOptions;

/// Reads a mesh file (OBJ, OFF or PLY) with its texture coordinates, vertex colors,
/// materials, groups and OpenSubdiv tags, within the memory this process may use.
///
/// Raises subcount.InputError for a file that cannot be read or is not a valid mesh file,
/// subcount.ResourceError for one too large for the memory available.
///
/// >>> m = subcount.read_mesh("pawn.obj")
/// >>> m.positions.dtype, m.face_vertex_indices.dtype
/// (dtype('float64'), dtype('int32'))
#[pyfunction]
fn read_mesh(py: Python<'_>, path: PathBuf) -> PyResult<Mesh> {
    entry(py, || {
        let read = py.detach(|| {
            attempt(|| {
                let source = MeshSource::File(path);
                let loaded = driver::load(&source, &OptionFlags::default())?;
                Ok(Mesh::new_with(loaded.poly, source.label(), false))
            })
        });
        read.map_err(|f| f.into_pyerr(py))
    })
}

/// Writes a mesh as OBJ, or as binary PLY for a name ending in .ply, replacing the file
/// atomically (a temporary file renamed over it once complete). `mesh` is a path, a
/// subcount.Mesh or (positions, faces).
///
/// OBJ keeps texture coordinates, vertex colors, materials and groups; PLY keeps texture
/// coordinates and colors (as bytes), and a subcount.Warning says what it leaves out. Other mesh formats' names (.stl, .off, .usd, ...) raise
/// subcount.UsageError.
#[pyfunction]
fn write_mesh(py: Python<'_>, mesh: &Bound<'_, PyAny>, path: PathBuf) -> PyResult<()> {
    entry(py, || {
        let mut notes = Vec::new();
        let written = attempt(|| {
            if let Some(ext) = driver::output::unwritten_mesh_format(&path) {
                return Err(Failure::Usage(format!(
                    "{}: write_mesh does not write {ext} files; it writes OBJ and PLY (name the file .obj or .ply)",
                    halfedge::io::escape_controls(&path.display().to_string())
                )));
            }
            let source = MeshArg::extract(py, mesh)?;
            py.detach(|| {
                attempt(|| {
                    let flags = OptionFlags::default();
                    let loaded = match source {
                        MeshArg::Path(file) => driver::load(&MeshSource::File(file), &flags)?,
                        MeshArg::Poly(poly, label) => {
                            driver::load_polygon_mesh(poly, &label, &flags)?
                        }
                    };
                    // What the output leaves out (PLY: materials and groups), as `-o` says it.
                    loaded.carry_notes(Some(&path), &mut |n| notes.push(n));
                    let poly = &loaded.poly;
                    let options = ObjWriteOptions::default().with_uvs(poly.uvs().is_some());
                    driver::output::write_polygon_mesh_file(poly, &path, &options)?;
                    Ok(())
                })
            })
        });
        warn_notes(py, &notes)?;
        written.map_err(|f| f.into_pyerr(py))
    })
}

/// Subdivides a mesh as `subcount subdivide` does and returns the last level (positions
/// equal to `subcount subdivide -o` to the bit).
///
/// mesh: a path, a subcount.Mesh, or (positions, faces) with faces an (F, k) integer array
/// or a tuple (face_vertex_counts, face_vertex_indices). The options are the command line's
/// flags: scheme (a built-in name: loop, catmull-clark, sqrt3, ...) or scheme_file (a scheme
/// file, as --scheme-file; with scheme too, scheme must be the file's name), levels (0 to 64),
/// boundary ("edge", "edge-and-corner", "none"), crease_method ("uniform", "chaikin"),
/// triangle_rule ("catmark", "smooth"), uv_interpolation ("none", "corners-only",
/// "corners-plus1", "corners-plus2", "boundaries", "all"), ignore_tags, precision ("f64" or
/// "f32": float32 arrays), threads (0: every core), no_uv, allow_large (lift the memory
/// guard), timings (the result's `timings`: the seconds of each part of the call), limit (the
/// limit surface: positions, UVs and colors by OpenSubdiv's limit masks, loop and
/// catmull-clark). The GIL is released while it works.
///
/// Notes (tags not read, options a rule does not apply) are warned as subcount.Warning.
/// Raises subcount.UsageError for a request that is wrong, subcount.InputError for a mesh
/// the scheme does not apply to or bad arrays, subcount.ResourceError when the result would
/// not fit the memory available (unless allow_large), TypeError for arguments of the wrong
/// type.
///
/// >>> out = subcount.subdivide("pawn.obj", scheme="catmull-clark", levels=2)
/// >>> out.n_faces == 16 * subcount.read_mesh("pawn.obj").n_faces   # quads: 4 per face per level
/// True
#[pyfunction]
#[pyo3(
    signature = (mesh, *, scheme=None, levels, **options),
    text_signature = "(mesh, *, scheme=None, levels, scheme_file=None, boundary=None, crease_method=None, triangle_rule=None, uv_interpolation=None, ignore_tags=False, precision='f64', threads=0, no_uv=False, allow_large=False, timings=False, limit=False)"
)]
fn subdivide(
    py: Python<'_>,
    mesh: &Bound<'_, PyAny>,
    scheme: Option<String>,
    levels: &Bound<'_, PyAny>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Mesh> {
    entry(py, || {
        let options = RunOptions::from_keywords(py, "subdivide", levels, options)?;
        let f32 = options.precision == "f32";
        let run = options.prepared(py, mesh, scheme, |prepared, _, notes, timings| {
            // The memory guard and the subdivision.
            let t = Instant::now();
            let level = prepared.run(&|_| {}, notes)?;
            timings.push(("subdivide_s", t.elapsed().as_secs_f64()));
            let t = Instant::now();
            let poly = level.into_polygon_mesh()?;
            timings.push(("result_s", t.elapsed().as_secs_f64()));
            Ok(poly)
        });
        let (poly, timings) = run?;
        let mut mesh = Mesh::handing_over(py, poly, ARRAYS_LABEL.to_owned(), f32)?;
        mesh.timings = options.timings.then_some(timings);
        Ok(mesh)
    })
}

/// A whole number argument (a Python int, not a bool): TypeError otherwise; one beyond 64
/// bits saturates (and is refused as out of range).
pub(crate) fn whole_number(obj: &Bound<'_, PyAny>, name: &str) -> Result<i64> {
    let is_bool = obj.is_instance_of::<pyo3::types::PyBool>();
    // An int, or an integer type that says it is one (`__index__`: numpy's int64, ...).
    let int = match obj.is_instance_of::<PyInt>() {
        true => Some(obj.clone()),
        false => obj.call_method0("__index__").ok(),
    };
    let Some(obj) = int.filter(|_| !is_bool) else {
        let type_name = obj.get_type().name()?.to_string();
        return Err(Failure::Type(format!(
            "{name} must be an int, not {type_name}"
        )));
    };
    match obj.extract::<i64>() {
        Ok(n) => Ok(n),
        Err(_) => Ok(if obj.lt(0)? { i64::MIN } else { i64::MAX }),
    }
}

/// Runs the command line `subcount ARGS` (the program name excluded) in this process, with
/// `mesh` (a path: `--mesh PATH`; a subcount.Mesh or (positions, faces): in memory) when given; the
/// GIL is released while it works. Returns (exit_code, stdout, notes, error): the command's
/// exit code, what it printed, the notes it would have printed on stderr, and its error
/// line's message. The package's `at`, `table`, ... build ARGS and read the JSON.
#[pyfunction]
#[pyo3(signature = (args, mesh=None))]
fn run_command(
    py: Python<'_>,
    args: Vec<std::ffi::OsString>,
    mesh: Option<&Bound<'_, PyAny>>,
) -> PyResult<(u8, String, Vec<String>, Option<String>)> {
    entry(py, || {
        let result = attempt(|| {
            let mut args = args;
            let memory = match mesh.map(|m| MeshArg::extract(py, m)).transpose()? {
                Some(MeshArg::Path(path)) => {
                    args.extend(["--mesh".into(), path.into_os_string()]);
                    None
                }
                Some(MeshArg::Poly(poly, label)) => Some((poly, label)),
                None => None,
            };
            py.detach(|| attempt(|| Ok(subcount_cli::run_captured(args, memory))))
        });
        let captured = result.map_err(|f| f.into_pyerr(py))?;
        let stdout = String::from_utf8_lossy(&captured.stdout).into_owned();
        Ok((captured.exit_code, stdout, captured.notes, captured.error))
    })
}

/// Exact subdivision counts and OpenSubdiv-grade subdivision (the Rust core of `subcount`).
#[pymodule]
fn _subcount(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<Mesh>()?;
    m.add_class::<refinement::Refinement>()?;
    m.add_function(wrap_pyfunction!(read_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(write_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(subdivide, m)?)?;
    m.add_function(wrap_pyfunction!(run_command, m)?)?;
    Ok(())
}
