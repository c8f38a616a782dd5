//! Criterion benches of prediction (SPEC §15), one group per question:
//!
//! - `predict`: laying out a move's future (`predict()`) for the bench moves (`benches/common`);
//! - `state at a cycle`: `Prediction::state_at` at the middle and near the end of the S-curve
//!   and trapezoid moves, beside stepping a copy the same number of cycles (the way to know it
//!   without prediction);
//! - `first cycle at a position`: `Prediction::first_cycle_at` halfway.
//!
//! `cargo bench -p profilegen-benches --bench prediction`
#![allow(missing_docs)] // criterion_group! generates undocumented items

mod common;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use profilegen::fixed::types::I32F32;
use profilegen::ProfileGenerator;

fn predict(c: &mut Criterion) {
    let mut group = c.benchmark_group("predict");
    let scurve = common::scurve();
    let trapezoid = common::trapezoidal();
    let velocity = common::velocity();
    group.bench_function("SCurve", |b| b.iter(|| black_box(&scurve).predict()));
    group.bench_function("Trapezoidal", |b| {
        b.iter(|| black_box(&trapezoid).predict())
    });
    group.bench_function("VelocityContouring", |b| {
        b.iter(|| black_box(&velocity).predict())
    });
    group.finish();
}

fn state_at(c: &mut Criterion) {
    let mut group = c.benchmark_group("state at a cycle");
    let scurve = common::scurve();
    let total = scurve.plan().total;
    let future = scurve.predict().expect("a planned move");
    for (name, n) in [("middle", total / 2), ("end", total - 1)] {
        group.bench_function(format!("SCurve predicted, {name} ({n} cycles)"), |b| {
            b.iter(|| future.state_at(black_box(n)))
        });
    }
    group.bench_function(
        format!("SCurve stepped, middle ({} cycles)", total / 2),
        |b| {
            b.iter(|| {
                let mut copy = black_box(&scurve).clone();
                (0..total / 2).fold(I32F32::ZERO, |sum, _| {
                    sum.wrapping_add(copy.step().position)
                })
            })
        },
    );
    let trapezoid = common::trapezoidal();
    let future = trapezoid.predict().expect("a planned move");
    let total = future.completion().expect("it arrives");
    group.bench_function(
        format!("Trapezoidal predicted, middle ({} cycles)", total / 2),
        |b| b.iter(|| future.state_at(black_box(total / 2))),
    );
    group.finish();
}

fn first_cycle_at(c: &mut Criterion) {
    let mut group = c.benchmark_group("first cycle at a position");
    let halfway = I32F32::from_num(common::DISTANCE / 2);
    let future = common::scurve().predict().expect("a planned move");
    group.bench_function("SCurve, halfway", |b| {
        b.iter(|| future.first_cycle_at(black_box(halfway)))
    });
    let future = common::trapezoidal().predict().expect("a planned move");
    group.bench_function("Trapezoidal, halfway", |b| {
        b.iter(|| future.first_cycle_at(black_box(halfway)))
    });
    group.finish();
}

criterion_group!(benches, predict, state_at, first_cycle_at);
criterion_main!(benches);
