//! Memory for the resource guards: how many bytes a [`HalfEdgeMesh`] occupies, exactly and from
//! predicted counts, the peak a subdivision will need ([`predicted_peak_bytes`]), and how many
//! bytes this process may still allocate ([`available_bytes`]), so that a subdivision, a base
//! mesh or a mesh file is refused before it is built.

use num_bigint::BigInt;
use num_traits::ToPrimitive;
use schemes::{MeshCounts, Scheme};

use crate::{HalfEdgeMesh, PolygonMesh};

/// Bytes per vertex: a `DVec3` position (24) and one outgoing half-edge (`u32`, 4).
pub const BYTES_PER_VERTEX: u64 = 24 + 4;
/// Bytes per edge: two half-edges, each with target vertex, face, next and prev (`u32` each).
pub const BYTES_PER_EDGE: u64 = 2 * 4 * 4;
/// Bytes per face: one half-edge (`u32`).
pub const BYTES_PER_FACE: u64 = 4;

impl HalfEdgeMesh {
    /// The bytes of the arrays of a mesh with `vertices`, `edges` and `faces` elements
    /// (exact for this crate's layout; capacity equals length when preallocated).
    ///
    /// ```
    /// use halfedge::HalfEdgeMesh;
    /// let ico = HalfEdgeMesh::try_from(&halfedge::shapes::icosahedron())?;
    /// assert_eq!(ico.heap_bytes() as u128, HalfEdgeMesh::bytes_for(12, 30, 20));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn bytes_for(vertices: u64, edges: u64, faces: u64) -> u128 {
        u128::from(vertices) * u128::from(BYTES_PER_VERTEX)
            + u128::from(edges) * u128::from(BYTES_PER_EDGE)
            + u128::from(faces) * u128::from(BYTES_PER_FACE)
    }

    /// The bytes this mesh's arrays occupy (their lengths; see [`bytes_for`](Self::bytes_for)).
    pub fn heap_bytes(&self) -> usize {
        self.positions.len() * std::mem::size_of::<glam::DVec3>()
            + (self.vertex_halfedge.len()
                + self.halfedge_vertex.len()
                + self.halfedge_face.len()
                + self.halfedge_next.len()
                + self.halfedge_prev.len()
                + self.face_halfedge.len())
                * std::mem::size_of::<u32>()
    }
}

impl PolygonMesh {
    /// The bytes of the arrays of a face list with `vertices` positions (a `DVec3`, 24 bytes
    /// each), `faces` faces (one `usize` offset each, plus one) and `corners` face corners in
    /// all (a `u32` each), as [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list)
    /// builds it (no file lines).
    ///
    /// ```
    /// use halfedge::PolygonMesh;
    /// let cube = halfedge::shapes::cube();
    /// assert_eq!(cube.heap_bytes() as u128, PolygonMesh::bytes_for(8, 6, 24));
    /// ```
    pub fn bytes_for(vertices: u64, faces: u64, corners: u64) -> u128 {
        u128::from(vertices) * 24
            + (u128::from(faces) + 1) * std::mem::size_of::<usize>() as u128
            + u128::from(corners) * 4
    }

    /// The bytes this face list's arrays occupy (their lengths, file lines included; see
    /// [`bytes_for`](Self::bytes_for)).
    pub fn heap_bytes(&self) -> usize {
        std::mem::size_of_val(self.positions.as_slice())
            + std::mem::size_of_val(self.face_offsets())
            + std::mem::size_of_val(self.face_indices())
            + self.face_lines_len() * std::mem::size_of::<u64>()
    }
}

