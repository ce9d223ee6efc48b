//! Output files: every file a front end writes (a subdivided mesh, a plot) replaces its
//! target atomically ([`write_atomically`]), `-` being standard output; a signal removes the
//! temporary file being written. The OBJ and PLY bytes themselves are the kernel's
//! (`halfedge::io`'s writers take any [`Write`]); [`write_polygon_mesh_file`] and
//! [`write_mesh_buffers_file`] put them in a file in the format the name says
//! ([`MeshFormat`]), [`write_obj_file`], [`write_polygon_obj_file`] and
//! [`write_buffers_obj_file`] as OBJ.
//!
//! # Design notes
//!
//! `write_atomically` is the one writer of output files (OBJ and plots): a temporary file in
//! the target's folder, then a rename over the resolved target; `-` is standard output, special
//! files are written directly, write-protected targets are refused, and a signal handler thread
//! (signal-hook) removes live temporary files on SIGINT/SIGTERM/SIGHUP. It moved here from the
//! geometry crate (issue 25): the kernel writes into a `Write` and never touches the process.
//! While the body writes, a thread starts the kernel's writeback of the pages written so far
//! (issue 30): the `sync_all` before the rename then waits for the last pages only (on a
//! 310 MB OBJ, 5 ms instead of 100).

use std::fs::{self, File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, OnceLock};

use halfedge::io::{FaceBuffers, ObjWriteOptions, UvBuffers};
use halfedge::{HalfEdgeMesh, PolygonMesh, Scalar};

use crate::error::{Error, Result};

/// Writes a half-edge mesh as OBJ ([`halfedge::io::write_obj_with`]) to `path` with
/// [`write_atomically`]: the text goes to a temporary file in the target's folder, which is
/// renamed over the target only once it is complete and synced; on any error the temporary
/// file is removed and the target is untouched.
///
/// # Errors
///
/// [`halfedge::Error::Io`] naming the file, [`Error::WriteProtected`] for a target the user may not
/// write.
pub fn write_obj_file(mesh: &HalfEdgeMesh, path: &Path, options: &ObjWriteOptions) -> Result<()> {
    write_atomically(path, |file| {
        halfedge::io::write_obj_with(mesh, file, options)
    })
}

/// Writes a face list as OBJ ([`halfedge::io::write_polygon_obj_with`]), atomically, like
/// [`write_obj_file`].
///
/// # Errors
///
/// As [`write_obj_file`].
pub fn write_polygon_obj_file(
    mesh: &PolygonMesh,
    path: &Path,
    options: &ObjWriteOptions,
) -> Result<()> {
    write_atomically(path, |file| {
        halfedge::io::write_polygon_obj_with(mesh, file, options)
    })
}

/// Writes caller-owned buffers as OBJ ([`halfedge::io::write_buffers_obj_with`]),
/// atomically, like [`write_obj_file`].
///
/// # Errors
///
/// As [`write_obj_file`], and [`halfedge::Error::Io`] for inconsistent buffers.
pub fn write_buffers_obj_file<T: Scalar>(
    positions: &[[T; 3]],
    faces: FaceBuffers<'_>,
    uvs: Option<UvBuffers<'_, T>>,
    path: &Path,
    options: &ObjWriteOptions,
) -> Result<()> {
    write_atomically(path, |file| {
        halfedge::io::write_buffers_obj_with(positions, faces, uvs, file, options)
    })
}

/// The format an output file is written in, by its name: binary PLY for a name ending in
/// `.ply` (any case), OBJ for every other name and for `-` (standard output).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshFormat {
    /// OBJ text ([`halfedge::io::write_polygon_obj_with`] and the other OBJ writers).
    Obj,
    /// Binary little-endian PLY ([`halfedge::io::write_polygon_ply`],
    /// [`halfedge::io::write_mesh_buffers_ply`]).
    Ply,
}

impl MeshFormat {
    /// The format of an output named `path`.
    ///
    /// ```
    /// use driver::output::MeshFormat;
    /// use std::path::Path;
    /// assert_eq!(MeshFormat::of(Path::new("out.PLY")), MeshFormat::Ply);
    /// assert_eq!(MeshFormat::of(Path::new("out.obj")), MeshFormat::Obj);
    /// assert_eq!(MeshFormat::of(Path::new("-")), MeshFormat::Obj);
    /// ```
    pub fn of(path: &Path) -> MeshFormat {
        let extension = path.extension().and_then(|e| e.to_str());
        match extension.map(str::to_ascii_lowercase).as_deref() {
            Some("ply") => MeshFormat::Ply,
            _ => MeshFormat::Obj,
        }
    }
}

