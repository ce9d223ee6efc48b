//! Exact counts at high levels: closed-form evaluation against powering, and digit
//! summaries at levels far beyond memory.
#![allow(missing_docs)] // criterion_group! generates an undocumented public function

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use num_bigint::BigInt;
use recurrence::{IntMatrix, Recurrence};

/// `(name, matrix, names, initial state)`: the paper's Loop (V, E), Loop (V, E, F) and
/// Catmull-Clark quad (V, E, F) recurrences on an icosahedron and a cube.
const CASES: &[(&str, &str, &str, &[i64])] = &[
    ("loop-ve", "[[1,1],[0,4]]", "V,E", &[12, 30]),
    (
        "loop-vef",
        "[[1,1,0],[0,2,3],[0,0,4]]",
        "V,E,F",
        &[12, 30, 20],
    ),
    (
        "catmull-clark-quad",
        "[[1,1,1],[0,2,4],[0,0,4]]",
        "V,E,F",
        &[8, 12, 6],
    ),
];

fn setup(m: &str, names: &str, x0: &[i64]) -> (Recurrence, Vec<BigInt>) {
    let m: IntMatrix = m.parse().expect("bench matrices parse");
    let r = Recurrence::with_names(m, names.split(',')).expect("bench names are valid");
    (r, x0.iter().map(|&x| BigInt::from(x)).collect())
}

fn evaluation(c: &mut Criterion) {
    let mut group = c.benchmark_group("exact-counts");
    group.sample_size(20);
    for (name, m, names, x0) in CASES {
        let (r, x0) = setup(m, names, x0);
        let form = r.closed_form();
        for s in [10u64, 1_000, 100_000, 1_000_000] {
            group.bench_with_input(
                BenchmarkId::new(format!("{name}/closed-form"), s),
                &s,
                |b, &s| b.iter(|| form.evaluate(black_box(&x0), s).expect("exact form")),
            );
            if s <= 100_000 || *name == "catmull-clark-quad" {
                group.bench_with_input(
                    BenchmarkId::new(format!("{name}/powering"), s),
                    &s,
                    |b, &s| b.iter(|| r.state_at(black_box(&x0), s).expect("lengths match")),
                );
            }
        }
    }
    group.finish();
}

fn summaries(c: &mut Criterion) {
    let mut group = c.benchmark_group("digit-summary");
    group.sample_size(20);
    for (name, m, names, x0) in CASES {
        let (r, x0) = setup(m, names, x0);
        let form = r.closed_form();
        group.bench_function(BenchmarkId::new(*name, "1e12"), |b| {
            b.iter(|| {
                form.summary_at(black_box(&x0), 1_000_000_000_000, 20)
                    .expect("exact form")
            })
        });
        let v = form.evaluate(&x0, 1_000_000).expect("exact form");
        group.bench_function(
            BenchmarkId::new(format!("{name}/materialized"), "1e6"),
            |b| b.iter(|| recurrence::digit_summary(black_box(&v[0]), 20)),
        );
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default();
    targets = evaluation, summaries
}
criterion_main!(benches);
