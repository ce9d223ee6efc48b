//! Times the mesh readers: `cargo run --release -p halfedge --example read_timing -- FILE... [-n RUNS]`.
//!
//! Each file is read `RUNS` times (default 5) by `halfedge::io::read_mesh_with` with the
//! default options and a memory limit of 64 GiB (as the CLI passes one); prints the median,
//! the minimum and the rate in MB/s (file bytes / median seconds).
//!
//! With `--dump`, each file is read once with several options instead (tags or not, memory
//! limits from 1 KiB up) and a line per read printed: the error, or a hash of the whole
//! `PolygonMesh`'s `Debug` text (every field: positions, faces, face lines, tags, UVs, groups,
//! colors, what is not carried). Two builds of the readers agree when their dumps do.
//!
//! With `--threshold`, prints for each file the least memory limit (`available_bytes`) it is
//! read within, found by bisection: where the memory budget starts to refuse it.

use std::time::Instant;

use halfedge::io::{read_mesh_with, ReadOptions};

fn main() {
    let mut runs = 5usize;
    let mut dump = false;
    let mut threshold = false;
    let mut files = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "--dump" {
            dump = true;
        } else if arg == "--threshold" {
            threshold = true;
        } else if arg == "-n" {
            runs = args.next().and_then(|n| n.parse().ok()).expect("-n RUNS");
        } else {
            files.push(arg);
        }
    }
    let options = ReadOptions::default().with_available_bytes(Some(64 << 30));
    if threshold {
        for file in &files {
            let read = |available| {
                let options = ReadOptions::default().with_available_bytes(Some(available));
                read_mesh_with(file, &options).is_ok()
            };
            let (mut low, mut high) = (0u64, 1u64 << 40);
            if !read(high) {
                println!("{file}: not read");
                continue;
            }
            while high - low > 1 {
                let mid = low + (high - low) / 2;
                if read(mid) {
                    high = mid;
                } else {
                    low = mid;
                }
            }
            println!("{file}: read within {high} bytes");
        }
        return;
    }
    if dump {
        files.iter().for_each(|f| dump_file(f));
        return;
    }
    for file in files {
        let bytes = std::fs::metadata(&file).map(|m| m.len()).unwrap_or(0);
        let mut times = Vec::new();
        let mut cpu = Vec::new();
        let mut faces = 0;
        for _ in 0..runs {
            let (start, start_cpu) = (Instant::now(), cpu_seconds());
            let mesh = read_mesh_with(&file, &options).expect("readable mesh");
            times.push(start.elapsed().as_secs_f64());
            cpu.push(cpu_seconds() - start_cpu);
            faces = mesh.n_faces();
            drop(mesh);
        }
        times.sort_by(f64::total_cmp);
        cpu.sort_by(f64::total_cmp);
        let median = times[times.len() / 2];
        println!(
            "{file}: {faces} faces, {bytes} bytes: median {median:.3} s, min {:.3} s, {:.0} MB/s; \
             on the CPU (this thread) median {:.3} s",
            times[0],
            bytes as f64 / median / 1e6,
            cpu[cpu.len() / 2]
        );
    }
}

/// The time this thread has run on a CPU (Linux's `/proc/thread-self/schedstat`; 0 elsewhere):
/// on a shared machine, what the read cost apart from waiting for a core.
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(0.0, |ns| ns / 1e9)
}

/// A hasher fed by `write!`.
struct HashWriter(std::collections::hash_map::DefaultHasher);

impl std::fmt::Write for HashWriter {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        std::hash::Hasher::write(&mut self.0, s.as_bytes());
        Ok(())
    }
}

fn dump_file(file: &str) {
    use std::fmt::Write;
    let size = std::fs::metadata(file).map(|m| m.len()).unwrap_or(0);
    let mut limits: Vec<Option<u64>> = vec![None];
    let mut limit = 1024u64;
    while limit < size.saturating_mul(8) {
        limits.push(Some(limit));
        limit *= 4;
    }
    // Limits above the file's size, where the mesh outgrows half of them part way.
    limits.extend([5, 6, 8, 12, 16].map(|k| Some(size * k / 4)));
    for tags in [true, false] {
        for &available in &limits {
            let options = if tags {
                ReadOptions::default()
            } else {
                ReadOptions::without_tags()
            };
            let options = options.with_available_bytes(available);
            let what = match read_mesh_with(file, &options) {
                Ok(mesh) => {
                    let mut h = HashWriter(Default::default());
                    write!(h, "{mesh:?}").expect("hashed");
                    let lines: Vec<Option<u64>> =
                        (0..mesh.n_faces()).map(|f| mesh.face_line(f)).collect();
                    write!(h, "{lines:?}").expect("hashed");
                    format!(
                        "ok {} vertices {} faces {:016x}",
                        mesh.n_vertices(),
                        mesh.n_faces(),
                        std::hash::Hasher::finish(&h.0)
                    )
                }
                Err(e) => format!("error {e} | {e:?}"),
            };
            println!("{file} tags={tags} available={available:?}: {what}");
        }
    }
}
