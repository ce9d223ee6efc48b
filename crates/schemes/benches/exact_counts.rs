//! Exact counts of every built-in scheme at s = 10, 10^3, 10^5, 10^6: closed-form evaluation
//! against matrix powering, and the decimal rendering of the largest count (issue 5).
//!
//! `cargo bench -p schemes --bench exact_counts` (filter with e.g. `-- loop/`).
#![allow(missing_docs)] // criterion_group! generates an undocumented public function

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use num_bigint::BigInt;
use schemes::{MeshCounts, Scheme};

/// A mesh each scheme applies to, as counts (icosahedron, icosahedron with two holes, cube,
/// an open mixed mesh), so every initial state is a real one.
fn counts_for(scheme: &Scheme) -> Vec<BigInt> {
    let ico = MeshCounts::from_polygons(&ICOSAHEDRON).expect("icosahedron");
    let cube = MeshCounts::from_polygons(&CUBE).expect("cube");
    let strip = MeshCounts::from_polygons(&[vec![0, 1, 2], vec![0, 2, 3], vec![2, 4, 5, 3]])
        .expect("strip");
    for counts in [&ico, &cube, &strip] {
        if let Ok(x0) = scheme.initial_state(counts) {
            return x0;
        }
    }
    panic!("no bench mesh for {}", scheme.name())
}

const ICOSAHEDRON: [[u32; 3]; 20] = [
    [0, 11, 5],
    [0, 5, 1],
    [0, 1, 7],
    [0, 7, 10],
    [0, 10, 11],
    [1, 5, 9],
    [5, 11, 4],
    [11, 10, 2],
    [10, 7, 6],
    [7, 1, 8],
    [3, 9, 4],
    [3, 4, 2],
    [3, 2, 6],
    [3, 6, 8],
    [3, 8, 9],
    [4, 9, 5],
    [2, 4, 11],
    [6, 2, 10],
    [8, 6, 7],
    [9, 8, 1],
];
const CUBE: [[u32; 4]; 6] = [
    [0, 1, 2, 3],
    [4, 7, 6, 5],
    [0, 4, 5, 1],
    [1, 5, 6, 2],
    [2, 6, 7, 3],
    [3, 7, 4, 0],
];

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("scheme-counts");
    group.sample_size(10);
    for scheme in schemes::builtins() {
        let x0 = counts_for(&scheme);
        let name = scheme.name().to_string();
        let phases = scheme.phases();
        let direct = match phases.as_slice() {
            [p] if p.first_level == 0 && p.period == 1 => Some(p.recurrence.closed_form()),
            _ => None,
        };
        for s in [10u64, 1_000, 100_000, 1_000_000] {
            if let Some(form) = direct.as_ref().filter(|f| f.is_exact()) {
                group.bench_with_input(
                    BenchmarkId::new(format!("{name}/closed-form"), s),
                    &s,
                    |b, &s| b.iter(|| form.evaluate(black_box(&x0), s).expect("exact form")),
                );
            }
            group.bench_with_input(
                BenchmarkId::new(format!("{name}/powering"), s),
                &s,
                |b, &s| b.iter(|| scheme.state_at(black_box(&x0), s).expect("state")),
            );
        }
        if name == "loop" || name == "catmull-clark-quad" {
            let state = scheme.state_at(&x0, 1_000_000).expect("state");
            let largest = state.iter().max().expect("non-empty state").clone();
            group.bench_function(
                BenchmarkId::new(format!("{name}/decimal"), 1_000_000),
                |b| b.iter(|| black_box(&largest).to_string()),
            );
        }
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
