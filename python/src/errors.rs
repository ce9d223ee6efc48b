//! Failures as Python exceptions: the driver's [`driver::Kind`] picks the class (the command
//! line's exit code), the message is the command line's (the error and its causes on one
//! line); a Rust panic is caught and raised as `subcount.Error`, never PyO3's
//! `PanicException`; the driver's notes become `subcount.Warning`s.
//!
//! The classes live in `subcount/_errors.py` (multiple inheritance: `UsageError(Error,
//! ValueError)`, ...), looked up when raised.

use std::any::Any;
use std::ffi::CString;
use std::panic::{catch_unwind, AssertUnwindSafe};

use pyo3::exceptions::{PyRuntimeError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::PyType;

/// Why a call failed, before it becomes a Python exception.
#[derive(Debug)]
pub(crate) enum Failure {
    /// The driver's error, classified by its [`driver::Kind`].
    Driver(driver::Error),
    /// A request that is wrong (`UsageError`, exit 2).
    Usage(String),
    /// Bad input arrays or files (`InputError`, exit 3).
    Input(String),
    /// A resource limit (`ResourceError`, exit 4).
    Resource(String),
    /// A value of the wrong type (`TypeError`).
    Type(String),
    /// A panic: a bug (`Error`).
    Bug(String),
    /// An exception Python raised while we called it.
    Python(PyErr),
}

impl From<driver::Error> for Failure {
    fn from(e: driver::Error) -> Failure {
        Failure::Driver(e)
    }
}

impl From<PyErr> for Failure {
    fn from(e: PyErr) -> Failure {
        Failure::Python(e)
    }
}

/// The result of the bindings' work.
pub(crate) type Result<T, E = Failure> = std::result::Result<T, E>;

impl Failure {
    /// The Python exception: the class of `subcount._errors` for the failure's kind.
    pub(crate) fn into_pyerr(self, py: Python<'_>) -> PyErr {
        let (class, message) = match self {
            Failure::Driver(e) => (class_of(e.kind()), one_line(&e) + e.advice()),
            Failure::Usage(m) => ("UsageError", m),
            Failure::Input(m) => ("InputError", m),
            Failure::Resource(m) => ("ResourceError", m),
            Failure::Bug(m) => ("Error", m),
            Failure::Type(m) => return PyTypeError::new_err(m),
            Failure::Python(e) => return e,
        };
        match exception_class(py, class) {
            Ok(class) => PyErr::from_type(class, message),
            // The package's classes cannot be found (a broken install, or no package: the
            // crate's own tests): the message is kept all the same.
            Err(_) => PyRuntimeError::new_err(message),
        }
    }
}

/// The exception class of a driver error's kind.
fn class_of(kind: driver::Kind) -> &'static str {
    match kind {
        driver::Kind::Mismatch => "MismatchError",
        driver::Kind::Usage => "UsageError",
        driver::Kind::Input => "InputError",
        driver::Kind::Guard => "ResourceError",
        _ => "Error",
    }
}

/// The class `name` of `subcount._errors`.
fn exception_class<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyType>> {
    let module = PyModule::import(py, "subcount._errors")?;
    Ok(module.getattr(name)?.cast_into::<PyType>()?)
}

/// The error and its causes on one line, `outer: inner`, skipping a cause whose text the
/// message already holds: the command line's message (`subcount`'s `main.rs`, `one_line`).
fn one_line(error: &(dyn std::error::Error + 'static)) -> String {
    let mut message = String::new();
    let mut cause = Some(error);
    while let Some(e) = cause {
        let text = e.to_string();
        if !message.contains(&text) {
            if !message.is_empty() {
                message.push_str(": ");
            }
            message.push_str(&text);
        }
        cause = e.source();
    }
    halfedge::io::escape_controls(&message.replace('\n', " ")).into_owned()
}

/// The body of a Python entry point (every `#[pyfunction]` and every method and getter of a
/// `#[pymethods]` block is one, `python/tests/test_mesh.py` checks the sources): a panic
/// anywhere in it is raised as `subcount.Error` with its message, never as PyO3's
/// `PanicException` (a panic is a bug in subcount).
pub(crate) fn entry<T>(py: Python<'_>, body: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    catch_unwind(AssertUnwindSafe(body))
        .unwrap_or_else(|payload| Err(bug(payload.as_ref()).into_pyerr(py)))
}

/// Runs `work`: a closure's `?` gives a [`Failure`] (panics are [`entry`]'s, which every
/// caller runs in, GIL-free sections included).
pub(crate) fn attempt<T>(work: impl FnOnce() -> Result<T>) -> Result<T> {
    work()
}

/// The failure of a panic, with its message.
fn bug(payload: &(dyn Any + Send)) -> Failure {
    let what = payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".to_owned());
    Failure::Bug(format!(
        "internal error (a bug in subcount; please report it): {what}"
    ))
}

/// Hands the driver's notes to `warnings.warn(note, subcount.Warning)`, in order (a warnings
/// filter set to `error` makes the first one raise).
pub(crate) fn warn_notes(py: Python<'_>, notes: &[String]) -> PyResult<()> {
    if notes.is_empty() {
        return Ok(());
    }
    let category = exception_class(py, "Warning")?;
    for note in notes {
        // Notes escape control characters (file names, tokens), so hold no NUL.
        let text = CString::new(note.replace('\0', "\\0")).unwrap_or_default();
        PyErr::warn(py, category.as_any(), &text, 2)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_in_an_entry_point_is_an_error_not_an_unwind() {
        Python::initialize();
        Python::attach(|py| {
            // The class lookup needs the package (absent here): a RuntimeError, the message
            // kept; the panic stops at `entry`.
            let caught = entry::<()>(py, || panic!("the index {} is out of bounds", 7));
            let text = caught.expect_err("a panic is an error").to_string();
            assert!(text.contains("a bug in subcount"), "{text}");
            assert!(text.ends_with("the index 7 is out of bounds"), "{text}");
            assert_eq!(entry(py, || Ok(5)).ok(), Some(5));
            // A panic where the GIL is released (the long calls' work) stops there too.
            let detached = entry::<()>(py, || py.detach(|| panic!("detached {}", 3)));
            let text = detached.expect_err("a panic is an error").to_string();
            assert!(text.ends_with("detached 3"), "{text}");
        });
    }

    #[test]
    fn driver_errors_keep_the_command_lines_class_and_message() {
        let error = driver::Error::RefineOnce;
        assert_eq!(class_of(error.kind()), "UsageError");
        assert_eq!(one_line(&error), error.to_string());
        let missing = driver::load(
            &driver::MeshSource::File("/nonexistent/mesh.obj".into()),
            &driver::OptionFlags::default(),
        )
        .unwrap_err();
        assert_eq!(class_of(missing.kind()), "InputError");
        assert!(one_line(&missing).contains("/nonexistent/mesh.obj"));
    }
}
