//! Exact counts of every built-in scheme at s = 10, 10^3, 10^5, 10^6: closed-form evaluation
//! against matrix powering (group `scheme-counts`). The decimal rendering of the largest counts
//! is benchmarked in the `decimal` crate (`cargo bench -p decimal --bench to_decimal`).
//!
//! `cargo bench -p schemes --bench exact_counts` (filter with e.g. `-- loop/`).
#![allow(missing_docs)] // criterion_group! generates an undocumented public function

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use num_bigint::BigInt;
use schemes::{CountsInput, Scheme};

/// The counts of a mesh each scheme applies to (icosahedron, cube, an open triangle strip,
/// an open mixed mesh), typed in, so every initial state is a real one.
fn counts_for(scheme: &Scheme) -> Vec<BigInt> {
    const MESHES: [&str; 4] = [
        "V=12,E=30,IE=30,BE=0,F=20,H=60",
        "V=8,E=12,IE=12,BE=0,F=6,H=24",
        "V=4,E=5,IE=1,BE=4,F=2,H=6",
        "V=6,E=8,IE=2,BE=6,F=3,H=10",
    ];
    MESHES
        .iter()
        .find_map(|text| {
            let input = CountsInput::parse(text).expect("bench counts parse");
            scheme.state_from_input(&input).ok()
        })
        .unwrap_or_else(|| panic!("no bench mesh for {}", scheme.name()))
}

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
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