/// Writes a face list (positions, faces, UVs, colors, groups) to `path` in the format its name
/// says ([`MeshFormat::of`]), atomically, like [`write_obj_file`].
///
/// # Errors
///
/// As [`write_obj_file`].
pub fn write_polygon_mesh_file(
    mesh: &PolygonMesh,
    path: &Path,
    options: &ObjWriteOptions,
) -> Result<()> {
    match MeshFormat::of(path) {
        MeshFormat::Obj => write_polygon_obj_file(mesh, path, options),
        MeshFormat::Ply => write_atomically(path, |file| {
            halfedge::io::write_polygon_ply(mesh, file, options)
        }),
    }
}

/// Writes a mesh in caller-owned buffers ([`halfedge::io::MeshBuffers`]: positions, faces,
/// UVs, colors, groups) in the format its name says ([`MeshFormat::of`]:
/// [`halfedge::io::write_mesh_buffers_obj`] or [`halfedge::io::write_mesh_buffers_ply`]),
/// atomically, like [`write_obj_file`].
///
/// # Errors
///
/// As [`write_buffers_obj_file`].
pub fn write_mesh_buffers_file<T: Scalar>(
    mesh: &halfedge::io::MeshBuffers<'_, T>,
    path: &Path,
    options: &ObjWriteOptions,
) -> Result<()> {
    write_atomically(path, |file| match MeshFormat::of(path) {
        MeshFormat::Obj => halfedge::io::write_mesh_buffers_obj(mesh, file, options),
        MeshFormat::Ply => halfedge::io::write_mesh_buffers_ply(mesh, file, options),
    })
}

/// Writes an output file so that what it replaces is never damaged: `body` writes the
/// contents into a [`File`], and where that file goes depends on `path`:
///
/// - `-` is standard output (a duplicate of its descriptor; nothing is renamed).
/// - A regular file, or a path that does not exist yet: `body` writes a temporary file in the
///   target's folder (a short name, `.<at most 24 bytes of the name>.<pid>.<n>.tmp`, so any
///   target name the file system accepts still works), which is synced and renamed over the
///   target only when complete; on any error it is removed and the target is untouched. The
///   new file keeps the permission bits of the file it replaces.
/// - A symbolic link is written through: the file it points to (following every link) is
///   replaced, and the link stays. A dangling link creates the file it names.
/// - A special file (`/dev/stdout` on a pipe or terminal, a FIFO, a character device such as
///   `/dev/null`) is opened and written directly, never renamed over.
///
/// An existing target the user may not write is refused and left intact
/// ([`Error::WriteProtected`]): one without any write permission bit (mode 444), even for
/// root, whom the kernel would let write it (the mode is the owner's statement that the file
/// is not to be changed, as `rm` and `cp -i` treat it), and one for which `access(W_OK)`
/// fails (the mode bits of the user's class, ACLs, a read-only file system). Renaming over a
/// file needs only the folder's permission, so without this check a read-only file would be
/// replaced.
///
/// While a temporary file exists, `SIGINT`, `SIGTERM` and `SIGHUP` remove it before the
/// process ends: the first call installs (with `signal-hook`) a thread that deletes every
/// live temporary file on those signals and then ends the process as the signal's default
/// action would (a shell reports exit status 130 for `SIGINT`, 143 for `SIGTERM`). A signal
/// the process ignores (as `nohup` arranges) stays ignored.
///
/// # Errors
///
/// [`halfedge::Error::Io`] naming `path` for any failure to open, write, sync or rename (the target is
/// then untouched, except for a special file, which is written as it goes), and
/// [`Error::WriteProtected`].
///
/// # Example
///
/// ```
/// use std::io::Write;
/// let dir = std::env::temp_dir().join(format!("write-atomically-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let target = dir.join("out.txt");
/// driver::output::write_atomically(&target, |file| file.write_all(b"hello\n"))?;
/// assert_eq!(std::fs::read_to_string(&target)?, "hello\n");
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_atomically(
    path: &Path,
    body: impl FnOnce(&mut File) -> std::io::Result<()>,
) -> Result<()> {
    let io_error = |source| {
        Error::Geometry(halfedge::Error::Io {
            path: path.to_path_buf(),
            source,
        })
    };
    if path.as_os_str() == "-" {
        return write_stdout(body).map_err(io_error);
    }
    match resolve_target(path).map_err(io_error)? {
        Target::Special => {
            let result = OpenOptions::new()
                .write(true)
                .open(path)
                .and_then(|mut file| body(&mut file).and_then(|()| file.flush()));
            result.map_err(io_error)
        }
        Target::Regular { resolved, existing } => {
            if let Some(metadata) = &existing {
                refuse_write_protected(path, &resolved, metadata)?;
            }
            let permissions = existing.map(|m| m.permissions());
            write_through_temporary(&resolved, permissions, body).map_err(io_error)
        }
    }
}

