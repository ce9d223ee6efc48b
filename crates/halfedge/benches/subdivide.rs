//! Subdivision throughput (output faces per second): the paper's Tables 1 and 2, redone.
//!
//! Inputs: the 81,920-face icosphere (the icosahedron after 6 levels of `icosphere`), built in
//! code, and the large meshes of `$SUBCOUNT_MESHES` (armadillo, bunny_closed, botijo,
//! buildings_400k, beast; read through the `testdata` crate, so a relative path starts at the
//! workspace root and a missing file is an error; with the variable unset, the run says so and
//! measures the icosphere alone). Jobs: `loop`, `catmull-clark`, `sqrt3` and `doo-sabin` at
//! levels 1 and 2, `loop` and `catmull-clark` at level 3 (icosphere and armadillo only, to keep
//! the whole run near 10 minutes). Variants:
//! `prealloc-1t` (arrays allocated once from the prediction, one thread) and `prealloc-2t`
//! (rayon, 2 threads; icosphere and armadillo only); for the schemes whose last level can be
//! written straight into a face list (`loop`, `catmull-clark`), `faces-1t` and `faces-2t` time
//! `subdivide_to_face_list` (what `subcount subdivide` runs). The paper's baseline, arrays
//! grown on demand (`grow-1t`), left with the growing builder in issue 26 (BENCHMARKS.md keeps
//! its last figures).
//!
//! Benchmark ids are `SCHEME-LLEVEL/MESH/VARIANT`, so criterion's filter selects a subset:
//!
//! ```text
//! cargo bench -p halfedge --bench subdivide -- 'loop-L3/icosphere'
//! cargo bench -p halfedge --bench subdivide -- 'prealloc-1t'
//! ```
//!
//! The output mesh is dropped outside the timed region (`iter_with_large_drop`), as in the
//! OpenMesh driver of `bench/peers`.

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, SamplingMode, Throughput};
use halfedge::subdivide::{
    direct_face_degree, subdivide, subdivide_to_face_list, Rule, SubdivideOptions,
};
use halfedge::{shapes, HalfEdgeMesh};

/// The large meshes of `$SUBCOUNT_MESHES` used here.
const MESHES: [&str; 5] = [
    "armadillo",
    "bunny_closed",
    "botijo",
    "buildings_400k",
    "beast",
];

/// `(scheme, level)` jobs on every input.
const JOBS: [(Rule, u32); 8] = [
    (Rule::Loop, 1),
    (Rule::Loop, 2),
    (Rule::CatmullClark, 1),
    (Rule::CatmullClark, 2),
    (Rule::Sqrt3, 1),
    (Rule::Sqrt3, 2),
    (Rule::DooSabin, 1),
    (Rule::DooSabin, 2),
];

/// Level-3 jobs, on the inputs named in [`LEVEL3_INPUTS`].
const JOBS_L3: [(Rule, u32); 2] = [(Rule::Loop, 3), (Rule::CatmullClark, 3)];
const LEVEL3_INPUTS: [&str; 2] = ["icosphere", "armadillo"];

/// `(variant name, threads, last level as a face list)`.
const VARIANTS: [(&str, usize, bool); 4] = [
    ("prealloc-1t", 1, false),
    ("prealloc-2t", 2, false),
    ("faces-1t", 1, true),
    ("faces-2t", 2, true),
];

fn icosphere() -> HalfEdgeMesh {
    let ico = HalfEdgeMesh::try_from(&shapes::icosahedron()).expect("the icosahedron is valid");
    let sphere = subdivide(&ico, Rule::Icosphere, 6, &SubdivideOptions::default())
        .expect("the icosahedron subdivides");
    assert_eq!(sphere.n_faces(), 81_920);
    sphere
}

fn inputs() -> Vec<(String, HalfEdgeMesh)> {
    let mut inputs = vec![("icosphere".to_owned(), icosphere())];
    if std::env::var_os(testdata::VAR).is_none() {
        eprintln!("SUBCOUNT_MESHES is unset: benchmarking the generated icosphere only");
        return inputs;
    }
    for name in MESHES {
        let path = testdata::mesh(&format!("{name}.obj"));
        let poly = halfedge::io::read_mesh(&path)
            .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
        let mesh = HalfEdgeMesh::try_from(&poly)
            .unwrap_or_else(|e| panic!("{} is not a half-edge mesh: {e}", path.display()));
        inputs.push((name.to_owned(), mesh));
    }
    inputs
}

fn bench_subdivision(c: &mut Criterion) {
    let inputs = inputs();
    let jobs = JOBS
        .iter()
        .map(|&(s, l)| (s, l, None))
        .chain(JOBS_L3.iter().map(|&(s, l)| (s, l, Some(LEVEL3_INPUTS))));
    for (scheme, level, only) in jobs {
        let mut group = c.benchmark_group(format!("{scheme}-L{level}"));
        group
            .sample_size(10)
            .sampling_mode(SamplingMode::Flat)
            .warm_up_time(Duration::from_millis(300))
            .measurement_time(Duration::from_secs(1));
        for (name, mesh) in &inputs {
            if only.is_some_and(|names| !names.contains(&name.as_str())) {
                continue;
            }
            // One untimed run: applicability and the output size for the throughput.
            let faces = match subdivide(mesh, scheme, level, &SubdivideOptions::default()) {
                Ok(out) => out.n_faces(),
                Err(e) => {
                    eprintln!("{scheme} level {level} does not apply to {name}: {e}");
                    continue;
                }
            };
            group.throughput(Throughput::Elements(faces as u64));
            for (variant, threads, faces) in VARIANTS {
                if threads > 1 && !LEVEL3_INPUTS.contains(&name.as_str())
                    || faces && direct_face_degree(scheme).is_none()
                {
                    continue;
                }
                let opts = SubdivideOptions::default().with_threads(threads);
                let id = BenchmarkId::new(name.as_str(), variant);
                if faces {
                    group.bench_function(id, |b| {
                        b.iter_with_large_drop(|| {
                            subdivide_to_face_list(mesh, scheme, level, &opts).expect("applies")
                        })
                    });
                } else {
                    group.bench_function(id, |b| {
                        b.iter_with_large_drop(|| {
                            subdivide(mesh, scheme, level, &opts).expect("checked above")
                        })
                    });
                }
            }
        }
        group.finish();
    }
}

// What `criterion_group!` and `criterion_main!` expand to, without their undocumented
// public function.
fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_subdivision(&mut c);
    c.final_summary();
}
