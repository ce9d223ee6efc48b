//! Times the half-edge build: `cargo run --release -p halfedge --example build_timing -- FILE [-n RUNS]`.
//!
//! Reads the file once, then builds the half-edge mesh from it (`try_from_polygon_mesh`) and
//! reads its counts (`HalfEdgeMesh::counts`, kept by the build since issue 30: a copy)
//! `RUNS` times each (default 5); prints the median and
//! the minimum of each, and a hash of the mesh built and of its counts (two builds agree when
//! their hashes do).

use std::hash::{Hash, Hasher};
use std::time::Instant;

use halfedge::io::{read_mesh_with, ReadOptions};
use halfedge::HalfEdgeMesh;

fn main() {
    let mut runs = 5usize;
    let mut file = None;
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        if arg == "-n" {
            runs = args.next().and_then(|n| n.parse().ok()).expect("-n RUNS");
        } else {
            file = Some(arg);
        }
    }
    let file = file.expect("a mesh file");
    let options = ReadOptions::default().with_available_bytes(Some(64 << 30));
    let poly = read_mesh_with(&file, &options).expect("readable mesh");
    let read_peak = peak_kib();
    let (mut build, mut count, mut cpu) = (Vec::new(), Vec::new(), Vec::new());
    let mut hashes = None;
    for _ in 0..runs {
        let (start, start_cpu) = (Instant::now(), cpu_seconds());
        let mesh = HalfEdgeMesh::try_from_polygon_mesh(&poly);
        build.push(start.elapsed().as_secs_f64());
        cpu.push(cpu_seconds() - start_cpu);
        let mesh = mesh.expect("valid mesh");
        let start = Instant::now();
        let counts = mesh.counts();
        count.push(start.elapsed().as_secs_f64());
        hashes.get_or_insert_with(|| (mesh_hash(&mesh), hash(&format!("{counts:?}"))));
    }
    let (mesh_hash, counts_hash) = hashes.unwrap_or_default();
    println!(
        "{file}: peak resident set {read_peak} KiB after the read, {} KiB after the builds",
        peak_kib()
    );
    let builds = [("build", &mut build), ("build on the CPU", &mut cpu)];
    for (what, times) in builds.into_iter().chain([("counts", &mut count)]) {
        times.sort_by(f64::total_cmp);
        println!(
            "{file}: {what}: median {:.3} s, min {:.3} s",
            times[times.len() / 2],
            times[0]
        );
    }
    println!("{file}: mesh {mesh_hash:016x}, counts {counts_hash:016x}");
}

/// The time this thread has run on a CPU (Linux's `/proc/thread-self/schedstat`; 0 elsewhere).
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(0.0, |ns| ns / 1e9)
}

/// The peak resident set so far (`VmHWM` of `/proc/self/status`; 0 elsewhere).
fn peak_kib() -> u64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .unwrap_or(0)
}

/// Every array of the mesh, through its accessors.
fn mesh_hash(mesh: &HalfEdgeMesh) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for p in mesh.positions() {
        p.to_array().map(f64::to_bits).hash(&mut h);
    }
    for v in mesh.vertices() {
        mesh.vertex_halfedge(v).0.hash(&mut h);
    }
    for e in mesh.halfedges() {
        let face = mesh.face(e).map(|f| f.0);
        (mesh.to_vertex(e).0, face, mesh.next(e).0, mesh.prev(e).0).hash(&mut h);
    }
    for f in mesh.faces() {
        mesh.face_halfedge(f).0.hash(&mut h);
    }
    mesh.unreferenced_vertices().hash(&mut h);
    h.finish()
}

fn hash(text: &str) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    text.hash(&mut h);
    h.finish()
}