/// The mesh formats an output name's extension may name that the writers do not write
/// (they write OBJ, and PLY for `.ply`): a file named `out.stl` holding OBJ text would mislead
/// every program that opens it.
pub const UNWRITTEN_MESH_FORMATS: &[&str] = &[
    "stl", "off", "glb", "gltf", "fbx", "usd", "usda", "usdc", "3ds", "dae",
];

/// The extension of `path` (lowercase) when it names a mesh format the writers do not write
/// ([`UNWRITTEN_MESH_FORMATS`]); `None` for `.obj`, `.ply` and every other name, written as
/// OBJ ([`MeshFormat`]: `.ply` as PLY).
///
/// ```
/// use driver::output::unwritten_mesh_format;
/// use std::path::Path;
/// assert_eq!(unwritten_mesh_format(Path::new("out.STL")).as_deref(), Some("stl"));
/// assert_eq!(unwritten_mesh_format(Path::new("out.ply")), None);
/// assert_eq!(unwritten_mesh_format(Path::new("out.obj")), None);
/// assert_eq!(unwritten_mesh_format(Path::new("out.txt")), None);
/// ```
pub fn unwritten_mesh_format(path: &Path) -> Option<String> {
    let extension = path.extension()?.to_str()?.to_ascii_lowercase();
    UNWRITTEN_MESH_FORMATS
        .contains(&extension.as_str())
        .then_some(extension)
}

/// Checks up front what [`write_atomically`] would refuse without writing anything: a
/// write-protected target or a folder, so that a long computation is not wasted on an output
/// that cannot be written. Everything else (`-`, a new file, a special file) passes.
///
/// # Errors
///
/// As [`write_atomically`]'s refusals: [`Error::WriteProtected`], [`halfedge::Error::Io`].
pub fn check_output(path: &Path) -> Result<()> {
    if path.as_os_str() == "-" {
        return Ok(());
    }
    let io_error = |source| {
        Error::Geometry(halfedge::Error::Io {
            path: path.to_path_buf(),
            source,
        })
    };
    match resolve_target(path).map_err(io_error)? {
        Target::Regular {
            resolved,
            existing: Some(metadata),
        } => refuse_write_protected(path, &resolved, &metadata),
        _ => Ok(()),
    }
}

/// Where [`write_atomically`] puts the bytes.
enum Target {
    /// Not a regular file: written directly.
    Special,
    /// A regular file (`existing` is its metadata) or a path to create, with every symbolic
    /// link resolved.
    Regular {
        resolved: PathBuf,
        existing: Option<fs::Metadata>,
    },
}

