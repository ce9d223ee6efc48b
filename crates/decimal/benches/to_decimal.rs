//! `decimal::to_decimal` against num-bigint's quadratic `to_string` (group `decimal`; issue 5).
//!
//! The numbers are the largest exact counts that subcount prints for two schemes, written
//! out here so this crate needs no scheme: the edge counts `E = 30 4^s` of `loop` on the
//! icosahedron and `E = 12 4^s` of `catmull-clark-quad` on the cube, at s = 10, 10^3, 10^5
//! and 10^6 (8 to 602,062 digits; `12 4^(10^6)` is the number python-flint's `str()` renders
//! in `bench/peers/compare.py`). Both have few one bits, so `power-of-three` adds numbers with
//! dense bits, `3^k` for k = 2^17 and 2^20 (62,538 and 500,298 digits).
//!
//! `cargo bench -p decimal --bench to_decimal` (filter with e.g. `-- '^decimal/loop/'`).
#![allow(missing_docs)] // criterion_group! generates an undocumented public function

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use num_bigint::BigInt;

/// Times both conversions of `n` under `name/num-bigint-to-string/param` and
/// `name/to-decimal/param`, after checking that they give the same text.
fn bench_pair(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    param: u64,
    n: &BigInt,
) {
    assert_eq!(decimal::to_decimal(n), n.to_string(), "{name} {param}");
    group.bench_with_input(
        BenchmarkId::new(format!("{name}/num-bigint-to-string"), param),
        n,
        |b, n| b.iter(|| black_box(n).to_string()),
    );
    group.bench_with_input(
        BenchmarkId::new(format!("{name}/to-decimal"), param),
        n,
        |b, n| b.iter(|| decimal::to_decimal(black_box(n))),
    );
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("decimal");
    group.sample_size(10);
    for (name, e0) in [("loop", 30u32), ("catmull-clark-quad", 12)] {
        for s in [10u64, 1_000, 100_000, 1_000_000] {
            // E0 4^s = E0 2^(2s).
            let count = BigInt::from(e0) << (2 * s);
            bench_pair(&mut group, name, s, &count);
        }
    }
    for k in [1u32 << 17, 1 << 20] {
        bench_pair(
            &mut group,
            "power-of-three",
            u64::from(k),
            &BigInt::from(3).pow(k),
        );
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
