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

/// A failure to write the output (exit 3).
pub(crate) fn write_failure(e: std::io::Error) -> Failure {
    Failure::new(
        Kind::Input,
        anyhow::Error::new(e).context("cannot write the output"),
    )
}

/// Maps a `schemes` error to an exit code: problems with the typed command line are usage
/// errors (2); a scheme that does not apply or a bad scheme file is exit 3; a search that
/// grew too large is exit 4.
pub(crate) fn scheme_failure(e: schemes::Error) -> Failure {
    use schemes::Error as E;
    let kind = match &e {
        E::NotApplicable { .. }
        | E::SchemeFile { .. }
        | E::NoMeshCounts { .. }
        | E::BadFace { .. }
        | E::NothingFits { .. } => Kind::Input,
        E::SearchTooLarge { .. } | E::SearchEstimateTooLarge { .. } | E::OutOfFloatRange { .. } => {
            Kind::Guard
        }
        _ => Kind::Usage,
    };
    Failure::new(kind, e)
}

impl From<schemes::Error> for Failure {
    fn from(e: schemes::Error) -> Failure {
        scheme_failure(e)
    }
}
