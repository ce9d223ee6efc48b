//! Face-varying UVs refined with the vertex data: what the UV channel adds to a refinement.
//!
//! Input: the shared meshes `spot_quadrangulated.obj` (Catmull-Clark) and
//! `spot_triangulated.obj` (Loop), 2,928 and 5,856 faces with a UV layout of 72 seam edges,
//! named by `SUBCOUNT_MESHES` as for the tests (the benchmark panics with the variable's
//! name when they are not there). Jobs at 3 levels, one thread, the face-varying mode
//! `corners-plus1`:
//!
//! - `uv-SCHEME-L3/spot/new`: `Refinement::new` without UVs, `new-uv` with them;
//! - `uv-SCHEME-L3/spot/positions-f32`: a per-frame evaluation of the positions
//!   (an `Evaluator`), `uvs-f32` of the UVs (`evaluate_uvs`), into caller buffers;
//! - `uv-SCHEME-L3/spot/uv-indices`: `write_uv_indices` of the last level.
//!
//! ```text
//! SUBCOUNT_MESHES=../shared/meshes cargo bench -p halfedge --bench uv
//! ```

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, SamplingMode, Throughput};
use halfedge::refine::Refinement;
use halfedge::subdivide::SubdivideOptions;
use halfedge::tags::{FaceVaryingInterpolation, SubdivisionOptions};
use halfedge::{io, HalfEdgeMesh, Rule};

const JOBS: [(&str, Rule, &str); 2] = [
    (
        "catmull-clark",
        Rule::CatmullClark,
        "spot_quadrangulated.obj",
    ),
    ("loop", Rule::Loop, "spot_triangulated.obj"),
];
const LEVELS: u32 = 3;

fn configure(group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>) {
    group
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2));
}

fn bench_job(c: &mut Criterion, name: &str, rule: Rule, file: &str) {
    let poly = io::read_obj(testdata::mesh(file)).expect("the shared mesh reads");
    let layout = poly.uv_layout().expect("the mesh has a UV layout");
    let mesh = HalfEdgeMesh::try_from(&poly).expect("the shared mesh is manifold");
    let subdivision =
        SubdivisionOptions::default().with_face_varying(FaceVaryingInterpolation::CornersPlus1);
    let plain = SubdivideOptions::default().with_subdivision(subdivision);
    let with_uvs = plain.with_uvs(&layout);

    let mut group = c.benchmark_group(format!("uv-{name}-L{LEVELS}"));
    configure(&mut group);
    let r = Refinement::new(&mesh, rule, LEVELS, &with_uvs).expect("the rule carries UVs");
    group.throughput(Throughput::Elements(r.n_faces(LEVELS) as u64));
    group.bench_function(BenchmarkId::new("spot", "new"), |b| {
        b.iter(|| Refinement::new(&mesh, rule, LEVELS, &plain).expect("applies"))
    });
    group.bench_function(BenchmarkId::new("spot", "new-uv"), |b| {
        b.iter(|| Refinement::new(&mesh, rule, LEVELS, &with_uvs).expect("applies"))
    });

    let positions: Vec<[f32; 3]> = mesh
        .positions()
        .iter()
        .map(|p| p.as_vec3().to_array())
        .collect();
    let mut out = vec![[0.0f32; 3]; r.n_vertices(LEVELS)];
    let mut evaluator = r.evaluator::<f32, 3>();
    group.throughput(Throughput::Bytes((out.len() * 12) as u64));
    group.bench_function(BenchmarkId::new("spot", "positions-f32"), |b| {
        b.iter(|| evaluator.evaluate(&positions, &mut out).expect("sizes"))
    });

    let base: Vec<[f32; 2]> = layout
        .values()
        .iter()
        .map(|uv| uv.as_vec2().to_array())
        .collect();
    let mut uvs = vec![[0.0f32; 2]; r.n_uvs(LEVELS)];
    group.throughput(Throughput::Bytes((uvs.len() * 8) as u64));
    group.bench_function(BenchmarkId::new("spot", "uvs-f32"), |b| {
        b.iter(|| r.evaluate_uvs(&base, &mut uvs).expect("sizes"))
    });

    let mut indices = vec![0u32; r.n_corners(LEVELS)];
    group.throughput(Throughput::Bytes((indices.len() * 4) as u64));
    group.bench_function(BenchmarkId::new("spot", "uv-indices"), |b| {
        b.iter(|| r.write_uv_indices(&mut indices).expect("sizes"))
    });
    group.finish();
    eprintln!(
        "{name} L{LEVELS}: heap {} bytes without UVs, {} with ({} UV values, {} vertices)",
        Refinement::new(&mesh, rule, LEVELS, &plain)
            .expect("applies")
            .heap_bytes(),
        r.heap_bytes(),
        r.n_uvs(LEVELS),
        r.n_vertices(LEVELS)
    );
}

// What `criterion_group!` and `criterion_main!` expand to, without their undocumented
// public function.
fn main() {
    let mut c = Criterion::default().configure_from_args();
    for (name, rule, file) in JOBS {
        bench_job(&mut c, name, rule, file);
    }
    c.final_summary();
}