fn resolve_target(path: &Path) -> std::io::Result<Target> {
    match fs::metadata(path) {
        Ok(metadata) if metadata.is_dir() => Err(std::io::Error::other("is a directory")),
        Ok(metadata) if !metadata.is_file() => Ok(Target::Special),
        Ok(metadata) => {
            let resolved = follow_links(path)?;
            // A link that does not lead to a path naming the same file (a /proc/self/fd link
            // to a deleted file, another mount namespace): the path cannot be renamed over,
            // so the file is written directly.
            let same = fs::metadata(&resolved).is_ok_and(|m| same_file(&m, &metadata));
            if same {
                Ok(Target::Regular {
                    resolved,
                    existing: Some(metadata),
                })
            } else {
                Ok(Target::Special)
            }
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(Target::Regular {
            // A dangling link creates the file it points to.
            resolved: follow_links(path)?,
            existing: None,
        }),
        Err(e) => Err(e),
    }
}

#[cfg(unix)]
fn same_file(a: &fs::Metadata, b: &fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt;
    (a.dev(), a.ino()) == (b.dev(), b.ino())
}

#[cfg(not(unix))]
fn same_file(_: &fs::Metadata, _: &fs::Metadata) -> bool {
    true
}

/// Follows symbolic links from `path` (at most 40, as Linux does) to the first path that is
/// not a link (or does not exist).
fn follow_links(path: &Path) -> std::io::Result<PathBuf> {
    let mut current = path.to_path_buf();
    for _ in 0..40 {
        match fs::symlink_metadata(&current) {
            Ok(m) if m.file_type().is_symlink() => {
                let target = fs::read_link(&current)?;
                current = match current.parent() {
                    Some(parent) if target.is_relative() => parent.join(target),
                    _ => target,
                };
            }
            Ok(_) => return Ok(current),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(current),
            Err(e) => return Err(e),
        }
    }
    Err(std::io::Error::other("too many levels of symbolic links"))
}

/// Refuses an existing regular file the user may not write (see [`write_atomically`]).
fn refuse_write_protected(path: &Path, resolved: &Path, metadata: &fs::Metadata) -> Result<()> {
    let refuse = |reason: String| Error::WriteProtected {
        path: path.to_path_buf(),
        reason,
    };
    if metadata.permissions().readonly() {
        return Err(refuse(mode_text(metadata)));
    }
    #[cfg(unix)]
    if let Err(e) = rustix::fs::access(resolved, rustix::fs::Access::WRITE_OK) {
        return Err(refuse(std::io::Error::from(e).to_string()));
    }
    let _ = resolved;
    Ok(())
}

#[cfg(unix)]
fn mode_text(metadata: &fs::Metadata) -> String {
    use std::os::unix::fs::PermissionsExt;
    format!(
        "it is read-only (mode {:o})",
        metadata.permissions().mode() & 0o7777
    )
}

#[cfg(not(unix))]
fn mode_text(_: &fs::Metadata) -> String {
    "it is read-only".to_string()
}

/// Writes to standard output through a duplicate of its descriptor (so `body` gets a
/// [`File`], and the shell's redirection, `>>` included, is kept).
#[cfg(unix)]
fn write_stdout(body: impl FnOnce(&mut File) -> std::io::Result<()>) -> std::io::Result<()> {
    use std::os::fd::AsFd;
    let stdout = std::io::stdout();
    // Whatever Rust buffered for stdout goes first.
    stdout.lock().flush()?;
    let mut file = File::from(stdout.as_fd().try_clone_to_owned()?);
    body(&mut file)?;
    file.flush()
}

#[cfg(not(unix))]
fn write_stdout(_: impl FnOnce(&mut File) -> std::io::Result<()>) -> std::io::Result<()> {
    Err(std::io::Error::other(
        "writing to standard output is supported on Unix only",
    ))
}

fn write_through_temporary(
    target: &Path,
    permissions: Option<fs::Permissions>,
    body: impl FnOnce(&mut File) -> std::io::Result<()>,
) -> std::io::Result<()> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let dir = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let file_name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name"))?;
    let prefix = short_prefix(&file_name, 24);
    install_signal_cleanup();
    let (temp_path, mut file) = loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let candidate = dir.join(format!(".{prefix}.{}.{n}.tmp", std::process::id()));
        // Registered before it exists, so a signal between creating and registering cannot
        // leave it behind.
        register_temporary(&candidate);
        match OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&candidate)
        {
            Ok(file) => break (candidate, file),
            Err(e) => {
                unregister_temporary(&candidate);
                if e.kind() == std::io::ErrorKind::AlreadyExists {
                    continue;
                }
                return Err(e);
            }
        }
    };
    let result = permissions
        .map_or(Ok(()), |p| file.set_permissions(p))
        .and_then(|()| with_early_writeback(&mut file, body))
        .and_then(|()| file.sync_all())
        .and_then(|()| {
            drop(file);
            fs::rename(&temp_path, target)
        });
    if result.is_err() {
        // Best effort: the temporary file may already be gone.
        let _ = fs::remove_file(&temp_path);
    }
    unregister_temporary(&temp_path);
    result
}

