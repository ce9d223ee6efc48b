//! CPU time of subdivision jobs, for a shared machine where wall time is noise.
//!
//! For each job this runs the subdivision `REPS` times (default 5, `SUBCOUNT_BENCH_REPS`) on
//! the calling thread (and once more with 2 threads) and prints the median wall time, the median
//! on-CPU time of the thread (from
//! `/proc/thread-self/schedstat`, nanoseconds; it excludes time spent waiting for a CPU) and
//! the user/system split of the process (from `/proc/self/stat`, clock ticks), with output
//! faces per CPU-second. The first argument that is not a flag filters the job names
//! (`loop-L3/icosphere/prealloc-1t` style, as in the criterion bench `subdivide`):
//!
//! ```text
//! cargo bench -p halfedge --bench subdivide_cpu -- loop-L3
//! ```
//!
//! Linux only (it prints a notice and exits elsewhere).

use std::time::Instant;

use halfedge::subdivide::{
    direct_face_degree, subdivide, subdivide_to_face_list, Rule, SubdivideOptions,
};
use halfedge::{shapes, HalfEdgeMesh};

/// On-CPU nanoseconds of the calling thread.
fn thread_cpu_ns() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    text.split_whitespace().next()?.parse().ok()
}

/// (user, system) clock ticks of the process.
fn process_ticks() -> Option<(u64, u64)> {
    let text = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name in parentheses; utime and stime are fields 14 and 15.
    let rest = text.rsplit_once(')')?.1;
    let mut fields = rest.split_whitespace().skip(11);
    Some((fields.next()?.parse().ok()?, fields.next()?.parse().ok()?))
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

fn main() {
    if thread_cpu_ns().is_none() || process_ticks().is_none() {
        eprintln!("no /proc/thread-self/schedstat or /proc/self/stat: nothing to measure here");
        return;
    }
    let filter = std::env::args()
        .skip(1)
        .find(|a| !a.starts_with('-'))
        .unwrap_or_default();
    let reps: usize = std::env::var("SUBCOUNT_BENCH_REPS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(5);
    let ico = HalfEdgeMesh::try_from(&shapes::icosahedron()).expect("the icosahedron is valid");
    let sphere = subdivide(&ico, Rule::Icosphere, 6, &SubdivideOptions::default())
        .expect("the icosahedron subdivides");
    let mut inputs = vec![("icosphere".to_owned(), sphere)];
    match std::env::var_os(testdata::VAR) {
        Some(_) => {
            let poly = halfedge::io::read_mesh(testdata::mesh("armadillo.obj"))
                .expect("armadillo.obj loads");
            inputs.push((
                "armadillo".to_owned(),
                HalfEdgeMesh::try_from(&poly).expect("armadillo is a half-edge mesh"),
            ));
        }
        None => eprintln!("SUBCOUNT_MESHES is unset: the generated icosphere only"),
    }
    let jobs = [
        (Rule::Loop, 3),
        (Rule::CatmullClark, 3),
        (Rule::Loop, 2),
        (Rule::CatmullClark, 2),
        (Rule::Sqrt3, 2),
        (Rule::DooSabin, 2),
    ];
    // (name, threads, last level as a face list); with 2 threads the thread
    // CPU column is the calling thread only, the process user/sys columns count both workers.
    // The face-list variants run `subdivide_to_face_list` (what `subcount subdivide` runs)
    // for the schemes that write their last level straight into a face list.
    let variants = [
        ("prealloc-1t", 1, false),
        ("prealloc-2t", 2, false),
        ("faces-1t", 1, true),
        ("faces-2t", 2, true),
    ];
    let ticks_per_s = 100.0; // USER_HZ on Linux
    println!(
        "job | median wall s | median thread CPU s | process user/sys s per run | M faces per thread-CPU-s | M faces per process-CPU-s"
    );
    for (name, mesh) in &inputs {
        for (scheme, level) in jobs {
            for (variant, threads, face_list) in variants {
                let id = format!("{scheme}-L{level}/{name}/{variant}");
                if !id.contains(&filter) || face_list && direct_face_degree(scheme).is_none() {
                    continue;
                }
                let opts = SubdivideOptions::default().with_threads(threads);
                let (mut cpu, mut wall) = (Vec::new(), Vec::new());
                let (u0, s0) = process_ticks().unwrap_or_default();
                let mut faces = 0;
                for _ in 0..reps {
                    let c0 = thread_cpu_ns().unwrap_or_default();
                    let t0 = Instant::now();
                    if face_list {
                        let out = subdivide_to_face_list(mesh, scheme, level, &opts)
                            .expect("the job applies");
                        wall.push(t0.elapsed().as_secs_f64());
                        cpu.push((thread_cpu_ns().unwrap_or_default() - c0) as f64 * 1e-9);
                        faces = out.mesh.n_faces();
                    } else {
                        let out = subdivide(mesh, scheme, level, &opts).expect("the job applies");
                        wall.push(t0.elapsed().as_secs_f64());
                        cpu.push((thread_cpu_ns().unwrap_or_default() - c0) as f64 * 1e-9);
                        faces = out.n_faces();
                    }
                }
                let (u1, s1) = process_ticks().unwrap_or_default();
                let per_run = |a: u64, b: u64| (b - a) as f64 / ticks_per_s / reps as f64;
                let cpu_med = median(cpu);
                let (user, sys) = (per_run(u0, u1), per_run(s0, s1));
                // With a pool the calling thread only waits: no per-thread rate.
                let thread_rate = if threads == 1 {
                    format!("{:.2}", faces as f64 / cpu_med / 1e6)
                } else {
                    "-".to_owned()
                };
                println!(
                    "{id} | {:.4} | {cpu_med:.4} | {user:.3}/{sys:.3} | {thread_rate} | {:.2}",
                    median(wall),
                    faces as f64 / (user + sys) / 1e6
                );
            }
        }
    }
}
