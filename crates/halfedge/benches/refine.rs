//! Refine once, evaluate many: the issue's per-frame and repeated one-shot targets.
//!
//! Input: the 81,920-face icosphere (the icosahedron after 6 levels of `icosphere`, built in
//! code as in `benches/subdivide.rs`). Jobs: Loop and Catmull-Clark at 3 levels.
//!
//! - `oneshot-SCHEME-L3/icosphere/Nt`: a repeated one-shot subdivision into the caller's
//!   buffers, reused between iterations (no fresh page faults): `Refinement::new`, one
//!   `evaluate` of the positions (`f64`) and `write_triangles` / `write_quads`, in `N`
//!   threads; throughput in output faces.
//! - `evaluate-SCHEME-L3/icosphere/{f64,f32}-Nt`: per-frame evaluation of the positions on a
//!   refinement built once (an `Evaluator`, so no allocation per frame); throughput in bytes
//!   written to the last level.
//! - `evaluate-SCHEME-L3/icosphere/memcpy-f64`: a `copy_from_slice` of the `f64` output size,
//!   in the same group: this machine's bandwidth reference.
//! - `creased-SCHEME-L3/icosphere/{new,f64}-1t`: the same jobs under crease rules (a closed
//!   chain of 1,000 edges of sharpness 2.5 and 100 corners of sharpness 1.5, so every level
//!   runs on weight tables): `Refinement::new` and a per-frame `f64` evaluation, one thread.
//!
//! ```text
//! cargo bench -p halfedge --bench refine -- 'evaluate-loop'
//! ```

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, SamplingMode, Throughput};
use halfedge::refine::{Refinement, Scalar};
use halfedge::subdivide::{subdivide, Sharpness, SubdivideOptions};
use halfedge::tags::Tags;
use halfedge::{shapes, HalfEdgeMesh, Rule};

const JOBS: [(&str, Rule, u32); 2] = [
    ("loop", Rule::Loop, 3),
    ("catmull-clark", Rule::CatmullClark, 3),
];
const THREADS: [usize; 2] = [1, 2];

fn icosphere() -> HalfEdgeMesh {
    let ico = HalfEdgeMesh::try_from(&shapes::icosahedron()).expect("the icosahedron is valid");
    let sphere = subdivide(&ico, Rule::Icosphere, 6, &SubdivideOptions::default())
        .expect("the icosahedron subdivides");
    assert_eq!(sphere.n_faces(), 81_920);
    sphere
}

fn configure(group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>) {
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
}

fn bench_oneshot(c: &mut Criterion, mesh: &HalfEdgeMesh) {
    let base: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
    for (name, rule, levels) in JOBS {
        let mut group = c.benchmark_group(format!("oneshot-{name}-L{levels}"));
        configure(&mut group);
        let probe = Refinement::new(mesh, rule, levels, &SubdivideOptions::default())
            .expect("the rule applies");
        let faces = probe.n_faces(levels);
        let degree = probe.face_degree().expect("uniform faces");
        group.throughput(Throughput::Elements(faces as u64));
        let mut positions = vec![[0.0f64; 3]; probe.n_vertices(levels)];
        let mut indices = vec![0u32; degree * faces];
        drop(probe);
        for threads in THREADS {
            let opts = SubdivideOptions::default().with_threads(threads);
            let id = BenchmarkId::new("icosphere", format!("{threads}t"));
            group.bench_function(id, |b| {
                b.iter(|| {
                    let r = Refinement::new(mesh, rule, levels, &opts).expect("applies");
                    r.evaluate(&base, &mut positions).expect("sizes");
                    if degree == 3 {
                        r.write_triangles(&mut indices).expect("triangles");
                    } else {
                        r.write_quads(&mut indices).expect("quads");
                    }
                    r
                })
            });
        }
        group.finish();
    }
}