/// How often [`with_early_writeback`] looks at what has been written.
const WRITEBACK_POLL: std::time::Duration = std::time::Duration::from_millis(10);

/// The least new bytes [`with_early_writeback`] advises on at once: each advice also drains
/// the kernel's per-CPU page lists.
const WRITEBACK_MIN_BYTES: u64 = 8 << 20;

/// Runs `body` on `file` while a thread starts the kernel's writeback of what it has written
/// so far, every [`WRITEBACK_POLL`] once [`WRITEBACK_MIN_BYTES`] more are there
/// (`fadvise(DONTNEED)` on the new whole pages queues them for writing without waiting; the
/// kernel drops only pages already written back: 283 of the 296 MiB of a 310 MB OBJ were
/// still cached after the write), so that the `sync_all` after it waits for little more than the
/// last pages instead of the whole file. Advice only: the bytes written are the same with or
/// without it, and without a thread or a second handle the body runs alone.
#[cfg(target_os = "linux")]
fn with_early_writeback(
    file: &mut File,
    body: impl FnOnce(&mut File) -> std::io::Result<()>,
) -> std::io::Result<()> {
    use rustix::fs::{fadvise, Advice};
    use std::sync::mpsc::{channel, RecvTimeoutError};
    // Without a second handle the file is written as before, synced at the end.
    let Ok(watched) = file.try_clone() else {
        return body(file);
    };
    // Whole pages only: the last one may be half written.
    let page = rustix::param::page_size() as u64;
    let (done, finished) = channel::<()>();
    std::thread::scope(|scope| {
        let watcher = move || {
            let mut started = 0u64;
            while let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(WRITEBACK_POLL) {
                let Ok(metadata) = watched.metadata() else {
                    return;
                };
                let end = metadata.len() / page * page;
                if end >= started + WRITEBACK_MIN_BYTES {
                    let len = std::num::NonZeroU64::new(end - started);
                    // Advice: a failure changes nothing but when the pages are written.
                    let _ = fadvise(&watched, started, len, Advice::DontNeed);
                    started = end;
                }
            }
        };
        // No thread to spare (a process or memory limit): the body runs alone.
        let _spawned = std::thread::Builder::new()
            .name("writeback".into())
            .spawn_scoped(scope, watcher);
        let result = body(file);
        drop(done);
        result
    })
}

#[cfg(not(target_os = "linux"))]
fn with_early_writeback(
    file: &mut File,
    body: impl FnOnce(&mut File) -> std::io::Result<()>,
) -> std::io::Result<()> {
    body(file)
}

/// At most `max` bytes of `name`, cut at a character boundary.
fn short_prefix(name: &str, max: usize) -> &str {
    let mut end = name.len().min(max);
    while !name.is_char_boundary(end) {
        end -= 1;
    }
    &name[..end]
}

/// The temporary files being written now, which a signal removes.
fn live_temporaries() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
    LIVE.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn register_temporary(path: &Path) {
    live_temporaries().push(path.to_path_buf());
}

fn unregister_temporary(path: &Path) {
    let mut live = live_temporaries();
    if let Some(i) = live.iter().position(|p| p == path) {
        live.swap_remove(i);
    }
}

/// Installs, once, the thread that removes live temporary files on `SIGINT`, `SIGTERM` and
/// `SIGHUP` and then ends the process as the signal would have (signals the process ignores
/// are left alone). Without Unix signals, or when the handler cannot be installed, nothing
/// happens: writing still works, only the cleanup on a signal is missing.
fn install_signal_cleanup() {
    static INSTALLED: OnceLock<()> = OnceLock::new();
    INSTALLED.get_or_init(|| {
        #[cfg(unix)]
        {
            use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
            let ignored = ignored_signals();
            let wanted: Vec<i32> = [SIGINT, SIGTERM, SIGHUP]
                .into_iter()
                .filter(|&s| ignored & (1u64 << (s - 1)) == 0)
                .collect();
            let Ok(mut signals) = signal_hook::iterator::Signals::new(&wanted) else {
                return;
            };
            let spawned = std::thread::Builder::new()
                .name("temporary-file-cleanup".into())
                .spawn(move || {
                    if let Some(signal) = signals.forever().next() {
                        for path in live_temporaries().drain(..) {
                            let _ = fs::remove_file(path);
                        }
                        // Ends the process as the signal's default action does; should
                        // that fail, the exit status a shell would show.
                        let _ = signal_hook::low_level::emulate_default_handler(signal);
                        std::process::exit(128 + signal);
                    }
                });
            drop(spawned);
        }
    });
}

