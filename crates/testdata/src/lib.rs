//! The shared test meshes of subcount, for tests and benchmarks.
//!
//! The real meshes (with their `stats.json`) live outside the repository, in `../shared/meshes`
//! beside it, and are named by the environment variable [`VAR`] (`SUBCOUNT_MESHES`). A relative
//! value is taken from the workspace root, so the README's full-suite command works as written:
//!
//! ```text
//! tools/osd-driver/build.sh
//! SUBCOUNT_MESHES=../shared/meshes SUBCOUNT_OSD_DRIVER=target/osd-driver/osd_driver \
//!   cargo test --workspace -- --ignored
//! ```
//!
//! (`SUBCOUNT_OSD_DRIVER` names the OpenSubdiv driver of the differential tests in
//! `crates/halfedge/tests/opensubdiv.rs`, which need it as these need the meshes.)
//!
//! A test that reads them is marked `#[ignore = "needs SUBCOUNT_MESHES"]` (so the plain
//! `cargo test --workspace` lists it as ignored, with the reason) and calls [`meshes_dir`] or
//! [`mesh`], which panic with a message naming the variable, the path and the expected folder
//! when the meshes are not there: such a test fails, it never passes without running.
//!
//! ```no_run
//! let bunny = testdata::mesh("bunny_closed.obj");
//! assert!(bunny.is_file());
//! ```
#![deny(missing_docs)]

use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// The environment variable naming the folder of shared test meshes.
pub const VAR: &str = "SUBCOUNT_MESHES";

/// The folder the shared meshes are expected in, relative to the workspace root.
pub const EXPECTED: &str = "../shared/meshes";

/// The folder of shared test meshes: `$SUBCOUNT_MESHES`, a relative value taken from the
/// workspace root.
///
/// # Panics
///
/// When `SUBCOUNT_MESHES` is unset or empty, or names no folder; the message names the
/// variable, the path and the expected folder `../shared/meshes`, and the panic is reported at
/// the caller (the test).
#[track_caller]
pub fn meshes_dir() -> PathBuf {
    match resolve(std::env::var_os(VAR), &workspace_root()) {
        Ok(dir) => dir,
        Err(message) => panic!("{message}"),
    }
}

/// The file `name` (a path relative to the folder, e.g. `broken/osd_catmark_fan.obj`) of the
/// shared test meshes.
///
/// # Panics
///
/// As [`meshes_dir`], and when the folder holds no file `name` (the message names it).
#[track_caller]
pub fn mesh(name: &str) -> PathBuf {
    match file_in(&meshes_dir(), name) {
        Ok(path) => path,
        Err(message) => panic!("{message}"),
    }
}

/// The workspace root (this crate lives in `crates/testdata`).
fn workspace_root() -> PathBuf {
    let manifest_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest_dir
        .ancestors()
        .nth(2)
        .unwrap_or(manifest_dir)
        .to_path_buf()
}

/// The meshes folder for the value `value` of `SUBCOUNT_MESHES`, or the message to fail with.
fn resolve(value: Option<OsString>, root: &Path) -> Result<PathBuf, String> {
    let value = value.filter(|v| !v.is_empty()).ok_or_else(|| {
        format!(
            "{VAR} is not set: this test reads the shared test meshes; run it with \
             {VAR}={EXPECTED} (the folder `{EXPECTED}` beside the repository), e.g. \
             `{VAR}={EXPECTED} cargo test --workspace -- --ignored`"
        )
    })?;
    let dir = root.join(PathBuf::from(value));
    if dir.is_dir() {
        Ok(dir)
    } else {
        Err(format!(
            "{VAR} names {}, which is not a folder: set it to the shared test meshes, \
             expected in `{EXPECTED}` beside the repository (a relative path is taken from the \
             workspace root {})",
            dir.display(),
            root.display()
        ))
    }
}

/// The file `name` of the meshes folder `dir`, or the message to fail with.
fn file_in(dir: &Path, name: &str) -> Result<PathBuf, String> {
    let path = dir.join(name);
    if path.is_file() {
        Ok(path)
    } else {
        Err(format!(
            "no file {name} in the shared test meshes ({VAR} = {}): expected {}",
            dir.display(),
            path.display()
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh folder under the system temporary directory, removed on drop.
    struct Scratch(PathBuf);

    impl Scratch {
        fn new(tag: &str) -> Self {
            let dir = std::env::temp_dir().join(format!("testdata-{tag}-{}", std::process::id()));
            std::fs::create_dir_all(dir.join("meshes/broken")).expect("a scratch folder");
            std::fs::write(dir.join("meshes/broken/a.obj"), "").expect("a scratch file");
            Scratch(dir)
        }
    }

    impl Drop for Scratch {
        fn drop(&mut self) {
            // Best effort: a leftover folder in the temporary directory harms nothing.
            std::fs::remove_dir_all(&self.0).ok();
        }
    }

    #[test]
    fn an_unset_or_empty_variable_names_the_variable_and_the_folder() {
        for value in [None, Some(OsString::new())] {
            let message = resolve(value, Path::new("/repo")).unwrap_err();
            assert!(
                message.starts_with("SUBCOUNT_MESHES is not set"),
                "{message}"
            );
            assert!(
                message.contains("SUBCOUNT_MESHES=../shared/meshes"),
                "{message}"
            );
            assert!(message.contains("-- --ignored"), "{message}");
        }
    }

    #[test]
    fn a_missing_folder_names_the_path_and_the_expected_folder() {
        let scratch = Scratch::new("missing");
        let message = resolve(Some("nowhere".into()), &scratch.0).unwrap_err();
        let path = scratch.0.join("nowhere");
        assert!(
            message.starts_with(&format!("SUBCOUNT_MESHES names {}", path.display())),
            "{message}"
        );
        assert!(message.contains("`../shared/meshes`"), "{message}");
        // A file is not a folder either.
        let file = scratch.0.join("meshes/broken/a.obj");
        let message = resolve(Some(file.clone().into()), &scratch.0).unwrap_err();
        assert!(message.contains(&file.display().to_string()), "{message}");
    }

    #[test]
    fn relative_values_start_at_the_root_and_absolute_ones_stand() {
        let scratch = Scratch::new("resolve");
        let dir = resolve(Some("meshes".into()), &scratch.0).expect("a relative folder");
        assert_eq!(dir, scratch.0.join("meshes"));
        let absolute = scratch.0.join("meshes");
        let dir = resolve(Some(absolute.clone().into()), Path::new("/elsewhere"))
            .expect("an absolute folder");
        assert_eq!(dir, absolute);
        assert_eq!(
            file_in(&dir, "broken/a.obj"),
            Ok(absolute.join("broken/a.obj"))
        );
        let message = file_in(&dir, "b.obj").unwrap_err();
        assert!(
            message.starts_with("no file b.obj in the shared test meshes"),
            "{message}"
        );
        assert!(
            message.contains(&absolute.join("b.obj").display().to_string()),
            "{message}"
        );
    }

    #[test]
    fn the_workspace_root_holds_this_crate() {
        assert!(workspace_root()
            .join("crates/testdata/Cargo.toml")
            .is_file());
    }
}