/// The bytes a subdivision of a mesh with `counts` by `scheme` to level `levels` needs at its
/// peak, from the scheme's exact counts: the input mesh plus the two levels alive at once at the
/// end (levels `levels - 1` and `levels`, the largest two; only level 1 when `levels = 1`; only
/// the input when `levels = 0`). With `last_faces = Some(d)` the last level is a face list of
/// `d`-gons as [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list) builds it
/// ([`PolygonMesh::bytes_for`]), else a half-edge mesh ([`HalfEdgeMesh::bytes_for`]). Computed
/// on big integers, so a level far beyond any memory is a number, not an overflow.
///
/// # Errors
///
/// The scheme's error when `counts` are outside its class ([`Scheme::counts_at`]).
///
/// ```
/// use halfedge::memory::predicted_peak_bytes;
/// use halfedge::HalfEdgeMesh;
/// let ico = HalfEdgeMesh::try_from(&halfedge::shapes::icosahedron())?;
/// let loop_ = schemes::builtin("loop")?;
/// let peak = predicted_peak_bytes(&loop_, &ico.counts(), 2, None)?;
/// let levels = [(12, 30, 20), (42, 120, 80), (162, 480, 320)];
/// let sum: u128 = levels.iter().map(|&(v, e, f)| HalfEdgeMesh::bytes_for(v, e, f)).sum();
/// assert_eq!(peak, sum.into());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn predicted_peak_bytes(
    scheme: &Scheme,
    counts: &MeshCounts,
    levels: u32,
    last_faces: Option<usize>,
) -> Result<BigInt, schemes::Error> {
    let bytes = |s: u64| -> Result<BigInt, schemes::Error> {
        let c = scheme.counts_at(counts, s)?;
        Ok(BigInt::from(BYTES_PER_VERTEX) * &c.vertices
            + BigInt::from(BYTES_PER_EDGE) * &c.edges
            + BigInt::from(BYTES_PER_FACE) * &c.faces)
    };
    let input = bytes(0)?;
    if levels == 0 {
        return Ok(input);
    }
    let last = match last_faces {
        Some(degree) => {
            // PolygonMesh::bytes_for on big integers: 24 per position, one `usize` per face
            // offset (one more than the faces), 4 per corner.
            let c = scheme.counts_at(counts, u64::from(levels))?;
            BigInt::from(24) * &c.vertices
                + BigInt::from(std::mem::size_of::<usize>()) * (&c.faces + 1)
                + BigInt::from(4 * degree) * &c.faces
        }
        None => bytes(u64::from(levels))?,
    };
    Ok(if levels == 1 {
        input + last
    } else {
        input + bytes(u64::from(levels) - 1)? + last
    })
}

/// Half the memory this process may still allocate ([`available_bytes`]), or half of 8 GiB
/// when nothing tells: the budget of [`check_peak`].
pub fn peak_limit() -> u128 {
    u128::from(available_bytes().unwrap_or(8 << 30)) / 2
}

/// The memory guard of real subdivision: [`predicted_peak_bytes`] of `scheme` to `levels`,
/// refused with [`Error::OverMemoryLimit`](crate::Error::OverMemoryLimit) when it exceeds `limit` (e.g. [`peak_limit`]).
///
/// # Errors
///
/// [`Error::OverMemoryLimit`](crate::Error::OverMemoryLimit), or [`Error::Scheme`](crate::Error::Scheme) when the scheme does not apply.
///
/// ```
/// use halfedge::memory::check_peak;
/// let ico = halfedge::stats::face_list_counts(&halfedge::shapes::icosahedron());
/// let lp = schemes::builtin("loop")?;
/// assert!(check_peak(&lp, &ico, 5, None, 1 << 30).is_ok());
/// let err = check_peak(&lp, &ico, 12, None, 1 << 30).unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "loop to level 12 needs about 25.8 GiB of memory (levels 11 and 12 with the input), more than the limit of 1.0 GiB (half the available memory)"
/// );
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn check_peak(
    scheme: &Scheme,
    counts: &MeshCounts,
    levels: u32,
    last_faces: Option<usize>,
    limit: u128,
) -> crate::Result<BigInt> {
    let need = predicted_peak_bytes(scheme, counts, levels, last_faces)?;
    within_limit(need, scheme.name(), levels, limit)
}

