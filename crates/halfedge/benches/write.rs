//! Mesh writing throughput (output bytes per second): OBJ text in `f64` and `f32` on one and two
//! threads, binary PLY, into `std::io::sink()` (no file system: the formatting alone).
//!
//! Input: the armadillo of `$SUBCOUNT_MESHES` after 3 levels of Loop (5.5 M faces, the 310 MB
//! OBJ of `subcount subdivide --levels 3`), or without the variable the 81,920-face icosphere
//! after 3 levels (5.2 M faces). Ids are `FORMAT/MESH/THREADS`:
//!
//! ```text
//! cargo bench -p halfedge --bench write -- 'obj-f64'
//! ```

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, SamplingMode, Throughput};
use halfedge::io::{
    write_mesh_buffers_obj, write_polygon_obj_with, write_polygon_ply, FaceBuffers, MeshBuffers,
    ObjWriteOptions,
};
use halfedge::subdivide::{subdivide, subdivide_to_face_list, Rule, SubdivideOptions};
use halfedge::{shapes, HalfEdgeMesh, PolygonMesh};

/// The level-3 mesh written, and its name.
fn input() -> (String, PolygonMesh) {
    let (name, base) = match std::env::var_os(testdata::VAR) {
        Some(_) => {
            let path = testdata::mesh("armadillo.obj");
            let poly = halfedge::io::read_mesh(&path)
                .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
            ("armadillo", HalfEdgeMesh::try_from(&poly).expect("valid"))
        }
        None => {
            eprintln!("SUBCOUNT_MESHES is unset: writing the generated icosphere");
            let ico = HalfEdgeMesh::try_from(&shapes::icosahedron()).expect("valid");
            let opts = SubdivideOptions::default();
            let sphere = subdivide(&ico, Rule::Icosphere, 6, &opts).expect("subdivides");
            ("icosphere", sphere)
        }
    };
    let level = subdivide_to_face_list(&base, Rule::Loop, 3, &SubdivideOptions::default())
        .expect("Loop applies");
    (format!("{name}-L3"), level.mesh)
}

/// The bytes `write` writes.
fn size(write: impl Fn(&mut Vec<u8>)) -> u64 {
    let mut out = Vec::new();
    write(&mut out);
    out.len() as u64
}

fn bench_writing(c: &mut Criterion) {
    let (name, mesh) = input();
    let positions32: Vec<[f32; 3]> = mesh
        .positions
        .iter()
        .map(|p| p.to_array().map(|x| x as f32))
        .collect();
    let faces = FaceBuffers::Uniform {
        degree: 3,
        indices: mesh.face_indices(),
    };
    let buffers32 = MeshBuffers::new(&positions32, faces);
    for format in ["obj-f64", "obj-f32", "ply-f64"] {
        let mut group = c.benchmark_group(format);
        group
            .sample_size(10)
            .sampling_mode(SamplingMode::Flat)
            .warm_up_time(Duration::from_millis(300))
            .measurement_time(Duration::from_secs(3));
        for threads in [1, 2] {
            let options = ObjWriteOptions::default().with_threads(threads);
            let write = |out: &mut dyn std::io::Write| match format {
                "obj-f64" => write_polygon_obj_with(&mesh, out, &options),
                "obj-f32" => write_mesh_buffers_obj(&buffers32, out, &options),
                _ => write_polygon_ply(&mesh, out, &options),
            };
            let bytes = size(|out| write(out).expect("written"));
            group.throughput(Throughput::Bytes(bytes));
            group.bench_function(BenchmarkId::new(name.as_str(), threads), |b| {
                b.iter(|| write(&mut std::io::sink()).expect("written"))
            });
        }
        group.finish();
    }
}

// What `criterion_group!` and `criterion_main!` expand to, without their undocumented
// public function.
fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_writing(&mut c);
    c.final_summary();
}
