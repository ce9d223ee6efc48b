//! The keywords of `subdivide` and `Refinement` (the command line's `subdivide` flags, named
//! with underscores): read once from the call's keywords, checked as the command line checks
//! its flags, turned into the driver's job and option flags, and the run prepared through
//! `driver::subdivide::prepare`.

use driver::refined::Precision;
use driver::subdivide::{Prepared, SubdivideJob};
use driver::{LoadedMesh, Notes, OptionFlags, SchemeChoice};
use halfedge::tags::{BoundaryInterpolation, CreaseMethod, FaceVaryingInterpolation, TriangleRule};
use std::path::PathBuf;
use std::time::Instant;

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict};

use crate::errors::{attempt, warn_notes, Failure, Result};
use crate::mesh::MeshArg;
use crate::tags::named;
use crate::whole_number;
use driver::limits;

/// The keywords of a run, with their defaults.
pub(crate) struct RunOptions<'py> {
    levels: &'py Bound<'py, PyAny>,
    /// A scheme file (`--scheme-file`), beside or instead of the scheme's name.
    scheme_file: Option<PathBuf>,
    boundary: Option<String>,
    crease_method: Option<String>,
    triangle_rule: Option<String>,
    uv_interpolation: Option<String>,
    ignore_tags: bool,
    /// `"f64"` or `"f32"` (`subdivide` only).
    pub(crate) precision: String,
    threads: i64,
    no_uv: bool,
    pub(crate) allow_large: bool,
    /// Keep the refinement (`Refinement`): `SubdivideJob::keep_refinement`.
    keep_refinement: bool,
    /// The limit surface (`--limit`): `subdivide` writes it, `Refinement` keeps its masks.
    limit: bool,
    /// Time the parts of the call (`subdivide` only).
    pub(crate) timings: bool,
}