/// The peak of refining once ([`crate::Refinement`]) by `rule` to `levels` and evaluating
/// positions of `scalar_bytes` per coordinate into caller buffers: the larger of the one-shot
/// peak of building the levels ([`predicted_peak_bytes`], last level as a face list) and the
/// input, the refinement kept ([`crate::Refinement::predicted_bytes`]) and the output
/// positions and indices (with `frames`, a moved copy of the base and a second output buffer).
///
/// # Errors
///
/// [`Error::Scheme`](crate::Error::Scheme) when the rule does not apply.
pub fn predicted_refinement_peak_bytes(
    rule: crate::Rule,
    counts: &MeshCounts,
    levels: u32,
    scalar_bytes: usize,
    frames: bool,
) -> crate::Result<BigInt> {
    let scheme = rule.scheme_for(counts)?;
    let building = predicted_peak_bytes(&scheme, counts, levels, Some(4))?;
    let kept = crate::Refinement::predicted_bytes(rule, counts, levels)?;
    let c = scheme.counts_at(counts, u64::from(levels))?;
    let point = BigInt::from(3 * scalar_bytes);
    let copies = if frames { 2 } else { 1 };
    let buffers = &point * &c.vertices * copies
        + BigInt::from(4 * 4) * &c.faces
        + &point * counts.vertices * u32::from(frames);
    // While levels are built the refinement's tables are filled level by level; afterwards
    // the refinement and the buffers are alive with the input: the larger of the two.
    let input = predicted_peak_bytes(&scheme, counts, 0, None)?;
    Ok(building.max(kept + buffers + input))
}

/// `need` if it is at most `limit`, else [`Error::OverMemoryLimit`](crate::Error::OverMemoryLimit)
/// naming `scheme` and `levels` (the test of [`check_peak`], for any prediction).
///
/// # Errors
///
/// [`Error::OverMemoryLimit`](crate::Error::OverMemoryLimit).
pub fn within_limit(need: BigInt, scheme: &str, levels: u32, limit: u128) -> crate::Result<BigInt> {
    if need > BigInt::from(limit) {
        return Err(crate::Error::OverMemoryLimit {
            scheme: scheme.to_owned(),
            levels,
            need: human_bytes(need.to_f64().unwrap_or(f64::INFINITY)),
            limit: human_bytes(limit as f64),
        });
    }
    Ok(need)
}

/// `1.5 GiB`-style rendering of a byte count (binary units, one decimal).
///
/// ```
/// use halfedge::memory::human_bytes;
/// assert_eq!(human_bytes(512.0), "512 bytes");
/// assert_eq!(human_bytes(1536.0), "1.5 KiB");
/// assert_eq!(human_bytes(f64::INFINITY), "10^30+ bytes");
/// ```
pub fn human_bytes(bytes: f64) -> String {
    if !bytes.is_finite() || bytes > 1e30 {
        return "10^30+ bytes".to_string();
    }
    const UNITS: [&str; 7] = ["bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut v = bytes;
    let mut unit = 0;
    while v >= 1024.0 && unit + 1 < UNITS.len() {
        v /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{v:.0} bytes")
    } else if v >= 1024.0 {
        format!("{:.3e} {}", v, UNITS[unit])
    } else {
        format!("{v:.1} {}", UNITS[unit])
    }
}

/// The bytes this process may still allocate, as far as Linux tells without `unsafe`: the
/// least of
///
/// - `MemAvailable` in `/proc/meminfo` (memory the kernel can give without swapping),
/// - the soft address-space limit (`RLIMIT_AS`, "Max address space" in `/proc/self/limits`,
///   as `ulimit -v` and `prlimit --as` set it) minus the address space in use (`VmSize` in
///   `/proc/self/status`),
/// - for the process's cgroup and each of its ancestors (from `/proc/self/cgroup`), the
///   limit minus the usage: `memory.max` minus `memory.current` under cgroup v2, and
///   `memory.limit_in_bytes` minus `memory.usage_in_bytes` under the v1 memory controller.
///
/// `None` when none of these can be read (not Linux, `/proc` not mounted); a limit that is
/// set to "unlimited" or cannot be read is left out.
///
/// ```
/// if let Some(bytes) = halfedge::memory::available_bytes() {
///     assert!(bytes < u64::MAX);
/// }
/// ```
pub fn available_bytes() -> Option<u64> {
    let read = |path: &str| std::fs::read_to_string(path).ok();
    let meminfo = read("/proc/meminfo").and_then(|t| mem_available(&t));
    let address_space = read("/proc/self/limits").and_then(|t| address_space_limit(&t));
    let in_use = read("/proc/self/status").and_then(|t| vm_size(&t));
    let rlimit = address_space.map(|limit| limit.saturating_sub(in_use.unwrap_or(0)));
    let cgroup = read("/proc/self/cgroup").and_then(|t| cgroup_room(&t, &|p| read(p)));
    [meminfo, rlimit, cgroup].into_iter().flatten().min()
}

/// The peak resident set size of this process (`VmHWM` of `/proc/self/status`), when the
/// system tells it: what `subcount subdivide --timings` reports as `peak_bytes`.
///
/// ```
/// if let Some(peak) = halfedge::memory::peak_resident_bytes() {
///     assert!(peak > 0);
/// }
/// ```
pub fn peak_resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    kilobytes_field(&status, "VmHWM:")
}

