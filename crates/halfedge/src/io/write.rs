//! OBJ writing, atomic for files.

use std::fs::{self, File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use glam::DVec3;

use crate::error::{Error, Result};
use crate::mesh::HalfEdgeMesh;
use crate::polygon::PolygonMesh;

/// Writes a mesh as OBJ text: one `v x y z` line per vertex, then one `f` line per face
/// (1-based indices, n-gons kept), nothing else.
///
/// Coordinates are written with Rust's shortest round-trip formatting, so reading the file
/// back gives the same `f64` values. The writer is wrapped in a `BufWriter` by this function.
///
/// # Errors
///
/// Any error of the writer.
///
/// # Example
///
/// ```
/// let mesh = halfedge::HalfEdgeMesh::try_from(&halfedge::shapes::tetrahedron())?;
/// let mut out = Vec::new();
/// halfedge::io::write_obj(&mesh, &mut out)?;
/// let text = String::from_utf8(out)?;
/// assert_eq!(text.lines().filter(|l| l.starts_with("f ")).count(), 4);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_obj(mesh: &HalfEdgeMesh, writer: impl Write) -> std::io::Result<()> {
    write_faces(
        mesh.positions(),
        mesh.faces().map(|f| mesh.face_vertices(f).map(|v| v.0)),
        writer,
    )
}

/// Writes a face list as OBJ text, like [`write_obj`] (every position is written, used or
/// not, so indices are kept).
///
/// # Errors
///
/// Any error of the writer.
pub fn write_polygon_obj(mesh: &PolygonMesh, writer: impl Write) -> std::io::Result<()> {
    write_faces(
        &mesh.positions,
        mesh.faces().map(|f| f.iter().copied()),
        writer,
    )
}

/// Writes a mesh to an OBJ file atomically: the text goes to a temporary file in the same
/// folder, which is renamed over `path` only once it is complete and synced; on any error the
/// temporary file is removed and `path` is untouched.
///
/// # Errors
///
/// [`Error::Io`] naming the file.
pub fn write_obj_file(mesh: &HalfEdgeMesh, path: impl AsRef<Path>) -> Result<()> {
    write_atomically(path.as_ref(), |file| write_obj(mesh, file))
}

/// Writes a face list to an OBJ file atomically, like [`write_obj_file`].
///
/// # Errors
///
/// [`Error::Io`] naming the file.
pub fn write_polygon_obj_file(mesh: &PolygonMesh, path: impl AsRef<Path>) -> Result<()> {
    write_atomically(path.as_ref(), |file| write_polygon_obj(mesh, file))
}

fn write_faces<F, I>(positions: &[DVec3], faces: F, writer: impl Write) -> std::io::Result<()>
where
    F: Iterator<Item = I>,
    I: Iterator<Item = u32>,
{
    let mut w = BufWriter::with_capacity(1 << 16, writer);
    for p in positions {
        writeln!(w, "v {:?} {:?} {:?}", p.x, p.y, p.z)?;
    }
    for face in faces {
        w.write_all(b"f")?;
        for v in face {
            write!(w, " {}", u64::from(v) + 1)?;
        }
        w.write_all(b"\n")?;
    }
    w.flush()
}

/// Writes `path` atomically: `body` fills a temporary file in the same folder, which is then renamed over `path`.
pub fn write_atomically(
    path: &Path,
    body: impl FnOnce(&mut File) -> std::io::Result<()>,
) -> Result<()> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let io_error = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let file_name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| {
            io_error(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "not a file name",
            ))
        })?;
    let (temp_path, mut file) = loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let candidate = dir.join(format!(".{file_name}.{}.{n}.tmp", std::process::id()));
        match OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&candidate)
        {
            Ok(file) => break (candidate, file),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(io_error(e)),
        }
    };
    let result = body(&mut file)
        .and_then(|()| file.sync_all())
        .and_then(|()| {
            drop(file);
            fs::rename(&temp_path, path)
        });
    if let Err(e) = result {
        // Best effort: the temporary file may already be gone.
        let _ = fs::remove_file(&temp_path);
        return Err(io_error(e));
    }
    Ok(())
}