/// The seconds of each part of a call, in order.
pub(crate) type Timings = Vec<(&'static str, f64)>;

impl<'py> RunOptions<'py> {
    /// The keywords of `function` (`subdivide`, or `Refinement`: no `precision`, the
    /// refinement kept): TypeError for an unknown keyword or a value of the wrong type, as
    /// Python raises for a function's own parameters.
    pub(crate) fn from_keywords(
        py: Python<'py>,
        function: &str,
        levels: &'py Bound<'py, PyAny>,
        keywords: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<RunOptions<'py>> {
        let refinement = function == "Refinement";
        let mut o = RunOptions {
            levels,
            scheme_file: None,
            boundary: None,
            crease_method: None,
            triangle_rule: None,
            uv_interpolation: None,
            ignore_tags: false,
            precision: "f64".to_owned(),
            threads: 0,
            no_uv: false,
            allow_large: false,
            keep_refinement: refinement,
            limit: false,
            timings: false,
        };
        let Some(keywords) = keywords else {
            return Ok(o);
        };
        let mut read = |key: &str, value: &Bound<'py, PyAny>| -> Result<()> {
            let text = || -> Result<Option<String>> {
                match value.is_none() {
                    true => Ok(None),
                    false => value.extract::<String>().map(Some).map_err(|_| {
                        Failure::Type(format!("{function}(): {key} must be a str or None"))
                    }),
                }
            };
            let flag = || -> Result<bool> {
                match value.cast::<PyBool>() {
                    Ok(b) => Ok(b.is_true()),
                    Err(_) => Err(Failure::Type(format!("{function}(): {key} must be a bool"))),
                }
            };
            match key {
                "scheme_file" if !value.is_none() => {
                    o.scheme_file = Some(value.extract::<PathBuf>().map_err(|_| {
                        Failure::Type(format!(
                            "{function}(): scheme_file must be a str, an os.PathLike or None"
                        ))
                    })?);
                }
                "scheme_file" => o.scheme_file = None,
                "boundary" => o.boundary = text()?,
                "crease_method" => o.crease_method = text()?,
                "triangle_rule" => o.triangle_rule = text()?,
                "uv_interpolation" => o.uv_interpolation = text()?,
                "ignore_tags" => o.ignore_tags = flag()?,
                "precision" if !refinement => {
                    o.precision = text()?.unwrap_or_else(|| "f64".to_owned());
                }
                "threads" => o.threads = whole_number(value, "threads")?,
                "no_uv" => o.no_uv = flag()?,
                "allow_large" => o.allow_large = flag()?,
                "limit" => o.limit = flag()?,
                "timings" if !refinement => o.timings = flag()?,
                _ => {
                    return Err(Failure::Type(format!(
                        "{function}() got an unexpected keyword argument '{key}'"
                    )))
                }
            }
            Ok(())
        };
        for (key, value) in keywords.iter() {
            let key: String = key.extract()?;
            read(&key, &value).map_err(|f| f.into_pyerr(py))?;
        }
        Ok(o)
    }

    /// Loads `mesh` with the options, prepares the run of `scheme` (the driver's checks and
    /// memory guard) and hands it to `finish`, the GIL released; the notes become warnings
    /// (before an error, as the command line prints them), failures exceptions. `timings`
    /// gets the seconds of the arguments' conversion (`convert_s`) and of the mesh's checks
    /// (`load_s`); `finish` adds its own.
    pub(crate) fn prepared<R: Send>(
        &self,
        py: Python<'_>,
        mesh: &Bound<'_, PyAny>,
        scheme: Option<String>,
        finish: impl FnOnce(Prepared<'_>, &LoadedMesh, Notes<'_>, &mut Timings) -> Result<R> + Send,
    ) -> PyResult<(R, Timings)> {
        let mut notes = Vec::new();
        let mut timings = Timings::new();
        let result = attempt(|| {
            let t0 = Instant::now();
            let (job, flags) = self.job()?;
            let source = MeshArg::extract(py, mesh)?;
            let choice =
                SchemeChoice::from_options(scheme, self.scheme_file.clone()).ok_or_else(|| {
                    Failure::Usage(
                        "give scheme= (a built-in scheme's name) or scheme_file= (a scheme file)"
                            .into(),
                    )
                })?;
            timings.push(("convert_s", t0.elapsed().as_secs_f64()));
            let t1 = Instant::now();
            let result = py.detach(|| {
                attempt(|| {
                    let loaded = source.load(&flags)?;
                    timings.push(("load_s", t1.elapsed().as_secs_f64()));
                    let t2 = Instant::now();
                    let mut note = |n: String| notes.push(n);
                    let prepared =
                        driver::subdivide::prepare(&loaded, &choice, &job, None, &mut note)?;
                    timings.push(("prepare_s", t2.elapsed().as_secs_f64()));
                    finish(prepared, &loaded, &mut note, &mut timings)
                })
            });
            // The library's whole call, the freeing of the input and the levels included.
            timings.push(("rust_s", t1.elapsed().as_secs_f64()));
            result
        });
        let result = result.map(|r| (r, timings));
        warn_notes(py, &notes)?;
        result.map_err(|f| f.into_pyerr(py))
    }

    /// The driver's job and option flags, or the refusal of a keyword (the command line's
    /// checks of the same flags).
    pub(crate) fn job(&self) -> Result<(SubdivideJob, OptionFlags)> {
        let levels = whole_number(self.levels, "levels")?;
        if levels < 0 {
            return Err(Failure::Usage(format!(
                "invalid levels: `{levels}` is negative"
            )));
        }
        if let Some(why) = limits::levels_refusal(levels as u64) {
            return Err(Failure::Resource(format!("levels={levels}: {why}")));
        }
        let threads = self.threads;
        // A negative count is refused with the range's reason too.
        let refusal = limits::threads_refusal(u64::try_from(threads).unwrap_or(u64::MAX));
        if let Some(why) = refusal {
            return Err(Failure::Usage(format!(
                "invalid threads: `{threads}`: {why}"
            )));
        }
        let flags = OptionFlags::new(
            named::<BoundaryInterpolation>(self.boundary.as_deref(), "boundary")?,
            named::<CreaseMethod>(self.crease_method.as_deref(), "crease_method")?,
            named::<TriangleRule>(self.triangle_rule.as_deref(), "triangle_rule")?,
            self.ignore_tags,
        );
        let uv_interpolation = named::<FaceVaryingInterpolation>(
            self.uv_interpolation.as_deref(),
            "uv_interpolation",
        )?;
        if self.no_uv && uv_interpolation.is_some() {
            return Err(Failure::Usage(
                "uv_interpolation and no_uv do not go together: no_uv refines no UVs".into(),
            ));
        }
        let mut job = SubdivideJob::new(levels as u32);
        job.threads = threads as usize;
        job.allow_large = self.allow_large;
        job.precision = match self.precision.as_str() {
            "f64" => Precision::F64,
            "f32" => Precision::F32,
            other => {
                return Err(Failure::Usage(format!(
                    "invalid precision `{other}`: expected \"f64\" or \"f32\""
                )))
            }
        };
        job.uvs = !self.no_uv;
        job.uv_interpolation = uv_interpolation;
        job.keep_refinement = self.keep_refinement;
        job.limit = self.limit;
        Ok((job, flags))
    }
}