/// `MemAvailable` of `/proc/meminfo` text, in bytes.
fn mem_available(meminfo: &str) -> Option<u64> {
    kilobytes_field(meminfo, "MemAvailable:")
}

/// `VmSize` of `/proc/self/status` text, in bytes.
fn vm_size(status: &str) -> Option<u64> {
    kilobytes_field(status, "VmSize:")
}

fn kilobytes_field(text: &str, key: &str) -> Option<u64> {
    let kb: u64 = text
        .lines()
        .find_map(|l| l.strip_prefix(key))?
        .split_whitespace()
        .next()?
        .parse()
        .ok()?;
    kb.checked_mul(1024)
}

/// The soft "Max address space" limit of `/proc/self/limits` text, in bytes (`None` when
/// unlimited or missing).
fn address_space_limit(limits: &str) -> Option<u64> {
    let rest = limits
        .lines()
        .find_map(|l| l.strip_prefix("Max address space"))?;
    rest.split_whitespace().next()?.parse().ok()
}

/// The least room (limit minus usage) over the memory cgroups of `/proc/self/cgroup` text
/// and their ancestors; `read` reads a file of `/sys/fs/cgroup`.
fn cgroup_room(cgroups: &str, read: &dyn Fn(&str) -> Option<String>) -> Option<u64> {
    let number = |text: Option<String>| text.and_then(|t| t.trim().parse::<u64>().ok());
    let mut least: Option<u64> = None;
    for line in cgroups.lines() {
        let mut fields = line.splitn(3, ':');
        let (Some(id), Some(controllers), Some(path)) =
            (fields.next(), fields.next(), fields.next())
        else {
            continue;
        };
        // (mount folders, limit file, usage file) for a v2 line or the v1 memory controller.
        let (mounts, limit, usage): (&[&str], _, _) = if id == "0" && controllers.is_empty() {
            (
                &["/sys/fs/cgroup", "/sys/fs/cgroup/unified"],
                "memory.max",
                "memory.current",
            )
        } else if controllers.split(',').any(|c| c == "memory") {
            (
                &["/sys/fs/cgroup/memory"],
                "memory.limit_in_bytes",
                "memory.usage_in_bytes",
            )
        } else {
            continue;
        };
        for mount in mounts {
            // The cgroup and each ancestor up to the mount's root (inside a container the
            // path may name a folder the mount does not show: its ancestors still count).
            let mut dir = path.trim_end_matches('/').to_string();
            loop {
                let folder = format!("{mount}{dir}");
                // "max" (v2) does not parse: no limit at this level.
                if let (Some(l), Some(u)) = (
                    number(read(&format!("{folder}/{limit}"))),
                    number(read(&format!("{folder}/{usage}"))),
                ) {
                    let room = l.saturating_sub(u);
                    least = Some(least.map_or(room, |x| x.min(room)));
                }
                match dir.rfind('/') {
                    Some(i) => dir.truncate(i),
                    None => break,
                }
            }
        }
    }
    least
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_predicted_peak_is_what_subdivision_allocates() {
        use crate::subdivide::{subdivide, subdivide_to_face_list, SubdivideOptions};
        let cube = HalfEdgeMesh::try_from(&crate::shapes::cube()).expect("cube");
        let cc = schemes::builtin("catmull-clark").expect("catmull-clark");
        let opts = SubdivideOptions::default();
        let bytes = |m: &HalfEdgeMesh| BigInt::from(m.heap_bytes());
        let peak = |levels, last| predicted_peak_bytes(&cc, &cube.counts(), levels, last);
        let l1 = subdivide(&cube, crate::Rule::CatmullClark, 1, &opts).expect("level 1");
        let l2 = subdivide(&cube, crate::Rule::CatmullClark, 2, &opts).expect("level 2");
        assert_eq!(peak(0, None).expect("0"), bytes(&cube));
        assert_eq!(peak(1, None).expect("1"), bytes(&cube) + bytes(&l1));
        assert_eq!(
            peak(2, None).expect("2"),
            bytes(&cube) + bytes(&l1) + bytes(&l2)
        );
        // The last level as a face list of quads: no face lines, so heap_bytes is exact.
        let faces =
            subdivide_to_face_list(&cube, crate::Rule::CatmullClark, 2, &opts).expect("faces");
        assert_eq!(
            peak(2, Some(4)).expect("2 as faces"),
            bytes(&cube) + bytes(&l1) + BigInt::from(faces.mesh.heap_bytes())
        );
        // Far beyond any memory: a number, not an overflow.
        assert!(peak(60, None).expect("60") > BigInt::from(u128::MAX));
    }

    #[test]
    fn the_predicted_peak_refuses_counts_outside_the_scheme() {
        let cube = HalfEdgeMesh::try_from(&crate::shapes::cube()).expect("cube");
        let loop_ = schemes::builtin("loop").expect("loop");
        let err = predicted_peak_bytes(&loop_, &cube.counts(), 1, None).unwrap_err();
        assert!(err.to_string().contains("triangle"), "{err}");
    }

    #[test]
    fn proc_files_are_parsed() {
        let meminfo = "MemTotal:       24000000 kB\nMemAvailable:   3000000 kB\n";
        assert_eq!(mem_available(meminfo), Some(3_000_000 * 1024));
        let limits = "Limit                     Soft Limit           Hard Limit           Units     \n\
                      Max stack size            8388608              unlimited            bytes     \n\
                      Max address space         2000000000           unlimited            bytes     \n";
        assert_eq!(address_space_limit(limits), Some(2_000_000_000));
        let unlimited =
            "Max address space         unlimited            unlimited            bytes\n";
        assert_eq!(address_space_limit(unlimited), None);
        assert_eq!(
            vm_size("Name:\tx\nVmSize:\t    3892 kB\n"),
            Some(3892 * 1024)
        );
    }

    #[test]
    fn the_tightest_cgroup_on_the_path_counts() {
        let files = |path: &str| -> Option<String> {
            Some(
                match path {
                    "/sys/fs/cgroup/a/b/memory.max" => "max\n",
                    "/sys/fs/cgroup/a/b/memory.current" => "100\n",
                    "/sys/fs/cgroup/a/memory.max" => "1000\n",
                    "/sys/fs/cgroup/a/memory.current" => "400\n",
                    "/sys/fs/cgroup/memory/memory.limit_in_bytes" => "9223372036854771712\n",
                    "/sys/fs/cgroup/memory/memory.usage_in_bytes" => "10\n",
                    _ => return None,
                }
                .to_string(),
            )
        };
        assert_eq!(cgroup_room("0::/a/b\n", &files), Some(600));
        // v1: the path is not visible, its root's limit still counts.
        assert_eq!(
            cgroup_room("4:memory:/x/y\n1:cpu:/\n", &files),
            Some(9223372036854771702)
        );
        assert_eq!(cgroup_room("1:cpu:/\n", &files), None);
    }

    #[test]
    fn this_process_has_a_figure() {
        // On Linux /proc/meminfo is always there.
        if std::path::Path::new("/proc/meminfo").exists() {
            assert!(available_bytes().is_some());
        }
    }
}
