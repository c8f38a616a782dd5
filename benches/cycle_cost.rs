//! Criterion benches (filled in by the benchmark issue).
#![allow(missing_docs)] // criterion_group! generates undocumented items
use criterion::{criterion_group, criterion_main, Criterion};

fn registers(c: &mut Criterion) {
    c.bench_function("register from_num", |b| {
        b.iter(|| profilegen::format::juno::TargetVelocity::from_num(criterion::black_box(13.825)))
    });
}

criterion_group!(benches, registers);
criterion_main!(benches);