fn evaluate_variant<T: Scalar>(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    r: &Refinement,
    base: &[[f64; 3]],
    label: &str,
) {
    let base: Vec<[T; 3]> = base.iter().map(|p| p.map(T::from_f64)).collect();
    let mut out = vec![[T::ZERO; 3]; r.n_vertices(r.levels())];
    let mut evaluator = r.evaluator::<T, 3>();
    let id = BenchmarkId::new("icosphere", label);
    group.bench_function(id, |b| {
        b.iter(|| evaluator.evaluate(&base, &mut out).expect("sizes"))
    });
}

fn bench_evaluate(c: &mut Criterion, mesh: &HalfEdgeMesh) {
    let base: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
    for (name, rule, levels) in JOBS {
        let mut group = c.benchmark_group(format!("evaluate-{name}-L{levels}"));
        configure(&mut group);
        for threads in THREADS {
            let opts = SubdivideOptions::default().with_threads(threads);
            let r = Refinement::new(mesh, rule, levels, &opts).expect("the rule applies");
            let n = r.n_vertices(levels);
            group.throughput(Throughput::Bytes((n * 24) as u64));
            evaluate_variant::<f64>(&mut group, &r, &base, &format!("f64-{threads}t"));
            group.throughput(Throughput::Bytes((n * 12) as u64));
            evaluate_variant::<f32>(&mut group, &r, &base, &format!("f32-{threads}t"));
            if threads == 1 {
                let src = vec![[1.0f64; 3]; n];
                let mut dst = vec![[0.0f64; 3]; n];
                group.throughput(Throughput::Bytes((n * 24) as u64));
                group.bench_function(BenchmarkId::new("icosphere", "memcpy-f64"), |b| {
                    b.iter(|| dst.copy_from_slice(&src))
                });
            }
        }
        group.finish();
    }
}

/// 1,000 edges (each vertex's first outgoing edge, from vertex 0 on) of sharpness 2.5 and 100
/// corners of sharpness 1.5.
fn creases(mesh: &HalfEdgeMesh) -> Sharpness {
    let mut tags = Tags::default();
    let mut seen = std::collections::HashSet::new();
    for v in mesh.vertices().take(1000) {
        let h = mesh.vertex_halfedge(v);
        let w = mesh.to_vertex(h);
        if seen.insert((v.0.min(w.0), v.0.max(w.0))) {
            tags.add_crease(v.0, w.0, 2.5).expect("valid");
        }
    }
    for v in mesh.vertices().step_by(811).take(100) {
        tags.add_corner(v.0, 1.5).expect("valid");
    }
    Sharpness::from_tags(mesh, &tags).expect("edges of the mesh")
}

fn bench_creased(c: &mut Criterion, mesh: &HalfEdgeMesh) {
    let base: Vec<[f64; 3]> = mesh.positions().iter().map(|p| p.to_array()).collect();
    let sharpness = creases(mesh);
    let opts = SubdivideOptions::default().with_sharpness(&sharpness);
    for (name, rule, levels) in JOBS {
        let mut group = c.benchmark_group(format!("creased-{name}-L{levels}"));
        configure(&mut group);
        let r = Refinement::new(mesh, rule, levels, &opts).expect("the rule applies");
        let n = r.n_vertices(levels);
        group.throughput(Throughput::Elements(r.n_faces(levels) as u64));
        group.bench_function(BenchmarkId::new("icosphere", "new-1t"), |b| {
            b.iter(|| Refinement::new(mesh, rule, levels, &opts).expect("applies"))
        });
        group.throughput(Throughput::Bytes((n * 24) as u64));
        evaluate_variant::<f64>(&mut group, &r, &base, "f64-1t");
        group.finish();
    }
}

// What `criterion_group!` and `criterion_main!` expand to, without their undocumented
// public function.
fn main() {
    let mut c = Criterion::default().configure_from_args();
    let mesh = icosphere();
    bench_oneshot(&mut c, &mesh);
    bench_evaluate(&mut c, &mesh);
    bench_creased(&mut c, &mesh);
    c.final_summary();
}
