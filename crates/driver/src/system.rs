//! What the system tells about this process's memory: the bytes it may still allocate
//! ([`available_bytes`]: `/proc/meminfo`, `RLIMIT_AS`, cgroup limits), the half of them the
//! memory guards allow ([`peak_limit`]) and the peak resident set ([`peak_resident_bytes`]).
//!
//! The geometry kernel (`halfedge`) only predicts sizes (`halfedge::memory`); what those
//! predictions are compared with is read here, by the front ends' layer.

/// Half the memory this process may still allocate ([`available_bytes`]), or half of 8 GiB
/// when nothing tells: the limit of the memory guards
/// ([`halfedge::memory::within_limit`]).
pub fn peak_limit() -> u128 {
    u128::from(available_bytes().unwrap_or(8 << 30)) / 2
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
/// if let Some(bytes) = driver::system::available_bytes() {
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
/// if let Some(peak) = driver::system::peak_resident_bytes() {
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