/// The mask of signals this process ignores (`SigIgn` of `/proc/self/status`; bit `s - 1`
/// for signal `s`), 0 when it cannot be read.
#[cfg(unix)]
fn ignored_signals() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|status| {
            let hex = status.lines().find_map(|l| l.strip_prefix("SigIgn:"))?;
            u64::from_str_radix(hex.trim(), 16).ok()
        })
        .unwrap_or(0)
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    fn temp_dir(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("halfedge-write-{name}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).expect("a temporary folder");
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir)
            .expect("listed")
            .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_write_protected_file_is_refused_and_left_intact() {
        use std::os::unix::fs::PermissionsExt;
        let dir = temp_dir("ro");
        let target = dir.join("ro.obj");
        fs::write(&target, "keep\n").expect("written");
        fs::set_permissions(&target, fs::Permissions::from_mode(0o444)).expect("chmod");
        let err = write_atomically(&target, |f| f.write_all(b"new\n")).unwrap_err();
        assert!(matches!(err, Error::WriteProtected { .. }), "{err:?}");
        assert_eq!(
            err.to_string(),
            format!(
                "{}: refusing to write over it: it is read-only (mode 444)",
                target.display()
            )
        );
        assert_eq!(fs::read_to_string(&target).expect("read"), "keep\n");
        assert_eq!(names(&dir), ["ro.obj"]);
        // The same refusal up front, before any work.
        let early = check_output(&target).unwrap_err();
        assert_eq!(early.to_string(), err.to_string());
        check_output(&dir.join("new.obj")).expect("a new file may be written");
        check_output(Path::new("-")).expect("stdout may be written");
        check_output(Path::new("/dev/null")).expect("a device may be written");
        fs::remove_dir_all(&dir).expect("cleanup");
    }

    #[test]
    fn a_symlink_is_written_through_and_the_mode_is_kept() {
        use std::os::unix::fs::PermissionsExt;
        let dir = temp_dir("link");
        fs::create_dir_all(dir.join("real")).expect("dir");
        let real = dir.join("real").join("mesh.obj");
        fs::write(&real, "old\n").expect("written");
        fs::set_permissions(&real, fs::Permissions::from_mode(0o640)).expect("chmod");
        let link = dir.join("link.obj");
        std::os::unix::fs::symlink("real/mesh.obj", &link).expect("link");
        // A chain of two links.
        let link2 = dir.join("link2.obj");
        std::os::unix::fs::symlink(&link, &link2).expect("link");
        write_atomically(&link2, |f| f.write_all(b"new\n")).expect("written");
        assert!(fs::symlink_metadata(&link)
            .expect("stat")
            .file_type()
            .is_symlink());
        assert!(fs::symlink_metadata(&link2)
            .expect("stat")
            .file_type()
            .is_symlink());
        assert_eq!(fs::read_to_string(&real).expect("read"), "new\n");
        let mode = fs::metadata(&real).expect("stat").permissions().mode() & 0o777;
        assert_eq!(mode, 0o640);
        assert_eq!(names(&dir.join("real")), ["mesh.obj"]);
        // A dangling link creates the file it names.
        let dangling = dir.join("dangling.obj");
        std::os::unix::fs::symlink("real/new.obj", &dangling).expect("link");
        write_atomically(&dangling, |f| f.write_all(b"made\n")).expect("written");
        assert_eq!(
            fs::read_to_string(dir.join("real/new.obj")).expect("read"),
            "made\n"
        );
        assert!(fs::symlink_metadata(&dangling)
            .expect("stat")
            .file_type()
            .is_symlink());
        fs::remove_dir_all(&dir).expect("cleanup");
    }

    #[test]
    fn special_files_are_written_directly() {
        // /dev/null is a character device: renaming over it would replace it.
        write_atomically(Path::new("/dev/null"), |f| f.write_all(b"gone\n")).expect("written");
        let meta = fs::symlink_metadata("/dev/null").expect("stat");
        assert!(!meta.is_file(), "/dev/null was replaced by a regular file");
        // A FIFO: a reader on the other end gets the bytes; the FIFO stays.
        let dir = temp_dir("fifo");
        let fifo = dir.join("pipe.obj");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            let reader = {
                let fifo = fifo.clone();
                std::thread::spawn(move || fs::read_to_string(fifo).expect("read"))
            };
            write_atomically(&fifo, |f| f.write_all(b"through\n")).expect("written");
            assert_eq!(reader.join().expect("joined"), "through\n");
            assert!(!fs::symlink_metadata(&fifo).expect("stat").is_file());
        }
        fs::remove_dir_all(&dir).expect("cleanup");
    }

    #[test]
    fn a_name_of_255_bytes_still_gets_a_temporary_file() {
        let dir = temp_dir("long");
        let name = format!("{}.obj", "é".repeat(125));
        assert_eq!(name.len(), 254);
        let target = dir.join(&name);
        write_atomically(&target, |f| f.write_all(b"ok\n")).expect("written");
        assert_eq!(fs::read_to_string(&target).expect("read"), "ok\n");
        assert_eq!(names(&dir), [name]);
        assert_eq!(short_prefix("éé", 3), "é");
        fs::remove_dir_all(&dir).expect("cleanup");
    }

    /// A file written slowly (24 MiB, the writeback advised several times on the way) has
    /// every byte in place, and an error of the body is the write's error. Integrity only:
    /// when the kernel writes the pages is not observable here.
    #[test]
    fn writing_while_the_writeback_starts_keeps_every_byte() {
        let dir = temp_dir("writeback");
        let target = dir.join("slow.bin");
        let block: Vec<u8> = (0..=255u8).cycle().take((1 << 20) + 17).collect();
        write_atomically(&target, |file| {
            for _ in 0..24 {
                file.write_all(&block)?;
                std::thread::sleep(WRITEBACK_POLL / 3);
            }
            Ok(())
        })
        .expect("written");
        assert_eq!(fs::read(&target).expect("read"), block.repeat(24));
        let err = write_atomically(&target, |file| {
            file.write_all(&block)?;
            std::thread::sleep(WRITEBACK_POLL * 2);
            Err(std::io::Error::other("the body failed"))
        })
        .unwrap_err();
        assert!(err.to_string().ends_with("the body failed"), "{err}");
        assert_eq!(fs::read(&target).expect("kept"), block.repeat(24));
        assert_eq!(names(&dir), ["slow.bin"]);
        fs::remove_dir_all(&dir).expect("cleanup");
    }

    #[test]
    fn a_directory_is_refused() {
        let dir = temp_dir("dir");
        let err = write_atomically(&dir, |f| f.write_all(b"x")).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("{}: is a directory", dir.display())
        );
        fs::remove_dir_all(&dir).expect("cleanup");
    }

    #[test]
    fn files_are_written_atomically() {
        let dir = temp_dir("atomic");
        let target = dir.join("out.obj");
        let options = ObjWriteOptions::default();
        let cube = HalfEdgeMesh::try_from(&halfedge::shapes::cube()).expect("valid");
        write_obj_file(&cube, &target, &options).expect("write");
        assert_eq!(halfedge::io::read_obj(&target).expect("read").n_faces(), 6);
        // Overwriting works too, and leaves only the target in the folder.
        let ico = halfedge::shapes::icosahedron();
        write_polygon_obj_file(&ico, &target, &options).expect("overwrite");
        assert_eq!(halfedge::io::read_obj(&target).expect("read").n_faces(), 20);
        assert_eq!(names(&dir), ["out.obj"]);
        // A failing rename (the target is a non-empty directory) leaves no temporary file.
        let blocked = dir.join("blocked.obj");
        fs::create_dir_all(blocked.join("inside")).expect("dir");
        let err = write_obj_file(&cube, &blocked, &options).unwrap_err();
        assert!(
            err.to_string()
                .starts_with(&format!("{}: ", blocked.display())),
            "{err}"
        );
        assert_eq!(names(&dir), ["blocked.obj", "out.obj"]);
        // A folder that does not exist: an error naming the file, nothing written.
        let err = write_obj_file(&cube, &dir.join("missing").join("x.obj"), &options);
        assert!(err.unwrap_err().to_string().contains("missing"));
        fs::remove_dir_all(&dir).expect("cleanup");
    }
}
