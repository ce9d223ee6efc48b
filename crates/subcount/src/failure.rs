//! The CLI's error type: a cause plus the exit code that classifies it.
//!
//! Exit codes are a public contract: 0 ok, 1 a verification mismatch, 2 a usage error, 3 a bad
//! input file or a scheme that does not apply, 4 refused by a resource guard.

use std::fmt;

/// What kind of failure, and so which exit code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Exit 1: a real subdivision disagreed with the prediction.
    Mismatch,
    /// Exit 2: the command line is wrong.
    Usage,
    /// Exit 3: an input file is bad, or the scheme does not apply to the mesh.
    Input,
    /// Exit 4: a resource guard refused the work.
    Guard,
}

impl Kind {
    pub(crate) fn exit_code(self) -> u8 {
        match self {
            Kind::Mismatch => 1,
            Kind::Usage => 2,
            Kind::Input => 3,
            Kind::Guard => 4,
        }
    }
}

/// A failed command: the cause (printed on one line) and its kind.
pub(crate) struct Failure {
    pub(crate) kind: Kind,
    pub(crate) error: anyhow::Error,
}

impl Failure {
    pub(crate) fn new(kind: Kind, error: impl Into<anyhow::Error>) -> Self {
        Failure {
            kind,
            error: error.into(),
        }
    }
}

impl fmt::Debug for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}: {:#}", self.kind, self.error)
    }
}

/// Shorthands: `usage!("...")` builds an exit-2 failure from a format string.
macro_rules! usage {
    ($($arg:tt)*) => {
        $crate::failure::Failure::new($crate::failure::Kind::Usage, anyhow::anyhow!($($arg)*))
    };
}

/// `input!("...")` builds an exit-3 failure from a format string.
macro_rules! input {
    ($($arg:tt)*) => {
        $crate::failure::Failure::new($crate::failure::Kind::Input, anyhow::anyhow!($($arg)*))
    };
}

pub(crate) use {input, usage};

thread_local! {
    /// The notes of a captured run ([`capturing_notes`]) on this thread.
    static CAPTURED: std::cell::RefCell<Option<Vec<String>>> = const { std::cell::RefCell::new(None) };
}

/// Prints a note (of the driver, of a command) on stderr, or keeps it for a captured run.
pub(crate) fn print_note(note: String) {
    let printed = CAPTURED.with(|c| match c.borrow_mut().as_mut() {
        Some(notes) => {
            notes.push(note);
            None
        }
        None => Some(note),
    });
    if let Some(note) = printed {
        eprintln!("{note}");
    }
}

/// Runs `work`, keeping the notes it prints on this thread ([`print_note`]); the capture
/// before it is restored even when `work` panics.
pub(crate) fn capturing_notes<T>(work: impl FnOnce() -> T) -> (T, Vec<String>) {
    /// Puts the outer capture back when dropped.
    struct Restore(Option<Vec<String>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let outer = self.0.take();
            CAPTURED.with(|c| *c.borrow_mut() = outer);
        }
    }
    let _restore = Restore(CAPTURED.with(|c| c.replace(Some(Vec::new()))));
    let result = work();
    let notes = CAPTURED.with(|c| c.borrow_mut().take()).unwrap_or_default();
    (result, notes)
}

/// A failure to write the output (exit 3).
pub(crate) fn write_failure(e: std::io::Error) -> Failure {
    Failure::new(
        Kind::Input,
        anyhow::Error::new(e).context("cannot write the output"),
    )
}

/// Maps a `schemes` error to an exit code ([`driver::Kind::of_scheme_error`]): problems with
/// the typed command line are usage errors (2); a scheme that does not apply or a bad scheme
/// file is exit 3; a search that grew too large is exit 4.
pub(crate) fn scheme_failure(e: schemes::Error) -> Failure {
    Failure::new(driver::Kind::of_scheme_error(&e).into(), e)
}

impl From<schemes::Error> for Failure {
    fn from(e: schemes::Error) -> Failure {
        scheme_failure(e)
    }
}

impl From<driver::Kind> for Kind {
    fn from(kind: driver::Kind) -> Kind {
        match kind {
            driver::Kind::Mismatch => Kind::Mismatch,
            driver::Kind::Usage => Kind::Usage,
            driver::Kind::Input => Kind::Input,
            _ => Kind::Guard,
        }
    }
}

/// The driver's errors, with the command line's advice where a flag helps: the memory guard
/// says how to lift it, crease input under a rule without creases how to drop it.
impl From<driver::Error> for Failure {
    fn from(e: driver::Error) -> Failure {
        let kind = e.kind().into();
        match e.advice() {
            "" => Failure::new(kind, e),
            advice => Failure::new(kind, anyhow::anyhow!("{e}{advice}")),
        }
    }
}

impl From<halfedge::Error> for Failure {
    fn from(e: halfedge::Error) -> Failure {
        driver::Error::from(e).into()
    }
}
